//! Fixed-step integrators with the same impacts as the exact engine: for
//! comparison in the work-precision benchmark.
//!
//! The committed state lives on the grid `t = n dt`. An impact inside a step is
//! located by bisection on the step fraction (re-integrating from the step's start),
//! resolved there, and the step finished with what remains of it. A state between
//! grid points is a partial step from the grid point before it, never committed, so
//! the state at a time does not depend on how often it is sampled.

use super::contact::{self, Resolution};
use super::hertz;
use super::impacts::{ImpactLog, Watch};
use super::params::{CradleParams, Integrator};

/// Bisection steps locating an impact inside a step: 2^-52 of a step.
const BISECTIONS: usize = 52;

/// A fixed-step solver.
#[derive(Debug, Clone)]
pub struct SteppedEngine {
    params: CradleParams,
    resolution: Resolution,
    method: Integrator,
    dt: f64,
    w0sq: f64,
    /// Steps committed: the state below is at `steps * dt`.
    steps: u64,
    theta: Vec<f64>,
    omega: Vec<f64>,
    collisions: u64,
    /// The impacts found on the committed grid and not yet taken; the Hertz
    /// contacts still open.
    impacts: ImpactLog,
    watch: Watch,
}

/// Where the committed steps report their impacts: the log, the Hertz watch,
/// and the time the step being taken starts at (s).
struct Found<'a> {
    log: &'a mut ImpactLog,
    watch: &'a mut Watch,
    t: f64,
}

impl SteppedEngine {
    /// A cradle starting at `t = 0`, stepping with `method` (not `Exact`) and step `dt` (s).
    #[must_use]
    pub fn new(
        params: CradleParams,
        resolution: Resolution,
        method: Integrator,
        dt: f64,
        theta: &[f64],
        omega: &[f64],
    ) -> Self {
        Self {
            params,
            resolution,
            method,
            dt,
            w0sq: params.w0().powi(2),
            steps: 0,
            theta: theta.to_vec(),
            omega: omega.to_vec(),
            collisions: 0,
            impacts: ImpactLog::default(),
            watch: Watch::new(theta.len().saturating_sub(1)),
        }
    }

    /// One integrator step of length `h` for one ball.
    fn step_ball(&self, theta: f64, omega: f64, h: f64) -> (f64, f64) {
        let acc = |th: f64| -self.w0sq * th.sin();
        match self.method {
            Integrator::Euler => {
                let w = omega + h * acc(theta);
                (theta + h * w, w)
            }
            Integrator::Verlet => verlet(theta, omega, h, &acc),
            Integrator::Yoshida4 => {
                // w1 = 1 / (2 - 2^(1/3)), w0 = -2^(1/3) w1 (Yoshida 1990).
                const W1: f64 = 1.351_207_191_959_657_8;
                const W0: f64 = -1.702_414_383_919_315_3;
                let (t, w) = verlet(theta, omega, W1 * h, &acc);
                let (t, w) = verlet(t, w, W0 * h, &acc);
                verlet(t, w, W1 * h, &acc)
            }
            Integrator::Rk4 | Integrator::Exact => {
                let (k1t, k1w) = (omega, acc(theta));
                let (k2t, k2w) = (omega + 0.5 * h * k1w, acc(theta + 0.5 * h * k1t));
                let (k3t, k3w) = (omega + 0.5 * h * k2w, acc(theta + 0.5 * h * k2t));
                let (k4t, k4w) = (omega + h * k3w, acc(theta + h * k3t));
                (
                    theta + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t),
                    omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w),
                )
            }
        }
    }

    fn step_all(&self, theta: &[f64], omega: &[f64], h: f64) -> (Vec<f64>, Vec<f64>) {
        theta
            .iter()
            .zip(omega)
            .map(|(&t, &w)| self.step_ball(t, w, h))
            .unzip()
    }

    /// True when pair `a` goes from apart to touching and approaching over the step.
    fn hits(&self, before: &[f64], after: (&[f64], &[f64]), a: usize) -> bool {
        let p = &self.params;
        contact::gap_fn(p, before[a], before[a + 1]) > 0.0
            && contact::gap_fn(p, after.0[a], after.0[a + 1]) <= 0.0
            && contact::closing_speed(
                p,
                (after.0[a], after.1[a]),
                (after.0[a + 1], after.1[a + 1]),
            ) < 0.0
    }

    /// With Hertz contact: runs the contact phase from `(theta, omega)` for at most
    /// `h` (s). Returns the time it took (all of `h` if the balls are still in
    /// contact) and the contacts in it.
    fn hertz_phase(
        &self,
        theta: &mut Vec<f64>,
        omega: &mut Vec<f64>,
        h: f64,
        found: Option<&mut Found<'_>>,
    ) -> (f64, u64) {
        let k = self.params.hertz.unwrap_or(0.0);
        let report = found.map(|f| hertz::Report {
            watch: f.watch,
            log: f.log,
            epoch: f.t,
        });
        let end = hertz::run_reported(&self.params, k, (0.0, theta, omega), h, report);
        *theta = end.theta;
        *omega = end.omega;
        (if end.separated { end.t } else { h }, end.contacts)
    }

    /// True when some pair overlaps (with Hertz contact the phase goes on).
    fn overlapping(&self, theta: &[f64]) -> bool {
        theta
            .windows(2)
            .any(|w| contact::gap_fn(&self.params, w[0], w[1]) < 0.0)
    }

    /// Advances `(theta, omega)` by `h`, resolving impacts inside; returns
    /// impacts. A committed step reports them to `found`.
    fn advance(
        &self,
        theta: &mut Vec<f64>,
        omega: &mut Vec<f64>,
        mut h: f64,
        mut found: Option<Found<'_>>,
    ) -> u64 {
        let mut impacts = 0;
        if self.params.hertz.is_some() && self.overlapping(theta) {
            // A contact carried over from the last step.
            let (took, n) = self.hertz_phase(theta, omega, h, found.as_mut());
            impacts += n;
            h -= took;
            if let Some(f) = found.as_mut() {
                f.t += took;
            }
            if h <= 0.0 {
                return impacts;
            }
        }
        // Each pass handles one impact; the bound only guards against a stuck state.
        for _ in 0..64 * theta.len() + 16 {
            let (t1, w1) = self.step_all(theta, omega, h);
            let hit: Vec<usize> = (0..theta.len().saturating_sub(1))
                .filter(|&a| self.hits(theta, (&t1, &w1), a))
                .collect();
            if hit.is_empty() {
                *theta = t1;
                *omega = w1;
                return impacts;
            }
            // Bisect on the step fraction: lo is apart for every pair, hi has a hit.
            let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
            let mut first = hit[0];
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                let (tm, wm) = self.step_all(theta, omega, mid * h);
                match (0..theta.len() - 1).find(|&a| self.hits(theta, (&tm, &wm), a)) {
                    Some(a) => {
                        hi = mid;
                        first = a;
                    }
                    None => lo = mid,
                }
            }
            let (mut tc, mut wc) = self.step_all(theta, omega, hi * h);
            if let Some(f) = found.as_mut() {
                f.t += hi * h;
            }
            if self.params.hertz.is_some() {
                let (took, n) = self.hertz_phase(&mut tc, &mut wc, h * (1.0 - hi), found.as_mut());
                impacts += n;
                *theta = tc;
                *omega = wc;
                h = h * (1.0 - hi) - took;
                if let Some(f) = found.as_mut() {
                    f.t += took;
                }
                if h <= 0.0 {
                    return impacts;
                }
                continue;
            }
            let before = (tc.clone(), wc.clone());
            let out = contact::resolve(&self.params, &self.resolution, &mut tc, &mut wc, first);
            impacts += out.impacts;
            if let Some(f) = found.as_mut() {
                let motion = (before.0.as_slice(), before.1.as_slice());
                f.log
                    .push_resolved(&self.params, f.t, motion, &wc, &out.hits);
            }
            *theta = tc;
            *omega = wc;
            h *= 1.0 - hi;
            if h <= 0.0 {
                return impacts;
            }
        }
        impacts
    }

    /// State at `t` (s, >= every earlier call's `t`).
    pub fn state_at(&mut self, t: f64) -> (Vec<f64>, Vec<f64>) {
        self.advance_until(t, None);
        self.state_now(t)
    }

    /// Takes the grid steps up to `t`, or as many as fit before `deadline`;
    /// returns the time the state can now be had at without more steps.
    pub fn advance_until(&mut self, t: f64, deadline: Option<std::time::Instant>) -> f64 {
        // Tolerate t a hair below a grid point (n*every vs m*dt rounding).
        let target = ((t / self.dt) * (1.0 + 1e-12)).floor() as u64;
        while self.steps < target {
            if deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                return self.steps as f64 * self.dt;
            }
            let (mut th, mut om) = (
                std::mem::take(&mut self.theta),
                std::mem::take(&mut self.omega),
            );
            let (mut log, mut watch) = (
                std::mem::take(&mut self.impacts),
                std::mem::take(&mut self.watch),
            );
            let found = Found {
                log: &mut log,
                watch: &mut watch,
                t: self.steps as f64 * self.dt,
            };
            self.collisions += self.advance(&mut th, &mut om, self.dt, Some(found));
            (self.impacts, self.watch) = (log, watch);
            self.theta = th;
            self.omega = om;
            self.steps += 1;
        }
        t
    }

    /// The state at `t`, at most one step past the last grid step taken.
    fn state_now(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        let rest = t - self.steps as f64 * self.dt;
        let (mut th, mut om) = (self.theta.clone(), self.omega.clone());
        if rest > 0.0 {
            self.advance(&mut th, &mut om, rest, None);
        }
        (th, om)
    }

    /// The impacts found on the committed grid, for the ones who read them.
    pub fn impacts(&mut self) -> &mut ImpactLog {
        &mut self.impacts
    }

    /// The impacts found so far, to read.
    #[must_use]
    pub fn log(&self) -> &ImpactLog {
        &self.impacts
    }

    /// Impacts so far on the committed grid.
    #[must_use]
    pub fn collisions(&self) -> u64 {
        self.collisions
    }
}

/// One velocity-Verlet step (kick, drift, kick).
fn verlet(theta: f64, omega: f64, h: f64, acc: &impl Fn(f64) -> f64) -> (f64, f64) {
    let half = omega + 0.5 * h * acc(theta);
    let t = theta + h * half;
    (t, half + 0.5 * h * acc(t))
}
