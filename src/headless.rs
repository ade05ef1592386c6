//! `newtons-cradle render`: frames of the swinging cradle without a window, as a
//! PNG, a numbered PNG sequence, an animated GIF or an animated PNG, and with
//! `--audio` the frames' soundtrack (`sound::track`) from the impacts each
//! frame reports.

use crate::config::Config;
use crate::export::{self, ApngWriter, GifWriter, Kind, WriteError};
use crate::scene::CradleWorld;
use crate::sound::track::Soundtrack;
use crate::trace::{self, Image};
use std::path::{Path, PathBuf};

/// What to render.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// One PNG at the start time.
    Png(PathBuf),
    /// `frames` PNGs `frame_0000.png`.. in a folder.
    /// `frames` PNGs `frame_KKKK.png`.. in a folder, from frame `first` on.
    Sequence {
        dir: PathBuf,
        first: u32,
        frames: u32,
        fps: f64,
    },
    /// An animated GIF of `frames` frames.
    Gif {
        path: PathBuf,
        frames: u32,
        fps: f64,
    },
    /// An animated PNG of `frames` frames (lossless).
    Apng {
        path: PathBuf,
        frames: u32,
        fps: f64,
    },
}

impl Output {
    /// Checks the paths this output will write, before anything is traced
    /// ([`export::check_output`]; a sequence's folder and every frame's name).
    ///
    /// # Errors
    /// A path that cannot or must not be written.
    pub fn check(&self, input: Option<&Path>) -> Result<(), WriteError> {
        match self {
            Self::Png(p) => export::check_output(p, Kind::Png, input),
            Self::Gif { path, .. } => export::check_output(path, Kind::Gif, input),
            Self::Apng { path, .. } => export::check_output(path, Kind::Png, input),
            Self::Sequence {
                dir, first, frames, ..
            } => (*first..first.saturating_add(*frames))
                .try_for_each(|n| export::check_output(&frame_path(dir, n), Kind::Png, input)),
        }
    }
}

/// Frame `n` of a sequence in `dir`.
fn frame_path(dir: &Path, n: u32) -> PathBuf {
    dir.join(format!("frame_{n:04}.png"))
}

impl Output {
    /// The soundtrack of this output's frames from simulated time `start` (s):
    /// from the first frame's time for as long as the frames last; `None` for
    /// one picture.
    fn soundtrack(&self, config: &Config, start: f64) -> Option<Soundtrack> {
        match self {
            Self::Png(_) => None,
            Self::Sequence {
                first, frames, fps, ..
            } => Some(Soundtrack::new(
                config,
                start + f64::from(*first) / fps,
                f64::from(*frames) / fps,
            )),
            Self::Gif { frames, fps, .. } | Self::Apng { frames, fps, .. } => {
                Some(Soundtrack::new(config, start, f64::from(*frames) / fps))
            }
        }
    }
}

/// Renders the cradle of `config` starting at simulated time `start` (s) on a
/// pool of `config.render.threads` threads, with the frames' soundtrack in
/// `audio` if given. Returns the files written.
///
/// # Errors
/// An output path that cannot be written.
pub fn render(
    config: &Config,
    start: f64,
    output: &Output,
    audio: Option<&Path>,
    input: Option<&Path>,
) -> anyhow::Result<Vec<PathBuf>> {
    let pool = trace::pool(config.render.threads)?;
    let mut world = CradleWorld::new(config);
    reach(&mut world, start);
    let mut track = audio.and_then(|_| output.soundtrack(config, start));
    // Frames after the first re-trace only what the swing can change, up to
    // 4K: its bookkeeping (what each pixel's rays met) costs about 80 bytes a
    // pixel, 5 GB at 8192x8192, where a whole frame takes seconds anyway.
    let pixels = u64::from(config.render.width) * u64::from(config.render.height);
    let mut inc = (pixels <= INCREMENTAL_PIXELS).then(trace::Incremental::new);
    let mut frame_at = |t: f64, track: &mut Option<Soundtrack>| -> Image {
        world.show_at(t);
        if let Some(track) = track {
            track.hear(world.impacts(), world.scene());
        }
        let change = world.take_change();
        match &mut inc {
            Some(inc) => pool.install(|| inc.render_changed(world.scene(), &change).clone()),
            None => pool.install(|| trace::render(world.scene())),
        }
    };
    let mut written = Vec::new();
    match output {
        Output::Png(path) => {
            // One frame: nothing to reuse, so no motion cells to note.
            world.show_at(start);
            let img = traced_with_progress(&pool, world.scene());
            export::write_png(path, &img)?;
            written.push(path.clone());
        }
        Output::Sequence {
            dir,
            first,
            frames,
            fps,
        } => {
            let progress = crate::bench::progress_bar(u64::from(*frames), "frames");
            // Frame n at time start + n / fps, whichever process renders it.
            for n in *first..*first + *frames {
                let path = frame_path(dir, n);
                // Each frame again, as all were before tracing: never over a file
                // put there since that is not a PNG, nor over the config. What
                // changed under a running sequence (its folder removed, a file
                // put in its way) is a failure of the run (exit 1), not bad input.
                export::check_output(&path, Kind::Png, input)
                    .and_then(|()| {
                        export::write_png(&path, &frame_at(start + f64::from(n) / fps, &mut track))
                    })
                    .map_err(|e| WriteError {
                        bad_path: false,
                        ..e
                    })?;
                written.push(path);
                progress.inc(1);
            }
            progress.finish_and_clear();
        }
        Output::Gif { path, frames, fps } => {
            let (w, h) = (config.render.width, config.render.height);
            let mut gif = GifWriter::create(path, w, h, *fps)?;
            let progress = crate::bench::progress_bar(u64::from(*frames), "frames");
            for n in 0..*frames {
                gif.push(frame_at(start + f64::from(n) / fps, &mut track))?;
                progress.inc(1);
            }
            progress.finish_and_clear();
            gif.finish()?;
            written.push(path.clone());
        }
        Output::Apng { path, frames, fps } => {
            let (w, h) = (config.render.width, config.render.height);
            let mut apng = ApngWriter::create(path, (w, h), *frames, false)?;
            let mut delays = export::Delays::in_units(*fps, 1000.0);
            let progress = crate::bench::progress_bar(u64::from(*frames), "frames");
            for n in 0..*frames {
                // Whole frames per second exactly (1/30 s), others in rounded
                // milliseconds that add up to the frame times.
                let delay = match u16::try_from(*fps as i64) {
                    Ok(whole) if fps.fract() == 0.0 => (1, whole),
                    _ => (delays.next_delay(), 1000),
                };
                apng.push(&frame_at(start + f64::from(n) / fps, &mut track), delay)?;
                progress.inc(1);
            }
            progress.finish_and_clear();
            apng.finish()?;
            written.push(path.clone());
        }
    }
    if let (Some(mut track), Some(path)) = (track, audio) {
        // The impacts after the last frame, to the track's end: a contact
        // starting just before it ends within a millisecond.
        world.show_at(track.end() + 1e-3);
        track.hear(world.impacts(), world.scene());
        // As the frames: checked again, and a failure now is the run's (exit 1).
        export::check_output(path, Kind::Wav, input)
            .and_then(|()| track.write(path))
            .map_err(|e| WriteError {
                bad_path: false,
                ..e
            })?;
        tracing::info!(
            "soundtrack: {} clicks over {:.3} s",
            track.clicks().len(),
            track.end() - track.start()
        );
        written.push(path.to_path_buf());
    }
    Ok(written)
}

/// The largest picture (pixels) whose sequences are traced incrementally.
const INCREMENTAL_PIXELS: u64 = 3840 * 2160;

/// One frame of `scene` traced on `pool`, its rows counted on a bar on a
/// terminal and, where it will take over 10 s (8K at 64 samples), in the log.
fn traced_with_progress(pool: &rayon::ThreadPool, scene: &trace::Scene) -> Image {
    let bar = crate::bench::progress_bar(1000, "thousandths of the frame");
    let mut estimate = crate::bench::Estimate::new("tracing the frame");
    let img = crate::bench::traced_watching(pool, scene, |done| {
        bar.set_position((1000.0 * done) as u64);
        estimate.done(done);
    });
    bar.finish_and_clear();
    img
}

/// Works out the swing up to the start time `start` (s), with a bar on a
/// terminal and, where it will take over 10 s, a log line saying how long.
fn reach(world: &mut CradleWorld, start: f64) {
    let clock = std::time::Instant::now();
    let bar = crate::bench::progress_bar(start.ceil().max(1.0) as u64, "s simulated");
    let mut said = false;
    world.reach(start, |t| {
        bar.set_position(t as u64);
        let spent = clock.elapsed().as_secs_f64();
        let left = if t > 0.0 {
            spent * (start / t - 1.0)
        } else {
            f64::INFINITY
        };
        if !said && spent >= 2.0 && left > 10.0 {
            said = true;
            tracing::info!(
                "working out the swing to t = {start} s: {:.0} s so far, about {:.0} s more",
                spent,
                left.min(1e9)
            );
        }
    });
    bar.finish_and_clear();
}

/// `render`: logs what it makes, renders it, and logs what it wrote.
///
/// # Errors
/// As [`render`].
pub fn run(
    config: &Config,
    start: f64,
    output: &Output,
    audio: Option<&Path>,
    input: Option<&Path>,
) -> anyhow::Result<()> {
    tracing::info!(
        "rendering {} at {}x{}",
        describe(output),
        config.render.width,
        config.render.height
    );
    let clock = std::time::Instant::now();
    let files = render(config, start, output, audio, input)?;
    tracing::info!(
        "wrote {} file(s) in {:.2} s",
        files.len(),
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Whether an error is a path the user gave that cannot be written (exit code 2).
#[must_use]
pub fn is_bad_path(e: &anyhow::Error) -> bool {
    e.downcast_ref::<WriteError>().is_some_and(|w| w.bad_path)
}

/// The folder and frames of a sequence, for logging.
#[must_use]
pub fn describe(output: &Output) -> String {
    match output {
        Output::Png(p) => format!("{}", p.display()),
        Output::Sequence {
            dir,
            first,
            frames,
            fps,
        } => format!(
            "{frames} frames from frame {first} at {fps} fps in {}",
            Path::new(dir).display()
        ),
        Output::Gif { path, frames, fps } | Output::Apng { path, frames, fps } => {
            format!("{frames} frames at {fps} fps in {}", path.display())
        }
    }
}
