//! The HUD's text from the session's facts: run state, rates, time, counts,
//! energy, momentum, help, and any config error ([`Readout::lines`]), and what
//! the window draws over the picture ([`Overlay`]); which of them shows
//! ([`HudMode`]).

/// What the HUD shows; H or F1 steps through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HudMode {
    /// State, timing, energy error, and a hint.
    Status,
    /// The status and the key list.
    Help,
    /// Nothing (errors still show).
    Off,
}

impl HudMode {
    pub(super) fn next(self) -> Self {
        match self {
            Self::Status => Self::Help,
            Self::Help => Self::Off,
            Self::Off => Self::Status,
        }
    }
}

/// A line of HUD text and its colour.
pub type HudLine = (String, [u8; 3]);

/// What the window draws over the picture: the status lines (top left), the
/// key help (at the bottom, in columns), and the notices (bottom left).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlay {
    /// Status lines and any config error; empty when the HUD is off and all
    /// is well.
    pub status: Vec<HudLine>,
    /// Whether the key help shows.
    pub help: bool,
    /// The notices showing now, oldest first.
    pub notices: Vec<HudLine>,
}

/// What the swing is doing, as the HUD's first line says it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Ball `0` (from 0 at the left) is held by the mouse.
    Holding(usize),
    /// Running, at these smoothed frames per second and trace milliseconds.
    Running { fps: f64, trace_ms: f64 },
    /// Paused: nothing is traced, so no rates.
    Paused,
}

/// How well the energy holds: what is left of a dissipating cradle's (a
/// share), or an ideal one's relative error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Energy {
    Left(f64),
    Error(f64),
}

/// The facts the HUD's status shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Readout<'a> {
    pub mode: HudMode,
    pub motion: Motion,
    /// Simulated time (s) and rate (simulated seconds per second).
    pub time: f64,
    pub rate: f64,
    /// The physics could not keep up with the rate.
    pub slowed: bool,
    pub balls: usize,
    /// The lifted balls as words ([`super::Session::lifted_text`]).
    pub lifted: String,
    /// The contact model's name.
    pub model: &'static str,
    pub energy: Energy,
    /// Total horizontal momentum (kg m/s).
    pub momentum: f64,
    pub muted: bool,
    /// The config error shown until the next good edit, if any.
    pub error: Option<&'a str>,
}

/// A rate as the HUD shows it: `1x`, `4x`, `1/16x`.
fn rate_text(rate: f64) -> String {
    if rate >= 1.0 {
        format!("{rate}x")
    } else {
        format!("1/{}x", (1.0 / rate).round())
    }
}

impl Readout<'_> {
    /// The status lines for the mode (none when off), plus any config error.
    #[must_use]
    pub fn lines(&self) -> Vec<HudLine> {
        let mut lines = Vec::new();
        if self.mode != HudMode::Off {
            // A cradle whose physics cannot keep up says so by its rate.
            let slowed = if self.slowed { " (physics slower)" } else { "" };
            let clock = format!(
                "t {:7.2} s  rate {}{slowed}",
                self.time,
                rate_text(self.rate)
            );
            lines.push(match self.motion {
                Motion::Holding(ball) => (
                    format!("HOLDING ball {}: let go to swing  {clock}", ball + 1),
                    [120, 200, 255],
                ),
                Motion::Running { fps, trace_ms } => (
                    format!("RUNNING  fps {fps:5.1}  trace {trace_ms:5.1} ms  {clock}"),
                    [140, 230, 140],
                ),
                Motion::Paused => (format!("PAUSED: press SPACE  {clock}"), [250, 210, 110]),
            });
            // A cradle that loses energy shows how much is left; an ideal one,
            // how well it keeps it.
            let energy = match self.energy {
                Energy::Left(left) => format!("energy left {:.1}%", 100.0 * left),
                Energy::Error(err) => format!("energy err {err:+.1e}"),
            };
            let muted = if self.muted { "  MUTED" } else { "" };
            lines.push((
                format!(
                    "balls {}  lifted {}  {}  {energy}  p {:+.3} kg m/s{muted}",
                    self.balls, self.lifted, self.model, self.momentum
                ),
                [235, 235, 235],
            ));
            if self.mode == HudMode::Status {
                lines.push(("H: help   TAB: panel".to_string(), [180, 190, 200]));
            }
        }
        if let Some(e) = self.error {
            for line in format!("config error: {e}").lines() {
                lines.push((line.to_string(), [255, 110, 100]));
            }
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::{Energy, HudMode, Motion, Readout, rate_text};

    fn readout(mode: HudMode, motion: Motion) -> Readout<'static> {
        Readout {
            mode,
            motion,
            time: 1.5,
            rate: 0.25,
            slowed: false,
            balls: 5,
            lifted: "1 at 30.0 deg".to_owned(),
            model: "hertz",
            energy: Energy::Left(0.875),
            momentum: 0.0,
            muted: true,
            error: None,
        }
    }

    #[test]
    fn rates_read_as_multiples_and_fractions() {
        assert_eq!(rate_text(4.0), "4x");
        assert_eq!(rate_text(1.0), "1x");
        assert_eq!(rate_text(1.0 / 16.0), "1/16x");
    }

    #[test]
    fn the_first_line_tells_the_state_and_the_second_the_cradle() {
        let paused = readout(HudMode::Status, Motion::Paused).lines();
        assert_eq!(paused.len(), 3, "state, cradle, hint: {paused:?}");
        assert!(paused[0].0.starts_with("PAUSED") && paused[0].0.contains("1/4x"));
        assert!(
            paused[1].0.contains("energy left 87.5%") && paused[1].0.ends_with("MUTED"),
            "{}",
            paused[1].0
        );
        let held = readout(HudMode::Help, Motion::Holding(2)).lines();
        assert_eq!(held.len(), 2, "no hint with the help shown");
        assert!(held[0].0.starts_with("HOLDING ball 3"), "{}", held[0].0);
        let mut r = readout(
            HudMode::Status,
            Motion::Running {
                fps: 60.0,
                trace_ms: 4.0,
            },
        );
        r.energy = Energy::Error(-2e-12);
        let running = r.lines();
        assert!(running[0].0.contains("fps  60.0"), "{}", running[0].0);
        assert!(
            running[1].0.contains("energy err -2.0e-12"),
            "{}",
            running[1].0
        );
    }

    #[test]
    fn a_config_error_shows_even_with_the_hud_off() {
        let mut r = readout(HudMode::Off, Motion::Paused);
        assert!(r.lines().is_empty());
        r.error = Some("cradle.ron:3:5: bad\nallowed: 1..=200");
        let lines = r.lines();
        assert_eq!(lines.len(), 2, "one line each: {lines:?}");
        assert_eq!(lines[0].0, "config error: cradle.ron:3:5: bad");
    }
}
