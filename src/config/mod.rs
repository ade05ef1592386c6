//! The config asset (`assets/cradle.ron`): one struct tree, every field with its
//! unit, default and allowed range. `load` parses and validates it with errors that
//! name the file, line and column; `validate` checks ranges.
//!
//! Every field has a default, so an asset only needs the keys it changes.

mod load;
mod locate;
mod validate;

pub use load::{ConfigError, ConfigSource, DEFAULT_ASSET, load_file, parse};
pub use validate::FieldError;

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
        }
    }
}

/// How the swing starts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StartConfig {
    /// How many balls, from the left, are lifted: 0..=balls. Default 1.
    pub lift: usize,
    /// Lift angle (degrees from the vertical, pulled to the left), 0 <= angle < 180.
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
}

impl Default for ContactConfig {
    fn default() -> Self {
        Self {
            model: ContactModel::Ideal,
            restitution: 1.0,
            youngs_modulus: 2.0e11,
            poisson_ratio: 0.29,
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

/// Picture size and tracing effort.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderConfig {
    /// Width in pixels, 16..=8192. Default 1200.
    pub width: u32,
    /// Height in pixels, 16..=8192. Default 600.
    pub height: u32,
    /// Reflection depth: mirror bounces after the primary hit, 0..=16. Default 3.
    pub max_depth: u32,
    /// Samples per pixel, 1..=64. Default 1. With `adaptive`, only edge pixels
    /// get them.
    pub samples: u32,
    /// Adaptive anti-aliasing: one sample per pixel, then `samples` only where a
    /// pixel differs from a neighbour by more than `adaptive_threshold`. Default false.
    pub adaptive: bool,
    /// Largest sRGB difference (0..=1, of any channel) between a pixel and its
    /// 4-neighbours that adaptive anti-aliasing leaves alone. Default 0.05.
    pub adaptive_threshold: f64,
    /// Tracing threads, 0..=256; 0 uses every core. Default 0.
    pub threads: usize,
    /// Colour of rays that hit nothing (linear RGB). Default a dim blue-grey.
    pub background: Rgb,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            width: 1200,
            height: 600,
            max_depth: 3,
            samples: 1,
            adaptive: false,
            adaptive_threshold: 0.05,
            threads: 0,
            background: [0.05, 0.06, 0.08],
        }
    }
}

/// The pinhole camera.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraConfig {
    /// Eye position (m). Default in front and above: (0, 0.36, 0.6).
    pub position: Vec3,
    /// Point looked at (m), not equal to `position`. Default (0, 0.12, 0).
    pub look_at: Vec3,
    /// Vertical field of view (degrees), 1..=170. Default 31.
    pub fov_deg: f64,
    /// Move the eye back along its line of sight, where needed, until the whole
    /// frame is in view (a long row of balls). Default true; the default camera
    /// already sees the default cradle, so it does not move.
    pub fit: bool,
}

impl Default for CameraConfig {
    fn default() -> Self {
        Self {
            position: [0.0, 0.36, 0.6],
            look_at: [0.0, 0.12, 0.0],
            fov_deg: 31.0,
            fit: true,
        }
    }
}

/// A light source. Intensities are >= 0 multipliers of `color`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum LightConfig {
    /// Light from everywhere, unshadowed.
    Ambient { color: Rgb, intensity: f64 },
    /// A point at `position` (m); falls off with no distance law (like the course
    /// project), shadowed.
    Point {
        position: Vec3,
        color: Rgb,
        intensity: f64,
    },
    /// Parallel light travelling along `direction` (non-zero), shadowed.
    Directional {
        direction: Vec3,
        color: Rgb,
        intensity: f64,
    },
}

/// Default lights: ambient plus two point lights, key and fill.
fn default_lights() -> Vec<LightConfig> {
    vec![
        LightConfig::Ambient {
            color: [1.0, 1.0, 1.0],
            intensity: 0.12,
        },
        LightConfig::Point {
            position: [-0.6, 0.9, 0.8],
            color: [1.0, 0.96, 0.9],
            intensity: 0.8,
        },
        LightConfig::Point {
            position: [0.7, 0.6, 0.5],
            color: [0.85, 0.9, 1.0],
            intensity: 0.45,
        },
    ]
}

/// One surface look.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialConfig {
    /// Diffuse colour (linear RGB, each 0..=1).
    pub color: Rgb,
    /// Phong specular exponent, 1..=10000; `None` for a matt surface.
    pub specular: Option<f64>,
    /// Mirror reflection weight, 0..=1.
    pub reflective: f64,
    /// Second colour of a checker pattern (floor only), or `None` for plain.
    pub checker: Option<Rgb>,
    /// Checker square size (m), > 0.
    pub checker_size: f64,
}

impl Default for MaterialConfig {
    fn default() -> Self {
        Self {
            color: [0.5, 0.5, 0.5],
            specular: None,
            reflective: 0.0,
            checker: None,
            checker_size: 0.1,
        }
    }
}

/// Surface looks of the four kinds of object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialsConfig {
    /// Polished chrome balls.
    pub ball: MaterialConfig,
    /// The strings.
    pub string: MaterialConfig,
    /// Rails and posts.
    pub frame: MaterialConfig,
    /// The floor under the cradle.
    pub floor: MaterialConfig,
}

impl Default for MaterialsConfig {
    fn default() -> Self {
        Self {
            ball: MaterialConfig {
                color: [0.55, 0.56, 0.58],
                specular: Some(120.0),
                reflective: 0.65,
                ..MaterialConfig::default()
            },
            string: MaterialConfig {
                color: [0.85, 0.85, 0.82],
                ..MaterialConfig::default()
            },
            frame: MaterialConfig {
                color: [0.12, 0.12, 0.13],
                specular: Some(40.0),
                reflective: 0.2,
                ..MaterialConfig::default()
            },
            floor: MaterialConfig {
                color: [0.32, 0.22, 0.14],
                specular: Some(20.0),
                reflective: 0.08,
                checker: Some([0.26, 0.17, 0.1]),
                checker_size: 0.05,
            },
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
            lights: default_lights(),
            materials: MaterialsConfig::default(),
        }
    }
}
