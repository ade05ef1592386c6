//! The user's view: the asset's (fitted) camera turned around its target (right
//! drag), moved nearer or further (wheel) and shifted sideways (middle drag), as
//! offsets that survive a respawn; C drops them. Window-free, in f64.

use crate::config::{CameraConfig, Config};
use crate::scene::fit::fitted_camera_within;
use crate::scene::view::{FIT_SIDE, camera};
use crate::trace;
use glam::DVec3;

/// Radians of turn per pixel dragged.
const TURN_PER_PIXEL: f64 = 0.005;
/// Distance factor per wheel step.
const ZOOM_PER_STEP: f64 = 0.9;
/// How far up or down the view may tilt (rad): short of straight up or down.
const MAX_PITCH: f64 = 1.45;
/// The eye stays within this of the origin (m), where the f32 tracer is precise
/// (the config's own limit for `camera.position`).
const MAX_EYE: f64 = 10.0;

/// Offsets of the view from the asset's camera.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Orbit {
    yaw: f64,
    pitch: f64,
    /// Log of the distance factor, in wheel steps.
    zoom: f64,
    pan: DVec3,
}

impl Orbit {
    /// Whether the view is the asset's.
    #[must_use]
    pub fn is_home(&self) -> bool {
        *self == Self::default()
    }

    /// Turns the view by a drag of `(dx, dy)` pixels.
    pub fn turn(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * TURN_PER_PIXEL;
        self.pitch += dy * TURN_PER_PIXEL;
    }

    /// Moves nearer (`steps > 0`) or further.
    pub fn zoom(&mut self, steps: f64) {
        self.zoom = (self.zoom + steps).clamp(-20.0, 40.0);
    }

    /// Shifts the view by a drag of `(dx, dy)` pixels of a `height`-pixel picture.
    pub fn pan(&mut self, config: &Config, dx: f64, dy: f64) {
        let cam = self.camera_config(config);
        let (eye, look) = (DVec3::from(cam.position), DVec3::from(cam.look_at));
        let forward = (look - eye).normalize();
        let right = forward.cross(DVec3::Y).normalize_or_zero();
        let up = right.cross(forward);
        // One pixel moves the target by one pixel's width at its distance.
        let per_pixel = 2.0 * (eye - look).length() * (0.5 * cam.fov_deg.to_radians()).tan()
            / f64::from(config.render.height);
        self.pan += (up * dy - right * dx) * per_pixel;
    }

    /// The camera of `config` with these offsets.
    #[must_use]
    pub fn camera_config(&self, config: &Config) -> CameraConfig {
        self.camera_config_within(config, 1.0 - FIT_SIDE)
    }

    /// The camera of `config` with these offsets, fitted left of `right` (a
    /// share of the picture's width; the control panel covers the rest).
    #[must_use]
    pub fn camera_config_within(&self, config: &Config, right: f32) -> CameraConfig {
        let mut cam = fitted_camera_within(config, right);
        if self.is_home() {
            return cam;
        }
        let look = DVec3::from(cam.look_at) + self.pan;
        let back = DVec3::from(cam.position) - DVec3::from(cam.look_at);
        let r0 = back.length();
        let yaw = back.x.atan2(back.z) + self.yaw;
        let pitch =
            ((back.y / r0).clamp(-1.0, 1.0).asin() + self.pitch).clamp(-MAX_PITCH, MAX_PITCH);
        let r = r0 * ZOOM_PER_STEP.powf(self.zoom);
        let dir = DVec3::new(
            pitch.cos() * yaw.sin(),
            pitch.sin(),
            pitch.cos() * yaw.cos(),
        );
        let mut eye = look + dir * r.max(1e-2);
        if eye.abs().max_element() > MAX_EYE {
            // Back towards the target until the eye is in the precise region.
            let k =
                (MAX_EYE - look.abs().max_element()).max(0.0) / (eye - look).abs().max_element();
            eye = look + (eye - look) * k.clamp(0.0, 1.0);
        }
        cam.position = eye.to_array();
        cam.look_at = look.to_array();
        cam
    }

    /// The tracer's camera of `config` with these offsets, fitted left of
    /// `right` (see [`Self::camera_config_within`]).
    #[must_use]
    pub fn camera(&self, config: &Config, right: f32) -> trace::Camera {
        camera(&self.camera_config_within(config, right))
    }
}

#[cfg(test)]
mod tests {
    use super::Orbit;
    use crate::config::Config;
    use glam::DVec3;

    fn eye_and_target(o: &Orbit, c: &Config) -> (DVec3, DVec3) {
        let cam = o.camera_config(c);
        (DVec3::from(cam.position), DVec3::from(cam.look_at))
    }

    #[test]
    fn turning_keeps_the_distance_and_the_target() {
        let c = Config::default();
        let home = Orbit::default();
        let (e0, t0) = eye_and_target(&home, &c);
        let mut o = home;
        o.turn(200.0, -50.0);
        let (e1, t1) = eye_and_target(&o, &c);
        assert!((t1 - t0).length() < 1e-12, "the target stays");
        // The same distance, to round-off of a few trigonometric functions.
        assert!(((e1 - t1).length() - (e0 - t0).length()).abs() < 1e-12);
        assert!((e1 - e0).length() > 0.1, "the eye moved");
    }

    #[test]
    fn zoom_scales_the_distance_and_pan_moves_the_target_sideways() {
        let c = Config::default();
        let (e0, t0) = eye_and_target(&Orbit::default(), &c);
        let mut o = Orbit::default();
        o.zoom(2.0);
        let (e1, t1) = eye_and_target(&o, &c);
        let ratio = (e1 - t1).length() / (e0 - t0).length();
        assert!((ratio - 0.81).abs() < 1e-12, "two steps of 0.9: {ratio}");
        let mut p = Orbit::default();
        p.pan(&c, 100.0, 0.0);
        let (e2, t2) = eye_and_target(&p, &c);
        assert!(
            (t2 - t0).x < -0.01 && (t2 - t0).y.abs() < 1e-12,
            "dragged right, the scene follows"
        );
        assert!(
            ((e2 - t2) - (e0 - t0)).length() < 1e-12,
            "the same direction"
        );
    }

    #[test]
    fn the_eye_stays_where_the_tracer_is_precise() {
        let c = Config::default();
        let mut o = Orbit::default();
        o.zoom(-40.0);
        let (e, _) = eye_and_target(&o, &c);
        assert!(e.abs().max_element() <= 10.0 + 1e-9, "{e}");
        assert!(Orbit::default().is_home());
        assert_eq!(
            Orbit::default().camera_config(&c),
            crate::scene::fit::fitted_camera(&c)
        );
    }
}
