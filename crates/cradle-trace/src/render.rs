//! The full frame: every pixel at every sample, or with adaptive
//! anti-aliasing one centre sample and then every sample at that picture's
//! edges; rows in parallel with rayon ([`render`]) or serially
//! ([`render_serial`], with [`RenderOptions::FULL`] the reference). Both run
//! the same per-pixel code (`frame`), so their bytes are equal. A scene traced
//! at one ray per block of pixels ([`Scene::coarse`], while the view moves) is
//! traced at the smaller size and stretched.

use super::adaptive::adaptive_full;
use super::color::Image;
use super::frame::Frame;
use super::motion::RowMotion;
use super::scene::Scene;
use super::stretch::stretch;
use std::sync::atomic::{AtomicU32, Ordering};

pub use super::frame::RenderOptions;

/// The whole picture, rows in parallel or one after another (the same bytes):
/// every pixel at every sample, or with adaptive anti-aliasing one centre
/// sample first and then every sample at the edges of that picture. Returns it
/// with each row's motion cells and segments (adaptive: cells only, as such
/// frames are never reused).
pub(crate) fn image(frame: &Frame<'_>, parallel: bool) -> (Image, Vec<RowMotion>) {
    image_counting(frame, parallel, None)
}

/// [`image`], adding 1 to `rows_done` as each row of each pass is done
/// (with adaptive anti-aliasing, two passes: `2 * height` in all; that frame
/// is `adaptive`'s).
fn image_counting(
    frame: &Frame<'_>,
    parallel: bool,
    rows_done: Option<&AtomicU32>,
) -> (Image, Vec<RowMotion>) {
    if let Some(edge) = frame.edge() {
        let (img, layers) = adaptive_full(frame, edge, (parallel, rows_done));
        return (img, layers.into_rows());
    }
    let mut img = Image {
        width: frame.width(),
        height: frame.height(),
        rgba: vec![0; frame.width() as usize * frame.height() as usize * 4],
    };
    let rows = img.for_rows(parallel, |y, row| {
        let motion = frame.row_with(y, row, frame.offsets(), None);
        if let Some(c) = rows_done {
            c.fetch_add(1, Ordering::Relaxed);
        }
        motion
    });
    (img, rows)
}

/// One row after another on this thread, with every skip: the serial twin of
/// [`render`].
#[must_use]
pub fn render_serial(scene: &Scene) -> Image {
    render_serial_with(scene, RenderOptions::FAST)
}

/// One row after another on this thread with the given skips;
/// `RenderOptions::FULL` is the reference renderer.
#[must_use]
pub fn render_serial_with(scene: &Scene, options: RenderOptions) -> Image {
    if scene.coarse > 1 {
        return coarse(scene, |s| render_serial_with(s, options), false);
    }
    image(&Frame::new(scene, options, false), false).0
}

/// Rows in parallel on the current rayon pool; byte-identical to [`render_serial`].
#[must_use]
pub fn render(scene: &Scene) -> Image {
    render_with(scene, RenderOptions::FAST)
}

/// Rows in parallel on the current rayon pool with the given skips (to
/// measure what each earns); the same bytes whatever they are.
#[must_use]
pub fn render_with(scene: &Scene, options: RenderOptions) -> Image {
    if scene.coarse > 1 {
        return coarse(scene, |s| render_with(s, options), true);
    }
    image(&Frame::new(scene, options, false), true).0
}

/// The size traced for a `width x height` picture at one ray per `k x k`
/// block of pixels ([`Scene::coarse`]): rounded up.
#[must_use]
pub fn coarse_size((width, height): (u32, u32), k: u32) -> (u32, u32) {
    let k = k.max(1);
    (width.div_ceil(k), height.div_ceil(k))
}

/// `scene` at one ray per block ([`Scene::coarse`]): traced by `trace` at
/// [`coarse_size`], one sample per pixel, then stretched to the scene's size.
fn coarse(scene: &Scene, trace: impl Fn(&Scene) -> Image, parallel: bool) -> Image {
    let small = Scene {
        size: coarse_size(scene.size, scene.coarse),
        samples: 1,
        adaptive: None,
        coarse: 1,
        ..scene.clone()
    };
    stretch(&trace(&small), scene.size, parallel)
}

/// [`render`], adding 1 to `rows_done` as each row of each pass is done, so
/// another thread can show a long frame's progress: `height` rows in all, or
/// `2 * height` with adaptive anti-aliasing (a pass of centre samples, then
/// the edges). The same picture, byte for byte.
#[must_use]
pub fn render_counting(scene: &Scene, rows_done: &AtomicU32) -> Image {
    if scene.coarse > 1 {
        return coarse(scene, |s| render_counting(s, rows_done), true);
    }
    image_counting(
        &Frame::new(scene, RenderOptions::FAST, false),
        true,
        Some(rows_done),
    )
    .0
}

/// A rayon pool of `threads` workers (0: one per core).
///
/// # Errors
/// When the operating system refuses the threads.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build()
}

#[cfg(test)]
mod tests;
