//! What the physics tests share: the cradle they start from.

use cradle_physics::CradleParams;
use cradle_physics::hertz::stiffness;

/// The default asset's cradle: `balls` steel balls (7850 kg/m^3) of 2 cm
/// radius on 16 cm strings, touching, under Earth's gravity, with elastic
/// Hertz contact of steel (E = 2e11 Pa, nu = 0.29); no losses.
pub fn steel(balls: usize) -> CradleParams {
    let radius = 0.02;
    CradleParams {
        balls,
        radius,
        mass: 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3),
        length: 0.16,
        gap: 0.0,
        gravity: 9.81,
        restitution: 1.0,
        hertz: Some(stiffness(2.0e11, 0.29, radius)),
        dissipation: 0.0,
        drag: 0.0,
    }
}
