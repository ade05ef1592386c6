//! The HUD's text: run state, rates, time, counts, help, and any config error.

use super::{HudLine, HudMode, Session};
use std::time::Instant;

/// A rate as the HUD shows it: `1x`, `4x`, `1/16x`.
fn rate_text(rate: f64) -> String {
    if rate >= 1.0 {
        format!("{rate}x")
    } else {
        format!("1/{}x", (1.0 / rate).round())
    }
}

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

impl Session {
    /// What to draw over the picture at `now` (notices past their time go).
    pub fn overlay(&mut self, now: Instant) -> Overlay {
        Overlay {
            status: self.hud_lines(),
            help: self.hud == HudMode::Help,
            notices: self.notices.at(now),
        }
    }

    /// Whether the HUD's status shows (screenshots then keep what the window
    /// shows; without it they are the bare picture).
    #[must_use]
    pub fn hud_on(&self) -> bool {
        self.hud != HudMode::Off
    }

    /// The lifted balls as the HUD and panel say it: the count and angle, or
    /// the balls and angle a drag to the right made.
    #[must_use]
    pub fn lifted_text(&self) -> String {
        match &self.custom {
            Some(custom) => format!("custom ({custom})"),
            None => format!(
                "{} at {:.1} deg",
                self.config.start.lift, self.config.start.angle_deg
            ),
        }
    }

    /// The HUD's status lines for its mode (none when off), plus any config error.
    #[must_use]
    pub fn hud_lines(&self) -> Vec<HudLine> {
        let mut lines = Vec::new();
        if self.hud != HudMode::Off {
            let white = [235, 235, 235];
            let cradle = self.world.cradle();
            let err = cradle.cradle.energy_rel_error(&cradle.snapshot);
            // A cradle whose physics cannot keep up says so by its rate.
            let slowed = if self.behind && self.running() {
                " (physics slower)"
            } else {
                ""
            };
            let clock = format!(
                "t {:7.2} s  rate {}{slowed}",
                self.time(),
                rate_text(self.rate)
            );
            let first = if let Some(ball) = self.dragging {
                (
                    format!("HOLDING ball {}: let go to swing  {clock}", ball + 1),
                    [120, 200, 255],
                )
            } else if self.running() {
                (
                    format!(
                        "RUNNING  fps {:5.1}  trace {:5.1} ms  {clock}",
                        self.fps, self.trace_ms
                    ),
                    [140, 230, 140],
                )
            } else {
                // While paused nothing is traced: no rates to show.
                (format!("PAUSED: press SPACE  {clock}"), [250, 210, 110])
            };
            lines.push(first);
            let c = &self.config;
            // A cradle that loses energy shows how much is left; an ideal one,
            // how well it keeps it.
            let energy = if cradle.cradle.params().dissipative() {
                let (_, (left, _)) = self.energies();
                format!("energy left {:.1}%", 100.0 * left)
            } else {
                format!("energy err {err:+.1e}")
            };
            let muted = if self.muted() { "  MUTED" } else { "" };
            let snap = &cradle.snapshot;
            let momentum = cradle.cradle.params().momentum(&snap.theta, &snap.omega);
            lines.push((
                format!(
                    "balls {}  lifted {}  {}  {energy}  p {momentum:+.3} kg m/s{muted}",
                    c.cradle.balls,
                    self.lifted_text(),
                    c.contact.model.name()
                ),
                white,
            ));
            if self.hud == HudMode::Status {
                lines.push(("H: help   TAB: panel".to_string(), [180, 190, 200]));
            }
        }
        if let Some(e) = &self.error {
            for line in format!("config error: {e}").lines() {
                lines.push((line.to_string(), [255, 110, 100]));
            }
        }
        lines
    }
}
