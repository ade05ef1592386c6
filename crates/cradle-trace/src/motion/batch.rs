//! The moved shapes together ([`NearSet`]) and the motion filter's inner
//! test, eight ray segments at a time: an incremental
//! frame gathers the segments of a row's pixels whose cells meet the moved ones
//! into a [`Batch`], and tests each full batch against each moved object at
//! once (the segments in lanes, the shape's numbers in every lane; each
//! object where it is now), by the boxes and by the distance from the shape's
//! line, which bounds the true distance from below. Only the pairs that test
//! leaves take the exact `Near::meets`. Written
//! once over the lane build (`crate::simd`): AVX2 where the CPU has it, the
//! portable build elsewhere; both find the pixels the one-by-one test
//! (`Near::meets` of every segment and shape) finds.

#![expect(
    clippy::inline_always,
    reason = "the batch code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::near::{Near, NearShape};
use super::{Cells, Seg};
use crate::bits::{BitRoom, RowBits};
use crate::simd::{Build, Kernel, Simd};
use glam::Vec3;

/// Segments per batch: the lanes.
const N: usize = 8;

/// Relative slack of the distance bounds (rounding of the f32 products).
const SLACK: f32 = 1.0001;

/// Up to eight segments, each with its pixel and its cells, in structure of
/// arrays. Unused lanes are never tested.
#[derive(Debug, Clone, Default)]
pub(crate) struct Batch {
    n: usize,
    /// Start and end of each segment, axis by axis.
    p: [[f32; N]; 3],
    q: [[f32; N]; 3],
    /// The pixel (index in its row) of each segment.
    who: [u32; N],
    /// Its cells that meet the moved ones.
    cells: [Cells; N],
}

impl Batch {
    /// Adds segment `seg` of pixel `who`, whose cells meeting the moved ones are
    /// `cells`: true when the batch is then full (to [`Self::test`]).
    #[inline(always)]
    pub(crate) fn push(&mut self, who: u32, cells: Cells, seg: &Seg) -> bool {
        let i = self.n;
        for j in 0..3 {
            self.p[j][i] = seg.a[j];
            self.q[j][i] = seg.b[j];
        }
        self.who[i] = who;
        self.cells[i] = cells;
        self.n += 1;
        self.n == N
    }

    /// Tests the batch's segments against the shapes of `set`, and adds pixel
    /// `who` to `hit` for each segment that comes within a shape whose cells
    /// meet its own (`Near::meets`); empties the batch.
    #[inline(always)]
    pub(crate) fn test<S: Simd>(&mut self, s: S, set: &NearSet, hit: &mut RowBits<'_>) {
        if self.n == 0 {
            return;
        }
        let l3 = |v: &[[f32; N]; 3]| [s.load(&v[0]), s.load(&v[1]), s.load(&v[2])];
        let (p, q) = (l3(&self.p), l3(&self.q));
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let lo = [S::min(p[0], q[0]), S::min(p[1], q[1]), S::min(p[2], q[2])];
        let hi = [S::max(p[0], q[0]), S::max(p[1], q[1]), S::max(p[2], q[2])];
        let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let valid = ((1u16 << self.n) - 1) as u8;
        let gt = |a, b| S::lt(b, a);
        let tiny = s.splat(1e-12);
        for (k, members) in set.groups() {
            let inside = S::le(s.splat(k.lo.x), hi[0])
                & S::le(s.splat(k.lo.y), hi[1])
                & S::le(s.splat(k.lo.z), hi[2])
                & S::le(lo[0], s.splat(k.hi.x))
                & S::le(lo[1], s.splat(k.hi.y))
                & S::le(lo[2], s.splat(k.hi.z));
            let inside = S::bits(inside) & valid;
            if inside == 0 {
                continue;
            }
            let w = [
                s.splat(k.a.x) - p[0],
                s.splat(k.a.y) - p[1],
                s.splat(k.a.z) - p[2],
            ];
            let r2 = s.splat(k.r2);
            let far = if k.ball {
                // |w x d|^2 / |d|^2: the squared distance from the centre to
                // the segment's line.
                let cx = w[1] * d[2] - w[2] * d[1];
                let cy = w[2] * d[0] - w[0] * d[2];
                let cz = w[0] * d[1] - w[1] * d[0];
                let c2 = cx * cx + cy * cy + cz * cz;
                gt(c2, r2 * d2 * s.splat(SLACK)) & gt(d2, tiny)
            } else {
                // With n = d x e, (w . n)^2 / |n|^2: the squared distance
                // between the two lines.
                let e = [s.splat(k.e.x), s.splat(k.e.y), s.splat(k.e.z)];
                let nx = d[1] * e[2] - d[2] * e[1];
                let ny = d[2] * e[0] - d[0] * e[2];
                let nz = d[0] * e[1] - d[1] * e[0];
                let n2 = nx * nx + ny * ny + nz * nz;
                let apart = w[0] * nx + w[1] * ny + w[2] * nz;
                gt(apart * apart, r2 * n2 * s.splat(SLACK)) & gt(n2, tiny)
            };
            let mut maybe = inside & !S::bits(far);
            while maybe != 0 {
                let i = maybe.trailing_zeros() as usize;
                maybe &= maybe - 1;
                let who = self.who[i];
                let at = |v: &[[f32; N]; 3]| Vec3::new(v[0][i], v[1][i], v[2][i]);
                let seg = Seg {
                    a: at(&self.p),
                    b: at(&self.q),
                };
                if !hit.has(who as usize)
                    && members
                        .iter()
                        .any(|(cells, near)| cells & self.cells[i] != 0 && near.meets(&seg))
                {
                    hit.set(who as usize);
                }
            }
        }
        self.n = 0;
    }
}

/// A moved shape's numbers for [`Batch::test`], or those of a shape that
/// holds a group of them: its box, a ball's centre or a string's first end
/// (`a`), a string's axis (`e`, zero for a ball), and its grown radius squared.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lanes {
    pub(crate) lo: Vec3,
    pub(crate) hi: Vec3,
    pub(crate) a: Vec3,
    pub(crate) e: Vec3,
    pub(crate) r2: f32,
    pub(crate) ball: bool,
}

impl Lanes {
    /// The numbers of `n`.
    fn of(n: &Near) -> Self {
        let (a, e, r, ball) = match n.shape {
            NearShape::Sphere(c, r) => (c, Vec3::ZERO, r, true),
            NearShape::Capsule(a, b, r) => (a, b - a, r, false),
        };
        Self {
            lo: n.lo,
            hi: n.hi,
            a,
            e,
            r2: r * r,
            ball,
        }
    }
}

/// The moved shapes, each with its motion cells, for testing segments against
/// them all ([`NearSet::meets`], and a row's segments eight at a time,
/// [`Batch`]), each a group of its own.
#[derive(Debug, Clone, Default)]
pub struct NearSet {
    nears: Vec<(Cells, Near)>,
    /// Each group's numbers for the batch test, and its shapes in `nears`.
    groups: Vec<(Lanes, std::ops::Range<usize>)>,
}

impl NearSet {
    /// The set of `nears`, each with its cells, each a group of its own.
    #[must_use]
    pub fn new(nears: Vec<(Cells, Near)>) -> Self {
        let groups = nears
            .iter()
            .enumerate()
            .map(|(i, (_, n))| (Lanes::of(n), i..i + 1))
            .collect();
        Self { nears, groups }
    }

    /// The groups of shapes: each group's numbers for the batch test and its
    /// shapes, each with its cells.
    pub(crate) fn groups(&self) -> impl Iterator<Item = (&Lanes, &[(Cells, Near)])> {
        self.groups
            .iter()
            .map(|(lanes, at)| (lanes, &self.nears[at.clone()]))
    }

    /// Whether segment `s` comes within one of the shapes whose cells meet
    /// `cells`: what [`Near::meets`]
    /// says of some such shape, by the batch test of this one segment
    /// (`super::batch`), in the AVX2 build where the CPU has AVX2, else the
    /// portable one.
    #[must_use]
    pub fn meets(&self, s: &Seg, cells: Cells) -> bool {
        Build::detect().run(MeetsOne {
            set: self,
            seg: s,
            cells,
        })
    }
}

/// [`NearSet::meets`] as a lane kernel: the batch test of one segment.
struct MeetsOne<'k> {
    set: &'k NearSet,
    seg: &'k Seg,
    cells: Cells,
}

impl Kernel for MeetsOne<'_> {
    type Output = bool;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> bool {
        let mut batch = Batch::default();
        let mut room = BitRoom::new();
        let mut hit = room.row(1);
        batch.push(0, self.cells, self.seg);
        batch.test(s, self.set, &mut hit);
        hit.has(0)
    }
}
