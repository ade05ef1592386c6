//! Which build of the SIMD code runs: the AVX2 one where the CPU has it (asked
//! at run time, so the binary stays portable x86-64), else the portable one
//! (SSE2 on x86-64, whatever the target has elsewhere). Both give the same bits.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set: the portable build runs even where the CPU has AVX2.
static PORTABLE: AtomicBool = AtomicBool::new(false);

/// Makes the SIMD code (packets, wide box tests) use the portable build even
/// where the CPU has AVX2, or lets it choose again. Both give the same bytes;
/// tests use this to check the build this machine would not otherwise run.
pub fn force_portable(on: bool) {
    PORTABLE.store(on, Ordering::Relaxed);
}

/// Whether to run the AVX2 build (std caches the CPU's answer).
#[inline]
#[must_use]
pub(crate) fn avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        !PORTABLE.load(Ordering::Relaxed) && std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The eight floats of `v` in an AVX register.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) fn load8(v: &[f32; 8]) -> std::arch::x86_64::__m256 {
    // SAFETY: an unaligned load of exactly the eight floats `v` holds.
    #[expect(unsafe_code, reason = "a load from a reference, in bounds by its type")]
    unsafe {
        std::arch::x86_64::_mm256_loadu_ps(v.as_ptr())
    }
}
