//! Motion tracking for incremental frames: the box every moving object stays in,
//! cut into 32 x 4 x 1 cells, and per pixel the set of cells its rays passed
//! through (one bit each in a `u128`) and the segments of its rays inside the
//! box. `shade` notes both as it traces; `incremental` re-traces the pixels whose
//! cells meet those of moved objects and one of whose segments comes near a moved
//! object, where it was or where it is ([`Near`]).

use super::geometry::{Aabb, Ray};
use glam::Vec3;

mod near;
pub use near::{Near, NearSet};

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
        // Clamped to the grid, then truncated: for the non-negative values left
        // that is the floor, without a call to `floorf` (the portable build has
        // no rounding instruction); NaN clamps to 0 either way.
        let c0 = ((lo - self.bounds.min) * self.inv_cell).clamp(Vec3::ZERO, n);
        let c1 = ((hi - self.bounds.min) * self.inv_cell).clamp(Vec3::ZERO, n);
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
