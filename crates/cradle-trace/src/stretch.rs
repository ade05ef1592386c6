//! A picture stretched to a larger size by bilinear interpolation of its sRGB
//! bytes, pixel centres to pixel centres: how a frame traced at one ray per
//! block of pixels (`Scene::coarse`, while the view moves) fills the window.
//! Each source row is first stretched across (16-bit, weights in 1/256), then
//! each output row blends the two source rows around it; rows in parallel.

use super::color::Image;
use rayon::prelude::*;

/// The two source positions around output position `i` of `out` (of `src`
/// in all), and the second's weight in 1/256: the output pixel's centre
/// `(i + 0.5) * src / out - 0.5` in source pixels, clamped to the picture.
fn taps(out: u32, src: u32) -> Vec<(usize, usize, u32)> {
    let scale = f64::from(src) / f64::from(out);
    let last = f64::from(src - 1);
    (0..out)
        .map(|i| {
            let u = ((f64::from(i) + 0.5) * scale - 0.5).clamp(0.0, last);
            let i0 = u.floor();
            let w = ((u - i0) * 256.0).round() as u32;
            let i0 = i0 as usize;
            (i0, (i0 + 1).min(src as usize - 1), w)
        })
        .collect()
}

/// `img` stretched to `width x height` (each at least the source's), rows in
/// parallel on the current rayon pool where `parallel`.
#[must_use]
pub(crate) fn stretch(img: &Image, (width, height): (u32, u32), parallel: bool) -> Image {
    let (sw, sh) = (img.width, img.height);
    let (xs, ys) = (taps(width, sw), taps(height, sh));
    let row_len = width as usize * 4;
    // Each source row stretched across, times 256.
    let across_row = |y: usize, out: &mut [u16]| {
        let src = &img.rgba[y * sw as usize * 4..(y + 1) * sw as usize * 4];
        for (o, &(a, b, w)) in out.chunks_exact_mut(4).zip(&xs) {
            for c in 0..4 {
                let (p, q) = (u32::from(src[a * 4 + c]), u32::from(src[b * 4 + c]));
                o[c] = (p * (256 - w) + q * w) as u16;
            }
        }
    };
    let mut across = vec![0u16; row_len * sh as usize];
    if parallel {
        across
            .par_chunks_exact_mut(row_len)
            .enumerate()
            .for_each(|(y, out)| across_row(y, out));
    } else {
        across
            .chunks_exact_mut(row_len)
            .enumerate()
            .for_each(|(y, out)| across_row(y, out));
    }
    // Then each output row from the two source rows around it.
    let across = &across;
    let down_row = |y: usize, out: &mut [u8]| {
        let (a, b, w) = ys[y];
        let (p, q) = (
            &across[a * row_len..(a + 1) * row_len],
            &across[b * row_len..(b + 1) * row_len],
        );
        for ((o, &p), &q) in out.iter_mut().zip(p).zip(q) {
            *o = ((u32::from(p) * (256 - w) + u32::from(q) * w + 32_768) >> 16) as u8;
        }
    };
    let mut rgba = vec![0u8; row_len * height as usize];
    if parallel {
        rgba.par_chunks_exact_mut(row_len)
            .enumerate()
            .for_each(|(y, out)| down_row(y, out));
    } else {
        rgba.chunks_exact_mut(row_len)
            .enumerate()
            .for_each(|(y, out)| down_row(y, out));
    }
    Image {
        width,
        height,
        rgba,
    }
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
