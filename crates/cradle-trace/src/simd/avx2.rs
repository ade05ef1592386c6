//! The AVX2 lane build: each lane operation one AVX instruction on a 256-bit
//! register. Its values exist only where the CPU has AVX2: they are made through
//! the [`Avx2`] token, which only [`Avx2::detect`] hands out, and every
//! operation here is inlined into a caller compiled for AVX2 (the intrinsics
//! inline once the kernel is). `vroundps` towards minus infinity is `floor`;
//! comparisons are ordered (false for NaN).

#![expect(
    clippy::inline_always,
    reason = "each operation must inline into its kernel, compiled for AVX2"
)]
#![expect(
    unsafe_code,
    reason = "AVX intrinsics, run only where an `Avx2` token proves the CPU has AVX2"
)]

use super::{Kernel, Simd};
use crate::color::{BUCKET_SHIFT, FIRST_BUCKET, IN_BUCKET, srgb_entries};
use std::arch::x86_64::{
    __m256, __m256i, _CMP_LE_OQ, _CMP_LT_OQ, _MM_HINT_T0, _mm_loadu_si128, _mm_prefetch,
    _mm256_add_epi32, _mm256_add_ps, _mm256_and_ps, _mm256_and_si256, _mm256_andnot_ps,
    _mm256_blendv_ps, _mm256_broadcastsi128_si256, _mm256_castps_si256, _mm256_castsi256_pd,
    _mm256_castsi256_ps, _mm256_cmp_ps, _mm256_cmpeq_epi32, _mm256_cmpeq_epi64, _mm256_cmpgt_epi32,
    _mm256_cvttps_epi32, _mm256_div_ps, _mm256_floor_ps, _mm256_i32gather_epi32, _mm256_loadu_ps,
    _mm256_loadu_si256, _mm256_max_epi32, _mm256_max_ps, _mm256_min_ps, _mm256_movemask_pd,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_ps, _mm256_or_si256, _mm256_set1_epi32,
    _mm256_set1_ps, _mm256_setr_epi32, _mm256_setzero_ps, _mm256_setzero_si256, _mm256_slli_epi32,
    _mm256_sqrt_ps, _mm256_srli_epi32, _mm256_storeu_ps, _mm256_storeu_si256, _mm256_sub_epi32,
    _mm256_sub_ps, _mm256_xor_ps,
};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// The AVX2 token: proof that the CPU has AVX2.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2(());

impl Avx2 {
    /// The token, where the AVX2 build is to run (`super::avx2`).
    #[inline]
    pub(crate) fn detect() -> Option<Self> {
        super::avx2().then_some(Self(()))
    }
}

/// `k` in the AVX2 build, compiled for AVX2 (no FMA, which AVX2 does not
/// imply): the kernel inlines here, and the lane operations into it.
#[target_feature(enable = "avx2")]
fn run_avx2<K: Kernel>(s: Avx2, k: K) -> K::Output {
    k.run(s)
}

/// Eight floats in an AVX register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct A8(__m256);

/// Eight conditions: all ones in a set lane, zero elsewhere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AM(__m256);

macro_rules! binary {
    ($tr:ident, $f:ident, $ty:ident, $op:ident) => {
        impl $tr for $ty {
            type Output = $ty;
            #[inline(always)]
            fn $f(self, b: $ty) -> $ty {
                // SAFETY: a value of this type exists only where the CPU has AVX2.
                $ty(unsafe { $op(self.0, b.0) })
            }
        }
    };
}
binary!(Add, add, A8, _mm256_add_ps);
binary!(Sub, sub, A8, _mm256_sub_ps);
binary!(Mul, mul, A8, _mm256_mul_ps);
binary!(Div, div, A8, _mm256_div_ps);
binary!(BitAnd, bitand, AM, _mm256_and_ps);
binary!(BitOr, bitor, AM, _mm256_or_ps);

impl Neg for A8 {
    type Output = A8;
    #[inline(always)]
    fn neg(self) -> A8 {
        // SAFETY: as for every A8, the CPU has AVX2.
        A8(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

impl Not for AM {
    type Output = AM;
    #[inline(always)]
    fn not(self) -> AM {
        // SAFETY: as for every AM, the CPU has AVX2.
        AM(unsafe { _mm256_xor_ps(self.0, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) })
    }
}

impl Simd for Avx2 {
    type F = A8;
    type M = AM;

    #[inline(always)]
    fn splat(self, v: f32) -> A8 {
        // SAFETY: the token proves the CPU has AVX2.
        A8(unsafe { _mm256_set1_ps(v) })
    }
    #[inline(always)]
    fn load(self, v: &[f32; 8]) -> A8 {
        // SAFETY: the token proves AVX2; the load reads exactly the eight floats of `v`.
        A8(unsafe { _mm256_loadu_ps(v.as_ptr()) })
    }
    #[inline(always)]
    fn mask(self, bits: u8) -> AM {
        // SAFETY: the token proves the CPU has AVX2.
        AM(unsafe {
            let each = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let set = _mm256_and_si256(_mm256_set1_epi32(i32::from(bits)), each);
            _mm256_castsi256_ps(_mm256_cmpeq_epi32(set, each))
        })
    }
    #[inline(always)]
    fn store(v: A8) -> [f32; 8] {
        let mut out = [0.0; 8];
        // SAFETY: the value proves AVX2; the store writes exactly the eight floats of `out`.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v.0) };
        out
    }
    #[inline(always)]
    fn bits(m: AM) -> u8 {
        // SAFETY: the value proves AVX2. Eight sign bits: a value below 256.
        (unsafe { _mm256_movemask_ps(m.0) }) as u8
    }
    #[inline(always)]
    fn sqrt(v: A8) -> A8 {
        // SAFETY: the value proves AVX2.
        A8(unsafe { _mm256_sqrt_ps(v.0) })
    }
    #[inline(always)]
    fn abs(v: A8) -> A8 {
        // SAFETY: the value proves AVX2.
        A8(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), v.0) })
    }
    #[inline(always)]
    fn min(a: A8, b: A8) -> A8 {
        // SAFETY: the values prove AVX2. `vminps` is `a < b ? a : b`.
        A8(unsafe { _mm256_min_ps(a.0, b.0) })
    }
    #[inline(always)]
    fn max(a: A8, b: A8) -> A8 {
        // SAFETY: the values prove AVX2. `vmaxps` is `a > b ? a : b`.
        A8(unsafe { _mm256_max_ps(a.0, b.0) })
    }
    #[inline(always)]
    fn trunc(v: A8) -> [i32; 8] {
        let mut out = [0; 8];
        // SAFETY: the value proves AVX2; the store writes exactly the eight i32 of `out`.
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast(), _mm256_cvttps_epi32(v.0)) };
        out
    }
    #[inline(always)]
    fn floor_small(v: A8) -> A8 {
        // SAFETY: the value proves AVX2.
        A8(unsafe { _mm256_floor_ps(v.0) })
    }
    #[inline(always)]
    fn lt(a: A8, b: A8) -> AM {
        // SAFETY: the values prove AVX2.
        AM(unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(a.0, b.0) })
    }
    #[inline(always)]
    fn le(a: A8, b: A8) -> AM {
        // SAFETY: the values prove AVX2.
        AM(unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(a.0, b.0) })
    }
    #[inline(always)]
    fn select(m: AM, a: A8, b: A8) -> A8 {
        // SAFETY: the values prove AVX2.
        A8(unsafe { _mm256_blendv_ps(b.0, a.0, m.0) })
    }
    #[inline(always)]
    fn prefetch<T>(self, v: *const T) {
        // SAFETY: the token proves AVX2 (and so SSE); a prefetch reads
        // nothing the program sees and never faults, whatever the address.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(v.cast()) }
    }
    #[inline(always)]
    fn meeting(self, v: &[u128; 8], with: u128) -> u8 {
        // SAFETY: the token proves AVX2; the loads read the 16 bytes of
        // `with` and, four times, 32 bytes of `v`'s 128.
        let zero = unsafe {
            let w = _mm256_broadcastsi128_si256(_mm_loadu_si128(std::ptr::from_ref(&with).cast()));
            let half = |j: usize| {
                let x = _mm256_loadu_si256(v.as_ptr().add(2 * j).cast());
                let z = _mm256_cmpeq_epi64(_mm256_and_si256(x, w), _mm256_setzero_si256());
                _mm256_movemask_pd(_mm256_castsi256_pd(z)) as u32
            };
            half(0) | half(1) << 4 | half(2) << 8 | half(3) << 12
        };
        // Bit 2i and 2i+1: the low and high halves of `v[i] & with` are
        // zero; a set is empty where both are.
        let mut m = !(zero & zero >> 1) & 0x5555;
        m = (m | m >> 1) & 0x3333;
        m = (m | m >> 2) & 0x0F0F;
        m = (m | m >> 4) & 0x00FF;
        m as u8
    }
    #[inline]
    fn enter<K: Kernel>(self, k: K) -> K::Output {
        // SAFETY: the token proves the CPU has AVX2, the one feature `run_avx2`
        // is compiled for.
        unsafe { run_avx2(self, k) }
    }
    /// Per channel the scalar steps of `srgb8`: the same clamp (`max` with 0
    /// takes 0 for NaN and -0), the bucket's entry by one gather, one
    /// comparison of bits; the channels are packed in the registers.
    #[inline(always)]
    fn rgba8(self, r: &[f32; 8], g: &[f32; 8], b: &[f32; 8]) -> [u32; 8] {
        let entries = srgb_entries();
        let (r, g, b) = (
            srgb_count(self, entries, r),
            srgb_count(self, entries, g),
            srgb_count(self, entries, b),
        );
        let mut out = [0u32; 8];
        // SAFETY: the token proves AVX2; the store writes the eight u32 of `out`.
        unsafe {
            let px = _mm256_or_si256(
                _mm256_or_si256(r, _mm256_slli_epi32::<8>(g)),
                _mm256_or_si256(_mm256_slli_epi32::<16>(b), _mm256_set1_epi32(-16_777_216)),
            );
            _mm256_storeu_si256(out.as_mut_ptr().cast(), px);
        }
        out
    }
}

/// One channel of [`Simd::rgba8`] in AVX2: each lane's sRGB byte (as `srgb8`),
/// by the bucket's entry. (A function, not a closure: a closure left as a call
/// is not compiled for AVX2.)
#[inline(always)]
fn srgb_count(_: Avx2, entries: &[u32], linear: &[f32; 8]) -> __m256i {
    // SAFETY: the token (the first argument) proves AVX2; the load reads
    // the eight floats of `linear`; the bucket index lies in 0..entries.len() (the value
    // is clamped to [0, 1], the index to >= 0), so the gather reads in
    // bounds.
    unsafe {
        let v = _mm256_loadu_ps(linear.as_ptr());
        let c = _mm256_castps_si256(_mm256_min_ps(
            _mm256_max_ps(v, _mm256_setzero_ps()),
            _mm256_set1_ps(1.0),
        ));
        let bucket = _mm256_max_epi32(
            _mm256_sub_epi32(
                _mm256_srli_epi32::<{ BUCKET_SHIFT as i32 }>(c),
                _mm256_set1_epi32(FIRST_BUCKET as i32),
            ),
            _mm256_setzero_si256(),
        );
        let entry = _mm256_i32gather_epi32::<4>(entries.as_ptr().cast(), bucket);
        let at = _mm256_and_si256(entry, _mm256_set1_epi32(0xFFFF));
        let here = _mm256_and_si256(c, _mm256_set1_epi32(IN_BUCKET as i32));
        // low + 1 + (-1 where at > here): both below 2^16, so signed
        // comparison is exact.
        _mm256_add_epi32(
            _mm256_add_epi32(_mm256_srli_epi32::<16>(entry), _mm256_set1_epi32(1)),
            _mm256_cmpgt_epi32(at, here),
        )
    }
}
