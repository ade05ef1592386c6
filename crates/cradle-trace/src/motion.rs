//! Motion tracking for incremental frames: the box every moving object stays in,
//! cut into 32 x 4 x 1 cells, and per pixel the set of cells its rays passed
//! through (one bit each in a `u128`) and the segments of its rays inside the
//! box. The scalar path notes both as it traces ([`Record`]; free segments leave
//! no cells: the filter finds those pixels on the screen); `incremental`
//! re-traces the pixels whose cells meet those of moved objects, or that lie
//! where a moved object shows, and one of whose segments comes near a moved
//! object, where it was or where it is ([`Near`]).

use super::geometry::{Aabb, Ray};
use glam::Vec3;

mod batch;
mod near;
mod row;
pub(crate) use batch::Batch;
pub use batch::NearSet;
pub use near::Near;
pub(crate) use row::{BLOCK, RowMotion, SUPER};

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
    /// The box widened by `pad`, where segments are clipped.
    outer: Aabb,
}

impl MotionGrid {
    /// Cells along x, y and z (32 * 4 * 1 = 128, the bits of a mask). `cells`
    /// counts on rows of 32 x cells and one z layer.
    const N: [usize; 3] = [32, 4, 1];

    /// The grid over `bounds`.
    #[must_use]
    pub fn new(bounds: Aabb) -> Self {
        let size = (bounds.max - bounds.min).max(Vec3::splat(1e-9));
        let pad = size * 1e-4 + Vec3::splat(1e-6);
        Self {
            bounds,
            inv_cell: Vec3::new(Self::N[0] as f32, Self::N[1] as f32, Self::N[2] as f32) / size,
            pad,
            outer: Aabb {
                min: bounds.min - pad,
                max: bounds.max + pad,
            },
        }
    }

    /// The cells a box from `lo` to `hi` overlaps (0 when it misses the grid).
    #[must_use]
    #[inline]
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
        // One run of x bits (none if x0 > x1), repeated in every row of 32, then
        // the rows y0..=y1 kept (one z layer: rows are y).
        // (Through i32, whose saturating conversion is shorter than u32's.)
        let [x0, y0, _] = c0.as_ivec3().to_array().map(i32::cast_unsigned);
        let [x1, y1, _] = c1.as_ivec3().to_array().map(i32::cast_unsigned);
        let run = Cells::from((u32::MAX >> (31 - x1)) & (u32::MAX << x0));
        let every_row = run | run << 32 | run << 64 | run << 96;
        every_row & ROWS[(y0 * 4 + y1) as usize]
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
        let t1 = (self.outer.min - ray.origin) * inv;
        let t2 = (self.outer.max - ray.origin) * inv;
        Self::clip_slabs(ray, (t1.min(t2), t1.max(t2)), t_max)
    }

    /// The (padded) box, where [`Self::clip`] clips.
    pub(crate) fn outer(&self) -> &Aabb {
        &self.outer
    }

    /// [`Self::clip`] given where `ray` enters and leaves each slab of the box,
    /// `(t1.min(t2), t1.max(t2))` (the packets compute those over their lanes).
    pub(crate) fn clip_slabs(ray: &Ray, (lo, hi): (Vec3, Vec3), t_max: f32) -> Option<Seg> {
        let near = lo.max_element().max(0.0);
        let far = hi.min_element().min(t_max);
        if near > far || far.is_nan() {
            return None;
        }
        Some(Seg {
            a: ray.at(near),
            b: ray.at(far.min(f32::MAX)),
        })
    }
}

// `cells` counts on rows of 32 x cells and one z layer.
const _: () = assert!(MotionGrid::N[0] == 32 && MotionGrid::N[1] == 4 && MotionGrid::N[2] == 1);

/// The bits of rows `y0..=y1` of x cells at `ROWS[y0 * 4 + y1]` (none where
/// `y0 > y1`).
const ROWS: [Cells; 16] = {
    let mut rows = [0; 16];
    let mut i = 0;
    while i < 16 {
        let (y0, y1) = (i / 4, i % 4);
        let mut y = y0;
        while y <= y1 {
            rows[i] |= (u32::MAX as Cells) << (32 * y);
            y += 1;
        }
        i += 1;
    }
    rows
};

/// A piece of a ray inside the motion box, from `a` to `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seg {
    /// Where it enters the box (or starts).
    pub a: Vec3,
    /// Where it leaves the box (or ends).
    pub b: Vec3,
}

/// Where the scalar path notes each ray's segment for incremental frames: it
/// is generic over this, so an untracked frame notes nothing at no cost
/// ([`NoRecord`]).
pub(crate) trait Record {
    /// Notes the segment of `ray` from its start to `t_max`; a free one (a
    /// camera ray, or a ray from where a camera ray met a plane) without its
    /// cells: whether it comes near a moved shape shows on the screen
    /// (`screen::Spans`).
    fn segment(&mut self, ray: &Ray, t_max: f32, free: bool);
}

/// Notes nothing: the recorder of frames that track no motion.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct NoRecord;

impl Record for NoRecord {
    #[inline]
    fn segment(&mut self, _: &Ray, _: f32, _: bool) {}
}

/// Which cells of the motion grid the rays of one pixel passed through, and their
/// segments inside its box: a pixel none of whose segments comes near an object
/// that moved keeps its colour. The cells leave out the pixel's free segments
/// ([`Record::segment`]), which the incremental filter finds on the screen
/// instead (`screen`).
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
}

impl Record for Motion {
    #[inline]
    fn segment(&mut self, ray: &Ray, t_max: f32, free: bool) {
        let Some(g) = &self.grid else {
            return;
        };
        if let Some(s) = g.clip(ray, t_max) {
            if !free {
                self.mask |= g.cells(s.a.min(s.b), s.a.max(s.b));
            }
            self.segs.push(s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::MotionGrid;
    use crate::geometry::Aabb;
    use glam::Vec3;

    #[test]
    fn a_box_claims_the_cells_of_its_x_run_in_each_of_its_rows() {
        let grid = MotionGrid::new(Aabb {
            min: Vec3::new(-0.4, 0.0, -0.1),
            max: Vec3::new(0.4, 0.4, 0.1),
        });
        // Cells are 0.025 wide (x) and 0.1 high (y); boxes well inside cells'
        // interiors (centres on a 0.0125 / 0.05 offset) so padding never
        // reaches a neighbour.
        for (x0, x1, y0, y1) in [
            (0, 0, 0, 0),
            (3, 9, 1, 2),
            (0, 31, 0, 3),
            (31, 31, 3, 3),
            (5, 6, 2, 3),
        ] {
            let at = |x: usize, y: usize| {
                Vec3::new(-0.4 + 0.025 * x as f32 + 0.0125, 0.1 * y as f32 + 0.05, 0.0)
            };
            let got = grid.cells(at(x0, y0), at(x1, y1));
            let mut want = 0u128;
            for y in y0..=y1 {
                for x in x0..=x1 {
                    want |= 1 << (y * 32 + x);
                }
            }
            assert_eq!(got, want, "x {x0}..={x1}, y {y0}..={y1}");
        }
        // Outside the box: no cells; larger than the box: all of them.
        assert_eq!(grid.cells(Vec3::splat(2.0), Vec3::splat(3.0)), 0);
        assert_eq!(grid.cells(Vec3::splat(-5.0), Vec3::splat(5.0)), u128::MAX);
    }
}
