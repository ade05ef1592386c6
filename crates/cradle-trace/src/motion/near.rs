//! One moved shape an incremental frame re-traces around, grown a little
//! ([`Near`]), and the exact distance of a ray segment from it: the test the
//! eight-lane one (`super::batch`) leaves the few pairs it cannot settle to.

use super::Seg;
use glam::Vec3;

/// A moved object where it is now, grown by [`Near::PAD`], with its bounding
/// box: a ray segment that stays farther from it cannot meet it.
#[derive(Debug, Clone, Copy)]
pub struct Near {
    pub(super) shape: NearShape,
    pub(super) lo: Vec3,
    pub(super) hi: Vec3,
}

/// The grown shape of a [`Near`].
#[derive(Debug, Clone, Copy)]
pub(super) enum NearShape {
    /// A ball: centre and radius (grown).
    Sphere(Vec3, f32),
    /// A string or rod: its axis from one end to the other and its radius
    /// (grown); the capsule around it holds the cylinder.
    Capsule(Vec3, Vec3, f32),
}

impl Near {
    /// How much the shapes are grown (m): 30 times the 3e-6 m within which the
    /// tracer's hit points lie on a surface (10 m from the eye), and 100 times
    /// the rounding of the f32 distances here (1e-6 m at 10 m), so a segment
    /// that met a shape, or ended on it, is always within reach.
    pub const PAD: f32 = 1e-4;

    /// `shape` grown by [`Self::PAD`]; `None` for a plane (never moving).
    #[must_use]
    pub fn of(shape: &crate::scene::Shape) -> Option<Self> {
        use crate::scene::Shape;
        // The box, grown by twice the pad so f32 rounding cannot cut the shape.
        let (shape, lo, hi, r) = match *shape {
            Shape::Sphere { centre, radius } => (
                NearShape::Sphere(centre, radius + Self::PAD),
                centre,
                centre,
                radius,
            ),
            Shape::Cylinder { a, b, radius } => (
                NearShape::Capsule(a, b, radius + Self::PAD),
                a.min(b),
                a.max(b),
                radius,
            ),
            Shape::Plane { .. } => return None,
        };
        let grow = Vec3::splat(r + 2.0 * Self::PAD);
        Some(Self {
            shape,
            lo: lo - grow,
            hi: hi + grow,
        })
    }

    /// The corners of its box.
    #[must_use]
    pub fn lo(&self) -> Vec3 {
        self.lo
    }

    /// See [`Self::lo`].
    #[must_use]
    pub fn hi(&self) -> Vec3 {
        self.hi
    }

    /// Whether segment `s` comes within the grown shape: first their boxes, then
    /// the distance (at worst it says yes where the answer is no).
    #[must_use]
    pub fn meets(&self, s: &Seg) -> bool {
        if s.a.max(s.b).cmplt(self.lo).any() || s.a.min(s.b).cmpgt(self.hi).any() {
            return false;
        }
        let (p, q) = (s.a, s.b);
        match self.shape {
            NearShape::Sphere(c, r) => point_segment(c, p, q) <= r,
            NearShape::Capsule(a, b, r) => {
                // The distance between the two lines bounds the segments' from
                // below: most segments pass a thin string by more than that.
                let n = (q - p).cross(b - a);
                let n2 = n.length_squared();
                let apart = (p - a).dot(n);
                if apart * apart > r * r * n2 * 1.0001 && n2 > 1e-12 {
                    return false;
                }
                segments_within(p, q, a, b, r)
            }
        }
    }
}

/// Distance from `c` to the segment `p`..`q`.
pub(crate) fn point_segment(c: Vec3, p: Vec3, q: Vec3) -> f32 {
    let d = q - p;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((c - p).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p + d * t).distance(c)
}

/// Whether segments `p`..`q` and `a`..`b` come within `r` of each other.
/// Where the closest points of their lines lie inside both segments, those
/// points are the closest of the segments; else the closest pair has an end
/// of one, so the least of the four end-to-segment distances decides.
fn segments_within(p: Vec3, q: Vec3, a: Vec3, b: Vec3, r: f32) -> bool {
    let (d1, d2, w) = (q - p, b - a, p - a);
    let (aa, ee, bb) = (d1.length_squared(), d2.length_squared(), d1.dot(d2));
    let (c, f) = (d1.dot(w), d2.dot(w));
    let denom = aa * ee - bb * bb;
    if denom > 1e-6 * aa * ee {
        let s = (bb * f - c * ee) / denom;
        let t = (aa * f - bb * c) / denom;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            return (p + d1 * s).distance(a + d2 * t) <= r;
        }
    }
    point_segment(p, a, b) <= r
        || point_segment(q, a, b) <= r
        || point_segment(a, p, q) <= r
        || point_segment(b, p, q) <= r
}
