//! The config asset (`assets/cradle.ron`): one struct tree, every field with its
//! unit, default and allowed range. `load` parses and validates it with errors that
//! name the file, line and column; `validate` checks ranges.
//!
//! Every field has a default, so an asset only needs the keys it changes.

mod damping;
mod load;
mod locate;
mod look;
pub mod ranges;
mod validate;

pub use load::{ConfigError, ConfigSource, DEFAULT_ASSET, load_file, parse};
pub use look::{CameraConfig, LightConfig, MaterialConfig, MaterialsConfig, RenderConfig};
pub use validate::{FieldError, MAX_ANGLE_DEG};

use crate::physics::{CradleParams, Integrator};
use serde::{Deserialize, Serialize};

/// The most balls a cradle may have (`cradle.balls`, `--balls`, the Up key).
pub const MAX_BALLS: usize = 200;

/// A linear RGB colour, each channel 0..=1.
pub type Rgb = [f64; 3];
/// A point or direction in metres: x to the right along the cradle, y up, z towards
/// the default camera.
pub type Vec3 = [f64; 3];

/// The whole asset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    /// The cradle's geometry and mass.
    pub cradle: CradleConfig,
    /// How the swing starts.
    pub start: StartConfig,
    /// What happens when balls touch.
    pub contact: ContactConfig,
    /// Which solver advances the balls.
    pub physics: PhysicsConfig,
    /// Picture size and tracing effort.
    pub render: RenderConfig,
    /// The pinhole camera.
    pub camera: CameraConfig,
    /// Light sources; at most 16.
    pub lights: Vec<LightConfig>,
    /// Surface looks.
    pub materials: MaterialsConfig,
    /// The clicks of the impacts.
    pub sound: SoundConfig,
}

/// The clicks of the impacts (the window; `render --audio`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SoundConfig {
    /// Loudness of the window's clicks, 0..=1 (0 = silent, as muted). Default
    /// 0.7. Soundtracks are written at full level.
    pub volume: f64,
}

impl Default for SoundConfig {
    fn default() -> Self {
        Self { volume: 0.7 }
    }
}

/// The cradle's geometry and mass (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CradleConfig {
    /// Number of balls, 1..=200. Default 5.
    pub balls: usize,
    /// Ball radius (m), > 0. Default 0.02.
    pub radius: f64,
    /// Ball density (kg/m^3), > 0; mass = density * 4/3 pi r^3. Default 7850 (steel).
    pub density: f64,
    /// String length from pivot to ball centre (m), > radius. Default 0.16.
    pub length: f64,
    /// Gap between neighbouring balls at rest (m), >= 0. Default 0 (touching).
    pub gap: f64,
    /// Height of the pivots (top rails) above the floor (m), > length + radius.
    /// Default 0.25.
    pub pivot_height: f64,
    /// Half the distance between the two top rails (m), > radius: each ball hangs
    /// on a V of two strings. Default 0.05.
    pub rail_spread: f64,
    /// Gravitational acceleration (m/s^2), > 0. Default 9.81.
    pub gravity: f64,
    /// Radius of the strings (m), > 0 and < radius. Default 0.0006.
    pub string_radius: f64,
    /// Radius of the frame's rods (m), > 0. Default 0.005.
    pub frame_radius: f64,
    /// Density of the air the balls swing through (kg/m^3), 0..=100; 0 = no air
    /// drag. Default 0. Drag needs `contact.model: hertz` and the exact integrator.
    pub air_density: f64,
    /// Drag coefficient of a ball, 0..=10: the drag is `air_density *
    /// drag_coefficient * pi r^2 v^2 / 2`. Default 0.47 (a smooth sphere at a desk toy's speeds).
    pub drag_coefficient: f64,
}

impl Default for CradleConfig {
    fn default() -> Self {
        Self {
            balls: 5,
            radius: 0.02,
            density: 7850.0,
            length: 0.16,
            gap: 0.0,
            pivot_height: 0.25,
            rail_spread: 0.05,
            gravity: 9.81,
            string_radius: 0.0006,
            frame_radius: 0.005,
            air_density: 0.0,
            drag_coefficient: 0.47,
        }
    }
}

/// How the swing starts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StartConfig {
    /// How many balls, from the left, are lifted: 0..=balls. Default 1.
    pub lift: usize,
    /// Lift angle (degrees from the vertical, pulled to the left), 0..=179.999.
    /// Default 30.
    pub angle_deg: f64,
    /// Whether the app starts swinging (true) or paused with the balls held up
    /// until Space (false). Default false.
    pub running: bool,
}

impl Default for StartConfig {
    fn default() -> Self {
        Self {
            lift: 1,
            angle_deg: 30.0,
            running: false,
        }
    }
}

/// Contact model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ContactModel {
    /// Instantaneous impacts with restitution.
    #[default]
    Ideal,
    /// Soft Hertz spheres (F = k delta^1.5), from Young's modulus and Poisson ratio.
    Hertz,
}

impl ContactModel {
    /// The name used in configs, flags and JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Ideal => "ideal",
            Self::Hertz => "hertz",
        }
    }
}

/// What happens when balls touch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ContactConfig {
    /// `ideal` or `hertz`. Default `ideal`.
    pub model: ContactModel,
    /// Coefficient of restitution of ideal impacts, 0..=1. Default 1 (elastic).
    pub restitution: f64,
    /// Young's modulus for Hertz contact (Pa), > 0. Default 2.0e11 (steel).
    pub youngs_modulus: f64,
    /// Poisson ratio for Hertz contact, 0 <= nu < 0.5. Default 0.29 (steel).
    pub poisson_ratio: f64,
    /// Hertz contact's dissipative constant A (s), 0..=1e-3: the viscoelastic
    /// force 3/2 A k sqrt(delta) d(delta)/dt adds to k delta^1.5. 0 = elastic.
    /// Default 0. Needs `model: hertz` and the exact integrator.
    pub dissipation: f64,
}

impl Default for ContactConfig {
    fn default() -> Self {
        Self {
            model: ContactModel::Ideal,
            restitution: 1.0,
            youngs_modulus: 2.0e11,
            poisson_ratio: 0.29,
            dissipation: 0.0,
        }
    }
}

/// Which solver advances the balls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PhysicsConfig {
    /// `exact`, `euler`, `verlet`, `rk4` or `yoshida4`. Default `exact`.
    pub integrator: Integrator,
    /// Step of the fixed-step integrators (s), 1e-7..=0.1. Default 0.001.
    pub dt: f64,
}

impl Default for PhysicsConfig {
    fn default() -> Self {
        Self {
            integrator: Integrator::Exact,
            dt: 1e-3,
        }
    }
}

impl Config {
    /// Ball mass (kg): density * 4/3 pi r^3.
    #[must_use]
    pub fn ball_mass(&self) -> f64 {
        self.cradle.density * 4.0 / 3.0 * std::f64::consts::PI * self.cradle.radius.powi(3)
    }

    /// The physics parameters of this config.
    #[must_use]
    pub fn cradle_params(&self) -> CradleParams {
        CradleParams {
            balls: self.cradle.balls,
            radius: self.cradle.radius,
            mass: self.ball_mass(),
            length: self.cradle.length,
            gap: self.cradle.gap,
            gravity: self.cradle.gravity,
            restitution: self.contact.restitution,
            hertz: (self.contact.model == ContactModel::Hertz).then(|| {
                crate::physics::hertz::stiffness(
                    self.contact.youngs_modulus,
                    self.contact.poisson_ratio,
                    self.cradle.radius,
                )
            }),
            dissipation: self.contact.dissipation,
            drag: CradleParams::drag_of(
                self.cradle.air_density,
                self.cradle.drag_coefficient,
                self.cradle.radius,
            ),
        }
    }

    /// The cradle this config starts: its physics, integrator and lifted balls.
    #[must_use]
    pub fn build_cradle(&self) -> crate::physics::Cradle {
        crate::physics::Cradle::new(
            self.cradle_params(),
            self.physics.integrator,
            self.physics.dt,
            self.start.lift,
            self.lift_angle(),
        )
    }

    /// Lift angle in radians.
    #[must_use]
    pub fn lift_angle(&self) -> f64 {
        self.start.angle_deg.to_radians()
    }
}

impl Default for Config {
    fn default() -> Self {
        Self {
            cradle: CradleConfig::default(),
            start: StartConfig::default(),
            contact: ContactConfig::default(),
            physics: PhysicsConfig::default(),
            render: RenderConfig::default(),
            camera: CameraConfig::default(),
            lights: look::default_lights(),
            materials: MaterialsConfig::default(),
            sound: SoundConfig::default(),
        }
    }
}
