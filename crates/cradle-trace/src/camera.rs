//! The pinhole camera: a ray through any point of the picture.

use super::geometry::Ray;
use super::scene::Camera;
use glam::Vec3;

/// A camera ready to make rays for a `width` x `height` picture.
#[derive(Debug, Clone, Copy)]
pub struct CameraRays {
    pub(crate) origin: Vec3,
    /// Centre of the image plane at distance 1, and its half-extent vectors.
    pub(crate) forward: Vec3,
    pub(crate) right: Vec3,
    pub(crate) up: Vec3,
    pub(crate) width: f32,
    pub(crate) height: f32,
}

impl CameraRays {
    /// A pinhole at `cam.position` looking at `cam.look_at` with vertical field of
    /// view `cam.fov_deg`; the aspect follows from the picture size.
    #[must_use]
    pub fn new(cam: &Camera, width: u32, height: u32) -> Self {
        let forward = (cam.look_at - cam.position).normalize();
        // World up is +y; looking straight up or down, use +z instead.
        let world_up = if forward.cross(Vec3::Y).length_squared() < 1e-8 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let right = forward.cross(world_up).normalize();
        let up = right.cross(forward);
        let half_h = (0.5 * cam.fov_deg.to_radians()).tan();
        let half_w = half_h * width as f32 / height as f32;
        Self {
            origin: cam.position,
            forward,
            right: right * half_w,
            up: up * half_h,
            width: width as f32,
            height: height as f32,
        }
    }

    /// The picture point (pixels) that `point` projects to, or `None` when it is
    /// not in front of the eye.
    #[must_use]
    pub fn project(&self, point: Vec3) -> Option<(f32, f32)> {
        let v = point - self.origin;
        let depth = v.dot(self.forward);
        if depth <= 1e-6 {
            return None;
        }
        // right and up carry the half-extents of the image plane at distance 1.
        let sx = v.dot(self.right) / (depth * self.right.length_squared());
        let sy = v.dot(self.up) / (depth * self.up.length_squared());
        Some((
            (sx + 1.0) * 0.5 * self.width,
            (1.0 - sy) * 0.5 * self.height,
        ))
    }

    /// The ray through picture point `(x, y)` in pixels, (0, 0) the top-left corner.
    #[must_use]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = 2.0 * x / self.width - 1.0;
        let sy = 1.0 - 2.0 * y / self.height;
        Ray {
            origin: self.origin,
            dir: (self.forward + self.right * sx + self.up * sy).normalize(),
        }
    }
}
