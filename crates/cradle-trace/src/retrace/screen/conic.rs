//! Row by row, where a ball's image under each of the screen filter's maps
//! (`super::Map`) lies: tighter than its screen box, most of all for a shadow,
//! which the box holds as a slanted ellipse in its corners.
//!
//! With `s = (sx, sy, 1)` a point of the screen (-1 to 1 across, `sy` up), the
//! camera ray's direction is `d = M s` (`M`'s columns `right`, `up`,
//! `forward`). What a ray must meet to be in the image is a cone (the ball seen
//! from the eye, or from the light, or along the light's direction, through
//! where the ray meets the plane); the rays in it satisfy `Q(s) = s' A s >= 0`
//! for a symmetric `A`, quadratic in `sx` along a row. Where that set is an
//! ellipse, a band of rows holds the pixels between the least left root and
//! the greatest right root over the band. `Q >= 0` also holds the cone's other
//! half (behind the light, or the ball's mirror image behind the eye): a
//! superset, and the caller meets it with the screen box.

use super::Map;
use crate::camera::CameraRays;
use glam::{DMat3, DVec3, Vec3};

/// The quadratic form of a ball's image over the screen: `Q(s) = s' a s`, the
/// picture's size, and what every band of rows asks of the ellipse: the `sy`
/// it spans (`None`: empty) and the `sy` of its leftmost and rightmost points.
#[derive(Debug, Clone, Copy)]
pub(super) struct Conic {
    a: DMat3,
    size: (f64, f64),
    rows: Option<[f64; 2]>,
    turns: [f64; 2],
}

impl Conic {
    /// The image of the ball at `c` of radius `r` under `m` seen by `cam`, where
    /// it is an ellipse on the screen (`None`: not bounded, or the eye or light
    /// inside the ball).
    pub(super) fn of_ball(cam: &CameraRays, (c, r): (Vec3, f32), m: &Map) -> Option<Self> {
        let d = |v: Vec3| v.as_dvec3();
        let (o, c, r2) = (d(cam.origin), d(c), f64::from(r) * f64::from(r));
        let screen = DMat3::from_cols(d(cam.right), d(cam.up), d(cam.forward));
        // `g g' - k N'N`: the points whose (N s) makes an angle with u within
        // the cone of half-angle asin(r / |u|).
        let cone = |n: DMat3, u: DVec3| {
            let k = u.length_squared() - r2;
            let g = n.transpose() * u;
            (k > 0.0).then(|| outer(g, g) - n.transpose() * n * k)
        };
        let a = match *m {
            Map::Eye => cone(screen, c - o)?,
            Map::Mirror { point, normal } => {
                let (p, n) = (d(point), d(normal));
                cone(screen, c - 2.0 * (c - p).dot(n) * n - o)?
            }
            Map::Cast {
                point,
                normal,
                from,
            } => {
                // (P - L)(n . d), P the ray's point on the plane, is linear in d.
                let (n, l) = (d(normal), d(from));
                let h = n.dot(o - d(point));
                let b = outer(o - l, n) - DMat3::IDENTITY * h;
                cone(b * screen, c - l)?
            }
            Map::Along {
                point,
                normal,
                along,
            } => {
                // v = (c - P)(n . d), linear in d; the line through P along `a`
                // meets the ball where |v x a|^2 <= r^2 |a|^2 (n . d)^2.
                let (n, a) = (d(normal), d(along));
                let b = (outer(c - o, n) + DMat3::IDENTITY * n.dot(o - d(point))) * screen;
                let (g, e) = (b.transpose() * a, screen.transpose() * n);
                let a2 = a.length_squared();
                outer(g, g) + outer(e, e) * (r2 * a2) - b.transpose() * b * a2
            }
        };
        // An ellipse: negative definite across the screen.
        let (axx, axy, ayy) = (a.x_axis.x, a.x_axis.y, a.y_axis.y);
        if !(axx < 0.0 && ayy < 0.0 && axx * ayy - axy * axy > 0.0) {
            return None;
        }
        let (ax1, ay1, a11) = (a.x_axis.z, a.y_axis.z, a.z_axis.z);
        // The rows it spans: where the row's greatest Q, cc - bx^2 / axx, is
        // not negative (a quadratic in y, negative leading term; Q along a row
        // is axx x^2 + 2 bx(y) x + cc(y)).
        let (qa, qb, qc) = (
            ayy - axy * axy / axx,
            ay1 - axy * ax1 / axx,
            a11 - ax1 * ax1 / axx,
        );
        let disc = qb * qb - qa * qc;
        let rows = (disc >= 0.0).then(|| {
            let (ya, yb) = ((-qb + disc.sqrt()) / qa, (-qb - disc.sqrt()) / qa);
            [ya.min(yb), ya.max(yb)]
        });
        // Its leftmost and rightmost points lie where dQ/dy = 0, on the line
        // axy x + ayy y + ay1 = 0.
        let (ex, ey) = (axx - axy * axy / ayy, ax1 - axy * ay1 / ayy);
        let ec = a11 - ay1 * ay1 / ayy;
        let xd = (ey * ey - ex * ec).max(0.0).sqrt();
        let turns = [(-ey + xd) / ex, (-ey - xd) / ex].map(|x| -(axy * x + ay1) / ayy);
        Some(Self {
            a,
            size: (f64::from(cam.width), f64::from(cam.height)),
            rows,
            turns,
        })
    }

    /// The least and greatest picture x (pixels) of the ellipse within the
    /// rows from picture y `y0` to `y1` (`y0 < y1`); `None` where it misses them.
    pub(super) fn band_x(&self, (y0, y1): (f32, f32)) -> Option<(f32, f32)> {
        let (w, h) = self.size;
        let sy = |y: f32| 1.0 - 2.0 * f64::from(y) / h;
        let (lo, hi) = (sy(y1), sy(y0));
        let a = &self.a;
        let (axx, axy, ax1) = (a.x_axis.x, a.x_axis.y, a.x_axis.z);
        let (ayy, ay1, a11) = (a.y_axis.y, a.y_axis.z, a.z_axis.z);
        let row = |y: f64| (axy * y + ax1, ayy * y * y + 2.0 * ay1 * y + a11);
        let [ya, yb] = self.rows?;
        let (c0, c1) = (lo.max(ya), hi.min(yb));
        if c0 > c1 {
            return None;
        }
        // Along the band the left root is convex in y and the right one
        // concave, so each is extreme at its extreme point's y clamped to the
        // band.
        let at = |y: f64| y.clamp(c0, c1);
        let root = |y: f64, side: f64| {
            let (b, c) = row(y);
            let q = (b * b - axx * c).max(0.0).sqrt();
            (-b + side * q) / axx
        };
        let (l, r) = (root(at(self.turns[0]), 1.0), root(at(self.turns[1]), -1.0));
        let px = |x: f64| ((x + 1.0) * 0.5 * w) as f32;
        (l <= r).then(|| (px(l), px(r)))
    }
}

/// `a b'`.
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}
