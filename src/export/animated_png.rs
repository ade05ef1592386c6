//! Animated PNGs (APNG), written frame by frame: the first frame whole, each
//! later one only as the rectangle that changed since the frame before, its
//! unchanged pixels transparent and blended over what is shown (lossless: a
//! decoder shows every frame exactly as traced).

use super::animation::{Rect, changed, changes_over};
use super::file::{AtomicFile, WriteError, create_folder, fail};
use crate::trace::Image;
use std::cell::RefCell;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// The file under the PNG writer, shared so that it can be committed once
/// the writer has finished (which consumes it).
#[derive(Clone)]
struct Sink(Rc<RefCell<AtomicFile>>);

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.0.borrow_mut().flush()
    }
}

/// An animated PNG being written, looping for ever; it appears at its path
/// only when [`Self::finish`] has written it whole.
pub struct ApngWriter {
    path: PathBuf,
    file: Sink,
    writer: png::Writer<Sink>,
    size: (u32, u32),
    /// The last frame's pixels.
    last: Option<Vec<u8>>,
}

impl ApngWriter {
    /// Starts an animation of `frames` frames of `width` x `height`;
    /// `quick`: compress for speed rather than size.
    ///
    /// # Errors
    /// When the file cannot be created.
    pub fn create(
        path: &Path,
        (width, height): (u32, u32),
        frames: u32,
        quick: bool,
    ) -> Result<Self, WriteError> {
        create_folder(path)?;
        let file = Sink(Rc::new(RefCell::new(AtomicFile::create(path)?)));
        let mut enc = png::Encoder::new(file.clone(), width, height);
        if quick {
            enc.set_compression(png::Compression::Fast);
        }
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        enc.set_animated(frames.max(1), 0)
            .map_err(|e| fail(path, e))?;
        let writer = enc.write_header().map_err(|e| fail(path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            file,
            writer,
            size: (width, height),
            last: None,
        })
    }

    /// Appends a frame shown for `delay` = (numerator, denominator) seconds.
    ///
    /// # Errors
    /// When the picture is not of the animation's size, or encoding fails.
    pub fn push(&mut self, img: &Image, delay: (u16, u16)) -> Result<(), WriteError> {
        let (w, h) = self.size;
        if (img.width, img.height) != self.size {
            return Err(fail(
                &self.path,
                format!(
                    "a {}x{} frame in a {w}x{h} animation",
                    img.width, img.height
                ),
            ));
        }
        let opaque = img.rgba.chunks_exact(4).all(|p| p[3] == 255);
        let (rect, data, blend) = match &self.last {
            // Only over opaque frames do transparent pixels mean "as before".
            Some(last) if opaque => {
                let rect = changed(last, &img.rgba, w, 4).unwrap_or(Rect {
                    x: 0,
                    y: 0,
                    width: 1,
                    height: 1,
                });
                let data = changes_over(last, &img.rgba, w, rect);
                (rect, data, png::BlendOp::Over)
            }
            _ => {
                let whole = Rect {
                    x: 0,
                    y: 0,
                    width: w,
                    height: h,
                };
                (whole, img.rgba.clone(), png::BlendOp::Source)
            }
        };
        let path = &self.path;
        let wr = &mut self.writer;
        wr.reset_frame_position().map_err(|e| fail(path, e))?;
        wr.set_frame_dimension(rect.width, rect.height)
            .map_err(|e| fail(path, e))?;
        wr.set_frame_position(rect.x, rect.y)
            .map_err(|e| fail(path, e))?;
        wr.set_blend_op(blend).map_err(|e| fail(path, e))?;
        wr.set_dispose_op(png::DisposeOp::None)
            .map_err(|e| fail(path, e))?;
        wr.set_frame_delay(delay.0, delay.1)
            .map_err(|e| fail(path, e))?;
        wr.write_image_data(&data).map_err(|e| fail(path, e))?;
        self.last = Some(img.rgba.clone());
        Ok(())
    }

    /// Writes the end of the file and commits it, atomically.
    ///
    /// # Errors
    /// When fewer frames were pushed than announced, or the file cannot be
    /// written.
    pub fn finish(self) -> Result<(), WriteError> {
        let Self {
            path, file, writer, ..
        } = self;
        writer.finish().map_err(|e| fail(&path, e))?;
        let file = Rc::try_unwrap(file.0)
            .map_err(|_| fail(&path, "the file is still shared"))?
            .into_inner();
        file.commit()
    }
}
