//! The moved shapes an incremental frame re-traces around: each one grown a
//! little ([`Near`]), and all of them together ([`NearSet`]), with each shape's
//! numbers for testing eight ray segments at once (`super::batch`) before the
//! exact distance is taken for the few pairs that test leaves.

use super::batch::{Lanes, meets_one};
use super::{Cells, Seg};
#[cfg(target_arch = "x86_64")]
use crate::simd::Avx2;
use crate::simd::Portable;
use glam::Vec3;

/// A moved object where it was or where it is, grown by [`Near::PAD`], with its
/// bounding box: a ray segment that stays farther from it cannot have met it,
/// nor can it now.
#[derive(Debug, Clone, Copy)]
pub struct Near {
    shape: NearShape,
    lo: Vec3,
    hi: Vec3,
}

/// The grown shape of a [`Near`].
#[derive(Debug, Clone, Copy)]
enum NearShape {
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
                segment_segment(p, q, a, b) <= r
            }
        }
    }
}

/// Distance from `c` to the segment `p`..`q`.
fn point_segment(c: Vec3, p: Vec3, q: Vec3) -> f32 {
    let d = q - p;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((c - p).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p + d * t).distance(c)
}

/// Distance between segments `p`..`q` and `a`..`b`: the least of the four
/// end-to-segment distances and, when the two closest points of the lines lie
/// inside both segments, of theirs (the minimum is at one or the other).
fn segment_segment(p: Vec3, q: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ends = point_segment(p, a, b)
        .min(point_segment(q, a, b))
        .min(point_segment(a, p, q))
        .min(point_segment(b, p, q));
    let (d1, d2, r) = (q - p, b - a, p - a);
    let (aa, ee, bb) = (d1.length_squared(), d2.length_squared(), d1.dot(d2));
    let (c, f) = (d1.dot(r), d2.dot(r));
    let denom = aa * ee - bb * bb;
    if denom <= 1e-6 * aa * ee {
        return ends;
    }
    let s = (bb * f - c * ee) / denom;
    let t = (aa * f - bb * c) / denom;
    if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
        ends.min((p + d1 * s).distance(a + d2 * t))
    } else {
        ends
    }
}

/// The moved shapes, each with its motion cells, for testing segments against
/// them all ([`NearSet::meets`], and a row's segments eight at a time in
/// `super::batch`).
#[derive(Debug, Clone, Default)]
pub struct NearSet {
    nears: Vec<(Cells, Near)>,
    /// Each shape's numbers for the batch test.
    lanes: Vec<Lanes>,
    /// The moved balls where they were and where they are: centre and radius.
    balls: [Vec<(Vec3, f32)>; 2],
}

impl NearSet {
    /// The set of `nears`, each with its cells.
    #[must_use]
    pub fn new(nears: Vec<(Cells, Near)>) -> Self {
        let lanes = nears
            .iter()
            .map(|(_, n)| {
                let (a, e, r, ball) = match n.shape {
                    NearShape::Sphere(c, r) => (c, Vec3::ZERO, r, true),
                    NearShape::Capsule(a, b, r) => (a, b - a, r, false),
                };
                Lanes {
                    lo: n.lo,
                    hi: n.hi,
                    a,
                    e,
                    r2: r * r,
                    ball,
                }
            })
            .collect();
        Self {
            nears,
            lanes,
            balls: Default::default(),
        }
    }

    /// The set with the moved balls where they were (`before`) and where they
    /// are (`after`): [`Self::meets`] then leaves out a segment that passes
    /// through one of each, each time well inside it (deeper than
    /// [`Near::PAD`]) with both its ends well outside. Were it a shadow ray's,
    /// that ray was blocked and still is, so it gives what it gave; and it
    /// cannot be the segment of a ray that ends at its nearest hit, which never
    /// passes through a ball (where it was). So a pixel need not be traced
    /// again for it.
    #[must_use]
    pub fn with_balls(mut self, before: Vec<(Vec3, f32)>, after: Vec<(Vec3, f32)>) -> Self {
        self.balls = [before, after];
        self
    }

    /// The moved balls where they were (side 0) and where they are (side 1),
    /// for [`super::batch::Batch::test`]: a segment that passes well inside one
    /// of each is not taken.
    pub(crate) fn balls(&self) -> &[Vec<(Vec3, f32)>; 2] {
        &self.balls
    }

    /// The shapes, each with its cells.
    pub(crate) fn nears(&self) -> &[(Cells, Near)] {
        &self.nears
    }

    /// Shape `j`'s numbers for the batch test.
    pub(crate) fn lanes(&self, j: usize) -> &Lanes {
        &self.lanes[j]
    }

    /// Whether segment `s` comes within one of the shapes whose cells meet
    /// `cells` (and is not left out, [`Self::with_balls`]): what [`Near::meets`]
    /// says of some such shape, by the batch test of this one segment
    /// (`super::batch`), in the AVX2 build where the CPU has AVX2, else the
    /// portable one.
    #[must_use]
    pub fn meets(&self, s: &Seg, cells: Cells) -> bool {
        #[cfg(target_arch = "x86_64")]
        if let Some(t) = Avx2::detect() {
            // SAFETY: the token proves the CPU has AVX2.
            #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
            return unsafe { meets_avx2(t, self, s, cells) };
        }
        meets_one(Portable, self, s, cells)
    }
}

/// [`meets_one`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn meets_avx2(t: Avx2, set: &NearSet, s: &Seg, cells: Cells) -> bool {
    meets_one(t, set, s, cells)
}
