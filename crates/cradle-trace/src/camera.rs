//! The pinhole camera: a ray through any point of the picture.

use super::geometry::Ray;
use super::scene::Camera;
use glam::{DVec3, Vec3};

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

    /// The picture box `[[x0, x1], [y0, y1]]` (pixels) that holds the image of
    /// the hull of `points` where it lies in front of the eye: the box of the
    /// points in front (as [`Self::project`] places them), opened to each side
    /// an edge from one of them to a point behind runs off the picture (an
    /// edge's image is a line: towards where the edge crosses the eye's plane;
    /// both sides where that crossing lies too near the eye to tell). Empty
    /// (`x0 > x1`) where no point is in front; unbounded where the hull holds
    /// the eye.
    #[must_use]
    pub fn hull_box(&self, points: &[Vec3; 8]) -> [[f32; 2]; 2] {
        let mut r = [[f32::INFINITY, f32::NEG_INFINITY]; 2];
        // Mostly every point lies in front.
        let front = points.iter().try_fold(r, |[x, y], &p| {
            let (px, py) = self.project(p)?;
            Some([[x[0].min(px), x[1].max(px)], [y[0].min(py), y[1].max(py)]])
        });
        if let Some(b) = front.filter(|b| b.iter().flatten().all(|v| v.is_finite())) {
            return b;
        }
        let mut grow = |axis: usize, v: f32| {
            r[axis] = [r[axis][0].min(v), r[axis][1].max(v)];
        };
        // Camera space in f64: across (x grows with it), up (y falls with
        // it), and depth.
        let (right, up, forward) = (
            self.right.as_dvec3(),
            self.up.as_dvec3(),
            self.forward.as_dvec3(),
        );
        let hs = points.map(|p| {
            let v = (p - self.origin).as_dvec3();
            DVec3::new(
                v.dot(right) / right.length_squared(),
                v.dot(up) / up.length_squared(),
                v.dot(forward),
            )
        });
        for (&p, h) in points.iter().zip(&hs) {
            if h.z <= 0.0 {
                continue;
            }
            match self.project(p) {
                Some((x, y)) if x.is_finite() && y.is_finite() => {
                    grow(0, x);
                    grow(1, y);
                }
                // Too near the eye's plane to place: it may be anywhere.
                _ => return [[f32::NEG_INFINITY, f32::INFINITY]; 2],
            }
            for g in hs.iter().filter(|g| g.z <= 0.0) {
                // Where the edge crosses the eye's plane, across and up.
                let c = h + (g - h) * (h.z / (h.z - g.z));
                let tol = 1e-6 * (h.length() + g.length());
                for (axis, (v, sign)) in [(c.x, 1.0), (c.y, -1.0)].into_iter().enumerate() {
                    if v.abs() <= tol {
                        grow(axis, f32::NEG_INFINITY);
                        grow(axis, f32::INFINITY);
                    } else {
                        grow(axis, (sign * v.signum()) as f32 * f32::INFINITY);
                    }
                }
            }
        }
        r
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

#[cfg(test)]
mod tests {
    use super::CameraRays;
    use crate::geometry::Aabb;
    use crate::scene::Camera;
    use glam::Vec3;

    /// A 400 x 200 picture from the origin looking down -z.
    fn cam() -> CameraRays {
        let cam = Camera {
            position: Vec3::ZERO,
            look_at: Vec3::NEG_Z,
            fov_deg: 60.0,
        };
        CameraRays::new(&cam, 400, 200)
    }

    /// The 8 corners of the box from `lo` to `hi`.
    fn corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
        Aabb { min: lo, max: hi }.corners()
    }

    /// Points of the box from `lo` to `hi`, 11 a side, inside and on it.
    fn grid(lo: Vec3, hi: Vec3) -> impl Iterator<Item = Vec3> {
        (0..11 * 11 * 11).map(move |i| {
            let t = Vec3::new((i % 11) as f32, (i / 11 % 11) as f32, (i / 121) as f32) / 10.0;
            lo + (hi - lo) * t
        })
    }

    #[test]
    fn a_hulls_box_holds_what_it_shows_in_front_of_the_eye() {
        let cam = cam();
        let holds = |[[x0, x1], [y0, y1]]: [[f32; 2]; 2], (x, y): (f32, f32)| {
            x0 <= x && x <= x1 && y0 <= y && y <= y1
        };
        // In front: the box of its corners' pictures, bounded.
        let (lo, hi) = (Vec3::new(-0.2, -0.1, -2.0), Vec3::new(0.1, 0.2, -1.0));
        let b = cam.hull_box(&corners(lo, hi));
        assert!(b.iter().flatten().all(|v| v.is_finite()), "{b:?}");
        for p in grid(lo, hi) {
            assert!(holds(b, cam.project(p).expect("in front")), "{p} {b:?}");
        }
        // Reaching behind the eye on its right: what lies in front shows in
        // the right half of the picture only, running off its right side,
        // over every row (as it nears the eye's plane, its rows spread out).
        let (lo, hi) = (Vec3::new(0.5, -0.1, -2.0), Vec3::new(0.7, 0.1, 1.0));
        let b = cam.hull_box(&corners(lo, hi));
        assert!(b[0][0] > 200.0 && b[0][1] == f32::INFINITY, "{b:?}");
        assert_eq!(b[1], [f32::NEG_INFINITY, f32::INFINITY]);
        let mut seen = 0;
        for p in grid(lo, hi) {
            if let Some(q) = cam.project(p) {
                assert!(holds(b, q), "{p} at {q:?}, {b:?}");
                seen += 1;
            }
        }
        assert!(seen > 500, "{seen} points in front");
        // Above the eye and reaching behind it: the rows above the middle
        // only, every column.
        let (lo, hi) = (Vec3::new(-0.1, 0.3, -1.0), Vec3::new(0.1, 0.4, 1.0));
        let b = cam.hull_box(&corners(lo, hi));
        assert_eq!(b[0], [f32::NEG_INFINITY, f32::INFINITY]);
        assert!(b[1][0] == f32::NEG_INFINITY && b[1][1] < 100.0, "{b:?}");
        // Wholly behind: nothing shows.
        let b = cam.hull_box(&corners(Vec3::new(-1.0, -1.0, 0.5), Vec3::ONE));
        assert!(b[0][0] > b[0][1] && b[1][0] > b[1][1], "{b:?}");
        // Holding the eye: anything may show.
        let b = cam.hull_box(&corners(Vec3::splat(-0.1), Vec3::splat(0.1)));
        assert_eq!(b, [[f32::NEG_INFINITY, f32::INFINITY]; 2]);
    }
}
