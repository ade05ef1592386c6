//! The floor under every lane kernel: the lane operations ([`Simd`]) in two
//! builds, and which of them runs. The AVX2 build runs where the CPU has it
//! (asked at run time, so the binary stays portable x86-64), else the portable
//! one (SSE2 on x86-64, whatever the target has elsewhere). Both give the same
//! bits.
//!
//! This module holds all of the tracer's `unsafe` code: the AVX intrinsics in
//! `avx2`, each behind the [`Avx2`] token, and the one dispatch point into code
//! compiled for AVX2, `Avx2`'s [`Simd::enter`] (reached through [`Build::run`]). A kernel
//! is written once as a [`Kernel`], generic over the lane build.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set: the portable build runs even where the CPU has AVX2.
static PORTABLE: AtomicBool = AtomicBool::new(false);

/// Makes the SIMD code (packets, wide box tests) use the portable build even
/// where the CPU has AVX2, or lets it choose again. Both give the same bytes;
/// tests use this to check the build this machine would not otherwise run.
pub fn force_portable(on: bool) {
    PORTABLE.store(on, Ordering::Relaxed);
}

/// Whether to run the AVX2 build (std caches the CPU's answer). Other
/// architectures run the portable build only.
#[cfg(target_arch = "x86_64")]
#[inline]
#[must_use]
pub(crate) fn avx2() -> bool {
    !PORTABLE.load(Ordering::Relaxed) && std::arch::is_x86_feature_detected!("avx2")
}

/// A piece of lane code written once over the lane build: [`Build::run`]
/// runs it in the build the CPU allows. Its `run` must be `#[inline(always)]`,
/// so that the AVX2 entry point compiles it (and what it inlines) for AVX2.
pub(crate) trait Kernel {
    /// What the kernel gives.
    type Output;
    /// The kernel in lane build `s`.
    fn run<S: Simd>(self, s: S) -> Self::Output;
}

/// The lane build that runs: chosen once (by [`Build::detect`]) and handed to
/// the kernels' calls.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Build {
    /// The portable build.
    Portable,
    /// The AVX2 build, with the token that proves the CPU has it.
    #[cfg(target_arch = "x86_64")]
    Avx2(Avx2),
}

impl Build {
    /// The AVX2 build where the CPU has it and [`force_portable`] is off,
    /// else the portable one.
    #[inline]
    #[must_use]
    pub(crate) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if let Some(s) = Avx2::detect() {
            return Self::Avx2(s);
        }
        Self::Portable
    }

    /// Runs `k` in this build.
    #[inline]
    pub(crate) fn run<K: Kernel>(self, k: K) -> K::Output {
        match self {
            Self::Portable => Portable.enter(k),
            #[cfg(target_arch = "x86_64")]
            Self::Avx2(s) => s.enter(k),
        }
    }

    /// Every build this CPU can run, the portable one first: tests check each
    /// against the scalar code.
    #[cfg(test)]
    #[must_use]
    pub(crate) fn all() -> Vec<Self> {
        let mut all = vec![Self::Portable];
        #[cfg(target_arch = "x86_64")]
        all.extend(Avx2::detect().map(Self::Avx2));
        all
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2;
mod portable;

#[cfg(target_arch = "x86_64")]
pub(crate) use avx2::Avx2;
pub(crate) use portable::Portable;

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Eight `f32` lanes and the operations the lane kernels use, each one IEEE
/// operation per lane, exactly the scalar one: so a kernel written once over
/// `S: Simd` computes in every lane what the scalar code computes, in the
/// portable build ([`Portable`]) and the AVX2 one ([`Avx2`]). No fused
/// multiply-add and no approximate reciprocal or square root exist here.
///
/// `Self` is a token: lane values are made only through it (`splat`, `load`,
/// `mask`), so an AVX2 lane value exists only where the CPU has AVX2.
pub(crate) trait Simd: Copy {
    /// Eight floats. `-x` flips the sign bit, as the scalar `-x` does.
    type F: Copy
        + Add<Output = Self::F>
        + Sub<Output = Self::F>
        + Mul<Output = Self::F>
        + Div<Output = Self::F>
        + Neg<Output = Self::F>;
    /// Eight conditions, one per lane.
    type M: Copy + BitAnd<Output = Self::M> + BitOr<Output = Self::M> + Not<Output = Self::M>;

    /// `v` in every lane.
    fn splat(self, v: f32) -> Self::F;
    /// The lanes `v[0]..v[7]`.
    fn load(self, v: &[f32; 8]) -> Self::F;
    /// Lane `i` set where bit `i` of `bits` is.
    fn mask(self, bits: u8) -> Self::M;
    /// The lanes as an array.
    fn store(v: Self::F) -> [f32; 8];
    /// Bit `i` set where lane `i` is.
    fn bits(m: Self::M) -> u8;
    /// `v.sqrt()`, correctly rounded.
    fn sqrt(v: Self::F) -> Self::F;
    /// `v.abs()`: the sign bit cleared.
    fn abs(v: Self::F) -> Self::F;
    /// `if a < b { a } else { b }` (glam's `min`).
    fn min(a: Self::F, b: Self::F) -> Self::F;
    /// `if a > b { a } else { b }` (glam's `max`).
    fn max(a: Self::F, b: Self::F) -> Self::F;
    /// `v as i32` (towards zero) where `v` lies in `i32`'s range; any value
    /// elsewhere.
    fn trunc(v: Self::F) -> [i32; 8];
    /// `v.floor()` where `|v| < 2^22`; any finite value elsewhere.
    fn floor_small(v: Self::F) -> Self::F;
    /// `a < b` (false for NaN).
    fn lt(a: Self::F, b: Self::F) -> Self::M;
    /// `a <= b` (false for NaN).
    fn le(a: Self::F, b: Self::F) -> Self::M;
    /// `if m { a } else { b }` per lane.
    fn select(m: Self::M, a: Self::F, b: Self::F) -> Self::F;
    /// Eight RGBA pixels of the linear colours `r`, `g`, `b`: the bytes of
    /// [`crate::color::rgba8_lanes`].
    fn rgba8(self, r: &[f32; 8], g: &[f32; 8], b: &[f32; 8]) -> [u32; 8];
    /// Bit `i` set where `v[i] & with` is not zero (eight sets of bits, each
    /// a `u128`, against one).
    fn meeting(self, v: &[u128; 8], with: u128) -> u8;
    /// Asks the CPU to bring the cache line at `v` in (a hint: no effect on
    /// any value, and no fault wherever `v` points, so it need not point into
    /// anything; the portable build does nothing).
    fn prefetch<T>(self, v: *const T);
    /// Runs `k` in this build: compiled for AVX2 in the AVX2 build (the one
    /// entry from code built for any x86-64 into code built for AVX2), inlined
    /// in the portable one.
    fn enter<K: Kernel>(self, k: K) -> K::Output;
}
