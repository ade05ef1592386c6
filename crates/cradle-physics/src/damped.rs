//! The damped engine: with air drag the flights have no closed form, so the whole
//! row is integrated as one system (`row`: gravity, viscoelastic Hertz contacts,
//! drag) with adaptive Dormand-Prince 5(4) steps, to the error bound of the Hertz
//! contact phases.
//!
//! Contacts need no events: they are part of the forces, and the step control
//! shortens the steps where a contact starts. The steps are taken from the start
//! and never depend on when the state is asked for; a state between two step
//! points is one shortened step from the one before. So the state at a time is
//! the same at any frame rate.

use super::dopri;
use super::hertz::TOL;
use super::impacts::{ImpactLog, Watch};
use super::params::CradleParams;
use super::row::Row;

/// The damped engine's state: the last step point and the step to try next.
#[derive(Debug, Clone)]
pub struct DampedEngine {
    params: CradleParams,
    k: f64,
    /// Time of the last step point (s).
    t: f64,
    /// State at `t`, with the energy lost so far.
    y: Vec<f64>,
    /// The step to try next (s).
    h: f64,
    /// Error scale of each component.
    scale: Vec<f64>,
    /// Pairs overlapping at `t`.
    touching: Vec<bool>,
    contacts: u64,
    /// No step could be taken (round-off ate the step): the state stays put.
    stuck: bool,
    /// The contacts found and not yet taken; those still open.
    impacts: ImpactLog,
    watch: Watch,
}

impl DampedEngine {
    /// A cradle starting at `t = 0` in state `(theta, omega)`; `params.hertz` is
    /// the contact stiffness (0 if missing: the balls then pass through).
    #[must_use]
    pub fn new(params: CradleParams, theta: &[f64], omega: &[f64]) -> Self {
        let n = theta.len();
        let k = params.hertz.unwrap_or(0.0);
        let row = Row::new(&params, k, n);
        let y = row.state(theta, omega);
        // Speeds to TOL of the fastest a ball can go: all the energy in one ball at
        // the bottom (or the rest floor of a contact phase when there is none).
        let e0 = params.energy(theta, omega);
        let top = (2.0 * e0 / params.inertia()).sqrt();
        let floor = 1e-6 * params.w0() * params.radius / params.length;
        let mut scale = vec![TOL * params.radius / params.length; row.len()];
        scale[n..2 * n].fill(TOL * top.max(floor));
        // The energy lost to TOL of the energy in play (see `hertz`).
        let in_play = 0.5 * params.inertia() * top.max(floor).powi(2);
        row.scale_extra(&mut scale, TOL * in_play);
        let touching = (0..n.saturating_sub(1))
            .map(|a| row.overlap(theta, a) > 0.0)
            .collect();
        Self {
            h: 1e-3 / params.w0(),
            params,
            k,
            t: 0.0,
            y,
            scale,
            touching,
            contacts: 0,
            stuck: false,
            impacts: ImpactLog::default(),
            watch: Watch::new(n.saturating_sub(1)),
        }
    }

    /// The row's system, with the impulses when impacts are kept.
    fn row(&self) -> Row<'_> {
        let n = self.touching.len() + 1;
        Row::new(&self.params, self.k, n).with_impulses(self.impacts.recording())
    }

    /// Keeps the contacts found from now on: the state carries each pair's
    /// impulse from here (the steps are the same).
    pub fn record_impacts(&mut self) {
        if self.impacts.recording() {
            return;
        }
        self.impacts.record();
        let len = self.row().len();
        self.y.resize(len, 0.0);
        self.scale.resize(len, f64::INFINITY);
    }

    /// The longest step (s): a fraction of a swing, well inside the method's
    /// stability region however smooth the motion.
    fn max_step(&self) -> f64 {
        0.5 / self.params.w0()
    }

    /// The step from the last step point the controller accepts: its length, the
    /// state after it, and the step to try next. `None` when the step shrinks
    /// below round-off.
    fn accepted(&self, row: &Row, k_buf: &mut [Vec<f64>; 7]) -> Option<(f64, Vec<f64>, f64)> {
        let deriv = |y: &[f64], out: &mut [f64]| row.deriv(y, out);
        let mut h = self.h;
        loop {
            let (y1, err) = dopri::step(&deriv, &self.y, h, &self.scale, k_buf);
            if err > 1.0 || !err.is_finite() {
                h *= (0.9 * err.powf(-0.2)).clamp(0.1, 0.9);
                if !h.is_finite() || self.t + h == self.t {
                    return None;
                }
                continue;
            }
            let next = (h * (0.9 * err.max(1e-10).powf(-0.2)).min(5.0)).min(self.max_step());
            return Some(self.to_onset(row, k_buf, (h, y1, next)));
        }
    }

    /// A step in which a pair starts to overlap is cut where it starts (to 1e-9
    /// of the step, by bisection), and the next step is a contact phase's first:
    /// stepping across the onset of the force's kink would leave its error to the
    /// error estimate, which does not see it well.
    fn to_onset(
        &self,
        row: &Row,
        k_buf: &mut [Vec<f64>; 7],
        (h, y1, next): (f64, Vec<f64>, f64),
    ) -> (f64, Vec<f64>, f64) {
        let n = self.touching.len() + 1;
        let starts = |y: &[f64]| {
            self.touching
                .iter()
                .enumerate()
                .any(|(a, &was)| !was && row.overlap(&y[..n], a) > 0.0)
        };
        if !starts(&y1) {
            return (h, y1, next);
        }
        let deriv = |y: &[f64], out: &mut [f64]| row.deriv(y, out);
        let (mut lo, mut hi, mut at) = (0.0, h, y1);
        while hi - lo > 1e-9 * h {
            let mid = 0.5 * (lo + hi);
            let y = dopri::step(&deriv, &self.y, mid, &self.scale, k_buf).0;
            if starts(&y) {
                (hi, at) = (mid, y);
            } else {
                lo = mid;
            }
        }
        // The phases' first step: a hundredth of the time to close a thousandth
        // of a radius at the fastest speed.
        let w = self.scale[n] / TOL;
        let first = (1e-5 * self.params.radius / (self.params.length * w)).min(next);
        (hi, at, first)
    }

    /// Takes every step that ends at or before `t`; returns the state at `t` and
    /// the energy lost by then (contacts, drag).
    pub fn state_at(&mut self, t: f64) -> (Vec<f64>, Vec<f64>, [f64; 2]) {
        self.advance_until(t, None);
        self.state_now(t)
    }

    /// Takes every step that ends at or before `t`, or as many as fit before
    /// `deadline`; returns the time the state can now be had at without more
    /// steps (the steps are the same either way).
    pub fn advance_until(&mut self, t: f64, deadline: Option<std::time::Instant>) -> f64 {
        let n = self.touching.len() + 1;
        let params = self.params;
        let row = Row::new(&params, self.k, n).with_impulses(self.impacts.recording());
        let mut k_buf: [Vec<f64>; 7] = std::array::from_fn(|_| vec![0.0; row.len()]);
        while !self.stuck && self.t < t {
            if deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                return self.t;
            }
            let Some((h, y1, next)) = self.accepted(&row, &mut k_buf) else {
                tracing::warn!(
                    "damped step below the resolution of t = {} s; state held",
                    self.t
                );
                self.stuck = true;
                break;
            };
            if self.t + h > t {
                break;
            }
            self.t += h;
            self.y = y1;
            self.h = next;
            for (a, was) in self.touching.iter_mut().enumerate() {
                let now = row.overlap(&self.y[..n], a) > 0.0;
                self.contacts += u64::from(now && !*was);
                *was = now;
            }
            self.watch.step(&row, self.t, &self.y, &mut self.impacts);
        }
        t
    }

    /// The contacts found so far, for the ones who read them.
    pub fn impacts(&mut self) -> &mut ImpactLog {
        &mut self.impacts
    }

    /// The impacts found so far, to read.
    #[must_use]
    pub fn log(&self) -> &ImpactLog {
        &self.impacts
    }

    /// The state at `t`: one shortened step from the last step point.
    fn state_now(&self, t: f64) -> (Vec<f64>, Vec<f64>, [f64; 2]) {
        let n = self.touching.len() + 1;
        let row = self.row();
        let mut k_buf: [Vec<f64>; 7] = std::array::from_fn(|_| vec![0.0; row.len()]);
        let y = if self.stuck || t <= self.t {
            self.y.clone()
        } else {
            let deriv = |y: &[f64], out: &mut [f64]| row.deriv(y, out);
            dopri::step(&deriv, &self.y, t - self.t, &self.scale, &mut k_buf).0
        };
        (y[..n].to_vec(), y[n..2 * n].to_vec(), row.lost(&y))
    }

    /// Contacts so far (onsets of overlap at step points).
    #[must_use]
    pub fn collisions(&self) -> u64 {
        self.contacts
    }
}
