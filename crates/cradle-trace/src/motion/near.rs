//! The moved shapes an incremental frame re-traces around: each one grown a
//! little ([`Near`]), and all of them together ([`NearSet`]), eight to a chunk in
//! structure of arrays, so that a ray segment is tested against a whole chunk at
//! once by its distance to each shape's line before the exact distance is taken
//! for the few it leaves.

use super::{Cells, Seg};
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

/// Shapes per chunk of a [`NearSet`].
const CHUNK: usize = 8;

type F8 = [f32; CHUNK];

/// Eight shapes in structure of arrays; unused lanes have an empty box.
#[derive(Debug, Clone, Copy)]
struct Chunk {
    lo: [F8; 3],
    hi: [F8; 3],
    /// A ball's centre, or a string's first end.
    a: [F8; 3],
    /// A string's axis, from its first end to the other (zero for a ball).
    e: [F8; 3],
    /// The grown radius, squared.
    r2: F8,
    /// A ball's lane: all bits set (a NaN), for the blend; a string's: 0.
    ball: F8,
}

/// The moved shapes, each with its motion cells, for testing segments against
/// them all ([`NearSet::meets`]).
#[derive(Debug, Clone, Default)]
pub struct NearSet {
    nears: Vec<(Cells, Near)>,
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "read by the AVX2 build only")
    )]
    chunks: Vec<Chunk>,
}

impl NearSet {
    /// The set of `nears`, each with its cells.
    #[must_use]
    pub fn new(nears: Vec<(Cells, Near)>) -> Self {
        let chunks = nears
            .chunks(CHUNK)
            .map(|c| {
                let mut k = Chunk {
                    lo: [[f32::INFINITY; CHUNK]; 3],
                    hi: [[f32::NEG_INFINITY; CHUNK]; 3],
                    a: [[0.0; CHUNK]; 3],
                    e: [[0.0; CHUNK]; 3],
                    r2: [0.0; CHUNK],
                    ball: [0.0; CHUNK],
                };
                for (i, (_, n)) in c.iter().enumerate() {
                    let (a, e, r, ball) = match n.shape {
                        NearShape::Sphere(c, r) => (c, Vec3::ZERO, r, true),
                        NearShape::Capsule(a, b, r) => (a, b - a, r, false),
                    };
                    for (j, (lo, hi)) in [(n.lo.x, n.hi.x), (n.lo.y, n.hi.y), (n.lo.z, n.hi.z)]
                        .into_iter()
                        .enumerate()
                    {
                        k.lo[j][i] = lo;
                        k.hi[j][i] = hi;
                    }
                    (k.a[0][i], k.a[1][i], k.a[2][i]) = (a.x, a.y, a.z);
                    (k.e[0][i], k.e[1][i], k.e[2][i]) = (e.x, e.y, e.z);
                    k.r2[i] = r * r;
                    k.ball[i] = if ball { f32::from_bits(u32::MAX) } else { 0.0 };
                }
                k
            })
            .collect();
        Self { nears, chunks }
    }

    /// Whether segment `s` comes within one of the shapes whose cells meet
    /// `cells`: what [`Near::meets`] says of some such shape. Where the CPU has
    /// AVX2, a chunk's eight lanes first test at once the boxes and the distance
    /// to each shape's line (a ball's: from its centre to the segment's line; a
    /// string's: between the two lines), which bound the true distance from
    /// below, with the same slack as [`Near::meets`]; only the lanes left take
    /// [`Near::meets`]. Elsewhere each shape takes it in turn.
    #[must_use]
    pub fn meets(&self, s: &Seg, cells: Cells) -> bool {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            return self.meets_with::<true>(s, cells);
        }
        self.meets_with::<false>(s, cells)
    }

    /// [`Self::meets`], with `AVX2` the AVX2 build: inlined into callers
    /// compiled for AVX2 (such as the row filter, `Moved::dirty`), so that the
    /// lanes' test does not stay a call. `AVX2` is set only where the CPU has
    /// AVX2.
    #[expect(
        clippy::inline_always,
        reason = "inlined into the AVX2 build of its caller"
    )]
    #[inline(always)]
    pub(crate) fn meets_with<const AVX2: bool>(&self, s: &Seg, cells: Cells) -> bool {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            let (p, q) = (s.a, s.b);
            let seg = [p, q - p, p.min(q), p.max(q)];
            return self.chunks.iter().enumerate().any(|(ci, k)| {
                // SAFETY: `AVX2` is set only where the CPU has AVX2.
                #[expect(unsafe_code, reason = "the AVX2 build's lane test")]
                let mut maybe = unsafe { k.maybe_avx2(&seg) };
                while maybe != 0 {
                    let i = maybe.trailing_zeros() as usize;
                    maybe &= maybe - 1;
                    let (c, n) = &self.nears[ci * CHUNK + i];
                    if c & cells != 0 && n.meets(s) {
                        return true;
                    }
                }
                false
            });
        }
        self.nears.iter().any(|(c, n)| c & cells != 0 && n.meets(s))
    }
}

#[cfg(target_arch = "x86_64")]
impl Chunk {
    /// A bit per lane whose shape the segment `[p, d, smin, smax]` (from `p`
    /// along `d`, within the box `smin..smax`) may come within.
    #[target_feature(enable = "avx2")]
    #[inline]
    fn maybe_avx2(&self, &[p, d, smin, smax]: &[Vec3; 4]) -> u32 {
        use crate::simd::load8;
        use std::arch::x86_64::{
            _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _mm256_add_ps as add, _mm256_and_ps,
            _mm256_andnot_ps, _mm256_blendv_ps, _mm256_cmp_ps, _mm256_movemask_ps, _mm256_mul_ps,
            _mm256_set1_ps as set, _mm256_sub_ps as sub,
        };
        let k = self;
        let (lo, hi) = (
            [load8(&k.lo[0]), load8(&k.lo[1]), load8(&k.lo[2])],
            [load8(&k.hi[0]), load8(&k.hi[1]), load8(&k.hi[2])],
        );
        let ge = |a, b| _mm256_cmp_ps::<_CMP_GE_OQ>(a, b);
        let le = |a, b| _mm256_cmp_ps::<_CMP_LE_OQ>(a, b);
        let inside = _mm256_and_ps(
            _mm256_and_ps(
                _mm256_and_ps(ge(set(smax.x), lo[0]), ge(set(smax.y), lo[1])),
                _mm256_and_ps(ge(set(smax.z), lo[2]), le(set(smin.x), hi[0])),
            ),
            _mm256_and_ps(le(set(smin.y), hi[1]), le(set(smin.z), hi[2])),
        );
        let mul = |a, b| _mm256_mul_ps(a, b);
        let w = [
            sub(load8(&k.a[0]), set(p.x)),
            sub(load8(&k.a[1]), set(p.y)),
            sub(load8(&k.a[2]), set(p.z)),
        ];
        let (dx, dy, dz) = (set(d.x), set(d.y), set(d.z));
        let d2 = d.length_squared();
        let r2 = load8(&k.r2);
        let slack = set(1.0001);
        let gt = |a, b| _mm256_cmp_ps::<_CMP_GT_OQ>(a, b);
        // A ball: |w x d|^2 / |d|^2 is the squared distance from its centre to
        // the segment's line.
        let cx = sub(mul(w[1], dz), mul(w[2], dy));
        let cy = sub(mul(w[2], dx), mul(w[0], dz));
        let cz = sub(mul(w[0], dy), mul(w[1], dx));
        let c2 = add(add(mul(cx, cx), mul(cy, cy)), mul(cz, cz));
        let ball_far = if d2 > 1e-12 {
            gt(c2, mul(mul(r2, set(d2)), slack))
        } else {
            set(0.0)
        };
        // A string: with n = d x e, (w . n)^2 / |n|^2 is the squared distance
        // between the two lines.
        let e = [load8(&k.e[0]), load8(&k.e[1]), load8(&k.e[2])];
        let nx = sub(mul(dy, e[2]), mul(dz, e[1]));
        let ny = sub(mul(dz, e[0]), mul(dx, e[2]));
        let nz = sub(mul(dx, e[1]), mul(dy, e[0]));
        let n2 = add(add(mul(nx, nx), mul(ny, ny)), mul(nz, nz));
        let apart = add(add(mul(w[0], nx), mul(w[1], ny)), mul(w[2], nz));
        let string_far = _mm256_and_ps(
            gt(mul(apart, apart), mul(mul(r2, n2), slack)),
            gt(n2, set(1e-12)),
        );
        let far = _mm256_blendv_ps(string_far, ball_far, load8(&k.ball));
        _mm256_movemask_ps(_mm256_andnot_ps(far, inside)) as u32
    }
}
