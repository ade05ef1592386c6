//! The tracer's output: linear colour to sRGB bytes (pixels' texture is
//! `Rgba8UnormSrgb`, PNGs are sRGB) and the RGBA8 [`Image`] the renderers fill.

/// An RGBA8 picture, sRGB-encoded, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

/// `THRESHOLDS[b]` is the linear value at which the sRGB byte becomes `b + 1`: the
/// decoded midpoint `(b + 0.5) / 255`, computed in f64 once.
fn thresholds() -> &'static [f32; 255] {
    static T: std::sync::OnceLock<[f32; 255]> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        std::array::from_fn(|b| {
            let s = (b as f64 + 0.5) / 255.0;
            let linear = if s <= 0.040_45 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            };
            linear as f32
        })
    })
}

/// Linear [0, 1] to an sRGB byte (IEC 61966-2-1), rounded to the nearest byte and
/// clamping out-of-range values: the count of decision points at or below the
/// value, found by binary search instead of a `powf` per channel.
#[must_use]
pub fn srgb8(linear: f32) -> u8 {
    // NaN counts as 0, like the clamp it replaces.
    thresholds().partition_point(|&t| t <= linear) as u8
}

/// [`srgb8`] of eight values at once, for packets: the same count of decision
/// points at or below each value, found by a binary search without branches
/// (eight halving steps over the 255 thresholds, indices at most 254), which the
/// compiler can run in SIMD lanes. NaN counts as 0, as there.
#[inline]
#[must_use]
pub fn srgb8_lanes(linear: [f32; 8]) -> [u8; 8] {
    let t = thresholds();
    let mut pos = [0u32; 8];
    let mut step = 128u32;
    while step > 0 {
        for (p, &v) in pos.iter_mut().zip(&linear) {
            // `*p + step - 1` <= 128 + 64 + ... + 1 - 1 = 254.
            if t[(*p + step - 1) as usize] <= v {
                *p += step;
            }
        }
        step /= 2;
    }
    bytes(pos)
}

/// The low byte of each lane (each lies in 0..=255): a plain loop, inlined,
/// where `array::map` stays a call.
#[expect(
    clippy::inline_always,
    reason = "inlined into each caller, so the AVX2 one compiles it for AVX2"
)]
#[inline(always)]
fn bytes(v: [u32; 8]) -> [u8; 8] {
    let mut out = [0; 8];
    for (o, p) in out.iter_mut().zip(v) {
        *o = p as u8;
    }
    out
}

/// Eight RGBA pixels (little-endian `u32`s: red, green, blue, 255) of the
/// linear colours `r`, `g`, `b`: [`srgb8_lanes`] of each channel.
#[inline]
#[must_use]
pub(crate) fn rgba8_lanes(r: [f32; 8], g: [f32; 8], b: [f32; 8]) -> [u32; 8] {
    let (r, g, b) = (srgb8_lanes(r), srgb8_lanes(g), srgb8_lanes(b));
    let mut out = [0; 8];
    for (i, o) in out.iter_mut().enumerate() {
        *o = u32::from_le_bytes([r[i], g[i], b[i], 255]);
    }
    out
}

/// [`rgba8_lanes`] with AVX2's gathers: each halving step of the search loads
/// the eight thresholds in one instruction (the same comparisons, so the same
/// bytes), and the channels are packed in the registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
#[must_use]
pub(crate) fn rgba8_avx2(r: &[f32; 8], g: &[f32; 8], b: &[f32; 8]) -> [u32; 8] {
    use std::arch::x86_64::{
        __m256i, _CMP_LE_OQ, _mm256_add_epi32, _mm256_and_si256, _mm256_castps_si256,
        _mm256_cmp_ps, _mm256_i32gather_ps, _mm256_loadu_ps, _mm256_or_si256, _mm256_set1_epi32,
        _mm256_setzero_si256, _mm256_slli_epi32, _mm256_storeu_si256,
    };
    let t = thresholds();
    // Each lane's count of thresholds at or below its value, 0..=255.
    let count = |linear: &[f32; 8]| -> __m256i {
        // SAFETY: loads the eight floats of `linear`; each gather reads
        // thresholds at indices `pos + step - 1` <= 254 < 255, in bounds.
        #[expect(unsafe_code, reason = "AVX2 loads and gathers within bounds")]
        unsafe {
            let v = _mm256_loadu_ps(linear.as_ptr());
            let mut pos = _mm256_setzero_si256();
            for step in [128, 64, 32, 16, 8, 4, 2, 1] {
                let idx = _mm256_add_epi32(pos, _mm256_set1_epi32(step - 1));
                let th = _mm256_i32gather_ps::<4>(t.as_ptr(), idx);
                let le = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LE_OQ>(th, v));
                pos = _mm256_add_epi32(pos, _mm256_and_si256(le, _mm256_set1_epi32(step)));
            }
            pos
        }
    };
    let (r, g, b) = (count(r), count(g), count(b));
    let px = _mm256_or_si256(
        _mm256_or_si256(r, _mm256_slli_epi32::<8>(g)),
        _mm256_or_si256(_mm256_slli_epi32::<16>(b), _mm256_set1_epi32(-16_777_216)),
    );
    let mut out = [0u32; 8];
    // SAFETY: stores the eight u32 of `out`.
    #[expect(unsafe_code, reason = "an AVX store within bounds")]
    unsafe {
        _mm256_storeu_si256(out.as_mut_ptr().cast(), px);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{rgba8_lanes, srgb8};

    #[test]
    fn lanes_of_pixels_hold_the_scalar_bytes() {
        // Every threshold and its neighbours, out-of-range values and NaN.
        let mut v: Vec<f32> = super::thresholds()
            .iter()
            .flat_map(|&t| [t.next_down(), t, t.next_up()])
            .collect();
        v.extend([-1.0, -0.0, 0.0, 1.0, 1.5, f32::INFINITY, f32::NAN]);
        for chunk in v.chunks_exact(24) {
            let lane = |k: usize| -> [f32; 8] { std::array::from_fn(|i| chunk[k * 8 + i]) };
            let (r, g, b) = (lane(0), lane(1), lane(2));
            #[cfg(target_arch = "x86_64")]
            let avx = std::arch::is_x86_feature_detected!("avx2").then(|| {
                // SAFETY: the CPU has AVX2, checked just above.
                #[expect(unsafe_code, reason = "calling the AVX2 build under test")]
                unsafe {
                    super::rgba8_avx2(&r, &g, &b)
                }
            });
            #[cfg(not(target_arch = "x86_64"))]
            let avx = None;
            for px in std::iter::once(rgba8_lanes(r, g, b)).chain(avx) {
                for i in 0..8 {
                    let want = [srgb8(r[i]), srgb8(g[i]), srgb8(b[i]), 255];
                    assert_eq!(px[i].to_le_bytes(), want, "{} {} {}", r[i], g[i], b[i]);
                }
            }
        }
    }
}
