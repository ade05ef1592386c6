//! A picture stretched to a larger size by bilinear interpolation of its sRGB
//! bytes, pixel centres to pixel centres: how a frame traced at one ray per
//! block of pixels (`Scene::coarse`, while the view moves) fills the window.
//! Each source row is first stretched across (16-bit, weights in 1/16), then
//! each output row blends the two source rows around it; rows in parallel.

use super::color::Image;
use rayon::prelude::*;

/// Weights are in 1/16: a blend of two bytes then of two such sums fits in
/// 16 bits (255 * 16 * 16 = 65,280), and a doubled picture's weights (1/4,
/// 3/4) are exact.
const ONE: u16 = 16;

/// The two source positions around output position `i` of `out` (of `src`
/// in all), and the second's weight in 1/16: the output pixel's centre
/// `(i + 0.5) * src / out - 0.5` in source pixels, clamped to the picture.
fn taps(out: u32, src: u32) -> Vec<(usize, usize, u16)> {
    let scale = f64::from(src) / f64::from(out);
    let last = f64::from(src - 1);
    (0..out)
        .map(|i| {
            let u = ((f64::from(i) + 0.5) * scale - 0.5).clamp(0.0, last);
            let i0 = u.floor();
            let w = ((u - i0) * f64::from(ONE)).round() as u16;
            let i0 = i0 as usize;
            (i0, (i0 + 1).min(src as usize - 1), w)
        })
        .collect()
}

/// A pixel's four bytes as four 16-bit lanes of a `u64`.
fn lanes(p: [u8; 4]) -> u64 {
    let x = u64::from(u32::from_le_bytes(p));
    let x = (x | (x << 16)) & 0x0000_FFFF_0000_FFFF;
    (x | (x << 8)) & 0x00FF_00FF_00FF_00FF
}

/// Source row `src` stretched across by the taps `xs`, times 16. Each pixel
/// is blended as four 16-bit lanes of a `u64` at once (no lane passes
/// 255 * 16, so none carries into the next).
fn across(
    src: &[[u8; 4]],
    xs: &[(usize, usize, u16)],
    spread: &mut Vec<u64>,
    out: &mut [[u16; 4]],
) {
    spread.clear();
    spread.extend(src.iter().map(|&p| lanes(p)));
    for (o, &(a, b, w)) in out.iter_mut().zip(xs) {
        let x = spread[a] * u64::from(ONE - w) + spread[b] * u64::from(w);
        *o = [
            x as u16,
            (x >> 16) as u16,
            (x >> 32) as u16,
            (x >> 48) as u16,
        ];
    }
}

/// An output row: stretched rows `p` and `q` blended, `q` weighing `w` in
/// 1/16, back to bytes (rounded).
fn down(p: &[u16], q: &[u16], w: u16, out: &mut [u8]) {
    let v = ONE - w;
    for ((o, &p), &q) in out.iter_mut().zip(p).zip(q) {
        *o = ((p * v + q * w + 128) >> 8) as u8;
    }
}

/// `img` stretched to `width x height` (each at least the source's), rows in
/// parallel on the current rayon pool where `parallel`.
#[must_use]
pub(crate) fn stretch(img: &Image, (width, height): (u32, u32), parallel: bool) -> Image {
    let (xs, ys) = (taps(width, img.width), taps(height, img.height));
    let (src, _) = img.rgba.as_chunks::<4>();
    let src_rows: Vec<&[[u8; 4]]> = src.chunks_exact(img.width as usize).collect();
    // Each source row stretched across, times 16.
    let mut wide = vec![[0u16; 4]; width as usize * img.height as usize];
    if parallel {
        wide.par_chunks_exact_mut(width as usize)
            .zip(src_rows.par_iter())
            .for_each_init(Vec::new, |spread, (out, src)| across(src, &xs, spread, out));
    } else {
        let mut spread = Vec::new();
        for (out, src) in wide.chunks_exact_mut(width as usize).zip(&src_rows) {
            across(src, &xs, &mut spread, out);
        }
    }
    // Then each output row from the two source rows around it.
    let wide: Vec<&[u16]> = wide
        .chunks_exact(width as usize)
        .map(<[[u16; 4]]>::as_flattened)
        .collect();
    let mut out = Image {
        width,
        height,
        rgba: vec![0u8; width as usize * height as usize * 4],
    };
    out.for_rows(parallel, |y, row| {
        let (a, b, w) = ys[y as usize];
        down(wide[a], wide[b], w, row);
    });
    out
}

#[cfg(test)]
mod tests {
    use super::stretch;
    use crate::color::Image;

    /// A `w x h` picture whose pixel `(x, y)` is `f(x, y)` in every colour
    /// channel, opaque.
    fn picture(w: u32, h: u32, f: impl Fn(u32, u32) -> u8) -> Image {
        let mut rgba = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let v = f(x, y);
                rgba.extend([v, v, v, 255]);
            }
        }
        Image {
            width: w,
            height: h,
            rgba,
        }
    }

    #[test]
    fn a_flat_picture_stays_flat_and_the_same_size_is_a_copy() {
        let flat = picture(5, 3, |_, _| 77);
        let big = stretch(&flat, (10, 6), true);
        assert_eq!((big.width, big.height), (10, 6));
        assert!(big.rgba.chunks(4).all(|p| p == [77, 77, 77, 255]));
        let ramp = picture(6, 4, |x, y| (x * 40 + y) as u8);
        assert_eq!(stretch(&ramp, (6, 4), false).rgba, ramp.rgba);
    }

    #[test]
    fn doubled_pixels_take_three_quarters_of_the_nearer_source_pixel() {
        // Source columns 0 and 1 are 0 and 200; output pixel 1's centre lies
        // a quarter of the way from source 0 to source 1 (50), pixel 2's three
        // quarters (150); the edges keep the edge pixels.
        let src = picture(2, 1, |x, _| if x == 0 { 0 } else { 200 });
        let out = stretch(&src, (4, 2), false);
        let row: Vec<u8> = out.rgba.chunks(4).take(4).map(|p| p[0]).collect();
        assert_eq!(row, [0, 50, 150, 200]);
        assert_eq!(out.rgba[..16], out.rgba[16..], "one source row: equal rows");
        assert_eq!(
            stretch(&src, (4, 2), true).rgba,
            out.rgba,
            "parallel: the same"
        );
    }
}
