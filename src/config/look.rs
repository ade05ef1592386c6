//! The config's look of the scene: picture size and tracing effort, camera,
//! lights and materials (every field with its unit, default and range).
//! Spawning turns them into the tracer's types once (`scene::view`).

use super::{Rgb, Vec3};
use serde::{Deserialize, Serialize};

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
    /// Samples per pixel, 1..=64. Default 4. With `adaptive`, only edge pixels
    /// get them.
    pub samples: u32,
    /// Adaptive anti-aliasing: one sample per pixel, then `samples` only where a
    /// pixel differs from a neighbour by more than `adaptive_threshold`. Default true.
    pub adaptive: bool,
    /// Largest sRGB difference (0..=1, of any channel) between a pixel and its
    /// 4-neighbours that adaptive anti-aliasing leaves alone. Default 0.15.
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
            samples: 4,
            adaptive: true,
            adaptive_threshold: 0.15,
            threads: 0,
            background: [0.05, 0.06, 0.08],
        }
    }
}

/// The pinhole camera.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraConfig {
    /// Eye position (m). Default in front and above: (0, 0.41, 0.725).
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
            position: [0.0, 0.41, 0.725],
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
pub(super) fn default_lights() -> Vec<LightConfig> {
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
            // No highlight: a broad one from lights near a long row's floor
            // saturates to white over much of the picture.
            floor: MaterialConfig {
                color: [0.32, 0.22, 0.14],
                specular: None,
                reflective: 0.08,
                checker: Some([0.26, 0.17, 0.1]),
                checker_size: 0.05,
            },
        }
    }
}
