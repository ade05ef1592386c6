//! The HUD's text: run state, rates, time, counts, help, and any config error.

use super::{HudLine, HudMode, Session};
use crate::app::keys;

/// A rate as the HUD shows it: `1x`, `4x`, `1/16x`.
fn rate_text(rate: f64) -> String {
    if rate >= 1.0 {
        format!("{rate}x")
    } else {
        format!("1/{}x", (1.0 / rate).round())
    }
}

impl Session {
    /// The HUD's lines for its mode (none when off), plus any config error.
    #[must_use]
    pub fn hud_lines(&self) -> Vec<HudLine> {
        let mut lines = Vec::new();
        if self.hud != HudMode::Off {
            let white = [235, 235, 235];
            let cradle = self.world.cradle();
            let err = cradle.cradle.energy_rel_error(&cradle.snapshot);
            let (state, color) = if self.running() {
                ("RUNNING", [140, 230, 140])
            } else {
                ("PAUSED - press SPACE", [250, 210, 110])
            };
            let c = &self.config;
            lines.push((format!("Newton's cradle   {state}"), color));
            // While paused nothing is traced: say so rather than show old rates.
            let timing = if self.running() {
                format!("fps {:5.1}   trace {:6.1} ms", self.fps, self.trace_ms)
            } else {
                "fps     -   trace      - ms".to_owned()
            };
            lines.push((
                format!(
                    "{timing}   t {:8.2} s   rate {}",
                    self.time(),
                    rate_text(self.rate)
                ),
                white,
            ));
            // A cradle that loses energy shows how much is left; an ideal one,
            // how well it keeps it.
            let energy = if cradle.cradle.params().dissipative() {
                let (_, (left, _)) = self.energies();
                format!("energy left {:.1}%", 100.0 * left)
            } else {
                format!("energy err {err:+.1e}")
            };
            lines.push((
                format!(
                    "balls {}  lifted {}  contact {}  {energy}",
                    c.cradle.balls,
                    c.start.lift,
                    c.contact.model.name()
                ),
                white,
            ));
            let grey = [180, 190, 200];
            if self.hud == HudMode::Help {
                lines.extend(keys::HELP.iter().map(|l| ((*l).to_string(), grey)));
            } else {
                lines.push(("H: help".to_string(), grey));
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
