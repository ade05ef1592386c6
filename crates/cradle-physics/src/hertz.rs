//! Hertz contact: soft elastic spheres pressing with `F = k delta^1.5`, integrated
//! with adaptive Dormand-Prince 5(4) steps through the ~0.1 ms a contact lasts.
//!
//! A contact phase starts when two balls meet (found by the engines' gap roots, as
//! for ideal impacts) and ends when no pair overlaps and no touching pair
//! approaches. During it the whole row is one system: every ball swings under
//! gravity and every overlapping pair pushes along its line of centres. The
//! potential `2/5 k delta^2.5` makes the system conservative, so energy and, along
//! the contact, momentum are kept to the integrator's tolerance.
//!
//! The step sequence depends only on the phase's start state, never on when the
//! state is asked for: a state inside a phase is one extra step from the step
//! point before it.

use super::contact;
use super::params::CradleParams;

/// Local error per step, as a fraction of the ball radius (positions) and of the
/// fastest speed at the phase start (velocities). 1e-13 keeps the energy error of
/// a whole contact below 1e-11 relative (measured by `tests/physics.rs`), well under
/// the 1e-9 asked of it, at ~100 steps per contact.
const TOL: f64 = 1e-13;

/// A phase that has not separated after this many steps is cut there and goes on
/// as a new phase: it bounds the work of a query inside a long contact.
const SEGMENT_STEPS: usize = 20_000;

/// Hertz stiffness `k = 4/3 E* sqrt(R*)` (N/m^1.5) of two equal spheres of radius
/// `r` (m): `E* = E / (2 (1 - nu^2))`, `R* = r / 2`.
#[must_use]
pub fn stiffness(youngs_modulus: f64, poisson_ratio: f64, radius: f64) -> f64 {
    let e_star = youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
    4.0 / 3.0 * e_star * (0.5 * radius).sqrt()
}

/// How a phase (or a segment of one) ended.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseEnd {
    /// Time of the last step (s).
    pub t: f64,
    /// Angles (rad).
    pub theta: Vec<f64>,
    /// Angular velocities (rad/s).
    pub omega: Vec<f64>,
    /// True when every pair has come apart; false when cut by the stop time or
    /// the segment length.
    pub separated: bool,
    /// Pairs that came into contact during it (onsets of overlap).
    pub contacts: u64,
}

/// The row of balls as one ODE system `y = (theta, omega)`.
struct System<'a> {
    p: &'a CradleParams,
    k: f64,
    /// `m g L / I` (1/s^2).
    grav: f64,
    inv_inertia: f64,
}

impl System<'_> {
    fn overlap(&self, theta: &[f64], a: usize) -> f64 {
        contact::overlap(self.p, theta[a], theta[a + 1])
    }

    /// `dy/dt` into `out`.
    fn deriv(&self, y: &[f64], out: &mut [f64]) {
        let n = y.len() / 2;
        let (theta, omega) = y.split_at(n);
        let (dtheta, domega) = out.split_at_mut(n);
        dtheta.copy_from_slice(omega);
        for (d, t) in domega.iter_mut().zip(theta) {
            *d = -self.grav * t.sin();
        }
        for a in 0..n.saturating_sub(1) {
            let delta = self.overlap(theta, a);
            if delta <= 0.0 {
                continue;
            }
            let force = self.k * delta * delta.sqrt();
            let (ja, jb) = contact::levers(self.p, theta[a], theta[a + 1]);
            domega[a] -= force * ja * self.inv_inertia;
            domega[a + 1] += force * jb * self.inv_inertia;
        }
    }
}

// Dormand-Prince 5(4) tableau (the system is autonomous: no stage times).
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
fn dopri_step(
    sys: &System,
    y: &[f64],
    h: f64,
    scale: &[f64],
    k: &mut [Vec<f64>; 7],
) -> (Vec<f64>, f64) {
    let m = y.len();
    let mut tmp = vec![0.0; m];
    sys.deriv(y, &mut k[0]);
    for s in 1..7 {
        for i in 0..m {
            let mut acc = 0.0;
            for (j, a) in A[s].iter().enumerate().take(s) {
                acc += a * k[j][i];
            }
            tmp[i] = y[i] + h * acc;
        }
        sys.deriv(&tmp, &mut k[s]);
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

/// Integrates a contact phase from `(theta, omega)` at `t0` until the balls come
/// apart, the step count reaches a segment, or `stop` (s) is reached; at `stop`
/// the state is one shortened step from the last step point, and the step
/// sequence is the one a run without `stop` takes.
///
/// `k` is the Hertz stiffness (N/m^1.5).
#[must_use]
pub fn run_phase(
    p: &CradleParams,
    k: f64,
    t0: f64,
    theta: &[f64],
    omega: &[f64],
    stop: f64,
) -> PhaseEnd {
    let n = theta.len();
    let sys = System {
        p,
        k,
        grav: p.mass * p.gravity * p.length / p.inertia(),
        inv_inertia: 1.0 / p.inertia(),
    };
    let mut y: Vec<f64> = theta.iter().chain(omega).copied().collect();
    // Error scales: positions to TOL radii, speeds to TOL of the fastest ball, or of
    // the speed gravity gives over the contact time when everything is at rest.
    let w_max = omega.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let w_floor = 1e-6 * p.w0() * p.radius / p.length;
    let mut scale = vec![TOL * p.radius / p.length; 2 * n];
    scale[n..].fill(TOL * w_max.max(w_floor));
    // First step: a hundredth of the time to close one radius's thousandth.
    let mut h = (1e-5 * p.radius / (p.length * w_max.max(w_floor))).min(1e-3 / p.w0());
    let mut t = t0;
    let mut k_buf: [Vec<f64>; 7] = std::array::from_fn(|_| vec![0.0; 2 * n]);
    let overlapping = |y: &[f64], a: usize| sys.overlap(&y[..n], a) > 0.0;
    let mut touching: Vec<bool> = (0..n.saturating_sub(1))
        .map(|a| overlapping(&y, a))
        .collect();
    let mut contacts = 0;
    let end = |t: f64, y: &[f64], separated: bool, contacts: u64| PhaseEnd {
        t,
        theta: y[..n].to_vec(),
        omega: y[n..].to_vec(),
        separated,
        contacts,
    };
    let mut steps = 0;
    loop {
        let (y1, err) = dopri_step(&sys, &y, h, &scale, &mut k_buf);
        if err > 1.0 || !err.is_finite() {
            h *= (0.9 * err.powf(-0.2)).clamp(0.1, 0.9);
            if !h.is_finite() || h <= f64::EPSILON * t.abs().max(1e-300) {
                // Cannot happen for finite states; end rather than loop.
                return end(t, &y, false, contacts);
            }
            continue;
        }
        if t + h > stop {
            let (ys, _) = dopri_step(&sys, &y, stop - t, &scale, &mut k_buf);
            return end(stop, &ys, false, contacts);
        }
        if t + h == t {
            // The step is below f64's resolution of time here: nothing could ever
            // advance. The ranges of the config keep this from happening; should
            // it, the contact ends here rather than the program hanging.
            tracing::warn!(
                "contact step {h:e} s is below the resolution of t = {t} s; contact ended"
            );
            return end(t, &y, true, contacts);
        }
        t += h;
        y = y1;
        steps += 1;
        for (a, was) in touching.iter_mut().enumerate() {
            let now = overlapping(&y, a);
            contacts += u64::from(now && !*was);
            *was = now;
        }
        if separated(p, &y, n) {
            return end(t, &y, true, contacts);
        }
        if steps >= SEGMENT_STEPS {
            return end(t, &y, false, contacts);
        }
        h *= (0.9 * err.max(1e-10).powf(-0.2)).min(5.0);
    }
}

/// True when no pair overlaps and no pair closer than a billionth of a radius
/// approaches (the phase starts at such a pair: the gap root's last positive time).
fn separated(p: &CradleParams, y: &[f64], n: usize) -> bool {
    let (theta, omega) = y.split_at(n);
    let touch_h = 4e-9 * p.radius * p.radius;
    (0..n.saturating_sub(1)).all(|a| {
        let h = contact::gap_fn(p, theta[a], theta[a + 1]);
        h >= 0.0
            && (h > touch_h
                || contact::closing_speed(p, (theta[a], omega[a]), (theta[a + 1], omega[a + 1]))
                    >= 0.0)
    })
}
