//! Impacts as the engines report them, for what reads the physics beside the
//! picture (the sound, offline soundtracks, `simulate --impacts`, the graphs):
//! when two neighbours met, how fast, where, and with Hertz contact how long
//! they touched, how hard they pressed and the impulse they passed; and, when
//! asked for, each impact's course ([`Course`]): a Hertz contact's force
//! against time, an ideal impact's velocities before and after.
//!
//! Ideal impacts are reported by `contact::resolve` (each pairwise impulse of a
//! chain, all at the impact's instant); Hertz contacts by a [`Watch`] over the
//! step points of the integrated contact (`hertz`, `damped`): a pair opens when
//! it starts to overlap and is reported when it comes apart. The force is the
//! integration's own at each step point, and the impulse the integral the
//! integration carries beside the motion (`row`), to its own order.

use super::contact;
use super::params::CradleParams;
use super::row::Row;
use std::collections::VecDeque;

/// At most this many impacts wait to be taken; older ones are dropped (and
/// counted): a reader that stops taking them costs bounded memory.
const CAPACITY: usize = 1 << 16;

/// At most this many courses wait to be taken (they are larger: a curve each).
const COURSES: usize = 256;

/// A force curve keeps at most this many points: a contact that lasts longer
/// (balls pressing together for seconds) keeps every other point, then every
/// fourth, and so on.
const CURVE_POINTS: usize = 2048;

/// One impact between neighbours `pair` and `pair + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// When the balls met (s).
    pub t: f64,
    /// The left ball of the pair.
    pub pair: usize,
    /// How fast they approached along the line of centres as they met (m/s, >= 0).
    pub speed: f64,
    /// The contact point in the plane of the swing (m): x along the row from the
    /// first ball's pivot, y up from the pivots (negative below them).
    pub at: (f64, f64),
    /// Hertz contact: how long the pair touched and how hard it pressed. `None`
    /// for an ideal (instantaneous) impact.
    pub contact: Option<Contact>,
}

/// A Hertz contact's course.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// How long the pair overlapped (s): about 0.1 ms for steel.
    pub duration: f64,
    /// The largest elastic force between the pair (N), `k delta_max^1.5`.
    pub peak_force: f64,
    /// The impulse the pair passed (N s): the force's integral over the contact,
    /// the momentum it moved from one ball to the other.
    pub impulse: f64,
}

/// How an impact went, for the graphs.
#[derive(Debug, Clone, PartialEq)]
pub enum Course {
    /// A Hertz contact of one pair: the force along the line of centres at the
    /// integration's step points, from the contact's start to the first point
    /// apart (0 N).
    Force {
        /// The contact, as reported on its own.
        impact: Impact,
        /// `(time since impact.t (s), force (N))`, in time order.
        curve: Vec<(f64, f64)>,
    },
    /// An ideal impact (the whole chain it set off, at one instant): each
    /// ball's centre velocity along the swing (m/s, `L omega`).
    Ideal {
        /// When (s).
        t: f64,
        before: Vec<f64>,
        after: Vec<f64>,
    },
}

impl Course {
    /// When the impact began (s).
    #[must_use]
    pub fn start(&self) -> f64 {
        match self {
            Self::Force { impact, .. } => impact.t,
            Self::Ideal { t, .. } => *t,
        }
    }
}

impl Impact {
    /// The impact of pair `a` at `t` (s) in state `theta`, closing at `speed` (m/s).
    #[must_use]
    pub fn between(p: &CradleParams, t: f64, a: usize, theta: &[f64], speed: f64) -> Self {
        let (xa, ya) = p.centre(a, theta[a]);
        let (xb, yb) = p.centre(a + 1, theta[a + 1]);
        Self {
            t,
            pair: a,
            speed: speed.max(0.0),
            at: (0.5 * (xa + xb), 0.5 * (ya + yb)),
            contact: None,
        }
    }
}

/// The closing speed of pair `a` (m/s): positive while the balls approach.
fn closing(p: &CradleParams, theta: &[f64], omega: &[f64], a: usize) -> f64 {
    -contact::closing_speed(p, (theta[a], omega[a]), (theta[a + 1], omega[a + 1]))
}

/// The impacts an engine found and nobody has taken yet, in the order found.
/// Off until asked for: a run that never reads them keeps none.
#[derive(Debug, Clone, Default)]
pub struct ImpactLog {
    on: bool,
    pending: VecDeque<Impact>,
    dropped: u64,
    /// Keep the courses too.
    courses_on: bool,
    courses: VecDeque<Course>,
}

impl ImpactLog {
    /// Keeps the impacts found from now on.
    pub fn record(&mut self) {
        self.on = true;
    }

    /// True while impacts are kept.
    #[must_use]
    pub fn recording(&self) -> bool {
        self.on
    }

    /// Keeps the impacts' courses too (with impacts kept), or stops keeping
    /// them and forgets those waiting.
    pub fn record_courses(&mut self, on: bool) {
        self.courses_on = on;
        if !on {
            self.courses.clear();
        }
    }

    /// True while courses are kept.
    #[must_use]
    pub fn recording_courses(&self) -> bool {
        self.on && self.courses_on
    }

    /// Adds one course (nothing unless courses are kept).
    pub fn push_course(&mut self, course: Course) {
        if !self.recording_courses() {
            return;
        }
        if self.courses.len() == COURSES {
            self.courses.pop_front();
        }
        self.courses.push_back(course);
    }

    /// Adds the impacts of one ideal resolution at `t` (s): each pairwise hit
    /// `(pair, closing speed)` of the chain, from the state `before`, and the
    /// course from the angular velocities before to `after`.
    pub fn push_resolved(
        &mut self,
        p: &CradleParams,
        t: f64,
        (theta, omega): (&[f64], &[f64]),
        after: &[f64],
        hits: &[(usize, f64)],
    ) {
        for &(pair, speed) in hits {
            self.push(Impact::between(p, t, pair, theta, speed));
        }
        if !hits.is_empty() && self.recording_courses() {
            let speeds = |w: &[f64]| w.iter().map(|w| p.length * w).collect();
            self.push_course(Course::Ideal {
                t,
                before: speeds(omega),
                after: speeds(after),
            });
        }
    }

    /// The courses that began at or before `t` (s), earliest first, taken out.
    pub fn take_courses_until(&mut self, t: f64) -> Vec<Course> {
        self.courses
            .make_contiguous()
            .sort_by(|x, y| x.start().total_cmp(&y.start()));
        let n = self.courses.partition_point(|c| c.start() <= t);
        self.courses.drain(..n).collect()
    }

    /// Adds one found impact (nothing when off).
    pub fn push(&mut self, impact: Impact) {
        if !self.on {
            return;
        }
        if self.pending.len() == CAPACITY {
            self.pending.pop_front();
            self.dropped += 1;
        }
        self.pending.push_back(impact);
    }

    /// The impacts at or before `t` (s), earliest first, taken out of the log.
    pub fn take_until(&mut self, t: f64) -> Vec<Impact> {
        // Hertz contacts are reported as they end, so a later onset can come
        // first; the log is short (a frame's worth), the sort cheap.
        self.pending
            .make_contiguous()
            .sort_by(|x, y| x.t.total_cmp(&y.t));
        let n = self.pending.partition_point(|i| i.t <= t);
        self.pending.drain(..n).collect()
    }

    /// Impacts dropped because nobody took them in time.
    #[must_use]
    pub fn dropped(&self) -> u64 {
        self.dropped
    }
}

/// A contact that has begun and not yet ended.
#[derive(Debug, Clone)]
struct Open {
    impact: Impact,
    deepest: f64,
    /// The impulse passed so far (N s).
    impulse: f64,
    /// The force curve so far (when courses are kept), and how many step
    /// points each kept point stands for.
    curve: Vec<(f64, f64)>,
    every: usize,
    seen: usize,
}

impl Open {
    /// Adds the force `f` (N) at time `t` (s) to the curve: every point of a
    /// contact's first [`CURVE_POINTS`], then every other, and so on, and
    /// always the `last`.
    fn sample(&mut self, t: f64, f: f64, last: bool) {
        self.seen += 1;
        if !last && !self.seen.is_multiple_of(self.every) {
            return;
        }
        if self.curve.len() == CURVE_POINTS {
            let mut i = 0;
            self.curve.retain(|_| {
                i += 1;
                i % 2 == 1
            });
            self.every *= 2;
        }
        self.curve.push((t - self.impact.t, f));
    }
}

/// Follows the Hertz contacts of a row over the step points of its integration.
#[derive(Debug, Clone, Default)]
pub(crate) struct Watch {
    open: Vec<Option<Open>>,
    /// Each pair's impulse in the state at the last step point (N s).
    last: Vec<f64>,
}

impl Watch {
    /// A watch over the `pairs` pairs of a row, no contact open.
    pub(crate) fn new(pairs: usize) -> Self {
        Self {
            open: vec![None; pairs],
            last: vec![0.0; pairs],
        }
    }

    /// At the start of a contact phase (`t`, s, from a gap root) in state `y`
    /// of `row` (impulses from 0): pairs that touch and approach open, though
    /// they may not overlap yet. `curves`: keep force curves.
    pub(crate) fn begin(&mut self, row: &Row, t: f64, y: &[f64], curves: bool) {
        let (theta, omega) = row.motion(y);
        let p = row.params();
        let touch_h = 4e-9 * p.radius * p.radius;
        self.last.fill(0.0);
        for a in 0..self.open.len() {
            if self.open[a].is_none()
                && contact::gap_fn(p, theta[a], theta[a + 1]) <= touch_h
                && closing(p, theta, omega, a) > 0.0
            {
                self.open_at(p, t, (theta, omega), a);
                if let Some(open) = self.open[a].as_mut().filter(|_| curves) {
                    open.sample(t, row.force(y, a), false);
                }
            }
        }
    }

    /// At a step point (`t`, s) in state `y` of `row`: pairs that overlap now
    /// open, pairs that no longer do end and go into `log`.
    pub(crate) fn step(&mut self, row: &Row, t: f64, y: &[f64], log: &mut ImpactLog) {
        let (theta, omega) = row.motion(y);
        let p = row.params();
        let impulses = row.impulses(y);
        let curves = log.recording_courses();
        for a in 0..self.open.len() {
            // The impulse passed since the last step point.
            let passed = impulses.get(a).map_or(0.0, |&j| j - self.last[a]);
            if let Some(&j) = impulses.get(a) {
                self.last[a] = j;
            }
            let delta = contact::overlap(p, theta[a], theta[a + 1]);
            if self.open[a].is_none() {
                if delta <= 0.0 {
                    continue;
                }
                self.open_at(p, t, (theta, omega), a);
            }
            let Some(open) = self.open[a].as_mut() else {
                continue;
            };
            open.impulse += passed;
            if curves {
                open.sample(t, row.force(y, a), delta <= 0.0);
            }
            if delta > 0.0 {
                open.deepest = open.deepest.max(delta);
                continue;
            }
            let Some(open) = self.open[a].take() else {
                continue;
            };
            let mut impact = open.impact;
            impact.contact = Some(Contact {
                duration: t - impact.t,
                peak_force: row.stiffness() * open.deepest.powf(1.5),
                impulse: open.impulse,
            });
            log.push(impact);
            log.push_course(Course::Force {
                impact,
                curve: open.curve,
            });
        }
    }

    /// Opens pair `a` at `t` (s).
    fn open_at(&mut self, p: &CradleParams, t: f64, (theta, omega): (&[f64], &[f64]), a: usize) {
        self.open[a] = Some(Open {
            impact: Impact::between(p, t, a, theta, closing(p, theta, omega, a)),
            deepest: 0.0,
            impulse: 0.0,
            curve: Vec::new(),
            every: 1,
            seen: 0,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::{Impact, ImpactLog, Open};

    fn at(t: f64) -> Impact {
        Impact {
            t,
            pair: 0,
            speed: 1.0,
            at: (0.0, 0.0),
            contact: None,
        }
    }

    #[test]
    fn a_log_keeps_nothing_until_asked_and_hands_out_impacts_in_time_order() {
        let mut log = ImpactLog::default();
        log.push(at(0.1));
        assert!(log.take_until(1.0).is_empty());
        log.record();
        for t in [0.3, 0.1, 0.2, 0.5] {
            log.push(at(t));
        }
        let times: Vec<f64> = log.take_until(0.3).iter().map(|i| i.t).collect();
        assert_eq!(times, [0.1, 0.2, 0.3]);
        let rest: Vec<f64> = log.take_until(f64::INFINITY).iter().map(|i| i.t).collect();
        assert_eq!(rest, [0.5]);
    }

    #[test]
    fn a_log_nobody_reads_stays_bounded() {
        let mut log = ImpactLog::default();
        log.record();
        for n in 0..super::CAPACITY + 10 {
            log.push(at(n as f64));
        }
        assert_eq!(log.dropped(), 10);
        let kept = log.take_until(f64::INFINITY);
        assert_eq!(kept.len(), super::CAPACITY);
        assert_eq!(kept[0].t, 10.0);
    }

    #[test]
    fn a_long_contact_keeps_a_bounded_curve_spread_over_it_and_its_end() {
        let mut open = Open {
            impact: at(1.0),
            deepest: 0.0,
            impulse: 0.0,
            curve: Vec::new(),
            every: 1,
            seen: 0,
        };
        let steps = 5 * super::CURVE_POINTS + 7;
        for n in 1..=steps {
            open.sample(1.0 + n as f64 * 1e-6, 1.0, n == steps);
        }
        let curve = &open.curve;
        assert!(curve.len() <= super::CURVE_POINTS + 1, "{}", curve.len());
        assert!(curve.len() > super::CURVE_POINTS / 2, "{}", curve.len());
        assert!(curve.windows(2).all(|w| w[1].0 > w[0].0));
        // The first point, and the last at the contact's end (1e-6 s a step).
        assert!((curve[0].0 - 1e-6).abs() < 1e-12);
        assert!((curve.last().unwrap().0 - steps as f64 * 1e-6).abs() < 1e-12);
        // Spread evenly: no gap wider than the stride 5 times the points call
        // for (every 8th step: full at 2,048, 4,096 and 8,192 steps).
        let widest = curve
            .windows(2)
            .map(|w| w[1].0 - w[0].0)
            .fold(0.0, f64::max);
        assert!(widest < 8.5e-6, "{widest}");
    }
}
