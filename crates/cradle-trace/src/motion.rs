//! Motion tracking for incremental frames: the box every moving object stays in,
//! cut into 32 x 2 x 1 cells, and per pixel the set of cells its rays passed
//! through (one bit each in the low 64 bits of a `u128`), the moving objects
//! its rays met ([`HITS`], the high 64), and the segments of its rays inside
//! the box. The scalar path notes them as it traces ([`Record`]; free segments
//! leave no cells: the filter finds those pixels on the screen); `incremental`
//! re-traces the pixels whose rays met a moved object where it was, and those
//! whose cells meet those of moved objects, or that lie where a moved object
//! shows, and one of whose segments comes near a moved object where it is now
//! ([`Near`]). A blocked shadow ray changes only when its blocker leaves: its
//! segment is kept, flagged, where the first blocker found moves (read only
//! when a ball of its bit moved, or where a bit is shared), and dropped where
//! it is still.

use super::geometry::{Aabb, Ray};
use glam::{Vec2, Vec3};

mod batch;
mod near;
mod row;
pub(crate) use batch::Batch;
pub use batch::NearSet;
pub use near::Near;
pub(crate) use near::point_segment;
pub(crate) use row::{BLOCK, RowMotion, SUPER};

/// A set of cells of the motion grid, one bit each.
pub type Cells = u128;

/// The box that holds every moving object at every time, cut into 32 x 2 x 1
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
    /// Cells along x, y and z (32 * 2 * 1 = 64, the low bits of a mask; the
    /// high 64 are [`HITS`]). `cells` counts on rows of 32 x cells and one z
    /// layer.
    const N: [usize; 3] = [32, 2, 1];

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
        self.xy_cells(lo.truncate(), hi.truncate())
    }

    /// [`Self::cells`] of the box of a segment from `a` to `b` that
    /// [`Self::clip`] gave, without the test for a box beside the grid: a
    /// clipped segment lies in the padded box, so that test fails only where
    /// rounding puts the segment's box a unit past the grid's edge, and there
    /// the cells at the edge are given (more cells only make more candidates).
    #[must_use]
    #[inline]
    pub(crate) fn segment_cells(&self, a: Vec3, b: Vec3) -> Cells {
        let pad = self.pad.truncate();
        self.xy_cells(a.min(b).truncate() - pad, a.max(b).truncate() + pad)
    }

    /// The cells of a padded box from `lo` to `hi` in x and y (the grid has
    /// one z layer), clamped to the grid.
    #[inline]
    fn xy_cells(&self, lo: Vec2, hi: Vec2) -> Cells {
        let (min, inv) = (self.bounds.min.truncate(), self.inv_cell.truncate());
        let n = Vec2::new(Self::N[0] as f32 - 1.0, Self::N[1] as f32 - 1.0);
        // Clamped to the grid, then truncated: for the non-negative values left
        // that is the floor, without a call to `floorf` (the portable build has
        // no rounding instruction); NaN clamps to 0 either way.
        let c0 = ((lo - min) * inv).clamp(Vec2::ZERO, n);
        let c1 = ((hi - min) * inv).clamp(Vec2::ZERO, n);
        // One run of x bits (none if x0 > x1), repeated in every row of 32, then
        // the rows y0..=y1 kept (one z layer: rows are y).
        // (Through i32, whose saturating conversion is shorter than u32's.)
        let [x0, y0] = c0.as_ivec2().to_array().map(i32::cast_unsigned);
        let [x1, y1] = c1.as_ivec2().to_array().map(i32::cast_unsigned);
        let run = Cells::from((u32::MAX >> (31 - x1)) & (u32::MAX << x0));
        let every_row = run | run << 32;
        every_row & ROWS[(y0 * 2 + y1) as usize]
    }

    /// The cells the segment of `ray` from its start to `t_max` passes through
    /// (a superset: those of its part inside the box's bounding box).
    #[must_use]
    pub fn segment(&self, ray: &Ray, t_max: f32) -> Cells {
        self.clip(ray, t_max)
            .map_or(0, |s| self.segment_cells(s.a, s.b))
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
        // The last bits of `a.x` and `b.x` are the flags ([`Seg::flagged`],
        // [`Seg::free`]), cleared: a unit in the last place, far within
        // `Near::PAD`.
        let (mut a, mut b) = (ray.at(near), ray.at(far.min(f32::MAX)));
        (a.x, b.x) = (with_last_bit(a.x, false), with_last_bit(b.x, false));
        Some(Seg { a, b })
    }
}

// `cells` counts on rows of 32 x cells and one z layer.
const _: () = assert!(MotionGrid::N[0] == 32 && MotionGrid::N[1] == 2 && MotionGrid::N[2] == 1);

/// The high 64 bits of a pixel's [`Cells`]: the moving objects its rays met
/// (a camera or mirror ray's nearest hit, a shadow ray's blockers), each as
/// [`moving_bits`] gives it.
pub const HITS: Cells = (u64::MAX as Cells) << 64;

/// The bits of [`HITS`] for the moving objects a camera or mirror ray met, or
/// a string that blocked a shadow ray (its segment is kept, flagged).
pub const MET: Cells = (u32::MAX as Cells) << 64;

/// The bits of [`HITS`] for the moving balls that blocked a shadow ray: its
/// segment is kept, flagged ([`Seg::flagged`]).
pub const SHADOW: Cells = (u32::MAX as Cells) << 96;

/// Per object of `objects`, its bit in [`MET`]: the moving objects in order,
/// each its own bit while there are at most 32 of them. Beyond, each is placed
/// in a row of pendulums: the k-th of n balls at k, the k-th of m other
/// moving objects (the strings) at `k * n / m`, so a pendulum's ball and
/// strings share a bit, and [`row_bit`] gives the bit of a place in the row.
/// 0 for an object that never moves.
#[must_use]
pub fn moving_bits(objects: &[crate::scene::Object]) -> Vec<Cells> {
    let ball = |o: &crate::scene::Object| matches!(o.shape, crate::scene::Shape::Sphere { .. });
    let n = objects.iter().filter(|o| o.moving).count();
    let balls = objects.iter().filter(|o| o.moving && ball(o)).count();
    let others = n - balls;
    let (mut rank, mut seen) = (0, [0, 0]);
    objects
        .iter()
        .map(|o| {
            if !o.moving {
                return 0;
            }
            let k = if n <= 32 {
                rank
            } else if ball(o) {
                row_bit(seen[0], balls)
            } else if balls > 0 {
                row_bit(seen[1] * balls / others, balls)
            } else {
                row_bit(seen[1], others)
            };
            rank += 1;
            seen[usize::from(!ball(o))] += 1;
            1 << (64 + k)
        })
        .collect()
}

/// What a shadow ray blocked first by `object`, whose bit among the moving
/// objects is `bit` ([`moving_bits`]), notes: a moving ball's [`SHADOW`] bit
/// (its bit 32 up), another moving object's [`MET`] bit, or nothing for a
/// still one.
#[must_use]
pub(crate) fn blocker_bits(object: &crate::scene::Object, bit: Cells) -> Cells {
    if matches!(object.shape, crate::scene::Shape::Sphere { .. }) {
        bit << 32
    } else {
        bit
    }
}

/// The bit of place `p` in a row of `n` (`p < n`): its own up to 32 places;
/// beyond, 16 bits for each half of the row, one place each at its end and
/// groups that grow towards the middle (the g-th starting `max(g, h g^3 /
/// 4096)` places from the end, `h` the half's length). The pendulums that swing
/// in a long row are those at its ends, so a group holds few that stay still
/// while its others move.
fn row_bit(p: usize, n: usize) -> usize {
    if n <= 32 {
        return p;
    }
    let half = n.div_ceil(2);
    let (d, side) = if p < half { (p, 0) } else { (n - 1 - p, 16) };
    let start = |g: usize| g.max(half * g * g * g / 4096);
    side + (0..16).rev().find(|&g| start(g) <= d).unwrap_or(0)
}

/// The bits of rows `y0..=y1` of x cells at `ROWS[y0 * 2 + y1]` (none where
/// `y0 > y1`).
const ROWS: [Cells; 4] = {
    let mut rows = [0; 4];
    let mut i = 0;
    while i < 4 {
        let (y0, y1) = (i / 2, i % 2);
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

impl Seg {
    /// Whether it is a blocked shadow ray's (the last bit of `a.x`).
    #[must_use]
    #[inline]
    pub fn flagged(&self) -> bool {
        self.a.x.to_bits() & 1 == 1
    }

    /// Flags it ([`Self::flagged`]).
    #[inline]
    pub fn flag(&mut self) {
        self.a.x = with_last_bit(self.a.x, true);
    }

    /// Whether it is a free segment's (`Record::segment`: it left no
    /// cells; the last bit of `b.x`).
    #[must_use]
    #[inline]
    pub fn free(&self) -> bool {
        self.b.x.to_bits() & 1 == 1
    }

    /// Marks it free ([`Self::free`]).
    #[inline]
    pub fn set_free(&mut self) {
        self.b.x = with_last_bit(self.b.x, true);
    }
}

/// `v` with the last bit of its representation set to `on` (where a
/// [`Seg`] keeps its flags).
#[inline]
fn with_last_bit(v: f32, on: bool) -> f32 {
    f32::from_bits(v.to_bits() & !1 | u32::from(on))
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
    /// Notes the moving objects a ray met ([`HITS`] bits).
    fn hit(&mut self, bits: Cells);
    /// The shadow ray whose segment it noted last was blocked, first by an
    /// object whose bits as a blocker are `by` ([`blocker_bits`]): a moving
    /// one's are noted and the segment stays, flagged; a still one (0) keeps
    /// it blocked whatever moves, and the segment goes.
    fn blocked(&mut self, by: Cells);
    /// Whether it notes anything (an untracked frame's does not: the
    /// blockers of its shadow rays need not be found).
    fn tracks(&self) -> bool;
}

/// Notes nothing: the recorder of frames that track no motion.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct NoRecord;

impl Record for NoRecord {
    #[inline]
    fn segment(&mut self, _: &Ray, _: f32, _: bool) {}
    #[inline]
    fn hit(&mut self, _: Cells) {}
    #[inline]
    fn blocked(&mut self, _: Cells) {}
    #[inline]
    fn tracks(&self) -> bool {
        false
    }
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
    /// Where the last segment noted went in `segs`, if it was kept.
    last: Option<usize>,
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
            last: None,
        }
    }
}

impl Record for Motion {
    #[inline]
    fn segment(&mut self, ray: &Ray, t_max: f32, free: bool) {
        let Some(g) = &self.grid else {
            return;
        };
        self.last = None;
        if let Some(mut s) = g.clip(ray, t_max) {
            if free {
                s.set_free();
            } else {
                self.mask |= g.segment_cells(s.a, s.b);
            }
            self.last = Some(self.segs.len());
            self.segs.push(s);
        }
    }

    #[inline]
    fn hit(&mut self, bits: Cells) {
        if self.grid.is_some() {
            self.mask |= bits;
        }
    }

    fn blocked(&mut self, by: Cells) {
        let Some(at) = self.last.take() else {
            return;
        };
        if by == 0 {
            self.segs.truncate(at);
        } else {
            self.segs[at].flag();
            self.mask |= by;
        }
    }

    #[inline]
    fn tracks(&self) -> bool {
        self.grid.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::{MET, Motion, MotionGrid, Record, SHADOW};
    use crate::geometry::{Aabb, Ray};
    use glam::Vec3;

    /// A motion box of 0.8 x 0.4 x 0.2 m around the origin's cradle.
    fn grid() -> MotionGrid {
        MotionGrid::new(Aabb {
            min: Vec3::new(-0.4, 0.0, -0.1),
            max: Vec3::new(0.4, 0.4, 0.1),
        })
    }

    /// A shadow ray's segment, noted, then reported blocked by `by`
    /// ([`super::blocker_bits`]):
    /// what the record keeps.
    fn blocked(by: u128) -> Motion {
        let mut m = Motion::new(Some(grid()));
        let ray = Ray {
            origin: Vec3::new(0.0, 0.05, 0.0),
            dir: Vec3::Y,
        };
        m.segment(&ray, 1.0, false);
        assert_eq!(m.segs.len(), 1, "the segment inside the box is noted");
        m.blocked(by);
        m
    }

    #[test]
    fn a_blocked_shadow_ray_keeps_its_segment_only_for_a_moving_blocker() {
        let bit = 1u128 << 64;
        // Blocked first by a moving ball: kept, flagged, with the ball's
        // shadow bit (the same rank, 32 bits up) and not its hit bit.
        let m = blocked(bit << 32);
        assert_eq!(m.segs.len(), 1);
        assert!(m.segs[0].flagged());
        assert_eq!(m.mask & SHADOW, bit << 32);
        assert_eq!(m.mask & MET, 0);
        // By another moving object (a string): kept, flagged, with the
        // object's hit bit.
        let m = blocked(bit);
        assert_eq!(m.segs.len(), 1);
        assert!(m.segs[0].flagged());
        assert_eq!(m.mask & MET, bit);
        assert_eq!(m.mask & SHADOW, 0);
        // By a still object: the ray stays blocked whatever moves, so
        // nothing of it is kept but the cells it passed.
        let m = blocked(0);
        assert!(m.segs.is_empty());
        assert_eq!(m.mask & (MET | SHADOW), 0);
        assert_ne!(m.mask, 0, "its cells are kept");
    }

    #[test]
    fn a_long_row_gives_its_ends_their_own_bits_and_groups_its_middle() {
        use super::row_bit;
        // Up to 32 places: one bit each.
        assert_eq!(
            (0..32).map(|p| row_bit(p, 32)).collect::<Vec<_>>(),
            (0..32).collect::<Vec<_>>()
        );
        for n in [33, 50, 200, 1000] {
            let bits: Vec<usize> = (0..n).map(|p| row_bit(p, n)).collect();
            // 32 bits, each held by a run of neighbours.
            assert!(bits.iter().all(|&b| b < 32), "{n}");
            for b in 0..32 {
                let at: Vec<usize> = (0..n).filter(|&p| bits[p] == b).collect();
                assert!(!at.is_empty(), "{n}: bit {b} unused");
                assert_eq!(at[at.len() - 1] - at[0] + 1, at.len(), "{n}: bit {b}");
            }
            assert_eq!(bits[0], 0);
            assert_eq!(bits[n - 1], 16);
            // The first three places at each end stand alone.
            for p in 0..3 {
                assert_eq!(
                    bits.iter().filter(|&&b| b == bits[p]).count(),
                    1,
                    "{n}: place {p}"
                );
                assert_eq!(
                    bits.iter().filter(|&&b| b == bits[n - 1 - p]).count(),
                    1,
                    "{n}: place {}",
                    n - 1 - p
                );
            }
        }
    }

    #[test]
    fn a_free_ray_leaves_its_segment_marked_and_no_cells() {
        let mut m = Motion::new(Some(grid()));
        let ray = Ray {
            origin: Vec3::new(0.0, 0.05, 0.0),
            dir: Vec3::X,
        };
        m.segment(&ray, 0.2, true);
        assert_eq!(m.mask, 0);
        m.segment(&ray, 0.2, false);
        assert_ne!(m.mask, 0);
        assert!(m.segs[0].free() && !m.segs[0].flagged());
        assert!(!m.segs[1].free() && !m.segs[1].flagged());
    }

    #[test]
    fn a_report_acts_on_the_last_ray_only() {
        let mut m = Motion::new(Some(grid()));
        let inside = Ray {
            origin: Vec3::new(0.0, 0.05, 0.0),
            dir: Vec3::X,
        };
        m.segment(&inside, 0.2, false);
        // A shadow ray that never enters the box, then blocked: the segment
        // of the ray before it is not its own, and stays as it was.
        let outside = Ray {
            origin: Vec3::new(0.0, 2.0, 0.0),
            dir: Vec3::Y,
        };
        m.segment(&outside, 1.0, false);
        m.blocked(1 << 96);
        assert_eq!(m.segs.len(), 1);
        assert!(!m.segs[0].flagged());
        assert_eq!(m.mask & (MET | SHADOW), 0);
    }

    #[test]
    fn a_box_claims_the_cells_of_its_x_run_in_each_of_its_rows() {
        let grid = grid();
        // Cells are 0.025 wide (x) and 0.2 high (y); boxes well inside cells'
        // interiors (centres on a 0.0125 / 0.1 offset) so padding never
        // reaches a neighbour.
        for (x0, x1, y0, y1) in [
            (0, 0, 0, 0),
            (3, 9, 0, 1),
            (0, 31, 0, 1),
            (31, 31, 1, 1),
            (5, 6, 1, 1),
        ] {
            let at = |x: usize, y: usize| {
                Vec3::new(-0.4 + 0.025 * x as f32 + 0.0125, 0.2 * y as f32 + 0.1, 0.0)
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
        assert_eq!(
            grid.cells(Vec3::splat(-5.0), Vec3::splat(5.0)),
            u128::from(u64::MAX)
        );
    }

    #[test]
    fn a_clipped_segment_claims_the_cells_of_its_box_whichever_way_it_runs() {
        let grid = grid();
        // Rays through the box (x -0.4..0.4, y 0..0.4, z -0.1..0.1) in
        // several directions, clipped, against the cells of each segment's
        // box found the long way.
        let rays = [
            (Vec3::new(-1.0, 0.05, 0.0), Vec3::new(1.0, 0.3, 0.05)),
            (Vec3::new(0.3, 0.9, 0.02), Vec3::new(-0.4, -1.0, -0.1)),
            (Vec3::new(0.0, 0.2, -0.5), Vec3::new(0.01, 0.0, 1.0)),
            (Vec3::new(0.9, 0.35, 0.09), Vec3::new(-1.0, 0.0, 0.0)),
        ];
        for (origin, dir) in rays {
            let ray = Ray { origin, dir };
            let s = grid.clip(&ray, 10.0).expect("the ray crosses the box");
            let want = grid.cells(s.a.min(s.b), s.a.max(s.b));
            assert_ne!(want, 0);
            assert_eq!(grid.segment_cells(s.a, s.b), want, "{ray:?}");
            assert_eq!(grid.segment_cells(s.b, s.a), want, "{ray:?} reversed");
            assert_eq!(grid.segment(&ray, 10.0), want);
        }
        // A segment past the grid's edge in depth, which `cells` gives no
        // cells (a clipped one lies there only by a rounding), still claims
        // the cells of its x and y: more candidates, never fewer.
        let (a, b) = (Vec3::new(0.0, 0.1, 0.1002), Vec3::new(0.1, 0.1, 0.1002));
        assert_eq!(grid.cells(a, b), 0);
        assert_ne!(grid.segment_cells(a, b), 0);
    }
}
