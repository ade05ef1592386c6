//! The exact engine: every ball flies in closed form ([`Flight`]) between impacts;
//! impacts are the roots of the neighbours' gap functions along those flights.
//!
//! How it works:
//! 1. After each event, the time after it is cut into windows of a fixed length
//!    (a 32nd of the shortest period in play), anchored at the event. Windows are
//!    scanned only as far as a caller asks for, but always the same windows, so the
//!    events found do not depend on when or how often the state is sampled.
//! 2. In a window, a pair whose gap goes from positive to non-positive, or whose
//!    gap has a minimum below zero, has an impact; the earliest one is refined to
//!    ~1e-14 s.
//! 3. The impact and the contacts it sets off are resolved ([`contact::resolve`]);
//!    the balls it changed get new flights. With Hertz contact the impact starts a
//!    contact phase instead ([`hertz::run_phase`]), integrated to the moment the
//!    balls come apart; every ball then gets a new flight.
//!
//! Times inside the engine are kept from an epoch that moves to each event
//! (`epoch`, absolute; every other time relative to it, so near zero): f64
//! resolves them to ~1e-16 s however long the run, and impacts are located to
//! 1e-14 s at t = 1e7 s as at t = 0. Only the epoch, moved by exactly
//! representable steps, carries the absolute time.

use super::contact::{self, Resolution};
use super::flight::Flight;
use super::hertz::{self, PhaseEnd};
use super::impacts::{ImpactLog, Watch};
use super::params::CradleParams;
use super::roots::{falling_root, rising_root};

/// Windows per shortest period: a gap function has at most two extrema per period
/// of either ball, so 32 windows never hide a crossing between two samples.
const WINDOWS_PER_PERIOD: f64 = 32.0;

/// Impact times are located to this (s), or to 4 ulps of the time (from the
/// epoch) where that is coarser.
const TIME_TOL: f64 = 1e-14;

/// Sustained contact (balls pressed together by gravity, as when one rests on its
/// neighbour at large angles) is stepped with impulses this fraction of a
/// small-angle period apart: the overlap stays below ~g (1e-3 T)^2, a few um.
const CONTACT_STEP: f64 = 1e-3;

/// The exact event-driven solver.
#[derive(Debug, Clone)]
pub struct ExactEngine {
    params: CradleParams,
    resolution: Resolution,
    w0: f64,
    flights: Vec<Flight>,
    /// The absolute time (s) every other time of the engine is counted from:
    /// moved to each event, so that those stay small and precise.
    epoch: f64,
    /// Time of the last event (or the start), from the epoch.
    t_event: f64,
    /// Window length after the last event.
    window: f64,
    /// Windows after the last event already scanned without finding an impact.
    scanned: u64,
    /// Pairs `(a, a+1)` that can collide before the next event.
    active: Vec<usize>,
    /// Per pair: the time of its last impulse if that was a resting contact.
    rest_since: Vec<Option<f64>>,
    /// Impulse step of sustained contact (s).
    contact_step: f64,
    collisions: u64,
    events: u64,
    /// The state at t = 0, returned as given (the closed form reproduces it to
    /// round-off only).
    start: (Vec<f64>, Vec<f64>),
    /// The latest Hertz contact phase (or segment of one), boxed: most engines
    /// never have one.
    phase: Option<Box<Phase>>,
    /// Energy lost in viscoelastic contacts by the end of the latest phase (J);
    /// the second entry (drag) stays 0 here.
    lost: [f64; 2],
    /// The impacts found and not yet taken; the Hertz contacts still open.
    impacts: ImpactLog,
    watch: Watch,
}

/// A Hertz contact phase: where it started and how it ended.
#[derive(Debug, Clone)]
struct Phase {
    t0: f64,
    /// The energy lost before it.
    lost_before: [f64; 2],
    theta: Vec<f64>,
    omega: Vec<f64>,
    end: PhaseEnd,
}

impl ExactEngine {
    /// A cradle starting at `t = 0` in state `(theta, omega)`.
    #[must_use]
    pub fn new(params: CradleParams, resolution: Resolution, theta: &[f64], omega: &[f64]) -> Self {
        let w0 = params.w0();
        let mut engine = Self {
            params,
            resolution,
            w0,
            flights: theta
                .iter()
                .zip(omega)
                .map(|(&t, &w)| Flight::new(0.0, t, w, w0))
                .collect(),
            epoch: 0.0,
            t_event: 0.0,
            window: 0.0,
            scanned: 0,
            active: Vec::new(),
            rest_since: vec![None; theta.len().saturating_sub(1)],
            contact_step: CONTACT_STEP * std::f64::consts::TAU / w0,
            collisions: 0,
            events: 0,
            start: (theta.to_vec(), omega.to_vec()),
            phase: None,
            lost: [0.0; 2],
            impacts: ImpactLog::default(),
            watch: Watch::new(theta.len().saturating_sub(1)),
        };
        // Balls that start touching and approaching (none in a lifted start) are
        // resolved before anything flies.
        let (mut th, mut om) = engine.state_now(0.0);
        if params.hertz.is_some() {
            let starts = (0..th.len().saturating_sub(1)).any(|a| {
                contact::gap_fn(&params, th[a], th[a + 1]) <= 0.0
                    && contact::closing_speed(&params, (th[a], om[a]), (th[a + 1], om[a + 1])) < 0.0
            });
            if starts {
                engine.run_segment(0.0, th, om);
            } else {
                engine.refly(&th, &om, &vec![false; om.len()]);
            }
            return engine;
        }
        let mut changed = vec![false; th.len()];
        for a in 0..th.len().saturating_sub(1) {
            let touching = contact::gap_fn(&params, th[a], th[a + 1]) <= 0.0;
            if touching
                && contact::closing_speed(&params, (th[a], om[a]), (th[a + 1], om[a + 1])) < 0.0
            {
                let out = contact::resolve(&params, &resolution, &mut th, &mut om, a);
                engine.collisions += out.impacts;
                changed
                    .iter_mut()
                    .zip(&out.changed)
                    .for_each(|(c, o)| *c |= o);
            }
        }
        engine.refly(&th, &om, &changed);
        engine
    }

    /// Angles and angular velocities of every ball at `t`, from the current flights.
    fn state_now(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        self.flights.iter().map(|f| f.state_at(t)).unzip()
    }

    /// New flights for the changed balls from time `t_event`, then the pairs and the
    /// window for the next scan.
    fn refly(&mut self, theta: &[f64], omega: &[f64], changed: &[bool]) {
        for (i, _) in changed.iter().enumerate().filter(|(_, c)| **c) {
            self.flights[i] = Flight::new(self.t_event, theta[i], omega[i], self.w0);
        }
        self.active = (0..self.flights.len().saturating_sub(1))
            .filter(|&a| {
                let (fa, fb) = (&self.flights[a], &self.flights[a + 1]);
                // Two balls at rest, or two moving alike (equal state, so equal
                // flight), keep their gap for ever.
                !(fa.is_rest() && fb.is_rest()) && fa != fb
            })
            .collect();
        let shortest = self
            .active
            .iter()
            .flat_map(|&a| [a, a + 1])
            .map(|i| self.flights[i].period())
            .fold(f64::INFINITY, f64::min);
        self.window = shortest / WINDOWS_PER_PERIOD;
        self.scanned = 0;
    }

    fn pair_state(&self, a: usize, t: f64) -> ((f64, f64), (f64, f64)) {
        (self.flights[a].state_at(t), self.flights[a + 1].state_at(t))
    }

    fn gap_at(&self, a: usize, t: f64) -> f64 {
        let (sa, sb) = self.pair_state(a, t);
        contact::gap_fn(&self.params, sa.0, sb.0)
    }

    fn gap_rate_at(&self, a: usize, t: f64) -> f64 {
        let (sa, sb) = self.pair_state(a, t);
        contact::gap_rate(&self.params, sa, sb)
    }

    /// Gap function and its rate from one evaluation of the two flights.
    fn gap_and_rate(&self, a: usize, t: f64) -> (f64, f64) {
        let (sa, sb) = self.pair_state(a, t);
        (
            contact::gap_fn(&self.params, sa.0, sb.0),
            contact::gap_rate(&self.params, sa, sb),
        )
    }

    /// True when pair `a` overlaps (or touches) and approaches at `t`.
    fn pressing(&self, a: usize, t: f64) -> bool {
        let (sa, sb) = self.pair_state(a, t);
        contact::gap_fn(&self.params, sa.0, sb.0) <= 0.0
            && contact::closing_speed(&self.params, sa, sb) < 0.0
    }

    /// The earliest impact of pair `a` inside `[t0, t1]`, if any.
    fn impact_in(&self, a: usize, t0: f64, t1: f64) -> Option<f64> {
        let step = self.contact_step;
        // After a resting contact the pair is in sustained contact: its next
        // impulse comes no sooner than one contact step later.
        let not_before = self.rest_since[a].map_or(t0, |tr| t0.max(tr + step));
        if not_before >= t1 {
            return None;
        }
        let mut t0 = not_before;
        if self.rest_since[a].is_some() || self.gap_at(a, t0) <= 0.0 {
            // Touching or overlapping: step on the grid anchored at the last event
            // until the pair presses (an impulse) or comes apart (a free flight).
            let mut j = ((t0 - self.t_event) / step).ceil().max(0.0);
            let mut last = f64::NEG_INFINITY;
            loop {
                let s = self.t_event + j * step;
                // A step below f64's resolution of time would never reach t1:
                // treat the pair as apart from here (the config's ranges keep
                // steps far above it).
                if s > t1 || s <= last {
                    return (s <= last).then(|| self.free_impact_in(a, s, t1)).flatten();
                }
                last = s;
                if s >= t0 {
                    if self.pressing(a, s) {
                        return Some(s);
                    }
                    if self.gap_at(a, s) > 0.0 {
                        t0 = s;
                        break;
                    }
                }
                j += 1.0;
            }
        }
        self.free_impact_in(a, t0, t1)
    }

    /// The earliest impact of pair `a` inside `[t0, t1]` given it is apart at `t0`.
    fn free_impact_in(&self, a: usize, t0: f64, t1: f64) -> Option<f64> {
        let tol = TIME_TOL.max(4.0 * f64::EPSILON * t1.abs());
        let ((h0, d0), (h1, d1)) = (self.gap_and_rate(a, t0), self.gap_and_rate(a, t1));
        if h0 <= 0.0 {
            return None;
        }
        if h1 <= 0.0 {
            return Some(falling_root(|t| self.gap_at(a, t), t0, t1, tol));
        }
        // Both ends apart: a grazing dip below zero shows as a minimum inside.
        if d0 < 0.0 && d1 > 0.0 {
            let tmin = rising_root(|t| self.gap_rate_at(a, t), t0, t1, tol);
            if self.gap_at(a, tmin) <= 0.0 {
                return Some(falling_root(|t| self.gap_at(a, t), t0, tmin, tol));
            }
        }
        None
    }

    /// Runs one segment of a Hertz contact phase from `(theta, omega)` at `t0`; if the
    /// balls came apart, every ball flies on from its end.
    fn run_segment(&mut self, t0: f64, theta: Vec<f64>, omega: Vec<f64>) {
        let k = self.params.hertz.unwrap_or(0.0);
        let report = hertz::Report {
            watch: &mut self.watch,
            log: &mut self.impacts,
            epoch: self.epoch,
        };
        let end = hertz::run_reported(
            &self.params,
            k,
            (t0, &theta, &omega),
            f64::INFINITY,
            Some(report),
        );
        self.collisions += end.contacts;
        let lost_before = self.lost;
        self.lost = [lost_before[0] + end.lost[0], lost_before[1] + end.lost[1]];
        let separated = end.separated;
        if separated {
            self.t_event = end.t;
            let all = vec![true; end.theta.len()];
            self.refly(&end.theta, &end.omega, &all);
        }
        self.phase = Some(Box::new(Phase {
            t0,
            lost_before,
            theta,
            omega,
            end,
        }));
        if separated {
            self.rebase();
        }
    }

    /// Handles every event up to time `t`.
    pub fn advance_to(&mut self, t: f64) {
        self.advance_until(t, None);
    }

    /// Handles every event up to time `t`, or as many as fit before `deadline`;
    /// returns the time the state can now be had at without handling more
    /// (the events are the same either way).
    pub fn advance_until(&mut self, at: f64, deadline: Option<std::time::Instant>) -> f64 {
        loop {
            // The time asked for, from the epoch (which events move).
            let t = at - self.epoch;
            if deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                return (self.epoch + self.known_until()).min(at);
            }
            if let Some(ph) = self.phase.as_ref().filter(|ph| !ph.end.separated) {
                // A contact still going on: its next segment, when asked for.
                if ph.end.t >= t {
                    return at;
                }
                let (t0, th, om) = (ph.end.t, ph.end.theta.clone(), ph.end.omega.clone());
                self.run_segment(t0, th, om);
                continue;
            }
            if self.active.is_empty() {
                return at;
            }
            let w0 = self.t_event + self.scanned as f64 * self.window;
            if w0 >= t {
                return at;
            }
            let w1 = self.t_event + (self.scanned + 1) as f64 * self.window;
            let hit = self
                .active
                .iter()
                .filter_map(|&a| self.impact_in(a, w0, w1).map(|te| (te, a)))
                .min_by(|x, y| x.0.total_cmp(&y.0));
            match hit {
                Some((te, a)) if te <= t => self.apply(te, a),
                // An impact after t stays unfound until asked for: rescanning this
                // window later finds the same one.
                Some(_) => return at,
                None => self.scanned += 1,
            }
        }
    }

    /// Moves the epoch to the last event: every time of the engine shifts by
    /// the same, exactly representable step (`(epoch + t_event) - epoch`, exact by
    /// Sterbenz's lemma), so nothing moves but the numbers that count it.
    fn rebase(&mut self) {
        let moved = self.epoch + self.t_event;
        let by = moved - self.epoch;
        if by == 0.0 {
            return;
        }
        self.epoch = moved;
        self.t_event -= by;
        for f in &mut self.flights {
            f.shift(by);
        }
        for since in self.rest_since.iter_mut().flatten() {
            *since -= by;
        }
        if let Some(ph) = self.phase.as_mut() {
            ph.t0 -= by;
            ph.end.t -= by;
        }
    }

    /// The time up to which every event is handled: the end of a contact
    /// segment still going on, else the end of the windows scanned.
    fn known_until(&self) -> f64 {
        match self.phase.as_ref().filter(|ph| !ph.end.separated) {
            Some(ph) => ph.end.t,
            None if self.active.is_empty() => f64::INFINITY,
            None => self.t_event + self.scanned as f64 * self.window,
        }
    }

    fn apply(&mut self, te: f64, a: usize) {
        let (mut th, mut om) = self.state_now(te);
        tracing::trace!(te, a, "impact");
        if self.params.hertz.is_some() {
            self.events += 1;
            self.run_segment(te, th, om);
            return;
        }
        let before = (th.clone(), om.clone());
        let out = contact::resolve(&self.params, &self.resolution, &mut th, &mut om, a);
        let motion = (before.0.as_slice(), before.1.as_slice());
        self.impacts
            .push_resolved(&self.params, self.epoch + te, motion, &om, &out.hits);
        self.collisions += out.impacts;
        self.events += 1;
        self.t_event = te;
        for (a, since) in self.rest_since.iter_mut().enumerate() {
            *since = match out.resting[a] {
                Some(true) => Some(te),
                // A real impact, or a ball of the pair kicked by another pair's
                // impact: no longer a slow contact, so no step to wait for.
                Some(false) => None,
                None if out.kicked[a] || out.kicked[a + 1] => None,
                None => *since,
            };
        }
        self.refly(&th, &om, &out.changed);
        self.rebase();
    }

    /// State at `t` (>= every earlier call's `t`): angles (rad), angular velocities
    /// (rad/s), and the energy lost by then in contacts and to drag (J).
    pub fn state_at(&mut self, at: f64) -> (Vec<f64>, Vec<f64>, [f64; 2]) {
        if at == 0.0 && self.events == 0 && self.collisions == 0 {
            return (self.start.0.clone(), self.start.1.clone(), self.lost);
        }
        self.advance_to(at);
        let t = at - self.epoch;
        if let Some(ph) = self.phase.as_ref().filter(|ph| t >= ph.t0 && t < ph.end.t) {
            // Inside a contact: the phase again from its start, cut at t.
            let k = self.params.hertz.unwrap_or(0.0);
            let cut = hertz::run_phase(&self.params, k, ph.t0, &ph.theta, &ph.omega, t);
            let b = ph.lost_before;
            return (
                cut.theta,
                cut.omega,
                [b[0] + cut.lost[0], b[1] + cut.lost[1]],
            );
        }
        if let Some(ph) = self.phase.as_ref().filter(|ph| !ph.end.separated) {
            return (ph.end.theta.clone(), ph.end.omega.clone(), self.lost);
        }
        let (theta, omega) = self.state_now(t);
        (theta, omega, self.lost)
    }

    /// The impacts found so far, for the ones who read them.
    pub fn impacts(&mut self) -> &mut ImpactLog {
        &mut self.impacts
    }

    /// The impacts found so far, to read.
    #[must_use]
    pub fn log(&self) -> &ImpactLog {
        &self.impacts
    }

    /// Impacts so far (pairwise impulses; resting contacts excluded).
    #[must_use]
    pub fn collisions(&self) -> u64 {
        self.collisions
    }

    /// Collision events so far (each may involve several pairwise impacts).
    #[must_use]
    pub fn events(&self) -> u64 {
        self.events
    }
}

#[cfg(test)]
mod tests {
    use super::ExactEngine;
    use crate::contact::Resolution;
    use crate::params::{CradleParams, lifted_start};

    /// The default cradle (5 steel balls, one lifted to 30 degrees) whose
    /// clock starts at `epoch` (s).
    fn default_at(epoch: f64) -> ExactEngine {
        let p = CradleParams {
            balls: 5,
            radius: 0.02,
            mass: 0.263,
            length: 0.16,
            gap: 0.0,
            gravity: 9.81,
            restitution: 1.0,
            hertz: None,
            dissipation: 0.0,
            drag: 0.0,
        };
        let (theta, omega) = lifted_start(5, 1, 30f64.to_radians());
        let speed = (2.0 * p.energy(&theta, &omega) / p.inertia()).sqrt() * p.length;
        let r = Resolution {
            restitution: 1.0,
            rest_speed: 1e-6 * speed,
            touch: 1e-9 * p.radius,
        };
        let mut e = ExactEngine::new(p, r, &theta, &omega);
        e.epoch = epoch;
        e
    }

    #[test]
    fn a_cradle_late_in_a_run_does_what_it_did_at_the_start() {
        // Counted from an epoch at each event, a cradle at t = 1e7 s (where an
        // ulp of t is 1.9e-9 s) finds its impacts as one at t = 0 does: the
        // same impacts by each sample over 60 s. With absolute times the
        // impacts were located only to 4 ulps of t, the touching balls were no
        // longer met at equal angles, and from t = 4.6e5 s the default cradle
        // made 2.5 times the impacts a second.
        let (mut early, mut late) = (default_at(0.0), default_at(1e7));
        for n in 1..=600 {
            let x = f64::from(n) * 0.1;
            let (a, wa, _) = early.state_at(x);
            let (b, wb, _) = late.state_at(1e7 + x);
            assert_eq!(early.collisions(), late.collisions(), "by {x} s");
            // The late query time itself is 1e7 + x rounded to 1.9e-9 s: its
            // angles differ by the balls' speed (< 2 rad/s) times that, 4e-9,
            // its speeds by their rate (< g / L = 61 rad/s^2) times it, 1.2e-7.
            for (p, q) in a.iter().zip(&b).chain(wa.iter().zip(&wb)) {
                assert!((p - q).abs() < 1e-6, "by {x} s: {a:?} {b:?}");
            }
        }
        assert!(early.collisions() > 500, "{}", early.collisions());
    }
}
