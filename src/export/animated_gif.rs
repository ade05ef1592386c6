//! Animated GIFs, written frame by frame: one palette for the whole animation,
//! chosen from its first frame (the scene's materials and light do not change,
//! so neither do its colours, and the palette does not flicker), and each
//! frame after the first only as the rectangle whose palette indices changed,
//! its unchanged pixels transparent over the frame before.

use super::animation::{Delays, Rect, changed, crop};
use super::file::{AtomicFile, WriteError, create_folder, fail};
use crate::trace::Image;
use color_quant::NeuQuant;
use std::path::{Path, PathBuf};

/// The palette index that means "as in the frame before".
const UNCHANGED: u8 = 255;

/// An animated GIF being written frame by frame, looping for ever; it appears
/// at its path only when [`Self::finish`] has written it whole.
pub struct GifWriter {
    path: PathBuf,
    size: (u16, u16),
    /// The file, until the first frame chooses the palette and starts the
    /// encoder on it.
    file: Option<AtomicFile>,
    encoder: Option<(gif::Encoder<AtomicFile>, NeuQuant)>,
    delays: Delays,
    /// The last frame's palette indices.
    last: Option<Vec<u8>>,
}

impl GifWriter {
    /// Starts a GIF of `width` x `height` at `fps` frames per second.
    ///
    /// # Errors
    /// When the size exceeds 65535 or the file cannot be created.
    pub fn create(path: &Path, width: u32, height: u32, fps: f64) -> Result<Self, WriteError> {
        let size = (
            u16::try_from(width).map_err(|e| fail(path, e))?,
            u16::try_from(height).map_err(|e| fail(path, e))?,
        );
        create_folder(path)?;
        Ok(Self {
            path: path.to_path_buf(),
            size,
            file: Some(AtomicFile::create(path)?),
            encoder: None,
            delays: Delays::new(fps),
            last: None,
        })
    }

    /// Appends a frame, its colours the palette's nearest (`NeuQuant`, 255
    /// colours; the 256th marks unchanged pixels).
    ///
    /// # Errors
    /// When the picture is not of the GIF's size, or encoding fails.
    pub fn push(&mut self, img: Image) -> Result<(), WriteError> {
        let (w, h) = self.size;
        if (img.width, img.height) != (u32::from(w), u32::from(h)) {
            return Err(fail(
                &self.path,
                format!("a {}x{} frame in a {w}x{h} GIF", img.width, img.height),
            ));
        }
        if self.encoder.is_none() {
            let quant = NeuQuant::new(10, 255, &img.rgba);
            let mut palette = quant.color_map_rgb();
            palette.resize(3 * 256, 0);
            let file = self.file.take().expect("taken only here");
            let mut encoder =
                gif::Encoder::new(file, w, h, &palette).map_err(|e| fail(&self.path, e))?;
            encoder
                .set_repeat(gif::Repeat::Infinite)
                .map_err(|e| fail(&self.path, e))?;
            self.encoder = Some((encoder, quant));
        }
        let Some((encoder, quant)) = self.encoder.as_mut() else {
            unreachable!("started above");
        };
        let indices: Vec<u8> = img
            .rgba
            .chunks_exact(4)
            .map(|p| quant.index_of(p) as u8)
            .collect();
        drop(img);
        let whole = Rect {
            x: 0,
            y: 0,
            width: u32::from(w),
            height: u32::from(h),
        };
        let mut frame = gif::Frame {
            width: w,
            height: h,
            dispose: gif::DisposalMethod::Keep,
            delay: self.delays.next_delay(),
            ..gif::Frame::default()
        };
        if let Some(last) = &self.last {
            let rect = changed(last, &indices, whole.width, 1).unwrap_or(Rect {
                width: 1,
                height: 1,
                ..whole
            });
            let mut buffer = crop(&indices, whole.width, 1, rect);
            for (b, was) in buffer.iter_mut().zip(crop(last, whole.width, 1, rect)) {
                if *b == was {
                    *b = UNCHANGED;
                }
            }
            frame.left = rect.x as u16;
            frame.top = rect.y as u16;
            frame.width = rect.width as u16;
            frame.height = rect.height as u16;
            frame.transparent = Some(UNCHANGED);
            frame.buffer = buffer.into();
        } else {
            frame.buffer = indices.clone().into();
        }
        encoder
            .write_frame(&frame)
            .map_err(|e| fail(&self.path, e))?;
        self.last = Some(indices);
        Ok(())
    }

    /// Writes the trailer and the whole file, atomically.
    ///
    /// # Errors
    /// When no frame was pushed, or the file cannot be written.
    pub fn finish(self) -> Result<(), WriteError> {
        let Some((encoder, _)) = self.encoder else {
            return Err(fail(&self.path, "a GIF needs at least one frame"));
        };
        let file = encoder.into_inner().map_err(|e| fail(&self.path, e))?;
        file.commit()
    }
}
