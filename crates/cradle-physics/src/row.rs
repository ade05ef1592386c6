//! The row of balls as one ODE system, for the integrated parts of the physics:
//! Hertz contact phases (`hertz`) and the damped engine (`damped`).
//!
//! The state is `y = (theta, omega)`, and with dissipation two more components:
//! the energy lost so far in contacts and to air drag (J). Forces:
//! - gravity on every ball;
//! - every overlapping pair pushes apart along its line of centres with
//!   `F = max(0, k delta^1.5 + 3/2 A k sqrt(delta) d(delta)/dt)`: Hertz's elastic
//!   force plus the viscoelastic term of Brilliantov et al. (1996), `A` the
//!   material's dissipative constant (s). The force never pulls: a pair that
//!   separates faster than the material recovers pushes with 0;
//! - quadratic air drag on each ball's centre, `c v^2` against its motion.
//!
//! With `A = 0` and no drag the forces are Hertz's alone, computed as before
//! the dissipation existed, so elastic runs stay byte for byte the same.

use super::contact;
use super::params::CradleParams;

/// The ODE system of a row of balls.
pub(crate) struct Row<'a> {
    p: &'a CradleParams,
    n: usize,
    /// Hertz stiffness (N/m^1.5).
    k: f64,
    /// `m g L / I` (1/s^2).
    grav: f64,
    inertia: f64,
    inv_inertia: f64,
    /// `3/2 A k` (N s / m^1.5).
    damp: f64,
    /// `c L^3 / I` (1/rad): `d omega/dt = -drag omega |omega|`.
    drag: f64,
}

impl<'a> Row<'a> {
    /// The row of `n` balls of `p` with Hertz stiffness `k`.
    pub(crate) fn new(p: &'a CradleParams, k: f64, n: usize) -> Self {
        let inertia = p.inertia();
        Self {
            p,
            n,
            k,
            grav: p.mass * p.gravity * p.length / inertia,
            inertia,
            inv_inertia: 1.0 / inertia,
            damp: 1.5 * p.dissipation * k,
            drag: p.drag * p.length.powi(3) / inertia,
        }
    }

    /// True when the state carries the energy lost (any dissipation).
    pub(crate) fn books(&self) -> bool {
        self.damp > 0.0 || self.drag > 0.0
    }

    /// Length of the state vector.
    pub(crate) fn len(&self) -> usize {
        2 * self.n + if self.books() { 2 } else { 0 }
    }

    /// The state vector of `(theta, omega)`, nothing lost yet.
    pub(crate) fn state(&self, theta: &[f64], omega: &[f64]) -> Vec<f64> {
        let mut y: Vec<f64> = theta.iter().chain(omega).copied().collect();
        y.resize(self.len(), 0.0);
        y
    }

    /// The energy lost in contacts and to drag recorded in `y` (J).
    pub(crate) fn lost(&self, y: &[f64]) -> [f64; 2] {
        if self.books() {
            [y[2 * self.n], y[2 * self.n + 1]]
        } else {
            [0.0; 2]
        }
    }

    /// Overlap of pair `a` (m).
    pub(crate) fn overlap(&self, theta: &[f64], a: usize) -> f64 {
        contact::overlap(self.p, theta[a], theta[a + 1])
    }

    /// `dy/dt` into `out`.
    pub(crate) fn deriv(&self, y: &[f64], out: &mut [f64]) {
        let n = self.n;
        let (theta, rest) = y.split_at(n);
        let omega = &rest[..n];
        let (dtheta, drest) = out.split_at_mut(n);
        let (domega, dlost) = drest.split_at_mut(n);
        dtheta.copy_from_slice(omega);
        for (d, t) in domega.iter_mut().zip(theta) {
            *d = -self.grav * t.sin();
        }
        let mut in_contacts = 0.0;
        for a in 0..n.saturating_sub(1) {
            let delta = self.overlap(theta, a);
            if delta <= 0.0 {
                continue;
            }
            let (ja, jb) = contact::levers(self.p, theta[a], theta[a + 1]);
            let root = delta.sqrt();
            let elastic = self.k * delta * root;
            let force = if self.damp > 0.0 {
                // d(delta)/dt: minus the closing speed.
                let rate = ja * omega[a] - jb * omega[a + 1];
                let f = (elastic + self.damp * root * rate).max(0.0);
                // dE/dt = (k delta^1.5 - F) d(delta)/dt <= 0 either way.
                in_contacts += (f - elastic) * rate;
                f
            } else {
                elastic
            };
            domega[a] -= force * ja * self.inv_inertia;
            domega[a + 1] += force * jb * self.inv_inertia;
        }
        if self.drag > 0.0 {
            for (d, w) in domega.iter_mut().zip(omega) {
                *d -= self.drag * w * w.abs();
            }
        }
        if self.books() {
            dlost[0] = in_contacts;
            // Power of the drag torques: I drag |omega|^3 per ball.
            dlost[1] =
                self.inertia * self.drag * omega.iter().map(|w| w.abs().powi(3)).sum::<f64>();
        }
    }
}
