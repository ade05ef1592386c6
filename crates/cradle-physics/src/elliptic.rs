//! Jacobi elliptic functions and elliptic integrals: the closed-form pendulum flight
//! (`flight.rs`) is built from these.
//!
//! Parameter convention: `m = k^2` (the parameter), `0 <= m <= 1`.
//! - `sn`, `cn`, `dn` by the descending Landen transformation (arithmetic-geometric
//!   mean, Abramowitz & Stegun 16.4), after reducing `u` modulo the real period `4K`.
//! - `K(m)` by the AGM: `K = pi / (2 AGM(1, sqrt(1 - m)))`.
//! - The incomplete integral `F(phi | m)` by Carlson's symmetric `R_F`, used to find
//!   the phase of a pendulum from its angle and angular velocity.
//!
//! All reach about 1e-15 relative accuracy for `m` not within 1e-12 of 1.

use std::f64::consts::{FRAC_PI_2, PI};

/// Largest number of AGM steps; the AGM converges quadratically, so 1e-16 is reached
/// in at most 6 steps for `m <= 1 - 1e-15`. The cap only guards against NaN input.
const MAX_AGM_STEPS: usize = 16;

/// Arithmetic-geometric mean of `a` and `b` (both > 0).
#[must_use]
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..MAX_AGM_STEPS {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        if (a - b).abs() <= 1e-16 * a {
            return an;
        }
        a = an;
        b = bn;
    }
    0.5 * (a + b)
}

/// Complete elliptic integral of the first kind `K(m)`, `m = k^2 in [0, 1)`.
/// Returns infinity at `m = 1`.
#[must_use]
pub fn ellip_k(m: f64) -> f64 {
    if m >= 1.0 {
        return f64::INFINITY;
    }
    PI / (2.0 * agm(1.0, (1.0 - m).sqrt()))
}

/// Jacobi elliptic functions `(sn, cn, dn)` of `u` with parameter `m = k^2 in [0, 1]`.
#[must_use]
pub fn sncndn(u: f64, m: f64) -> (f64, f64, f64) {
    sncndn_k(u, m, ellip_k(m))
}

/// [`sncndn`] with `K(m)` already known (a flight keeps its own), saving an AGM.
#[must_use]
pub fn sncndn_k(u: f64, m: f64, quarter: f64) -> (f64, f64, f64) {
    if m <= 0.0 {
        return (u.sin(), u.cos(), 1.0);
    }
    if m >= 1.0 {
        let c = 1.0 / u.cosh();
        return (u.tanh(), c, c);
    }
    // Reduce u to [-2K, 2K] so that 2^N a_N u stays small and sin() keeps its digits.
    let period = 4.0 * quarter;
    let u = u - period * (u / period).round();

    let mut a = [0.0_f64; MAX_AGM_STEPS + 1];
    let mut c = [0.0_f64; MAX_AGM_STEPS + 1];
    a[0] = 1.0;
    let mut b = (1.0 - m).sqrt();
    c[0] = m.sqrt();
    let mut n = 0;
    while n < MAX_AGM_STEPS && c[n].abs() > 1e-16 {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = f64::from(1u32 << n) * a[n] * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (c[i] / a[i] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    // dn from the identity is accurate to the last bit where the Landen form
    // cos(phi0)/cos(phi1 - phi0) loses digits near cn = 0.
    let dn = (1.0 - m * sn * sn).max(0.0).sqrt();
    (sn, cn, dn)
}

/// Carlson's symmetric elliptic integral `R_F(x, y, z)` (at most one argument zero),
/// by the duplication theorem (Carlson 1995, relative error ~1e-16).
#[must_use]
pub fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    for _ in 0..64 {
        let mu = (x + y + z) / 3.0;
        let dx = 1.0 - x / mu;
        let dy = 1.0 - y / mu;
        let dz = 1.0 - z / mu;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-4 {
            // Fifth-order Taylor tail: error ~ (1e-4)^6 / 10, below 1e-24.
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / mu.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sx * sz + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    let mu = (x + y + z) / 3.0;
    1.0 / mu.sqrt()
}

/// Incomplete elliptic integral of the first kind `F(phi | m)` for any real `phi`,
/// `m in [0, 1)`: `F(phi + n pi) = F(phi) + 2 n K`.
#[must_use]
pub fn ellip_f(phi: f64, m: f64) -> f64 {
    let turns = (phi / PI).round();
    let rest = phi - turns * PI; // in [-pi/2, pi/2]
    let (s, c) = rest.sin_cos();
    let partial = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
    if turns == 0.0 {
        partial
    } else {
        partial + 2.0 * turns * ellip_k(m)
    }
}

/// The phase `u` in `[-2K, 2K]` with `sn(u) = s`, `cn(u) = c` (given `s^2 + c^2 = 1`).
#[must_use]
pub fn phase_of(s: f64, c: f64, m: f64) -> f64 {
    let phi = s.atan2(c); // in [-pi, pi]
    if phi.abs() <= FRAC_PI_2 {
        ellip_f(phi, m)
    } else {
        // sn(2K - u) = sn(u), cn(2K - u) = -cn(u): mirror into the principal range.
        let k2 = 2.0 * ellip_k(m);
        let mirrored = phi.signum() * PI - phi;
        phi.signum() * k2 - ellip_f(mirrored, m)
    }
}
