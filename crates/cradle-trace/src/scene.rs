//! The flat scene: world-space shapes with materials, lights and camera, in f32,
//! with no ECS types. Built fresh each frame by the extract stage.

use glam::Vec3;

/// A world-space shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere { centre: Vec3, radius: f32 },
    /// A finite cylinder with flat caps from `a` to `b`, any axis.
    Cylinder { a: Vec3, b: Vec3, radius: f32 },
    /// An infinite plane through `point` facing `normal` (unit).
    Plane { point: Vec3, normal: Vec3 },
}

/// How a surface looks; colours are linear RGB.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Diffuse colour.
    pub color: Vec3,
    /// Phong specular exponent; `None` for a matt surface.
    pub specular: Option<f32>,
    /// Mirror reflection weight 0..=1.
    pub reflective: f32,
    /// Second checker colour and square size (m).
    pub checker: Option<(Vec3, f32)>,
}

/// One object of the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Object {
    /// Its shape in world space.
    pub shape: Shape,
    /// Its look.
    pub material: Material,
    /// Whether it moves while the cradle swings (balls and strings).
    pub moving: bool,
}

/// A light, its colour already multiplied by its intensity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Light {
    /// Unshadowed light from everywhere.
    Ambient { color: Vec3 },
    /// A point light.
    Point { position: Vec3, color: Vec3 },
    /// Parallel light travelling along `direction` (unit).
    Directional { direction: Vec3, color: Vec3 },
}

/// A pinhole camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Point looked at.
    pub look_at: Vec3,
    /// Vertical field of view (degrees).
    pub fov_deg: f32,
}

/// Everything the tracer needs for one frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Shapes with materials.
    pub objects: Vec<Object>,
    /// Lights.
    pub lights: Vec<Light>,
    /// The camera.
    pub camera: Camera,
    /// Colour of rays that hit nothing.
    pub background: Vec3,
    /// Picture width and height in pixels.
    pub size: (u32, u32),
    /// Mirror bounces after the primary hit.
    pub max_depth: u32,
    /// Samples per pixel (with `adaptive`, only at edges).
    pub samples: u32,
    /// Adaptive anti-aliasing: `Some(t)` traces one sample per pixel, then
    /// `samples` in the pixels whose sRGB colour differs from a 4-neighbour's by
    /// more than `t` (0..=1) in some channel; `None` gives every pixel `samples`.
    pub adaptive: Option<f32>,
    /// A box every moving object stays inside at every time (min, max corners), if
    /// known: pixels whose rays never enter it never change while the rest of the
    /// scene stays the same.
    pub motion_bounds: Option<(Vec3, Vec3)>,
    /// Pixels per side of the blocks traced with one ray each: 1 traces every
    /// pixel; 2 (while the view moves) one ray at the centre of each 2x2
    /// block, the picture then stretched to the whole size (`samples` and
    /// `adaptive` are ignored then).
    pub coarse: u32,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            objects: Vec::new(),
            lights: Vec::new(),
            camera: Camera {
                position: Vec3::new(0.0, 0.0, 1.0),
                look_at: Vec3::ZERO,
                fov_deg: 45.0,
            },
            background: Vec3::ZERO,
            size: (16, 16),
            max_depth: 0,
            samples: 1,
            adaptive: None,
            motion_bounds: None,
            coarse: 1,
        }
    }
}
