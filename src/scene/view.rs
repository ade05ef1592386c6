//! What the tracer sees besides the objects, worked out once per spawn: the
//! camera (moved back by `camera.fit` until the frame is in view, using the
//! tracer's own projection), the lights, the render settings, and the box the
//! moving objects stay in (from the physics' energy bound). Spawning stores them
//! in the flat scene; `extract` then only copies transforms.

use super::spawn::Layout;
use crate::config::{CameraConfig, Config, LightConfig, Vec3 as CVec3};
use crate::physics::params::swing_bound;
use crate::trace::{self, camera::CameraRays};
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

/// The camera of `config`, with `camera.fit` moved back along its line of sight
/// until every corner of the frame, and of the box the swing stays in (lift
/// angles over 90 degrees reach above the rails), projects (by the tracer's
/// projection) inside the fit region: [`FIT_SIDE`] clear at each side, and
/// clear of the bands above [`FIT_TOP`] and below [`FIT_BOTTOM`] where the
/// window draws its status, help and notices. A camera that sees all that
/// already, or looks straight down, is left as it is. A row too long to read
/// that way is looked at along its length instead ([`super::long_row`]).
///
/// A pure function of `config`, remembered for the last config on each thread:
/// the window asks for it at every move of a drag that turns the view, and the
/// search for a long row's view costs milliseconds.
#[must_use]
pub fn fitted_camera(config: &Config) -> CameraConfig {
    fitted_camera_within(config, 1.0 - FIT_SIDE)
}

/// [`fitted_camera`] with the fit region's right edge at `right` (a share of
/// the width) instead of [`FIT_SIDE`] from the edge: the window's control
/// panel covers the rest. The camera moves sideways, keeping its direction,
/// so that the cradle sits in the middle of the narrower region.
#[must_use]
pub fn fitted_camera_within(config: &Config, right: f32) -> CameraConfig {
    type Fitted = Option<(Config, u32, CameraConfig)>;
    thread_local! {
        static LAST: std::cell::RefCell<Fitted> = const { std::cell::RefCell::new(None) };
    }
    if let Some(cam) = LAST.with_borrow(|last| {
        last.as_ref()
            .filter(|(c, r, _)| c == config && *r == right.to_bits())
            .map(|(_, _, cam)| cam.clone())
    }) {
        return cam;
    }
    let cam = fit(config, right);
    LAST.set(Some((config.clone(), right.to_bits(), cam.clone())));
    cam
}

/// [`fitted_camera_within`], worked out.
fn fit(config: &Config, right: f32) -> CameraConfig {
    let mut cam = config.camera.clone();
    let (w, h) = (config.render.width, config.render.height);
    let (swing_lo, swing_hi) = motion_bounds(config);
    let swing = (0..8).map(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| f64::from(if i & bit == 0 { lo } else { hi });
        DVec3::new(
            pick(1, swing_lo.x, swing_hi.x),
            pick(2, swing_lo.y, swing_hi.y),
            pick(4, swing_lo.z, swing_hi.z),
        )
    });
    let corners: Vec<DVec3> = frame_corners(config).into_iter().chain(swing).collect();
    let (lo, mut hi) = fit_region(w, h);
    hi.x = hi.x.min(right * w as f32);
    // How far (pixels) the region's middle lies right of the picture's.
    let off_centre = f64::from(0.5 * (lo.x + hi.x) - 0.5 * w as f32);
    let inside = |cam: &CameraConfig| {
        let rays = CameraRays::new(&camera(cam), w, h);
        corners.iter().all(|&p| {
            rays.project(p.as_vec3()).is_some_and(|(x, y)| {
                let at = Vec2::new(x, y);
                at.cmpge(lo).all() && at.cmple(hi).all()
            })
        })
    };
    let look = DVec3::from(cam.look_at);
    let back = DVec3::from(cam.position) - look;
    let sideways = back.cross(DVec3::Y).normalize_or_zero();
    if !cam.fit || sideways == DVec3::ZERO {
        return cam;
    }
    // 2% further each step (the first: as the asset has it): at most ~350
    // steps to 1000 times the distance.
    for i in 0..=350 {
        let back = back * 1.02_f64.powi(i);
        let shift = sideways * (off_centre * pixel_size(&cam, h, back.length()));
        cam.position = (look + back + shift).to_array();
        cam.look_at = (look + shift).to_array();
        if inside(&cam) {
            if i == 0 {
                // The asset's camera sees it all: no other view is looked for.
                return cam;
            }
            break;
        }
    }
    match super::long_row::along_the_row(config, &cam) {
        Some(mut along) => {
            let (eye, target) = (DVec3::from(along.position), DVec3::from(along.look_at));
            let shift = (eye - target).cross(DVec3::Y).normalize_or_zero()
                * (off_centre * pixel_size(&along, h, (eye - target).length()));
            along.position = (eye + shift).to_array();
            along.look_at = (target + shift).to_array();
            along
        }
        None => cam,
    }
}

/// The width (m) one pixel of a picture `h` pixels high covers at `distance`
/// (m) from the eye of `cam`.
fn pixel_size(cam: &CameraConfig, h: u32, distance: f64) -> f64 {
    2.0 * distance * (0.5 * cam.fov_deg.to_radians()).tan() / f64::from(h.max(1))
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

/// The flat scene of `config` without objects: camera, lights and render settings,
/// ready for `extract` to add the objects each frame.
#[must_use]
pub fn static_scene(config: &Config) -> trace::Scene {
    let r = &config.render;
    trace::Scene {
        objects: Vec::new(),
        lights: config.lights.iter().map(light).collect(),
        camera: camera(&fitted_camera(config)),
        background: f32x3(r.background),
        size: (r.width, r.height),
        max_depth: r.max_depth,
        samples: r.samples,
        adaptive: r.adaptive.then_some(r.adaptive_threshold as f32),
        motion_bounds: Some(motion_bounds(config)),
    }
}
