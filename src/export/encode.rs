//! Whole files at once: a PNG picture, a WAV soundtrack.

use super::file::{AtomicFile, WriteError, create_folder, fail};
use crate::trace::Image;
use std::path::Path;

/// Writes an RGBA8 sRGB image as PNG, atomically.
///
/// # Errors
/// When the file cannot be created or written.
pub fn write_png(path: &Path, img: &Image) -> Result<(), WriteError> {
    create_folder(path)?;
    let mut f = AtomicFile::create(path)?;
    {
        let mut enc = png::Encoder::new(&mut f, img.width, img.height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = enc.write_header().map_err(|e| fail(path, e))?;
        writer
            .write_image_data(&img.rgba)
            .map_err(|e| fail(path, e))?;
        writer.finish().map_err(|e| fail(path, e))?;
    }
    f.commit()
}

/// Writes a 16-bit stereo WAV of `frames` frames at `rate` Hz, atomically,
/// asking `chunk` for interleaved left/right samples a second at a time from
/// frame `first` on: a long soundtrack never sits whole in memory.
///
/// # Errors
/// When the file cannot be created or written.
pub fn write_wav(
    path: &Path,
    rate: u32,
    frames: u64,
    mut chunk: impl FnMut(u64, &mut [i16]),
) -> Result<(), WriteError> {
    create_folder(path)?;
    let spec = hound::WavSpec {
        channels: 2,
        sample_rate: rate,
        bits_per_sample: 16,
        sample_format: hound::SampleFormat::Int,
    };
    let mut f = AtomicFile::create(path)?;
    let mut wav = hound::WavWriter::new(&mut f, spec).map_err(|e| fail(path, e))?;
    let mut buf = Vec::new();
    let mut first = 0;
    while first < frames {
        let n = (frames - first).min(u64::from(rate));
        buf.clear();
        buf.resize(2 * n as usize, 0);
        chunk(first, &mut buf);
        for v in &buf {
            wav.write_sample(*v).map_err(|e| fail(path, e))?;
        }
        first += n;
    }
    wav.finalize().map_err(|e| fail(path, e))?;
    f.commit()
}
