//! The control panel's side of the session: its settings, applying them by the
//! rule of [`Controls::apply_to`], and the energies it shows.

use super::{RATES, Session};
use crate::app::controls::{Apply, Controls};
use crate::app::notice;

impl Session {
    /// Whether the control panel is shown.
    #[must_use]
    pub fn panel_open(&self) -> bool {
        self.panel
    }

    /// The control panel's settings now.
    #[must_use]
    pub fn controls(&self) -> Controls {
        Controls::of(&self.config, self.rate.log2().round() as i32)
    }

    /// Applies the control panel's settings ([`Controls::apply_to`]); a refused
    /// edit is shown in the HUD and changes nothing.
    pub fn apply_controls(&mut self, controls: &Controls) {
        let rate = 2f64.powi(controls.rate_exp.clamp(*RATES.start(), *RATES.end()));
        let applied = controls.apply_to(&self.config);
        if rate != self.rate || matches!(applied, Ok(Apply::Live(_) | Apply::Restart(_))) {
            self.remember();
        }
        self.rate = rate;
        match applied {
            Ok(Apply::Same) => {}
            Ok(Apply::Live(c)) => {
                self.config = c;
                self.apply_quality();
                self.retrace = true;
                self.error = None;
            }
            Ok(Apply::Restart(c)) => {
                self.config = c;
                self.error = None;
                self.respawn();
            }
            Err(e) => {
                let first = e.lines().next().unwrap_or_default().to_owned();
                self.notify(format!("not applied: {first}"), notice::BAD);
                self.error = Some(e);
            }
        }
    }

    /// Each ball's share of the starting energy; the share left in all, and its
    /// relative error (of the energy balance when the cradle dissipates).
    #[must_use]
    pub fn energies(&self) -> (Vec<f64>, (f64, f64)) {
        let cradle = self.world.cradle();
        let p = self.config.cradle_params();
        let e0 = cradle.cradle.initial_energy();
        let s = &cradle.snapshot;
        let shares = s
            .theta
            .iter()
            .zip(&s.omega)
            .map(|(&t, &w)| {
                if e0 > 0.0 {
                    p.ball_energy(t, w) / e0
                } else {
                    0.0
                }
            })
            .collect();
        let left = if e0 > 0.0 {
            cradle.cradle.energy(s) / e0
        } else {
            1.0
        };
        (shares, (left, cradle.cradle.energy_rel_error(s)))
    }
}
