//! How the window's surface draws the traced bytes: the pixel formats of
//! pixels' texture and surface, the scaling, and whether presenting is a plain
//! copy of the texture onto the surface. Window-free, so it is tested here.
//!
//! The traced bytes are sRGB already. pixels' texture and surface are both sRGB
//! by default, so its scaling pass decodes every texel to linear and encodes it
//! back, for the same bytes. Where the surface offers the plain twin of that
//! format, both become plain ([`plain_of`]); where the texture then has the
//! surface's own format and the window shows the picture pixel for pixel,
//! presenting copies the texture onto the surface instead of drawing it
//! ([`copies`]): under Mesa's lavapipe the draw cost llvmpipe's threads 8.5 ms
//! of CPU a frame in sRGB and 6 plain; the copy costs them nothing, and the
//! app's threads no more than before that can be told from the noise
//! (docs/performance.md). A `Bgra8Unorm` surface (X11's) gets a `Bgra8Unorm`
//! texture, filled by [`put_bgra`].

use pixels::ScalingMode;
use pixels::wgpu::{TextureFormat, TextureUsages};

/// How the framebuffer of size `buffer` is drawn on a window of size `window`:
/// pixel by pixel (each pixel a k x k square) where the window is an exact
/// multiple k of it, the cheap draw that leaves the bytes as they are; scaled to
/// fit, keeping the aspect, otherwise (pixel-perfect drawing would crop a
/// smaller window and border a larger one).
pub(super) fn scaling((bw, bh): (u32, u32), (ww, wh): (u32, u32)) -> ScalingMode {
    let exact = bw > 0 && bh > 0 && ww % bw == 0 && wh % bh == 0 && ww / bw == wh / bh;
    if exact && ww >= bw {
        ScalingMode::PixelPerfect
    } else {
        ScalingMode::Fill
    }
}

/// The surface format without sRGB encoding that matches pixels' `chosen`
/// (sRGB) one, where the surface offers it (`offered`).
pub(super) fn plain_of(chosen: TextureFormat, offered: &[TextureFormat]) -> Option<TextureFormat> {
    let plain = chosen.remove_srgb_suffix();
    (plain != chosen && offered.contains(&plain)).then_some(plain)
}

/// pixels' texture format for a plain `surface` format: the surface's own where
/// it holds 8-bit RGBA in either order (so the texture can be copied onto it),
/// else `Rgba8Unorm`, the traced bytes' order.
pub(super) fn texture_for(surface: TextureFormat) -> TextureFormat {
    match surface {
        TextureFormat::Bgra8Unorm => TextureFormat::Bgra8Unorm,
        _ => TextureFormat::Rgba8Unorm,
    }
}

/// Whether presenting can copy a `texture` of size `buffer` onto a `surface`
/// (with `usages`) of size `window`: the same format, the same size, and a
/// surface that may be copied to.
pub(super) fn copies(
    (texture, surface): (TextureFormat, TextureFormat),
    usages: TextureUsages,
    buffer: (u32, u32),
    window: (u32, u32),
) -> bool {
    texture == surface && usages.contains(TextureUsages::COPY_DST) && buffer == window
}

/// Writes the RGBA bytes `rgba` into `out` (as long), red and blue swapped:
/// each pixel as a little-endian word, bytes 0 and 2 exchanged by masks and
/// shifts, which compile to four pixels a vector instruction (byte by byte it
/// took 13 instructions a pixel).
#[inline(never)]
pub(super) fn put_bgra(out: &mut [u8], rgba: &[u8]) {
    let (out, rgba) = (out.as_chunks_mut::<4>().0, rgba.as_chunks::<4>().0);
    for (o, p) in out.iter_mut().zip(rgba) {
        let v = u32::from_le_bytes(*p);
        *o = ((v & 0xff00_ff00) | ((v >> 16) & 0xff) | ((v & 0xff) << 16)).to_le_bytes();
    }
}

#[cfg(test)]
mod tests {
    use super::{copies, plain_of, put_bgra, scaling, texture_for};
    use pixels::ScalingMode;
    use pixels::wgpu::{TextureFormat as F, TextureUsages as U};

    #[test]
    fn the_plain_twin_of_an_srgb_surface_only_where_offered() {
        let offered = [F::Bgra8UnormSrgb, F::Bgra8Unorm, F::Rgba16Float];
        assert_eq!(plain_of(F::Bgra8UnormSrgb, &offered), Some(F::Bgra8Unorm));
        // Not offered, or the surface already plain (or not 8-bit): as it is.
        assert_eq!(plain_of(F::Rgba8UnormSrgb, &offered), None);
        assert_eq!(plain_of(F::Bgra8UnormSrgb, &[F::Bgra8UnormSrgb]), None);
        assert_eq!(plain_of(F::Bgra8Unorm, &offered), None);
        assert_eq!(plain_of(F::Rgba16Float, &offered), None);
    }

    #[test]
    fn pixel_by_pixel_only_at_exact_multiples() {
        let pp = |b, w| matches!(scaling(b, w), ScalingMode::PixelPerfect);
        assert!(pp((1200, 600), (1200, 600)));
        assert!(pp((1200, 600), (2400, 1200)));
        assert!(pp((7, 3), (21, 9)));
        // Not a multiple, different factors, smaller, or empty: scaled.
        assert!(!pp((1200, 600), (1201, 600)));
        assert!(!pp((1200, 600), (2400, 600)));
        assert!(!pp((1200, 600), (600, 300)));
        assert!(!pp((1200, 600), (0, 0)));
        assert!(!pp((0, 0), (1200, 600)));
    }

    #[test]
    fn the_texture_takes_a_bgra_surfaces_order_and_else_the_traced_one() {
        assert_eq!(texture_for(F::Bgra8Unorm), F::Bgra8Unorm);
        assert_eq!(texture_for(F::Rgba8Unorm), F::Rgba8Unorm);
        assert_eq!(texture_for(F::Rgb10a2Unorm), F::Rgba8Unorm);
    }

    #[test]
    fn presenting_copies_only_the_same_format_at_the_same_size_onto_a_copyable_surface() {
        let both = U::RENDER_ATTACHMENT | U::COPY_DST;
        let same = (F::Bgra8Unorm, F::Bgra8Unorm);
        assert!(copies(same, both, (1200, 600), (1200, 600)));
        assert!(copies(
            (F::Rgba8Unorm, F::Rgba8Unorm),
            both,
            (16, 16),
            (16, 16)
        ));
        // A surface that cannot be copied to, another format (an sRGB one
        // included), another size (pixel-perfect at 2x too): drawn.
        assert!(!copies(
            same,
            U::RENDER_ATTACHMENT,
            (1200, 600),
            (1200, 600)
        ));
        assert!(!copies(
            (F::Rgba8Unorm, F::Bgra8Unorm),
            both,
            (1200, 600),
            (1200, 600)
        ));
        assert!(!copies(
            (F::Bgra8Unorm, F::Bgra8UnormSrgb),
            both,
            (1200, 600),
            (1200, 600)
        ));
        assert!(!copies(same, both, (1200, 600), (2400, 1200)));
        assert!(!copies(same, both, (1200, 600), (1201, 600)));
    }

    #[test]
    fn bgra_swaps_red_and_blue_and_keeps_green_and_alpha() {
        let rgba = [1, 2, 3, 4, 10, 20, 30, 40];
        let mut out = [0; 8];
        put_bgra(&mut out, &rgba);
        assert_eq!(out, [3, 2, 1, 4, 30, 20, 10, 40]);
    }
}
