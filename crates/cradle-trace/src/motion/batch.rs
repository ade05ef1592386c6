//! The moved shapes together ([`NearSet`]) and the motion filter's inner
//! test, eight ray segments at a time: an incremental
//! frame gathers the segments of a row's pixels whose cells meet the moved ones
//! into a [`Batch`], and tests each full batch against each moved object at
//! once (the segments in lanes, the shape's numbers in every lane; an object
//! where it was and where it is as one shape around both), by the boxes and by
//! the distance from the shape's line, which bounds the true distance from
//! below. Only the pairs that test leaves take the exact `Near::meets`, of
//! each of the object's two places. Written
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
use crate::geometry::midway;
use crate::simd::{Build, Kernel, Simd};
use glam::Vec3;

/// Segments per batch: the lanes.
const N: usize = 8;

/// Three lanes of numbers: x, y and z.
type L3<S> = [<S as Simd>::F; 3];

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
        // Worked out when first needed: the lanes left out (`NearSet::with_balls`).
        let mut out: Option<u8> = None;
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
            if maybe != 0 {
                if out.is_none() {
                    out = Some(left_out(s, set, (&p, &q, &d, d2)));
                }
                maybe &= !out.unwrap_or(0);
            }
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

/// The lanes whose segments (from `p` to `q`, `d = q - p`, `d2 = |d|^2`)
/// pass through a moved ball where it was and one where it is
/// (`NearSet::with_balls`): each time the nearest point of the segment to the
/// centre within it and nearer than the radius less [`Near::PAD`] (with
/// the rounding's slack), both ends farther than the radius and the pad.
#[inline(always)]
fn left_out<S: Simd>(s: S, set: &NearSet, (p, q, d, d2): (&L3<S>, &L3<S>, &L3<S>, S::F)) -> u8 {
    let [before, after] = set.balls();
    if before.is_empty() || after.is_empty() {
        return 0;
    }
    let pad = Near::PAD;
    // (No closure: one left as a call is not compiled for AVX2.)
    let mut through = [0u8; 2];
    for (side, balls) in [before, after].into_iter().enumerate() {
        if side == 1 && through[0] == 0 {
            // No segment passes through a ball where it was.
            return 0;
        }
        for &(c, r) in balls {
            let (inner, outer) = (r - pad, r + pad);
            let w = [
                s.splat(c.x) - p[0],
                s.splat(c.y) - p[1],
                s.splat(c.z) - p[2],
            ];
            let v = [
                s.splat(c.x) - q[0],
                s.splat(c.y) - q[1],
                s.splat(c.z) - q[2],
            ];
            let wd = w[0] * d[0] + w[1] * d[1] + w[2] * d[2];
            let cx = w[1] * d[2] - w[2] * d[1];
            let cy = w[2] * d[0] - w[0] * d[2];
            let cz = w[0] * d[1] - w[1] * d[0];
            let c2 = cx * cx + cy * cy + cz * cz;
            let w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let out2 = s.splat(outer * outer * SLACK);
            let deep = S::lt(c2 * s.splat(SLACK), s.splat(inner * inner) * d2)
                & S::lt(s.splat(0.0), wd)
                & S::lt(wd, d2)
                & S::lt(out2, w2)
                & S::lt(out2, v2);
            through[side] |= S::bits(deep);
        }
    }
    through[0] & through[1]
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

    /// A shape of the same kind that holds both `was` and `is` (`None` when
    /// they are of two kinds): for two balls, the ball around the midpoint of
    /// their centres whose radius is theirs and half the distance between
    /// the centres; for two capsules, the capsule between the midpoints of
    /// their ends whose radius is theirs and half the larger distance between
    /// matching ends (a point of either axis lies that near the axis between
    /// the midpoints). The radius is grown by a hundredth of a percent against
    /// the rounding of these sums (and by 1e-6 m); the box holds both boxes.
    /// Two shapes farther apart than twice their radius stay two (`None`): a
    /// shape around both would send the batch test's segments to the exact
    /// test more often than it saves.
    fn around(was: &Near, is: &Near) -> Option<Self> {
        const GROW: f32 = 1.0001;
        let (a, e, r, half, ball) = match (was.shape, is.shape) {
            (NearShape::Sphere(c0, r0), NearShape::Sphere(c1, r1)) => {
                let ((c, _), half) = midway((c0, c0), (c1, c1));
                (c, Vec3::ZERO, r0.max(r1), half, true)
            }
            (NearShape::Capsule(a0, b0, r0), NearShape::Capsule(a1, b1, r1)) => {
                let ((a, b), half) = midway((a0, b0), (a1, b1));
                (a, b - a, r0.max(r1), half, false)
            }
            _ => return None,
        };
        if half > 2.0 * r {
            return None;
        }
        let r = (r + half) * GROW + 1e-6;
        Some(Self {
            lo: was.lo.min(is.lo),
            hi: was.hi.max(is.hi),
            a,
            e,
            r2: r * r,
            ball,
        })
    }
}

/// The moved shapes, each with its motion cells, for testing segments against
/// them all ([`NearSet::meets`], and a row's segments eight at a time,
/// [`Batch`]). The batch test takes them in groups: a moved object where it
/// was and where it is, in one shape that holds both ([`NearSet::moved`]).
#[derive(Debug, Clone, Default)]
pub struct NearSet {
    nears: Vec<(Cells, Near)>,
    /// Each group's numbers for the batch test, and its shapes in `nears`.
    groups: Vec<(Lanes, std::ops::Range<usize>)>,
    /// The moved balls where they were and where they are: centre and radius.
    balls: [Vec<(Vec3, f32)>; 2],
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
        Self {
            nears,
            groups,
            balls: Default::default(),
        }
    }

    /// The set of moved objects, each where it was and where it is with its
    /// cells: the batch test takes each pair as one shape that holds both
    /// ([`Lanes::around`]), then tests the segments it leaves against each of
    /// the two. What the set finds is what [`Self::new`] of the shapes one by
    /// one finds; the batch test has half as many shapes to test.
    #[must_use]
    pub fn moved(pairs: Vec<[(Cells, Near); 2]>) -> Self {
        let mut nears = Vec::with_capacity(2 * pairs.len());
        let mut groups = Vec::with_capacity(pairs.len());
        for [was, is] in pairs {
            let i = nears.len();
            if let Some(both) = Lanes::around(&was.1, &is.1) {
                groups.push((both, i..i + 2));
            } else {
                groups.push((Lanes::of(&was.1), i..i + 1));
                groups.push((Lanes::of(&is.1), i + 1..i + 2));
            }
            nears.extend([was, is]);
        }
        Self {
            nears,
            groups,
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

    /// The groups of shapes: each group's numbers for the batch test and its
    /// shapes, each with its cells.
    pub(crate) fn groups(&self) -> impl Iterator<Item = (&Lanes, &[(Cells, Near)])> {
        self.groups
            .iter()
            .map(|(lanes, at)| (lanes, &self.nears[at.clone()]))
    }

    /// Whether segment `s` comes within one of the shapes whose cells meet
    /// `cells` (and is not left out, [`Self::with_balls`]): what [`Near::meets`]
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
