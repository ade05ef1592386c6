//! The cradle as the rest of the program sees it: parameters, a start, and the
//! state at any time, from whichever engine the config picks.

use super::contact::Resolution;
use super::damped::DampedEngine;
use super::exact::ExactEngine;
use super::impacts::{Course, Impact, ImpactLog};
use super::params::{CradleParams, Integrator, REST_FRACTION, lifted_start};
use super::stepped::SteppedEngine;

/// The state of every ball at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Time (s).
    pub t: f64,
    /// Angle of each ball from the vertical (rad), positive towards +x.
    pub theta: Vec<f64>,
    /// Angular velocity of each ball (rad/s).
    pub omega: Vec<f64>,
    /// Impacts so far (Hertz contact: onsets of contact).
    pub collisions: u64,
    /// Energy lost so far (J) in viscoelastic contacts and to air drag: zeros for
    /// a cradle without dissipation.
    pub lost: [f64; 2],
}

#[derive(Debug, Clone)]
enum Engine {
    Exact(ExactEngine),
    Damped(DampedEngine),
    Stepped(SteppedEngine),
}

/// A running cradle. Sample it with [`Cradle::snapshot`] at non-decreasing times.
#[derive(Debug, Clone)]
pub struct Cradle {
    params: CradleParams,
    engine: Engine,
    energy0: f64,
    /// The time of the last snapshot: a later one is never earlier.
    last: f64,
}

impl Cradle {
    /// A cradle whose `lift` leftmost balls are released from `-angle` (rad) at t = 0.
    /// `dt` (s) is the step of fixed-step integrators; `Exact` ignores it.
    #[must_use]
    pub fn new(
        params: CradleParams,
        integrator: Integrator,
        dt: f64,
        lift: usize,
        angle: f64,
    ) -> Self {
        let (theta, omega) = lifted_start(params.balls, lift, angle);
        Self::from_state(params, integrator, dt, &theta, &omega)
    }

    /// A cradle starting from any state at t = 0.
    #[must_use]
    pub fn from_state(
        params: CradleParams,
        integrator: Integrator,
        dt: f64,
        theta: &[f64],
        omega: &[f64],
    ) -> Self {
        let energy0 = params.energy(theta, omega);
        // The fastest a ball can go is when all the energy is in one ball at the
        // bottom; the rest speed is a tiny fraction of that.
        let top_speed = (2.0 * energy0 / params.inertia()).sqrt() * params.length;
        let resolution = Resolution {
            restitution: params.restitution,
            rest_speed: (REST_FRACTION * top_speed).max(f64::MIN_POSITIVE),
            touch: 1e-9 * params.radius,
        };
        let engine = match integrator {
            Integrator::Exact if params.dissipative() && params.drag > 0.0 => {
                Engine::Damped(DampedEngine::new(params, theta, omega))
            }
            Integrator::Exact => Engine::Exact(ExactEngine::new(params, resolution, theta, omega)),
            method => Engine::Stepped(SteppedEngine::new(
                params, resolution, method, dt, theta, omega,
            )),
        };
        Self {
            params,
            engine,
            energy0,
            last: 0.0,
        }
    }

    /// The state at time `t` (s). Times must not decrease from call to call.
    pub fn snapshot(&mut self, t: f64) -> Snapshot {
        self.last = self.last.max(t);
        let (theta, omega, lost, collisions) = match &mut self.engine {
            Engine::Exact(e) => {
                let (th, om, lost) = e.state_at(t);
                (th, om, lost, e.collisions())
            }
            Engine::Damped(e) => {
                let (th, om, lost) = e.state_at(t);
                (th, om, lost, e.collisions())
            }
            Engine::Stepped(e) => {
                let (th, om) = e.state_at(t);
                (th, om, [0.0; 2], e.collisions())
            }
        };
        Snapshot {
            t,
            theta,
            omega,
            collisions,
            lost,
        }
    }

    /// The state at `t` (s), or, if getting there takes past `deadline`, at the
    /// latest time before `t` reached by then (its `t` says which): a frame
    /// loop can show a slow cradle in slow motion and stay responsive. The
    /// engine's steps and events are those of [`Self::snapshot`], so every state
    /// is the one a call without a deadline gives at that time.
    pub fn snapshot_by(&mut self, t: f64, deadline: std::time::Instant) -> Snapshot {
        let reached = match &mut self.engine {
            Engine::Exact(e) => e.advance_until(t, Some(deadline)),
            Engine::Damped(e) => e.advance_until(t, Some(deadline)),
            Engine::Stepped(e) => e.advance_until(t, Some(deadline)),
        };
        self.snapshot(reached.max(self.last).min(t))
    }

    /// Keeps the impacts found from now on, for [`Self::take_impacts`]: the sound
    /// reads them. Off by default, so that a run that never takes them keeps none.
    pub fn record_impacts(&mut self) {
        match &mut self.engine {
            Engine::Damped(e) => e.record_impacts(),
            _ => self.log().record(),
        }
    }

    /// With impacts kept, keeps their courses too (for [`Self::take_courses`]),
    /// or stops: a Hertz contact's force curve, an ideal impact's velocities.
    pub fn record_courses(&mut self, on: bool) {
        self.log().record_courses(on);
    }

    /// True while impacts' courses are kept.
    #[must_use]
    pub fn recording_courses(&self) -> bool {
        match &self.engine {
            Engine::Exact(e) => e.log().recording_courses(),
            Engine::Damped(e) => e.log().recording_courses(),
            Engine::Stepped(e) => e.log().recording_courses(),
        }
    }

    /// The courses of the impacts up to time `t` (s), as [`Self::take_impacts`].
    pub fn take_courses(&mut self, t: f64) -> Vec<Course> {
        self.log().take_courses_until(t)
    }

    /// The impacts up to time `t` (s) found by the snapshots so far, earliest
    /// first, each handed out once. A Hertz contact is handed out once it has
    /// ended, so one still going on at `t` comes with a later call.
    pub fn take_impacts(&mut self, t: f64) -> Vec<Impact> {
        self.log().take_until(t)
    }

    fn log(&mut self) -> &mut ImpactLog {
        match &mut self.engine {
            Engine::Exact(e) => e.impacts(),
            Engine::Damped(e) => e.impacts(),
            Engine::Stepped(e) => e.impacts(),
        }
    }

    /// The physical parameters.
    #[must_use]
    pub fn params(&self) -> &CradleParams {
        &self.params
    }

    /// Energy at the start (J).
    #[must_use]
    pub fn initial_energy(&self) -> f64 {
        self.energy0
    }

    /// Energy of a snapshot (J).
    #[must_use]
    pub fn energy(&self, s: &Snapshot) -> f64 {
        self.params.energy(&s.theta, &s.omega)
    }

    /// Relative energy error of a snapshot against the start (0 when no energy):
    /// of the energy balance `E + lost - E0` when the cradle dissipates.
    #[must_use]
    pub fn energy_rel_error(&self, s: &Snapshot) -> f64 {
        let e = if self.params.dissipative() {
            self.energy(s) + s.lost[0] + s.lost[1]
        } else {
            self.energy(s)
        };
        if self.energy0 == 0.0 {
            return e.abs();
        }
        (e - self.energy0) / self.energy0
    }
}
