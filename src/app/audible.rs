//! The window's impacts on their way to the sound: each frame's impacts wait
//! for the frame that shows them to be presented (a running window shows a
//! frame one step after it was stepped, while the next traces), and are then
//! made into clicks timed against that presentation.

use crate::physics::Impact;
use crate::scene::FrameImpacts;
use crate::sound::track::pan_in;
use crate::sound::{Click, Timbre};
use crate::trace;

/// One stepped frame's impacts.
#[derive(Debug, Clone)]
pub struct Audible {
    /// The frame's simulated time (s).
    pub t: f64,
    /// Its impacts, with where they are in the world.
    pub impacts: FrameImpacts,
}

impl Audible {
    /// The frame's clicks, each `at` its impact's wall-clock time relative to
    /// the frame (s, <= 0) at time `rate`, panned to where `scene` shows it.
    #[must_use]
    pub fn clicks(&self, timbre: &Timbre, scene: &trace::Scene, rate: f64) -> Vec<Click> {
        self.impacts
            .impacts
            .iter()
            .filter_map(|i: &Impact| {
                let at = (i.t - self.t) / rate;
                Click::of(i, timbre, at, pan_in(scene, self.impacts.place(i)))
            })
            .collect()
    }
}

/// Impacts waiting for their frame to be presented.
#[derive(Debug, Clone, Default)]
pub struct Pending {
    /// Stepped and still tracing (shown after the next step).
    tracing: Option<Audible>,
    /// Shown by the frame about to be presented.
    shown: Vec<Audible>,
}

impl Pending {
    /// A frame was stepped; `pipelined`: it is shown after the next step, else
    /// by the frame about to be presented.
    pub fn stepped(&mut self, frame: Audible, pipelined: bool) {
        self.shown.extend(self.tracing.take());
        if pipelined {
            self.tracing = Some(frame);
        } else {
            self.shown.push(frame);
        }
    }

    /// A frame without impacts was stepped and traced at once: the one still
    /// tracing, if any, is shown by it.
    pub fn stepped_none(&mut self) {
        self.shown.extend(self.tracing.take());
    }

    /// The impacts of the frame being presented, taken.
    pub fn take_shown(&mut self) -> Vec<Audible> {
        std::mem::take(&mut self.shown)
    }

    /// Forgets everything waiting: the swing stopped, restarted or was grabbed.
    pub fn clear(&mut self) {
        self.tracing = None;
        self.shown.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::{Audible, Pending};
    use crate::scene::FrameImpacts;

    fn frame(t: f64) -> Audible {
        Audible {
            t,
            impacts: FrameImpacts::default(),
        }
    }

    #[test]
    fn a_pipelined_frame_is_heard_when_the_next_step_presents_it() {
        let mut p = Pending::default();
        p.stepped(frame(1.0), true);
        assert!(p.take_shown().is_empty(), "still tracing");
        p.stepped(frame(2.0), true);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [1.0]);
        // Paused frames trace at once: shown now, with the one still waiting.
        p.stepped(frame(3.0), false);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [2.0, 3.0]);
        p.stepped(frame(4.0), true);
        p.clear();
        p.stepped(frame(5.0), false);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [5.0], "nothing from before the clear");
    }
}
