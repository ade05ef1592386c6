//! Dormand-Prince 5(4): the adaptive Runge-Kutta step that the Hertz contact
//! phases (`hertz`) and the damped engine (`damped`) take. The systems are
//! autonomous, so the stages carry no times.
//!
//! A component whose error scale is infinite is integrated but not error
//! controlled (the energy dissipated, which follows from the state).

/// The stage coefficients.
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights (the last row of `A`, so the last stage is FSAL).
const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
/// Fifth minus fourth order weights: the error estimate.
const E: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339_200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];

/// One Dormand-Prince step of length `h` from `y`: the new state and the scaled
/// error norm (max over components of `|err| / scale`).
pub(crate) fn step(
    deriv: &impl Fn(&[f64], &mut [f64]),
    y: &[f64],
    h: f64,
    scale: &[f64],
    k: &mut [Vec<f64>; 7],
) -> (Vec<f64>, f64) {
    let m = y.len();
    let mut tmp = vec![0.0; m];
    deriv(y, &mut k[0]);
    for s in 1..7 {
        for i in 0..m {
            let mut acc = 0.0;
            for (j, a) in A[s].iter().enumerate().take(s) {
                acc += a * k[j][i];
            }
            tmp[i] = y[i] + h * acc;
        }
        deriv(&tmp, &mut k[s]);
    }
    let mut err: f64 = 0.0;
    let mut out = vec![0.0; m];
    for i in 0..m {
        let mut hi = 0.0;
        let mut e = 0.0;
        for s in 0..7 {
            hi += B[s] * k[s][i];
            e += E[s] * k[s][i];
        }
        out[i] = y[i] + h * hi;
        err = err.max((h * e).abs() / scale[i]);
    }
    (out, err)
}
