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

impl Image {
    /// Runs `f(y, row)` over the rows, in parallel on the current rayon pool
    /// or serially (the same rows, the same results), and collects what it
    /// returns per row.
    pub(crate) fn for_rows<R: Send>(
        &mut self,
        parallel: bool,
        f: impl Fn(u32, &mut [u8]) -> R + Sync,
    ) -> Vec<R> {
        use rayon::prelude::*;
        let stride = self.width as usize * 4;
        if parallel {
            self.rgba
                .par_chunks_exact_mut(stride)
                .enumerate()
                .map(|(y, row)| f(y as u32, row))
                .collect()
        } else {
            self.rgba
                .chunks_exact_mut(stride)
                .enumerate()
                .map(|(y, row)| f(y as u32, row))
                .collect()
        }
    }
}

/// Buckets of the floats in [2^-14, 1]: 256 per octave (the top 8 bits of the
/// mantissa), each holding at most one threshold (neighbouring thresholds are
/// at least 0.9% apart, a bucket spans at most 0.4%).
pub(crate) const BUCKET_SHIFT: u32 = 15;
/// The bucket of 2^-14 (below every threshold, the first is 1.5e-4).
pub(crate) const FIRST_BUCKET: u32 = (1.0f32 / 16384.0).to_bits() >> BUCKET_SHIFT;
/// Buckets up to and including that of 1.0.
const BUCKETS: usize = ((1.0f32.to_bits() >> BUCKET_SHIFT) - FIRST_BUCKET + 1) as usize;

/// The low 15 bits of a float: its place within its bucket. Two positive
/// floats of one bucket compare as these bits do.
pub(crate) const IN_BUCKET: u32 = (1 << BUCKET_SHIFT) - 1;
/// A bucket entry's place of the next threshold when it lies past the bucket:
/// above every [`IN_BUCKET`] value.
const PAST: u32 = 1 << BUCKET_SHIFT;

/// Per bucket one entry: the byte of its lowest value and where in the bucket
/// the next threshold lies.
struct Table {
    /// Per bucket, `low << 16 | at`: `low` the byte of the bucket's lowest
    /// value (the count of thresholds at or below it), `at` the [`IN_BUCKET`]
    /// bits of the next threshold, `thresholds()[low]`, where it lies in the
    /// bucket, else [`PAST`]. So a value of the bucket has byte `low + 1` where
    /// its own `IN_BUCKET` bits are at least `at`, else `low`: one lookup.
    entries: Vec<u32>,
}

/// The linear value at which the sRGB byte becomes `b + 1`, for `b` in
/// 0..255: the decoded midpoint `(b + 0.5) / 255`, computed in f64; entry 255
/// is infinity (no byte above 255).
fn thresholds() -> [f32; 256] {
    std::array::from_fn(|b| {
        if b == 255 {
            return f32::INFINITY;
        }
        let s = (b as f64 + 0.5) / 255.0;
        let linear = if s <= 0.040_45 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        };
        linear as f32
    })
}

/// The bucket entries of [`srgb8`] (see `Table`), for the AVX2 build's gathers.
pub(crate) fn srgb_entries() -> &'static [u32] {
    &table().entries
}

fn table() -> &'static Table {
    static T: std::sync::OnceLock<Table> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        let thresholds = thresholds();
        let entries = (0..BUCKETS as u32)
            .map(|i| {
                let bucket = FIRST_BUCKET + i;
                let lowest = f32::from_bits(bucket << BUCKET_SHIFT);
                let low = thresholds.partition_point(|&t| t <= lowest) as u32;
                let next = thresholds[low as usize].to_bits();
                let at = if next >> BUCKET_SHIFT == bucket {
                    next & IN_BUCKET
                } else {
                    PAST
                };
                low << 16 | at
            })
            .collect();
        Table { entries }
    })
}

/// Linear [0, 1] to an sRGB byte (IEC 61966-2-1), rounded to the nearest byte and
/// clamping out-of-range values: the count of decision points at or below the
/// value. The value's bucket gives the count at the bucket's start and where
/// the next threshold lies in it; one comparison of bits finishes it (no
/// `powf`, no search). Below 2^-14 every value takes the first bucket, whose
/// next threshold lies past it: byte 0.
#[must_use]
pub fn srgb8(linear: f32) -> u8 {
    let t = table();
    // NaN and negatives count as 0, values over 1 as 1 (the clamp it replaces).
    let c = if linear > 0.0 { linear.min(1.0) } else { 0.0 };
    let bits = c.to_bits();
    let bucket = ((bits >> BUCKET_SHIFT).saturating_sub(FIRST_BUCKET)) as usize;
    let entry = t.entries[bucket];
    ((entry >> 16) + u32::from(bits & IN_BUCKET >= entry & 0xFFFF)) as u8
}

/// [`srgb8`] of eight values at once, for packets (the same steps per lane).
#[inline]
#[must_use]
pub fn srgb8_lanes(linear: [f32; 8]) -> [u8; 8] {
    let mut out = [0; 8];
    for (o, v) in out.iter_mut().zip(linear) {
        *o = srgb8(v);
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

#[cfg(test)]
mod tests {
    use super::{BUCKET_SHIFT, BUCKETS, FIRST_BUCKET, rgba8_lanes, srgb8};

    /// The lane builds' `rgba8` as a kernel.
    struct Rgba8<'a>(&'a [f32; 8], &'a [f32; 8], &'a [f32; 8]);

    #[expect(
        clippy::inline_always,
        reason = "a kernel inlines into its build's entry point, which compiles it for AVX2 in the AVX2 build"
    )]
    impl crate::simd::Kernel for Rgba8<'_> {
        type Output = [u32; 8];
        #[inline(always)]
        fn run<S: crate::simd::Simd>(self, s: S) -> [u32; 8] {
            s.rgba8(self.0, self.1, self.2)
        }
    }

    /// The definition: the count of thresholds at or below the value (NaN: 0).
    fn by_search(linear: f32) -> u8 {
        super::thresholds()[..255].partition_point(|&t| t <= linear) as u8
    }

    #[test]
    fn the_buckets_give_the_searched_byte_everywhere() {
        // Both answers are constant between the points where one can change:
        // the thresholds (the search) and the bucket starts (the buckets), so
        // comparing at each such point and the float just below it compares them
        // on every float.
        let starts =
            (0..=BUCKETS as u32 + 1).map(|i| f32::from_bits((FIRST_BUCKET + i) << BUCKET_SHIFT));
        let thresholds = super::thresholds();
        for x in starts.chain(thresholds[..255].iter().copied()) {
            for v in [x.next_down(), x, x.next_up()] {
                assert_eq!(srgb8(v), by_search(v), "{v:e}");
            }
        }
        for v in [
            -1.0,
            -0.0,
            0.0,
            1e-30,
            1.0,
            1.5,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ] {
            assert_eq!(srgb8(v), by_search(v.max(0.0)), "{v}");
        }
        // The encoding's end points, and 18% grey: 1.055 * 0.18^(1/2.4) - 0.055 =
        // 0.4614, 117.6 of 255.
        assert_eq!((srgb8(0.0), srgb8(1.0), srgb8(0.18)), (0, 255, 118));
    }

    #[test]
    fn lanes_of_pixels_hold_the_scalar_bytes() {
        // Every threshold and its neighbours, out-of-range values and NaN.
        let mut v: Vec<f32> = super::thresholds()[..255]
            .iter()
            .flat_map(|&t| [t.next_down(), t, t.next_up()])
            .collect();
        v.extend([-1.0, -0.0, 0.0, 1.0, 1.5, f32::INFINITY, f32::NAN]);
        for chunk in v.chunks_exact(24) {
            let lane = |k: usize| -> [f32; 8] { std::array::from_fn(|i| chunk[k * 8 + i]) };
            let (r, g, b) = (lane(0), lane(1), lane(2));
            let builds = crate::simd::Build::all()
                .into_iter()
                .map(|build| build.run(Rgba8(&r, &g, &b)));
            for px in std::iter::once(rgba8_lanes(r, g, b)).chain(builds) {
                for i in 0..8 {
                    let want = [srgb8(r[i]), srgb8(g[i]), srgb8(b[i]), 255];
                    assert_eq!(px[i].to_le_bytes(), want, "{} {} {}", r[i], g[i], b[i]);
                }
            }
        }
    }
}
