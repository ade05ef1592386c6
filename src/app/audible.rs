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

/// What the window hears: impacts waiting for their frame to be presented,
/// the mute, and the times the swing stopped, restarted or was grabbed.
#[derive(Debug, Clone, Default)]
pub struct Hearing {
    /// Stepped and still tracing (shown after the next step).
    tracing: Option<Audible>,
    /// Shown by the frame about to be presented.
    shown: Vec<Audible>,
    /// M: no clicks.
    muted: bool,
    /// Why the window is silent whatever M says (no audio server), if it is.
    silent: Option<String>,
    /// Times the swing stopped, restarted or was grabbed: clicks from before
    /// such a time are stale.
    hushes: u64,
}

impl Hearing {
    /// Nothing waiting; muted if `muted` (`--mute`).
    #[must_use]
    pub fn new(muted: bool) -> Self {
        Self {
            muted,
            ..Self::default()
        }
    }

    /// A frame was stepped, with its impacts if it had any; `pipelined`: it is
    /// shown after the next step, else by the frame about to be presented.
    /// Either way the frame stepped before is presented now.
    pub fn stepped(&mut self, frame: Option<Audible>, pipelined: bool) {
        self.shown.extend(self.tracing.take());
        if pipelined {
            self.tracing = frame;
        } else {
            self.shown.extend(frame);
        }
    }

    /// The impacts of the frame being presented, taken; none when muted.
    pub fn take_shown(&mut self) -> Vec<Audible> {
        let shown = std::mem::take(&mut self.shown);
        if self.muted { Vec::new() } else { shown }
    }

    /// The swing stopped, restarted or was grabbed: everything waiting goes,
    /// and the sound is told to drop what it has not played.
    pub fn hush(&mut self) {
        self.tracing = None;
        self.shown.clear();
        self.hushes += 1;
    }

    /// How many times [`Self::hush`] was called.
    #[must_use]
    pub fn hushes(&self) -> u64 {
        self.hushes
    }

    /// Muted.
    #[must_use]
    pub fn muted(&self) -> bool {
        self.muted
    }

    /// Mutes or unmutes (M); says what that did.
    pub fn toggle_mute(&mut self) -> String {
        self.muted = !self.muted;
        match (&self.silent, self.muted) {
            (_, true) => "sound muted (M: on)".to_owned(),
            (Some(why), false) => format!("sound on, but silent: {why}"),
            (None, false) => "sound on".to_owned(),
        }
    }

    /// The window is silent whatever M says, for `why` (no audio server).
    pub fn set_silent(&mut self, why: impl Into<String>) {
        self.silent = Some(why.into());
    }
}

#[cfg(test)]
mod tests {
    use super::{Audible, Hearing};
    use crate::scene::FrameImpacts;

    fn frame(t: f64) -> Audible {
        Audible {
            t,
            impacts: FrameImpacts::default(),
        }
    }

    #[test]
    fn a_pipelined_frame_is_heard_when_the_next_step_presents_it() {
        let mut p = Hearing::default();
        p.stepped(Some(frame(1.0)), true);
        assert!(p.take_shown().is_empty(), "still tracing");
        p.stepped(Some(frame(2.0)), true);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [1.0]);
        // A frame without impacts still presents the one before.
        p.stepped(None, true);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [2.0]);
        // Paused frames trace at once: shown now, with the one still waiting.
        p.stepped(Some(frame(3.0)), true);
        p.stepped(Some(frame(4.0)), false);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [3.0, 4.0]);
        p.stepped(Some(frame(5.0)), true);
        p.hush();
        assert_eq!(p.hushes(), 1);
        p.stepped(Some(frame(6.0)), false);
        let shown: Vec<f64> = p.take_shown().iter().map(|a| a.t).collect();
        assert_eq!(shown, [6.0], "nothing from before the hush");
        // Muted: nothing, and M says why an unmuted window may stay silent.
        p.set_silent("no audio server");
        assert!(p.toggle_mute().contains("muted"));
        p.stepped(Some(frame(7.0)), false);
        assert!(p.take_shown().is_empty());
        assert!(p.toggle_mute().contains("no audio server"));
    }
}
