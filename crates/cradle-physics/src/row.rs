//! The row of balls as one ODE system, for the integrated parts of the physics:
//! Hertz contact phases (`hertz`) and the damped engine (`damped`).
//!
//! The state is `y = (theta, omega)`, with dissipation two more components: the
//! energy lost so far in contacts and to air drag (J), and when impacts are
//! reported one more per pair: the impulse its contacts have passed so far
//! (N s, the integral of the force, for `impacts`). Neither feeds back into the
//! motion, and both go without error control (`dopri`), so the steps are the
//! same with or without them. Forces:
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
    /// The state carries each pair's impulse so far.
    impulses: bool,
}

/// What one overlapping pair does at a state.
struct Push {
    /// The force along the line of centres (N, >= 0).
    force: f64,
    /// The pair's levers (m): `contact::levers`.
    levers: (f64, f64),
    /// The power the force takes out of the motion beyond the elastic force's (W, <= 0).
    lossy_power: f64,
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
            impulses: false,
        }
    }

    /// The same system whose state also carries each pair's impulse so far.
    pub(crate) fn with_impulses(self, on: bool) -> Self {
        Self {
            impulses: on,
            ..self
        }
    }

    /// True when the state carries the energy lost (any dissipation).
    pub(crate) fn books(&self) -> bool {
        self.damp > 0.0 || self.drag > 0.0
    }

    /// Length of the state vector.
    pub(crate) fn len(&self) -> usize {
        self.impulse_at() + if self.impulses { self.pairs() } else { 0 }
    }

    fn pairs(&self) -> usize {
        self.n.saturating_sub(1)
    }

    /// Where the impulses start in the state.
    fn impulse_at(&self) -> usize {
        2 * self.n + if self.books() { 2 } else { 0 }
    }

    /// Sets the error scales of the components beyond the motion: `lost` for
    /// the energy lost (J), none for the impulses (infinite: they follow from
    /// the motion and are not error controlled).
    pub(crate) fn scale_extra(&self, scale: &mut [f64], lost: f64) {
        let at = self.impulse_at();
        scale[2 * self.n..at].fill(lost);
        scale[at..].fill(f64::INFINITY);
    }

    /// The cradle's parameters.
    pub(crate) fn params(&self) -> &CradleParams {
        self.p
    }

    /// The Hertz stiffness (N/m^1.5).
    pub(crate) fn stiffness(&self) -> f64 {
        self.k
    }

    /// The angles and angular velocities in `y`.
    pub(crate) fn motion<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64]) {
        (&y[..self.n], &y[self.n..2 * self.n])
    }

    /// Each pair's impulse so far in `y` (N s): empty unless carried.
    pub(crate) fn impulses<'y>(&self, y: &'y [f64]) -> &'y [f64] {
        if self.impulses {
            &y[self.impulse_at()..]
        } else {
            &[]
        }
    }

    /// The force between pair `a` in state `y` (N): 0 unless it overlaps.
    pub(crate) fn force(&self, y: &[f64], a: usize) -> f64 {
        let (theta, omega) = self.motion(y);
        self.push(theta, omega, a).map_or(0.0, |push| push.force)
    }

    /// What pair `a` does at `(theta, omega)`; `None` unless it overlaps.
    fn push(&self, theta: &[f64], omega: &[f64], a: usize) -> Option<Push> {
        let delta = self.overlap(theta, a);
        if delta <= 0.0 {
            return None;
        }
        let (ja, jb) = contact::levers(self.p, theta[a], theta[a + 1]);
        let root = delta.sqrt();
        let elastic = self.k * delta * root;
        let (force, lossy_power) = if self.damp > 0.0 {
            // d(delta)/dt: minus the closing speed.
            let rate = ja * omega[a] - jb * omega[a + 1];
            let f = (elastic + self.damp * root * rate).max(0.0);
            // dE/dt = (k delta^1.5 - F) d(delta)/dt <= 0 either way.
            (f, (f - elastic) * rate)
        } else {
            (elastic, 0.0)
        };
        Some(Push {
            force,
            levers: (ja, jb),
            lossy_power,
        })
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
        let (domega, dextra) = drest.split_at_mut(n);
        let (dlost, dimpulse) = dextra.split_at_mut(self.impulse_at() - 2 * n);
        dtheta.copy_from_slice(omega);
        for (d, t) in domega.iter_mut().zip(theta) {
            *d = -self.grav * t.sin();
        }
        dimpulse.fill(0.0);
        let mut in_contacts = 0.0;
        for a in 0..self.pairs() {
            let Some(push) = self.push(theta, omega, a) else {
                continue;
            };
            let (ja, jb) = push.levers;
            in_contacts += push.lossy_power;
            domega[a] -= push.force * ja * self.inv_inertia;
            domega[a + 1] += push.force * jb * self.inv_inertia;
            if let Some(d) = dimpulse.get_mut(a) {
                *d = push.force;
            }
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
