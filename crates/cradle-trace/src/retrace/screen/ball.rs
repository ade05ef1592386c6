//! The exact screen box of a ball under each of the screen filter's maps
//! (`super::Map`): tighter than the box of its box's corners.

use super::Map;
use crate::camera::CameraRays;
use glam::{DVec3, Vec3};

/// A plane `n . x + d = 0` as `(n, d)`, in f64.
type Plane4 = (DVec3, f64);

/// The screen box of the image of the ball at `c` of radius `r` under `m`,
/// `[[x0, x1], [y0, y1]]` in pixels, from the screen lines that touch it: a
/// screen column (or row) is a plane through the eye, linear in the column's
/// place `s`; where a point of the ball shows in column `s`, that plane (for a
/// shadow, the plane through the light and the line where it cuts the plane
/// of the shadow; for a mirror image, the plane against the mirrored ball)
/// meets the ball, so `s` lies where the quadratic `dist^2 - r^2` (times the
/// normal's length squared) is not positive: between its roots. `None` where
/// that set is not an interval.
pub(super) fn ball_box(cam: &CameraRays, (c, r): (Vec3, f32), m: &Map) -> Option<[[f32; 2]; 2]> {
    let d = |v: Vec3| v.as_dvec3();
    let (o, f, right, up) = (d(cam.origin), d(cam.forward), d(cam.right), d(cam.up));
    let mut c = d(c);
    // The cast's plane and light (homogeneous: w = 0 for a direction).
    let mut cast: Option<(Plane4, DVec3, f64)> = None;
    match *m {
        Map::Eye => {}
        Map::Mirror { point, normal } => {
            let (p, n) = (d(point), d(normal));
            c -= 2.0 * (c - p).dot(n) * n;
        }
        Map::Cast {
            point,
            normal,
            from,
        } => cast = Some(((d(normal), -d(normal).dot(d(point))), d(from), 1.0)),
        Map::Along {
            point,
            normal,
            along,
        } => cast = Some(((d(normal), -d(normal).dot(d(point))), d(along), 0.0)),
    }
    let through_eye = |n: DVec3| (n, -n.dot(o));
    // Column s: the plane through the eye holding `up` and `forward + right s`;
    // row s: the one holding `right` and `forward + up s`.
    let range = |(a, b): (Plane4, Plane4)| -> Option<[f64; 2]> {
        let at = |p: Plane4, x: DVec3, w: f64| p.0.dot(x) + p.1 * w;
        // Against the cast: the plane through the light and the line where
        // plane p cuts the plane of the shadow, p (pi . L) - pi (p . L).
        let lift = |p: Plane4| match cast {
            None => p,
            Some((pi, l, w)) => {
                let (k, j) = (at(pi, l, w), at(p, l, w));
                (p.0 * k - pi.0 * j, p.1 * k - pi.1 * j)
            }
        };
        let (a, b) = (lift(a), lift(b));
        let r2 = f64::from(r) * f64::from(r);
        let (a0, a1) = (at(a, c, 1.0), at(b, c, 1.0));
        let alpha = a1 * a1 - r2 * b.0.length_squared();
        let beta = 2.0 * (a0 * a1 - r2 * a.0.dot(b.0));
        let gamma = a0 * a0 - r2 * a.0.length_squared();
        let disc = beta * beta - 4.0 * alpha * gamma;
        // Not an interval (or a tiny, ill-conditioned one): the corners decide.
        if alpha <= 1e-9 * (a1 * a1 + r2 * b.0.length_squared()) || disc < 0.0 {
            return None;
        }
        let q = disc.sqrt();
        Some([(-beta - q) / (2.0 * alpha), (-beta + q) / (2.0 * alpha)])
    };
    let sx = range((through_eye(up.cross(f)), through_eye(up.cross(right))))?;
    let sy = range((through_eye(right.cross(f)), through_eye(right.cross(up))))?;
    let (w, h) = (f64::from(cam.width), f64::from(cam.height));
    let px = |s: f64| ((s + 1.0) * 0.5 * w) as f32;
    let py = |s: f64| ((1.0 - s) * 0.5 * h) as f32;
    Some([[px(sx[0]), px(sx[1])], [py(sy[1]), py(sy[0])]])
}
