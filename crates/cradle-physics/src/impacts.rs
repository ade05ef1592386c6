//! Impacts as the engines report them, for what reads the physics beside the
//! picture (the sound, offline soundtracks, `simulate --impacts`): when two
//! neighbours met, how fast, where, and with Hertz contact how long they
//! touched and how hard they pressed.
//!
//! Ideal impacts are reported by `contact::resolve` (each pairwise impulse of a
//! chain, all at the impact's instant); Hertz contacts by a [`Watch`] over the
//! step points of the integrated contact (`hertz`, `damped`): a pair opens when
//! it starts to overlap and is reported when it comes apart.

use super::contact;
use super::params::CradleParams;
use std::collections::VecDeque;

/// At most this many impacts wait to be taken; older ones are dropped (and
/// counted): a reader that stops taking them costs bounded memory.
const CAPACITY: usize = 1 << 16;

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

/// The impacts an engine found and nobody has taken yet, in the order found.
/// Off until asked for: a run that never reads them keeps none.
#[derive(Debug, Clone, Default)]
pub struct ImpactLog {
    on: bool,
    pending: VecDeque<Impact>,
    dropped: u64,
}

impl ImpactLog {
    /// Keeps the impacts found from now on.
    pub fn record(&mut self) {
        self.on = true;
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
#[derive(Debug, Clone, Copy)]
struct Open {
    impact: Impact,
    started: f64,
    deepest: f64,
}

/// Follows the Hertz contacts of a row over the step points of its integration.
#[derive(Debug, Clone, Default)]
pub(crate) struct Watch {
    open: Vec<Option<Open>>,
}

impl Watch {
    /// A watch over the `pairs` pairs of a row, no contact open.
    pub(crate) fn new(pairs: usize) -> Self {
        Self {
            open: vec![None; pairs],
        }
    }

    /// At the start of a contact phase (`t`, s, from a gap root): pairs that
    /// touch and approach open, though they may not overlap yet.
    pub(crate) fn begin(&mut self, p: &CradleParams, t: f64, theta: &[f64], omega: &[f64]) {
        let touch_h = 4e-9 * p.radius * p.radius;
        for a in 0..self.open.len() {
            if self.open[a].is_none()
                && contact::gap_fn(p, theta[a], theta[a + 1]) <= touch_h
                && closing(p, theta, omega, a) > 0.0
            {
                self.open_at(p, t, theta, omega, a);
            }
        }
    }

    /// At a step point (`t`, s): pairs that overlap now open, pairs that no
    /// longer do end and go into `log`. `k` is the Hertz stiffness (N/m^1.5).
    pub(crate) fn step(
        &mut self,
        p: &CradleParams,
        k: f64,
        t: f64,
        (theta, omega): (&[f64], &[f64]),
        log: &mut ImpactLog,
    ) {
        for a in 0..self.open.len() {
            let delta = contact::overlap(p, theta[a], theta[a + 1]);
            match &mut self.open[a] {
                Some(open) if delta > 0.0 => open.deepest = open.deepest.max(delta),
                Some(open) => {
                    let mut impact = open.impact;
                    impact.contact = Some(Contact {
                        duration: t - open.started,
                        peak_force: k * open.deepest.powf(1.5),
                    });
                    log.push(impact);
                    self.open[a] = None;
                }
                None if delta > 0.0 => {
                    self.open_at(p, t, theta, omega, a);
                    if let Some(open) = &mut self.open[a] {
                        open.deepest = delta;
                    }
                }
                None => {}
            }
        }
    }

    fn open_at(&mut self, p: &CradleParams, t: f64, theta: &[f64], omega: &[f64], a: usize) {
        self.open[a] = Some(Open {
            impact: Impact::between(p, t, a, theta, closing(p, theta, omega, a)),
            started: t,
            deepest: 0.0,
        });
    }
}

/// How fast pair `a` approaches (m/s): positive while closing.
fn closing(p: &CradleParams, theta: &[f64], omega: &[f64], a: usize) -> f64 {
    -contact::closing_speed(p, (theta[a], omega[a]), (theta[a + 1], omega[a + 1]))
}

#[cfg(test)]
mod tests {
    use super::{Impact, ImpactLog};

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
}
