//! What the control panel edits, window-free: the settings it shows, and the
//! rule for applying them. Changes the running swing can absorb (anti-aliasing,
//! the time rate, the volume) apply live; the others restart from the start position, as the
//! keys do. An edit the config's validation refuses is shown, not applied.

use crate::config::{Config, ContactModel};
use crate::physics::Integrator;

/// The panel's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Controls {
    /// Balls, 1..=200.
    pub balls: usize,
    /// Balls lifted from the left.
    pub lift: usize,
    /// Lift angle (degrees).
    pub angle_deg: f64,
    /// Gap between balls at rest (m).
    pub gap: f64,
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Contact model.
    pub contact: ContactModel,
    /// Hertz contact's dissipative constant (s): 0 elastic.
    pub dissipation: f64,
    /// Air density (kg/m^3): 0 no drag.
    pub air_density: f64,
    /// Solver.
    pub integrator: Integrator,
    /// Samples per pixel.
    pub samples: u32,
    /// Adaptive anti-aliasing.
    pub adaptive: bool,
    /// Time rate as a power of two.
    pub rate_exp: i32,
    /// Loudness of the clicks, 0..=1.
    pub volume: f64,
}

/// How an edit applies.
#[derive(Debug, Clone, PartialEq)]
pub enum Apply {
    /// Nothing changed.
    Same,
    /// Only what the running swing absorbs changed.
    Live(Config),
    /// The cradle changed: respawn from the start position.
    Restart(Config),
}

impl Controls {
    /// The settings of `config` at time rate `2^rate_exp`.
    #[must_use]
    pub fn of(config: &Config, rate_exp: i32) -> Self {
        Self {
            balls: config.cradle.balls,
            lift: config.start.lift,
            angle_deg: config.start.angle_deg,
            gap: config.cradle.gap,
            restitution: config.contact.restitution,
            contact: config.contact.model,
            dissipation: config.contact.dissipation,
            air_density: config.cradle.air_density,
            integrator: config.physics.integrator,
            samples: config.render.samples,
            adaptive: config.render.adaptive,
            rate_exp,
            volume: config.sound.volume,
        }
    }

    /// How these settings apply to `config`.
    ///
    /// # Errors
    /// The config's validation refuses them: its messages, one per line.
    pub fn apply_to(&self, config: &Config) -> Result<Apply, String> {
        let mut c = config.clone();
        c.cradle.balls = self.balls;
        c.start.lift = self.lift.min(self.balls);
        c.start.angle_deg = self.angle_deg;
        c.cradle.gap = self.gap;
        c.contact.restitution = self.restitution;
        c.contact.model = self.contact;
        c.contact.dissipation = self.dissipation;
        c.cradle.air_density = self.air_density;
        c.physics.integrator = self.integrator;
        c.render.samples = self.samples;
        c.render.adaptive = self.adaptive;
        c.sound.volume = self.volume;
        c.validate().map_err(|errors| {
            errors
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("\n")
        })?;
        Ok(if c == *config {
            Apply::Same
        } else if absorbed(config, &c) {
            Apply::Live(c)
        } else {
            Apply::Restart(c)
        })
    }
}

/// Whether going from `from` to `to` is a change the running swing absorbs:
/// they differ in anti-aliasing and volume at most.
#[must_use]
pub fn absorbed(from: &Config, to: &Config) -> bool {
    let mut swing = from.clone();
    swing.render.samples = to.render.samples;
    swing.render.adaptive = to.render.adaptive;
    swing.sound.volume = to.sound.volume;
    swing == *to
}

/// Changes within this long of the one before are one step of the history:
/// a slider's drag is one change, not one per frame.
pub const ONE_CHANGE: std::time::Duration = std::time::Duration::from_millis(700);

/// The most steps the history keeps.
const STEPS: usize = 64;

/// The states before the panel's last changes, newest last, for Ctrl+Z.
#[derive(Debug)]
pub struct History<T> {
    steps: Vec<T>,
    /// When the last change was recorded.
    last: Option<std::time::Instant>,
}

impl<T> Default for History<T> {
    fn default() -> Self {
        Self {
            steps: Vec::new(),
            last: None,
        }
    }
}

impl<T> History<T> {
    /// `before`, the state a change at `now` leaves, unless the change before
    /// came within [`ONE_CHANGE`] (then both undo as one).
    pub fn record(&mut self, before: T, now: std::time::Instant) {
        let joined = self
            .last
            .is_some_and(|t| now.saturating_duration_since(t) < ONE_CHANGE);
        self.last = Some(now);
        if joined && !self.steps.is_empty() {
            return;
        }
        if self.steps.len() == STEPS {
            self.steps.remove(0);
        }
        self.steps.push(before);
    }

    /// The state before the last change, taken off the history.
    pub fn undo(&mut self) -> Option<T> {
        self.last = None;
        self.steps.pop()
    }
}

#[cfg(test)]
mod tests {
    use super::{Apply, Controls, History};
    use crate::config::{Config, ContactModel};

    #[test]
    fn quality_applies_live_the_cradle_restarts_and_bad_edits_are_refused() {
        let c = Config::default();
        let same = Controls::of(&c, 0);
        assert_eq!(same.apply_to(&c), Ok(Apply::Same));
        let mut aa = same.clone();
        aa.samples = 16;
        aa.adaptive = true;
        assert!(matches!(aa.apply_to(&c), Ok(Apply::Live(n)) if n.render.samples == 16));
        let mut quiet = same.clone();
        quiet.volume = 0.2;
        assert!(matches!(quiet.apply_to(&c), Ok(Apply::Live(n)) if n.sound.volume == 0.2));
        let mut more = same.clone();
        more.balls = 7;
        assert!(matches!(more.apply_to(&c), Ok(Apply::Restart(n)) if n.cradle.balls == 7));
        // Hertz contact is elastic: with restitution 0.5 it is refused, with its range.
        let mut bad = same;
        bad.contact = ContactModel::Hertz;
        bad.restitution = 0.5;
        let e = bad.apply_to(&c).expect_err("refused");
        assert!(e.contains("contact.restitution"), "{e}");
    }

    #[test]
    fn quick_changes_undo_as_one_and_slow_ones_one_by_one() {
        let t0 = std::time::Instant::now();
        let ms = |m| t0 + std::time::Duration::from_millis(m);
        let mut h = History::default();
        // A slider dragged through 1, 2, 3 in quick frames: one step back to 1.
        h.record(1, ms(0));
        h.record(2, ms(16));
        h.record(3, ms(32));
        // A second change two seconds later: its own step.
        h.record(4, ms(2000));
        assert_eq!(h.undo(), Some(4));
        assert_eq!(h.undo(), Some(1));
        assert_eq!(h.undo(), None);
    }
}
