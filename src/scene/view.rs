//! What the tracer sees besides the objects, as the config gives it: the
//! camera as the tracer's, the region of the picture a fitted camera keeps the
//! cradle in, the frame's corners, the lights, and the box the moving objects
//! stay in (from the physics' energy bound). `fit` moves the camera back until
//! all of it is in view and builds the flat scene from these.

use super::layout::Layout;
use crate::config::{CameraConfig, Config, LightConfig, Vec3 as CVec3};
use crate::physics::params::swing_bound;
use crate::trace;
use glam::{DVec3, Vec2, Vec3};

/// The share of the picture's height above the cradle that the fitted camera
/// keeps clear of it: the window's status lines sit there.
pub const FIT_TOP: f32 = 0.12;
/// The share of the height from the top below which the fitted camera keeps
/// the cradle clear: the window's key help and notices sit there.
pub const FIT_BOTTOM: f32 = 0.88;
/// The share of the width the fitted camera keeps clear at each side.
pub const FIT_SIDE: f32 = 0.025;

/// A config vector in the tracer's f32.
pub(crate) fn f32x3(a: CVec3) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

/// The frame's eight corners (posts, rails and feet, with their thickness).
#[must_use]
pub fn frame_corners(config: &Config) -> [DVec3; 8] {
    let c = &config.cradle;
    let layout = Layout::new(config);
    let (x, top, z) = (
        layout.half_width + c.frame_radius,
        c.pivot_height + c.frame_radius,
        c.rail_spread + c.frame_radius,
    );
    [
        DVec3::new(-x, 0.0, -z),
        DVec3::new(x, 0.0, -z),
        DVec3::new(-x, 0.0, z),
        DVec3::new(x, 0.0, z),
        DVec3::new(-x, top, -z),
        DVec3::new(x, top, -z),
        DVec3::new(-x, top, z),
        DVec3::new(x, top, z),
    ]
}

/// A config camera as the tracer's.
#[must_use]
pub fn camera(cam: &CameraConfig) -> trace::Camera {
    trace::Camera {
        position: f32x3(cam.position),
        look_at: f32x3(cam.look_at),
        fov_deg: cam.fov_deg as f32,
    }
}

/// The fit region of a `w x h` picture, its top-left and bottom-right corners
/// in pixels.
#[must_use]
pub fn fit_region(w: u32, h: u32) -> (Vec2, Vec2) {
    let (w, h) = (w as f32, h as f32);
    (
        Vec2::new(FIT_SIDE * w, FIT_TOP * h),
        Vec2::new((1.0 - FIT_SIDE) * w, FIT_BOTTOM * h),
    )
}

/// A config light as the tracer's, its colour times its intensity.
#[must_use]
pub fn light(l: &LightConfig) -> trace::Light {
    let lit = |color: CVec3, intensity: f64| f32x3(color) * intensity as f32;
    match l {
        LightConfig::Ambient { color, intensity } => trace::Light::Ambient {
            color: lit(*color, *intensity),
        },
        LightConfig::Point {
            position,
            color,
            intensity,
        } => trace::Light::Point {
            position: f32x3(*position),
            color: lit(*color, *intensity),
        },
        LightConfig::Directional {
            direction,
            color,
            intensity,
        } => trace::Light::Directional {
            // Normalized in f64: an f32 copy of a tiny or huge vector would lose it.
            direction: glam::DVec3::from(*direction).normalize().as_vec3(),
            color: lit(*color, *intensity),
        },
    }
}

/// A box holding every position balls and strings can take at any time: the
/// physics' energy bound on the swing ([`swing_bound`]), strings running from the
/// rails (at `+-rail_spread`, height `pivot_height`) to the balls.
#[must_use]
pub fn motion_bounds(config: &Config) -> (Vec3, Vec3) {
    let layout = Layout::new(config);
    let c = &config.cradle;
    let theta_max = swing_bound(
        config.physics.integrator,
        config.start.lift,
        config.lift_angle(),
    );
    let side = c.length * theta_max.min(std::f64::consts::FRAC_PI_2).sin();
    let reach = c.radius + c.string_radius;
    let (first, last) = (layout.pivot(0), layout.pivot(c.balls - 1));
    let top = (first.y - c.length * theta_max.cos()).max(first.y);
    let z = c.rail_spread + c.string_radius;
    let lo = DVec3::new(first.x - side - reach, first.y - c.length - reach, -z);
    let hi = DVec3::new(last.x + side + reach, top + reach, z);
    // f32 rounding of the corners must not shrink the box: widen by a micrometre.
    (
        lo.as_vec3() - Vec3::splat(1e-6),
        hi.as_vec3() + Vec3::splat(1e-6),
    )
}
