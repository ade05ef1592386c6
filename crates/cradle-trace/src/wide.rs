//! Eight boxes at a time: the bounded objects' boxes stored as structure of
//! arrays, so one ray meets eight of them in one pass of SIMD arithmetic. Each
//! lane computes exactly what [`Aabb::hit`] computes (the same IEEE operations,
//! `f32::min`/`max` for the slabs, no fused multiply-add), so the answer for
//! every box is the scalar one: a scan in chunks takes the same boxes as the
//! scan one box at a time.
//!
//! Used by the secondary-ray queries of `Prepared`
//! (nearest hit, shadow rays) in place of walking the hierarchy, which for a few
//! dozen objects costs more in its node tests than the boxes it skips.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::geometry::{Aabb, Ray, T_MIN};
use super::simd::{Build, Kernel, Simd};
pub(crate) use super::tuning::WIDE_AT_MOST;
use glam::Vec3;

/// Boxes per chunk.
pub(crate) const W: usize = 8;

/// Up to eight boxes and the items they belong to.
#[derive(Debug, Clone)]
pub(crate) struct Chunk {
    min: [[f32; W]; 3],
    max: [[f32; W]; 3],
    items: [u32; W],
    /// Lanes in use: the bits of the first `len` lanes.
    used: u8,
    /// A box strictly around the chunk's boxes ([`Self::hull`]).
    hull: Aabb,
}

/// Boxes in chunks of eight, in the order given.
#[derive(Debug, Clone, Default)]
pub(crate) struct WideBoxes {
    chunks: Vec<Chunk>,
}

/// A list of boxes in chunks of eight, borrowed: a [`WideBoxes`], or one of
/// the lists [`push_chunks`] laid out one after another in a shared vector.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WideList<'a> {
    chunks: &'a [Chunk],
}

/// Appends the boxes of `items` (item, box), in that order, to `chunks` as
/// whole chunks of their own: `chunks[before..after]` is then their list.
pub(crate) fn push_chunks(chunks: &mut Vec<Chunk>, items: impl IntoIterator<Item = (usize, Aabb)>) {
    let first = chunks.len();
    for (n, (item, b)) in items.into_iter().enumerate() {
        let j = n % W;
        if j == 0 {
            chunks.push(Chunk {
                min: [[0.0; W]; 3],
                max: [[0.0; W]; 3],
                items: [0; W],
                used: 0,
                hull: Aabb::EMPTY,
            });
        }
        let c = &mut chunks[first + n / W];
        c.hull = c.hull.union(b);
        for a in 0..3 {
            c.min[a][j] = b.min[a];
            c.max[a][j] = b.max[a];
        }
        c.items[j] = u32::try_from(item).expect("object indices fit in u32");
        c.used |= 1 << j;
    }
    for c in &mut chunks[first..] {
        c.hull = widened(c.hull);
    }
}

/// `b` widened by far more than a rounding step of its coordinates, so that
/// each face lies strictly outside `b`.
fn widened(b: Aabb) -> Aabb {
    let pad = 1e-5 * (1.0 + b.min.abs().max(b.max.abs()).max_element());
    Aabb {
        min: b.min - pad,
        max: b.max + pad,
    }
}

/// The lanes of one chunk the ray meets before `t_max`: bit `j` for lane `j`,
/// in lane build `S`. Lane `j` is [`Aabb::hit`] of that box, operation for
/// operation, NaN rules included: `t1 = (min - o) * inv`, `t2 = (max - o) *
/// inv`; glam's `min` and `max` of vectors pick with `a < b ? a : b` and `a > b
/// ? a : b` (the second operand when either is NaN), `max_element` is `max(x,
/// max(y, z))`; the last `max(T_MIN)` and `min(t_max)` are `f32`'s, which pick
/// the same here, as `T_MIN` and `t_max` are never NaN.
#[inline(always)]
fn lanes<S: Simd>(s: S, c: &Chunk, o: Vec3, inv: Vec3, t_max: f32) -> u8 {
    let (lx, hx) = slab(s, c, 0, (o.x, inv.x));
    let (ly, hy) = slab(s, c, 1, (o.y, inv.y));
    let (lz, hz) = slab(s, c, 2, (o.z, inv.z));
    let near = S::max(S::max(lx, S::max(ly, lz)), s.splat(T_MIN));
    let far = S::min(S::min(hx, S::min(hy, hz)), s.splat(t_max));
    S::bits(S::le(near, far)) & c.used
}

/// The entries and exits of the chunk's slabs along axis `a` (ray origin and
/// inverse direction `o`, `inv` on it). (A function, not a closure: a closure
/// left as a call is not compiled for AVX2.)
#[inline(always)]
fn slab<S: Simd>(s: S, c: &Chunk, a: usize, (o, inv): (f32, f32)) -> (S::F, S::F) {
    let t1 = (s.load(&c.min[a]) - s.splat(o)) * s.splat(inv);
    let t2 = (s.load(&c.max[a]) - s.splat(o)) * s.splat(inv);
    (S::min(t1, t2), S::max(t1, t2))
}

/// [`lanes`] as a lane kernel.
struct ChunkKernel<'k> {
    c: &'k Chunk,
    o: Vec3,
    inv: Vec3,
    t_max: f32,
}

#[expect(
    clippy::inline_always,
    reason = "a kernel inlines into its build's entry point, which compiles it for AVX2 in the AVX2 build"
)]
impl Kernel for ChunkKernel<'_> {
    type Output = u8;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> u8 {
        lanes(s, self.c, self.o, self.inv, self.t_max)
    }
}

impl WideBoxes {
    /// The chunks: each holds the next run's boxes (up to eight), in order.
    #[inline]
    pub(crate) fn chunks(&self) -> &[Chunk] {
        &self.chunks
    }

    /// The boxes of each run of `runs` (item, box) in chunks of their own:
    /// the runs' items, in order.
    pub(crate) fn in_runs(runs: &[Vec<(usize, Aabb)>]) -> Self {
        let mut chunks = Vec::new();
        for run in runs {
            push_chunks(&mut chunks, run.iter().copied());
        }
        Self { chunks }
    }

    /// Its boxes as a list.
    #[inline]
    pub(crate) fn list(&self) -> WideList<'_> {
        WideList {
            chunks: &self.chunks,
        }
    }
}

impl Chunk {
    /// A box holding each of the chunk's boxes strictly inside it (every face
    /// apart): a ray that misses it before `t_max` (`Aabb::hit`'s slab test,
    /// in lanes or not) misses each of them before `t_max` or any smaller
    /// limit. Each slab's entry and exit bound a contained box's (subtraction
    /// and multiplication by one inverse keep their order when rounded), and
    /// `0 * inf` (an origin on a face, a direction along it) arises only on
    /// the hull's faces, where the contained boxes, strictly inside, are missed.
    #[inline]
    pub(crate) fn hull(&self) -> &Aabb {
        &self.hull
    }

    /// The chunk's items, in order.
    #[inline]
    pub(crate) fn items(&self) -> &[u32] {
        &self.items[..self.used.count_ones() as usize]
    }
}

impl<'a> WideList<'a> {
    /// The list of `chunks[range]`, as [`push_chunks`] laid it out.
    #[inline]
    pub(crate) fn of(chunks: &'a [Chunk], range: std::ops::Range<usize>) -> Self {
        Self {
            chunks: &chunks[range],
        }
    }

    /// The items, in order.
    pub(crate) fn items(self) -> impl Iterator<Item = usize> + 'a {
        self.chunks.iter().flat_map(|c| {
            (0..W)
                .filter(|&j| c.used >> j & 1 != 0)
                .map(|j| c.items[j] as usize)
        })
    }

    /// The items with their boxes, in order.
    pub(crate) fn entries(self) -> impl Iterator<Item = (usize, Aabb)> + 'a {
        self.chunks.iter().flat_map(|c| {
            (0..W).filter(|&j| c.used >> j & 1 != 0).map(|j| {
                let b = Aabb {
                    min: Vec3::new(c.min[0][j], c.min[1][j], c.min[2][j]),
                    max: Vec3::new(c.max[0][j], c.max[1][j], c.max[2][j]),
                };
                (c.items[j] as usize, b)
            })
        })
    }

    /// Calls `visit(item, box, t_max)` for every box, in order, that the ray
    /// meets before `t_max`, which is `limit()` asked again at each chunk: a
    /// `visit` whose limit fell within the chunk tests the box again with it.
    /// Stops and returns true as soon as `visit` does.
    #[inline]
    pub(crate) fn scan(
        self,
        ray: &Ray,
        inv: Vec3,
        limit: impl Fn() -> f32,
        mut visit: impl FnMut(usize, &Aabb, f32) -> bool,
    ) -> bool {
        let build = Build::detect();
        for c in self.chunks {
            let t_max = limit();
            let mut bits = build.run(ChunkKernel {
                c,
                o: ray.origin,
                inv,
                t_max,
            });
            while bits != 0 {
                let j = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let b = Aabb {
                    min: Vec3::new(c.min[0][j], c.min[1][j], c.min[2][j]),
                    max: Vec3::new(c.max[0][j], c.max[1][j], c.max[2][j]),
                };
                if visit(c.items[j] as usize, &b, t_max) {
                    return true;
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::{ChunkKernel, W, WideBoxes};
    use crate::geometry::{Aabb, Ray};
    use crate::simd::Build;
    use glam::Vec3;

    /// Both builds of the eight-box test against `Aabb::hit`, box by box.
    fn check(boxes: &[Aabb], ray: &Ray, t_max: f32) {
        let inv = ray.dir.recip();
        let wide = WideBoxes::in_runs(&[boxes.iter().copied().enumerate().collect()]);
        for (k, c) in wide.chunks.iter().enumerate() {
            let want = (0..W).fold(0u8, |bits, j| {
                let i = k * W + j;
                bits | (u8::from(i < boxes.len() && boxes[i].hit(ray, inv, t_max)) << j)
            });
            // The hull: missed only where every box of the chunk is.
            if !c.hull.hit(ray, inv, t_max) {
                assert_eq!(want, 0, "hull of chunk {k} missed, {ray:?}");
            }
            for build in Build::all() {
                let got = build.run(ChunkKernel {
                    c,
                    o: ray.origin,
                    inv,
                    t_max,
                });
                assert_eq!(got, want, "{build:?}, {ray:?}");
            }
        }
    }

    #[test]
    fn eight_boxes_at_once_answer_as_each_box_alone() {
        // Boxes around the origin, flat ones and one of zero size; rays from
        // all around, along the axes (a zero direction component: infinite
        // inverses, NaN slabs where the origin lies on a face), and grazing.
        let mut boxes = Vec::new();
        for i in 0..19 {
            let c = Vec3::new(
                i as f32 * 0.1 - 0.9,
                (i % 3) as f32 * 0.2,
                (i % 5) as f32 * -0.1,
            );
            let e = Vec3::new(0.05, 0.02 * (i % 4) as f32, 0.03);
            boxes.push(Aabb {
                min: c - e,
                max: c + e,
            });
        }
        let mut origins = vec![Vec3::new(0.0, 1.0, 2.0), Vec3::new(-2.0, 0.1, 0.0)];
        origins.push(boxes[3].min);
        origins.push(Vec3::new(boxes[5].max.x, 0.0, 0.0));
        // On the chunks' hulls: corners and faces, where `0 * inf` arises.
        let hulls = WideBoxes::in_runs(&[boxes.iter().copied().enumerate().collect()]);
        for c in &hulls.chunks {
            let (lo, hi) = (c.hull.min, c.hull.max);
            origins.extend([
                lo,
                hi,
                Vec3::new(lo.x, 0.1, 0.0),
                Vec3::new(0.0, hi.y, -0.1),
            ]);
            origins.push(Vec3::new(0.0, lo.y, lo.z));
        }
        let mut seed = 1u32;
        let mut rnd = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        for o in origins {
            let mut dirs = vec![
                Vec3::X,
                -Vec3::X,
                Vec3::Y,
                Vec3::Z,
                Vec3::new(1.0, 0.0, 1.0),
            ];
            for _ in 0..200 {
                dirs.push(Vec3::new(rnd(), rnd(), rnd()));
            }
            for d in dirs {
                let ray = Ray {
                    origin: o,
                    dir: d.normalize(),
                };
                for t_max in [f32::INFINITY, 1.0, 1e-6] {
                    check(&boxes, &ray, t_max);
                }
            }
        }
    }
}
