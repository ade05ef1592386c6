//! Motion tracking for incremental frames: the box every moving object stays in,
//! cut into 32 x 4 x 1 cells, and per pixel the set of cells its rays passed
//! through (one bit each in a `u128`) and the segments of its rays inside the
//! box. `shade` notes both as it traces; `incremental` re-traces the pixels whose
//! cells meet those of moved objects and one of whose segments comes near a moved
//! object, where it was or where it is ([`Near`]).

use super::geometry::{Aabb, Ray};
use glam::Vec3;

/// A set of cells of the motion grid, one bit each.
pub type Cells = u128;

/// The box that holds every moving object at every time, cut into 32 x 4 x 1
/// cells (finest along x, the way the balls swing): a set of cells is a bit mask.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionGrid {
    /// The box.
    pub bounds: Aabb,
    inv_cell: Vec3,
    /// Boxes are widened by this before finding their cells, so that rounding in
    /// a segment's end points never drops a cell it passes through.
    pad: Vec3,
}

impl MotionGrid {
    /// Cells along x, y and z (32 * 4 * 1 = 128, the bits of a mask).
    const N: [usize; 3] = [32, 4, 1];

    /// The grid over `bounds`.
    #[must_use]
    pub fn new(bounds: Aabb) -> Self {
        let size = (bounds.max - bounds.min).max(Vec3::splat(1e-9));
        Self {
            bounds,
            inv_cell: Vec3::new(Self::N[0] as f32, Self::N[1] as f32, Self::N[2] as f32) / size,
            pad: size * 1e-4 + Vec3::splat(1e-6),
        }
    }

    /// The cells a box from `lo` to `hi` overlaps (0 when it misses the grid).
    #[must_use]
    pub fn cells(&self, lo: Vec3, hi: Vec3) -> Cells {
        let (lo, hi) = (lo - self.pad, hi + self.pad);
        if lo.cmpgt(self.bounds.max).any() || hi.cmplt(self.bounds.min).any() {
            return 0;
        }
        let [nx, ny, nz] = Self::N;
        let n = Vec3::new(nx as f32 - 1.0, ny as f32 - 1.0, nz as f32 - 1.0);
        let c0 = ((lo - self.bounds.min) * self.inv_cell)
            .floor()
            .clamp(Vec3::ZERO, n);
        let c1 = ((hi - self.bounds.min) * self.inv_cell)
            .floor()
            .clamp(Vec3::ZERO, n);
        // One run of x bits, repeated for each (y, z) row in range.
        let (x0, x1) = (c0.x as u32, c1.x as u32);
        let run = ((1 << (x1 + 1)) - 1) & !((1 << x0) - 1);
        let mut mask = 0;
        for z in c0.z as usize..=c1.z as usize {
            for y in c0.y as usize..=c1.y as usize {
                mask |= run << ((z * ny + y) * nx);
            }
        }
        mask
    }

    /// The cells the segment of `ray` from its start to `t_max` passes through
    /// (a superset: those of its part inside the box's bounding box).
    #[must_use]
    pub fn segment(&self, ray: &Ray, t_max: f32) -> Cells {
        self.clip(ray, t_max)
            .map_or(0, |s| self.cells(s.a.min(s.b), s.a.max(s.b)))
    }

    /// The part of the segment of `ray` from its start to `t_max` inside the
    /// (padded) box, if any.
    #[must_use]
    pub fn clip(&self, ray: &Ray, t_max: f32) -> Option<Seg> {
        let inv = ray.dir.recip();
        let t1 = (self.bounds.min - self.pad - ray.origin) * inv;
        let t2 = (self.bounds.max + self.pad - ray.origin) * inv;
        let near = t1.min(t2).max_element().max(0.0);
        let far = t1.max(t2).min_element().min(t_max);
        if near > far || far.is_nan() {
            return None;
        }
        Some(Seg {
            a: ray.at(near),
            b: ray.at(far.min(f32::MAX)),
        })
    }
}

/// A piece of a ray inside the motion box, from `a` to `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seg {
    /// Where it enters the box (or starts).
    pub a: Vec3,
    /// Where it leaves the box (or ends).
    pub b: Vec3,
}

/// Which cells of the motion grid the rays of one pixel passed through, and their
/// segments inside its box: a pixel none of whose segments comes near an object
/// that moved keeps its colour.
#[derive(Debug, Clone)]
pub struct Motion {
    /// The grid, or `None` to track nothing.
    pub grid: Option<MotionGrid>,
    /// Cells passed so far.
    pub mask: Cells,
    /// Segments inside the box so far, appended (a row's buffer, lent).
    pub segs: Vec<Seg>,
}

impl Motion {
    /// Tracking on `grid`.
    #[must_use]
    pub fn new(grid: Option<MotionGrid>) -> Self {
        Self::with(grid, Vec::new())
    }

    /// Tracking on `grid`, appending segments to `segs`.
    #[must_use]
    pub fn with(grid: Option<MotionGrid>, segs: Vec<Seg>) -> Self {
        Self {
            grid,
            mask: 0,
            segs,
        }
    }

    /// Notes the segment of `ray` from its start to `t_max`.
    pub(crate) fn segment(&mut self, ray: &Ray, t_max: f32) {
        if let Some(g) = &self.grid
            && let Some(s) = g.clip(ray, t_max)
        {
            self.mask |= g.cells(s.a.min(s.b), s.a.max(s.b));
            self.segs.push(s);
        }
    }
}

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
    pub fn of(shape: &super::scene::Shape) -> Option<Self> {
        use super::scene::Shape;
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
