//! The config keys of a cradle that loses energy: viscoelastic contacts
//! (`contact.dissipation`) and air drag (`cradle.air_density`,
//! `cradle.drag_coefficient`), checked with what they need (Hertz contact, the
//! exact integrator).

use super::validate::Checker;
use super::{Config, ContactModel, ranges};
use crate::physics::Integrator;

impl Config {
    /// True when the air drags the balls (both drag keys above 0).
    #[must_use]
    pub fn has_drag(&self) -> bool {
        self.cradle.air_density > 0.0 && self.cradle.drag_coefficient > 0.0
    }

    /// The largest `contact.dissipation` this cradle takes (s), and the shortest
    /// Hertz contact it can have (s), of which that is a tenth: two balls
    /// meeting at twice the speed of one let go from the top (a drag in the
    /// window can lift a ball there), pendulums of reduced mass `I / L^2 / 2`.
    /// Infinite where the other keys are out of range.
    #[must_use]
    pub fn dissipation_limit(&self) -> (f64, f64) {
        let p = self.cradle_params();
        let Some(k) = p.hertz.filter(|k| k.is_finite() && *k > 0.0) else {
            return (f64::INFINITY, f64::INFINITY);
        };
        let v = 2.0 * p.release_speed(super::MAX_ANGLE_DEG.to_radians());
        let m = 0.5 * p.inertia() / (p.length * p.length);
        let shortest = crate::physics::hertz::contact_time(k, m, v);
        if shortest.is_finite() && shortest > 0.0 {
            (0.1 * shortest, shortest)
        } else {
            (f64::INFINITY, f64::INFINITY)
        }
    }

    /// Range checks of the dissipation keys, and what they need.
    pub(super) fn check_damping(&self, c: &mut Checker) {
        let (k, ct) = (&self.cradle, &self.contact);
        c.num(
            "cradle.air_density",
            k.air_density,
            ranges::AIR_DENSITY.contains(&k.air_density),
            "0..=100 (kg/m^3; air at 20 C is 1.2, 0 = no drag)",
        );
        c.num(
            "cradle.drag_coefficient",
            k.drag_coefficient,
            (0.0..=10.0).contains(&k.drag_coefficient),
            "0..=10 (a smooth sphere: 0.47)",
        );
        c.num(
            "contact.dissipation",
            ct.dissipation,
            ranges::DISSIPATION.contains(&ct.dissipation),
            "0..=1e-3 (s; 0 = elastic)",
        );
        let hertz = ct.model == ContactModel::Hertz;
        let exact = self.physics.integrator == Integrator::Exact;
        if hertz && ct.dissipation > 0.0 {
            let (most, shortest) = self.dissipation_limit();
            if ct.dissipation > most {
                c.fail(
                    "contact.dissipation",
                    ct.dissipation,
                    &format!(
                        "0..={most:.2e} (s) for this cradle: a tenth of its shortest \
                         contact ({shortest:.2e} s); the viscoelastic model holds only for \
                         constants much shorter than the contact they damp"
                    ),
                );
            }
        }
        let needs = "with contact.model hertz and physics.integrator exact only";
        if ct.dissipation > 0.0 && !(hertz && exact) {
            c.fail(
                "contact.dissipation",
                ct.dissipation,
                &format!("0, or 0..=1e-3 (s) {needs}"),
            );
        }
        if self.has_drag() && !(hertz && exact) {
            c.fail(
                "cradle.air_density",
                k.air_density,
                &format!("0, or 0..=100 (kg/m^3) {needs}"),
            );
        }
    }
}
