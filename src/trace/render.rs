//! Turning a scene into pixels: one function per pixel, rows in parallel with
//! rayon or serially; both run the same per-pixel code, so their bytes are equal.

use super::camera::CameraRays;
use super::prepared::Prepared;
use super::scene::Scene;
use super::shade::{radiance_bound, trace};
use glam::Vec3;
use rayon::prelude::*;

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

/// Linear [0, 1] to an sRGB byte (IEC 61966-2-1), clamping out-of-range values.
#[must_use]
pub fn srgb8(linear: f32) -> u8 {
    let x = linear.clamp(0.0, 1.0);
    let s = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Sub-pixel sample offsets: the pixel centre for one sample, else the first `n`
/// points of the R2 low-discrepancy sequence (the same for every pixel).
#[must_use]
pub fn sample_offsets(n: u32) -> Vec<(f32, f32)> {
    if n <= 1 {
        return vec![(0.5, 0.5)];
    }
    // Roberts' R2: steps by the inverse powers of the plastic number.
    const A1: f64 = 0.754_877_666_246_692_7;
    const A2: f64 = 0.569_840_290_998_053_3;
    (0..n)
        .map(|i| {
            (
                ((0.5 + A1 * f64::from(i)) % 1.0) as f32,
                ((0.5 + A2 * f64::from(i)) % 1.0) as f32,
            )
        })
        .collect()
}

/// Everything one row needs, shared by the serial and parallel paths.
struct Frame<'a> {
    prepared: Prepared<'a>,
    camera: CameraRays,
    offsets: Vec<(f32, f32)>,
    bound: f32,
    width: u32,
}

impl<'a> Frame<'a> {
    fn new(scene: &'a Scene) -> Self {
        let prepared = Prepared::new(scene);
        let bound = radiance_bound(&prepared);
        Self {
            camera: CameraRays::new(&scene.camera, scene.size.0, scene.size.1),
            offsets: sample_offsets(scene.samples),
            prepared,
            bound,
            width: scene.size.0,
        }
    }

    /// The linear colour of pixel `(x, y)`.
    fn pixel(&self, x: u32, y: u32) -> Vec3 {
        let sum: Vec3 = self
            .offsets
            .iter()
            .map(|&(dx, dy)| {
                let ray = self.camera.ray(x as f32 + dx, y as f32 + dy);
                trace(&self.prepared, &ray, 0, 1.0, self.bound)
            })
            .sum();
        sum / self.offsets.len() as f32
    }

    fn row(&self, y: u32, out: &mut [u8]) {
        for (x, px) in (0..self.width).zip(out.chunks_exact_mut(4)) {
            let c = self.pixel(x, y);
            px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        }
    }
}

fn blank(scene: &Scene) -> Image {
    let (width, height) = scene.size;
    Image {
        width,
        height,
        rgba: vec![0; width as usize * height as usize * 4],
    }
}

/// The reference renderer: one row after another on this thread.
#[must_use]
pub fn render_serial(scene: &Scene) -> Image {
    let frame = Frame::new(scene);
    let mut img = blank(scene);
    let stride = img.width as usize * 4;
    for (y, row) in img.rgba.chunks_exact_mut(stride).enumerate() {
        frame.row(y as u32, row);
    }
    img
}

/// Rows in parallel on the current rayon pool; byte-identical to [`render_serial`].
#[must_use]
pub fn render(scene: &Scene) -> Image {
    let frame = Frame::new(scene);
    let mut img = blank(scene);
    let stride = img.width as usize * 4;
    img.rgba
        .par_chunks_exact_mut(stride)
        .enumerate()
        .for_each(|(y, row)| frame.row(y as u32, row));
    img
}

/// A rayon pool of `threads` workers (0: one per core).
///
/// # Errors
/// When the operating system refuses the threads.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build()
}
