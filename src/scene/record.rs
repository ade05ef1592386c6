//! What the graphs read: the physics system's state, recorded each frame while
//! the graphs are open (a resource the physics fills; nothing while closed),
//! over the last 30 s of simulated time, the last impacts, and the course of
//! the last one (the physics keeps courses only while recording).

use super::components::{CradleState, FrameImpacts};
use crate::physics::{Course, CradleParams, Impact};
use bevy_ecs::prelude::*;
use std::collections::VecDeque;

/// How much simulated time the graphs show (s).
pub const SPAN: f64 = 30.0;

/// How many of the last impacts are kept.
pub const IMPACTS: usize = 20;

/// Hertz contacts closer in time than this fraction of the swing's period
/// are one strike: its pulse runs down a touching chain pair by pair, tens of
/// microseconds apart, and down a chain with gaps milliseconds apart (20 ms
/// for the default cradle), while strikes come half a period apart.
const SAME_STRIKE: f64 = 0.025;

/// At most this many contacts make one strike (a row of balls pressing
/// together for long would otherwise chain them without end).
const STRIKE_CONTACTS: usize = 64;

/// One recorded frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Simulated time (s).
    pub t: f64,
    /// Each ball's angle (rad) and angular velocity (rad/s).
    pub theta: Vec<f64>,
    pub omega: Vec<f64>,
    /// Each ball's energy (J): kinetic and potential.
    pub energy: Vec<f64>,
    /// Each ball's horizontal momentum (kg m/s).
    pub momentum: Vec<f64>,
    /// The whole cradle's energy (J; with Hertz contact the pairs' elastic
    /// energy too) and its relative error against the start (of the balance
    /// with the losses when the cradle loses energy).
    pub total: f64,
    pub error: f64,
    /// Energy lost so far in contacts and to drag (J).
    pub lost: [f64; 2],
}

impl Sample {
    /// The sample of `state`.
    #[must_use]
    pub fn of(state: &CradleState) -> Self {
        let p = state.cradle.params();
        let s = &state.snapshot;
        let per_ball = |f: fn(&CradleParams, f64, f64) -> f64| {
            s.theta
                .iter()
                .zip(&s.omega)
                .map(|(&t, &w)| f(p, t, w))
                .collect()
        };
        Self {
            t: s.t,
            theta: s.theta.clone(),
            omega: s.omega.clone(),
            energy: per_ball(CradleParams::ball_energy),
            momentum: per_ball(CradleParams::ball_momentum),
            total: state.cradle.energy(s),
            error: state.cradle.energy_rel_error(s),
            lost: s.lost,
        }
    }

    /// Total horizontal momentum (kg m/s).
    #[must_use]
    pub fn total_momentum(&self) -> f64 {
        self.momentum.iter().sum()
    }

    /// Ball `k`'s swing amplitude (rad): the angle its energy would carry it
    /// to, swinging freely, `2 asin(sqrt(E / (2 m g L)))` (at most pi).
    #[must_use]
    pub fn amplitude(&self, p: &CradleParams, k: usize) -> f64 {
        let top = 2.0 * p.mass * p.gravity * p.length;
        2.0 * (self.energy[k] / top).clamp(0.0, 1.0).sqrt().asin()
    }

    /// Every ball's swing amplitude (rad), as [`Self::amplitude`].
    #[must_use]
    pub fn amplitudes(&self, p: &CradleParams) -> Vec<f64> {
        (0..self.energy.len())
            .map(|k| self.amplitude(p, k))
            .collect()
    }
}

/// The recording the graphs read.
#[derive(Resource, Debug, Clone, Default)]
pub struct Recording {
    /// Record while true (the graphs are open).
    pub on: bool,
    /// Frames of the last [`SPAN`] seconds, oldest first.
    pub samples: VecDeque<Sample>,
    /// The last [`IMPACTS`] impacts, oldest first.
    pub impacts: VecDeque<Impact>,
    /// The last impact's course: for Hertz contact each pair's force curve
    /// (the contacts of one strike, earliest first), for an ideal impact the
    /// velocities before and after.
    pub strike: Vec<Course>,
    /// The cradle's parameters (for amplitudes and the CSV's header).
    pub params: Option<CradleParams>,
}

impl Recording {
    /// Forgets what was recorded (a new cradle).
    pub fn clear(&mut self) {
        self.samples.clear();
        self.impacts.clear();
        self.strike.clear();
        self.params = None;
    }

    /// Adds a course to the last impact, or starts the next one with it.
    fn add_course(&mut self, course: &Course) {
        let span = |c: &Course| match c {
            Course::Force { impact, curve } => {
                (impact.t, impact.t + curve.last().map_or(0.0, |p| p.0))
            }
            Course::Ideal { t, .. } => (*t, *t),
        };
        let (lo, hi) = span(course);
        let apart = SAME_STRIKE * self.params.map_or(0.0, |p| std::f64::consts::TAU / p.w0());
        let joins = matches!(course, Course::Force { .. })
            && self.strike.len() < STRIKE_CONTACTS
            && self
                .strike
                .iter()
                .all(|c| matches!(c, Course::Force { .. }))
            && self.strike.iter().any(|c| {
                let (l, h) = span(c);
                lo <= h + apart && hi >= l - apart
            });
        if !joins {
            self.strike.clear();
        }
        self.strike.push(course.clone());
        self.strike.sort_by(|a, b| a.start().total_cmp(&b.start()));
    }
}

/// Physics: while the graphs are open, records the frame's state (once per
/// simulated time: a paused frame adds nothing) and its impacts, and has the
/// physics keep the impacts' courses (only then).
pub fn record(
    mut state: ResMut<CradleState>,
    impacts: Res<FrameImpacts>,
    mut rec: ResMut<Recording>,
) {
    if state.cradle.recording_courses() != rec.on {
        // Not a change of the cradle's state: what moves stays put.
        state
            .bypass_change_detection()
            .cradle
            .record_courses(rec.on);
    }
    if !rec.on {
        return;
    }
    let p = *state.cradle.params();
    let t = state.snapshot.t;
    // A new cradle starts again at t = 0: what was recorded was another's.
    if rec.params != Some(p) || rec.samples.back().is_some_and(|s| s.t > t) {
        rec.clear();
        rec.params = Some(p);
    }
    if rec.samples.back().is_some_and(|s| s.t == t) {
        return;
    }
    rec.samples.push_back(Sample::of(&state));
    while rec.samples.front().is_some_and(|s| s.t < t - SPAN) {
        rec.samples.pop_front();
    }
    for i in &impacts.impacts {
        if rec.impacts.len() == IMPACTS {
            rec.impacts.pop_front();
        }
        rec.impacts.push_back(*i);
    }
    for c in &impacts.courses {
        rec.add_course(c);
    }
}

/// The recording as CSV: a header row, then one row per frame: time, total
/// energy and its error, the energy lost in contacts and to drag, total
/// momentum, then per ball its energy, momentum, angle, angular velocity and
/// amplitude.
#[must_use]
pub fn csv(rec: &Recording) -> String {
    use std::fmt::Write;
    let n = rec.samples.front().map_or(0, |s| s.theta.len());
    let mut out =
        String::from("t_s,energy_J,energy_rel_error,lost_contacts_J,lost_drag_J,momentum_kg_m_s");
    for what in [
        "energy_J",
        "momentum_kg_m_s",
        "theta_rad",
        "omega_rad_s",
        "amplitude_rad",
    ] {
        for i in 1..=n {
            let _ = write!(out, ",ball{i}_{what}");
        }
    }
    out.push('\n');
    let Some(p) = rec.params else {
        return out;
    };
    for s in &rec.samples {
        let _ = write!(
            out,
            "{},{},{},{},{},{}",
            s.t,
            s.total,
            s.error,
            s.lost[0],
            s.lost[1],
            s.total_momentum()
        );
        let amplitudes = s.amplitudes(&p);
        for series in [&s.energy, &s.momentum, &s.theta, &s.omega, &amplitudes] {
            for v in series {
                let _ = write!(out, ",{v}");
            }
        }
        out.push('\n');
    }
    out
}
