//! Writing pictures headless: PNG frames and animated GIFs.

use crate::trace::Image;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// An output file that could not be written: bad input (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {reason}", path.display())]
pub struct WriteError {
    /// The path.
    pub path: PathBuf,
    /// Why.
    pub reason: String,
}

fn fail(path: &Path, reason: impl ToString) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        reason: reason.to_string(),
    }
}

/// Creates `path` (and the folders above it) for writing.
///
/// # Errors
/// When the folder or file cannot be created.
pub fn create(path: &Path) -> Result<BufWriter<File>, WriteError> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|e| fail(path, e))?;
    }
    File::create(path)
        .map(BufWriter::new)
        .map_err(|e| fail(path, e))
}

/// Writes an RGBA8 sRGB image as PNG.
///
/// # Errors
/// When the file cannot be created or written.
pub fn write_png(path: &Path, img: &Image) -> Result<(), WriteError> {
    let mut enc = png::Encoder::new(create(path)?, img.width, img.height);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = enc.write_header().map_err(|e| fail(path, e))?;
    writer
        .write_image_data(&img.rgba)
        .map_err(|e| fail(path, e))?;
    writer.finish().map_err(|e| fail(path, e))
}

/// An animated GIF being written frame by frame, looping for ever.
pub struct GifWriter {
    path: PathBuf,
    encoder: gif::Encoder<BufWriter<File>>,
    delay_cs: u16,
}

impl GifWriter {
    /// Starts a GIF of `width` x `height` at `fps` frames per second.
    ///
    /// # Errors
    /// When the file cannot be created, or the size exceeds 65535.
    pub fn create(path: &Path, width: u32, height: u32, fps: f64) -> Result<Self, WriteError> {
        let (w, h) = (
            u16::try_from(width).map_err(|e| fail(path, e))?,
            u16::try_from(height).map_err(|e| fail(path, e))?,
        );
        let mut encoder = gif::Encoder::new(create(path)?, w, h, &[]).map_err(|e| fail(path, e))?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| fail(path, e))?;
        // GIF delays are in centiseconds.
        let delay_cs = (100.0 / fps).round().clamp(1.0, 65535.0) as u16;
        Ok(Self {
            path: path.to_path_buf(),
            encoder,
            delay_cs,
        })
    }

    /// Appends a frame (quantised to 256 colours with `NeuQuant`).
    ///
    /// # Errors
    /// When writing fails.
    pub fn push(&mut self, img: &Image) -> Result<(), WriteError> {
        let mut rgba = img.rgba.clone();
        let (w, h) = (img.width as u16, img.height as u16);
        let mut frame = gif::Frame::from_rgba_speed(w, h, &mut rgba, 10);
        frame.delay = self.delay_cs;
        self.encoder
            .write_frame(&frame)
            .map_err(|e| fail(&self.path, e))
    }
}
