//! The moved shapes together ([`NearSet`]) and the motion filter's inner
//! tests, eight ray segments at a time: an incremental
//! frame gathers the segments of a row's pixels whose cells meet the moved ones
//! into a [`Batch`], and tests each full batch against each moved object at
//! once (the segments in lanes, the shape's numbers in every lane; each
//! object where it is now), by the boxes and by the distance from the shape's
//! line, which bounds the true distance from below. Only the pairs that test
//! leaves take the exact `Near::meets`. Blocked shadow rays whose blocker is
//! known to have met a moved ball where it was go to a batch of their own,
//! each lane with its pixel's shadow bits in place of cells, and are tested
//! against the balls where they are ([`Batch::test_blocked`]). Written
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
    /// Its cells that meet the moved ones (in a batch of blocked shadow
    /// rays, its pixel's shadow bits of moved balls).
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

    /// For a batch of blocked shadow rays' segments (flagged), each with its
    /// pixel's [`super::SHADOW`] bits of moved balls in place of its cells:
    /// adds to `hit` the pixel of each segment that passes well through none
    /// of the `balls` (each where it was and is, its radius and its shadow
    /// bit) whose bits its pixel holds: its nearest point to the centre
    /// inside it and nearer than the radius less [`Near::PAD`], both its ends
    /// farther than the radius and the pad. Empties the batch.
    #[inline(always)]
    pub(crate) fn test_blocked<S: Simd>(
        &mut self,
        s: S,
        balls: &[(Vec3, Vec3, f32, Cells)],
        hit: &mut RowBits<'_>,
    ) {
        if self.n == 0 {
            return;
        }
        let l3 = |v: &[[f32; N]; 3]| [s.load(&v[0]), s.load(&v[1]), s.load(&v[2])];
        let (p, q) = (l3(&self.p), l3(&self.q));
        let dot = |a: &[S::F; 3], b: &[S::F; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let d2 = dot(&d, &d);
        let zero = s.splat(0.0);
        let pad = Near::PAD;
        let mut still = 0u8;
        for &(_, c1, r, bit) in balls {
            let with = (0..self.n).fold(0u8, |m, i| m | u8::from(self.cells[i] & bit != 0) << i);
            if with & !still == 0 {
                continue;
            }
            let c = [s.splat(c1.x), s.splat(c1.y), s.splat(c1.z)];
            let w = [c[0] - p[0], c[1] - p[1], c[2] - p[2]];
            let v = [c[0] - q[0], c[1] - q[1], c[2] - q[2]];
            let wd = dot(&w, &d);
            let cross = [
                w[1] * d[2] - w[2] * d[1],
                w[2] * d[0] - w[0] * d[2],
                w[0] * d[1] - w[1] * d[0],
            ];
            let c2 = dot(&cross, &cross);
            let (inner, outer) = (r - pad, r + pad);
            let out2 = s.splat(outer * outer * 1.001);
            let through = S::lt(c2 * s.splat(1.001), s.splat(inner * inner) * d2)
                & S::lt(zero, wd)
                & S::lt(wd, d2)
                & S::lt(out2, dot(&w, &w))
                & S::lt(out2, dot(&v, &v));
            still |= S::bits(through) & with;
        }
        let valid = ((1u16 << self.n) - 1) as u8;
        let mut lit = valid & !still;
        while lit != 0 {
            let i = lit.trailing_zeros() as usize;
            lit &= lit - 1;
            hit.set(self.who[i] as usize);
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

#[cfg(test)]
mod tests {
    use super::Batch;
    use crate::bits::BitRoom;
    use crate::motion::{Cells, Near, Seg};
    use crate::simd::{Build, Kernel, Simd};
    use glam::Vec3;

    /// The pixels of `segs` (pixel `i` for segment `i`, every one with shadow
    /// bit `bit`) that [`Batch::test_blocked`] in lane build `build` takes.
    fn lit(
        build: Build,
        segs: &[Seg],
        balls: &[(Vec3, Vec3, f32, Cells)],
        bit: Cells,
    ) -> Vec<usize> {
        struct Run<'a>(&'a [Seg], &'a [(Vec3, Vec3, f32, Cells)], Cells);
        impl Kernel for Run<'_> {
            type Output = Vec<usize>;
            fn run<S: Simd>(self, s: S) -> Vec<usize> {
                let mut room = BitRoom::new();
                let mut hit = room.row(self.0.len());
                let mut batch = Batch::default();
                for (i, seg) in self.0.iter().enumerate() {
                    if batch.push(i as u32, self.2, seg) {
                        batch.test_blocked(s, self.1, &mut hit);
                    }
                }
                batch.test_blocked(s, self.1, &mut hit);
                hit.iter().collect()
            }
        }
        build.run(Run(segs, balls, bit))
    }

    #[test]
    fn a_batch_takes_the_rays_that_pass_well_through_no_ball_of_their_pixel() {
        let r = 0.02;
        let c = Vec3::new(0.1, 0.2, 0.0);
        let bit: Cells = 1 << 96;
        // Rays along y at offsets across the ball, long (ends far outside
        // it) or stopping short of it or inside it; each offset well away
        // from the radius less the pad, so the answer does not hang on
        // rounding.
        let mut segs = Vec::new();
        let mut want = Vec::new();
        for (k, off) in [0.0, 0.005, 0.0150, 0.0195, 0.0205, 0.03, 0.1]
            .into_iter()
            .enumerate()
        {
            for (y0, y1) in [
                (-0.1, 0.3),
                (0.0, 0.15),
                (0.19, 0.21),
                (-0.1, 0.205),
                (0.21, 0.5),
            ] {
                let a = Vec3::new(c.x + off, y0, c.z + 0.001 * k as f32);
                let b = Vec3::new(c.x + off, y1, c.z + 0.001 * k as f32);
                let mut s = Seg { a, b };
                s.flag();
                // Well through: the line passes within the radius less the
                // pad of the centre, its nearest point (at the centre's
                // height) inside the segment, both ends outside the ball
                // and the pad.
                let depth = (off * off + (0.001 * k as f32).powi(2)).sqrt();
                let outside = |e: Vec3| e.distance(c) > r + Near::PAD;
                let through =
                    depth < r - Near::PAD && y0 < c.y && c.y < y1 && outside(a) && outside(b);
                if !through {
                    want.push(segs.len());
                }
                segs.push(s);
            }
        }
        let balls = [(Vec3::ZERO, c, r, bit)];
        for build in Build::all() {
            assert_eq!(lit(build, &segs, &balls, bit), want, "{build:?}");
            // A ball whose bit the pixels do not hold blocks nothing: every
            // ray is taken.
            let other = [(Vec3::ZERO, c, r, bit << 1)];
            let all: Vec<usize> = (0..segs.len()).collect();
            assert_eq!(lit(build, &segs, &other, bit), all, "{build:?}");
        }
    }
}
