//! Bracketed root finding for impact times: Illinois regula falsi with bisection
//! fallback, keeping a bracket whose left end never overlaps.

/// Finds `t` in `(a, b]` where `f` changes from positive to non-positive, given
/// `f(a) > 0 >= f(b)`. Returns the left end of the final bracket (the last time at
/// which `f` is still positive), within `tol` of the root.
pub fn falling_root(mut f: impl FnMut(f64) -> f64, mut a: f64, mut b: f64, tol: f64) -> f64 {
    let mut fa = f(a);
    let mut fb = f(b);
    let mut side = 0i8;
    for i in 0..200 {
        if b - a <= tol {
            break;
        }
        // Regula falsi with the Illinois halving; every 4th step bisects so that a
        // bad curvature can not stall the bracket.
        let mut t = if i % 4 == 3 || fa == fb {
            0.5 * (a + b)
        } else {
            (a * fb - b * fa) / (fb - fa)
        };
        if !(t > a && t < b) {
            t = 0.5 * (a + b);
        }
        let ft = f(t);
        if ft > 0.0 {
            a = t;
            fa = ft;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            b = t;
            fb = ft;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
    }
    a
}

/// Finds where `df` (a derivative) goes from negative to positive inside `[a, b]`,
/// given `df(a) < 0 < df(b)`: the time of a minimum.
pub fn rising_root(mut df: impl FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    falling_root(|t| -df(t), a, b, tol)
}
