//! `newtons-cradle render`: frames of the swinging cradle without a window, as a
//! PNG, a numbered PNG sequence, or an animated GIF.

use crate::config::Config;
use crate::export::{self, GifWriter, WriteError};
use crate::scene::CradleWorld;
use crate::trace::{self, Image};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

/// What to render.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// One PNG at the start time.
    Png(PathBuf),
    /// `frames` PNGs `frame_0000.png`.. in a folder.
    Sequence { dir: PathBuf, frames: u32, fps: f64 },
    /// An animated GIF of `frames` frames.
    Gif {
        path: PathBuf,
        frames: u32,
        fps: f64,
    },
}

/// Renders the cradle of `config` starting at simulated time `start` (s) on a
/// pool of `config.render.threads` threads. Returns the files written.
///
/// # Errors
/// An output path that cannot be written.
pub fn render(config: &Config, start: f64, output: &Output) -> anyhow::Result<Vec<PathBuf>> {
    let pool = trace::pool(config.render.threads)?;
    let mut world = CradleWorld::new(config);
    // Frames after the first re-trace only what the swing can change.
    let mut inc = trace::Incremental::new();
    let mut frame_at = |t: f64| -> Image {
        world.show_at(t);
        pool.install(|| inc.render(world.scene()).clone())
    };
    let mut written = Vec::new();
    match output {
        Output::Png(path) => {
            // One frame: nothing to reuse, so no motion cells to note.
            world.show_at(start);
            export::write_png(path, &pool.install(|| trace::render(world.scene())))?;
            written.push(path.clone());
        }
        Output::Sequence { dir, frames, fps } => {
            let progress = Progress::new(*frames);
            for n in 0..*frames {
                let path = dir.join(format!("frame_{n:04}.png"));
                export::write_png(&path, &frame_at(start + f64::from(n) / fps))?;
                written.push(path);
                progress.tick(n + 1);
            }
            progress.done();
        }
        Output::Gif { path, frames, fps } => {
            let (w, h) = (config.render.width, config.render.height);
            let mut gif = GifWriter::create(path, w, h, *fps)?;
            let progress = Progress::new(*frames);
            for n in 0..*frames {
                gif.push(&frame_at(start + f64::from(n) / fps))?;
                progress.tick(n + 1);
            }
            progress.done();
            written.push(path.clone());
        }
    }
    Ok(written)
}

/// Whether an error is a path the user gave that cannot be written (exit code 2).
#[must_use]
pub fn is_bad_path(e: &anyhow::Error) -> bool {
    e.downcast_ref::<WriteError>().is_some()
}

/// A one-line progress bar on stderr, drawn only when stdout is a terminal.
struct Progress {
    total: u32,
    live: bool,
}

impl Progress {
    fn new(total: u32) -> Self {
        Self {
            total,
            live: std::io::stdout().is_terminal() && std::io::stderr().is_terminal(),
        }
    }

    fn tick(&self, done: u32) {
        if self.live {
            let width = 30;
            let filled = (done as usize * width) / self.total.max(1) as usize;
            eprint!(
                "\r[{}{}] {done}/{} frames",
                "#".repeat(filled),
                " ".repeat(width - filled),
                self.total
            );
            std::io::stderr().flush().ok();
        }
    }

    fn done(&self) {
        if self.live {
            eprintln!();
        }
    }
}

/// The folder and frames of a sequence, for logging.
#[must_use]
pub fn describe(output: &Output) -> String {
    match output {
        Output::Png(p) => format!("{}", p.display()),
        Output::Sequence { dir, frames, fps } => format!(
            "{frames} frames at {fps} fps in {}",
            Path::new(dir).display()
        ),
        Output::Gif { path, frames, fps } => {
            format!("{frames} frames at {fps} fps in {}", path.display())
        }
    }
}
