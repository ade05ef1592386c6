//! The camera the cradle is seen through and the flat scene built on it,
//! worked out once per spawn: the config's camera, with `camera.fit` moved back
//! (by the tracer's own projection) until the frame and the swing are in view,
//! or for a long row the view along it (`long_row`). Spawning stores the scene;
//! `extract` then only copies transforms.

use super::components::Quality;
use super::long_row::along_the_row;
use super::view::{FIT_SIDE, camera, f32x3, fit_region, frame_corners, light, motion_bounds};
use crate::config::{CameraConfig, Config};
use crate::trace::{self, camera::CameraRays};
use glam::{DVec3, Vec2};

/// The camera of `config`, with `camera.fit` moved back along its line of sight
/// until every corner of the frame, and of the box the swing stays in (lift
/// angles over 90 degrees reach above the rails), projects (by the tracer's
/// projection) inside the fit region: [`FIT_SIDE`] clear at each side, and
/// clear of the bands above [`FIT_TOP`](super::view::FIT_TOP) and below
/// [`FIT_BOTTOM`](super::view::FIT_BOTTOM) where the
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
    match along_the_row(config, &cam) {
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

/// The flat scene of `config` without objects: camera, lights and render settings,
/// ready for `extract` to add the objects each frame.
#[must_use]
pub fn static_scene(config: &Config) -> trace::Scene {
    let r = &config.render;
    let mut scene = trace::Scene {
        objects: Vec::new(),
        lights: config.lights.iter().map(light).collect(),
        camera: camera(&fitted_camera(config)),
        background: f32x3(r.background),
        size: (r.width, r.height),
        max_depth: r.max_depth,
        motion_bounds: Some(motion_bounds(config)),
        // Sampling: set just below.
        ..trace::Scene::default()
    };
    Quality::at_rest(r).set_on(&mut scene);
    scene
}
