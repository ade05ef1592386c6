//! The command line parsed and checked once into a typed [`Job`]: each
//! subcommand's own flags first (before anything is loaded), then the config with
//! the common overrides. `main` only dispatches the job.

use super::args::Short;
use super::args::{
    BenchCommand, BenchMode, BenchPhysicsArgs, BenchRenderArgs, Cli, Command, Common, RenderArgs,
    SimulateArgs, Skip,
};
use super::overrides::InputError;
use crate::bench::physics::Plan;
use crate::config::{Config, ConfigSource};
use crate::export::{self, Kind};
use crate::headless::Output;
use std::path::PathBuf;

/// What the program was asked to do, with every value checked.
#[derive(Debug)]
pub enum Job {
    /// Open the window.
    Run {
        /// The config with the overrides applied.
        config: Config,
        /// Where it came from (watched for hot reload).
        source: ConfigSource,
        /// The overrides, applied again to each reload.
        overrides: Common,
    },
    /// `simulate`: JSON Lines of the state.
    Simulate {
        /// The config.
        config: Config,
        /// Simulated seconds.
        duration: f64,
        /// Sampling interval (s).
        every: f64,
        /// Print the impacts too.
        impacts: bool,
    },
    /// `render`: frames without a window.
    Render {
        /// The config.
        config: Config,
        /// Simulated time of the first frame (s).
        time: f64,
        /// What to write.
        output: Output,
        /// Where to write the soundtrack, if asked.
        audio: Option<PathBuf>,
        /// The config file being read, never to be replaced.
        input: Option<PathBuf>,
    },
    /// `bench render`.
    BenchRender {
        /// The config.
        config: Config,
        /// Thread counts to time.
        threads: Vec<usize>,
        /// Frames timed per thread count.
        frames: u32,
        /// Which modes to time: `full`, `incremental` or both.
        modes: Vec<&'static str>,
        /// The full frames' skips (`--without` turns some off).
        options: crate::trace::RenderOptions,
        /// JSON Lines instead of a table.
        json: bool,
    },
    /// `bench physics`.
    BenchPhysics {
        /// The sweep.
        plan: Plan,
        /// JSON Lines instead of a table.
        json: bool,
        /// Where to draw the diagram.
        plot: Option<PathBuf>,
    },
    /// `bench stress`.
    BenchStress {
        /// Durations relative to the test suite's.
        scale: f64,
        /// JSON Lines instead of a table.
        json: bool,
    },
    /// `bench rocking`.
    BenchRocking {
        /// The config.
        config: Config,
        /// Simulated seconds.
        duration: f64,
        /// One JSON line instead of a table.
        json: bool,
        /// Where to draw the amplitudes.
        plot: Option<PathBuf>,
    },
    /// `bench render-quality`.
    BenchQuality {
        /// The config.
        config: Config,
        /// Frames timed per row.
        frames: u32,
        /// JSON Lines instead of a table.
        json: bool,
        /// Where to draw the plot.
        plot: Option<PathBuf>,
    },
}

impl Job {
    /// Checks the command line and loads the config it names.
    ///
    /// # Errors
    /// A flag out of range or a bad config asset (exit code 2).
    pub fn from_cli(cli: Cli) -> Result<Self, InputError> {
        let common = cli.common;
        let asset = || load(&common).map(|(config, _)| config);
        Ok(match cli.command {
            None | Some(Command::Run) => {
                let (config, source) = load(&common)?;
                Self::Run {
                    config,
                    source,
                    overrides: common,
                }
            }
            Some(Command::Simulate(a)) => {
                check_simulate(&a)?;
                Self::Simulate {
                    config: asset()?,
                    duration: a.duration,
                    every: a.every,
                    impacts: a.impacts,
                }
            }
            Some(Command::Render(a)) => {
                let output = render_output(&a)?;
                let (config, source) = load(&common)?;
                // Before any tracing: a path that cannot or must not be written.
                let input = match &source {
                    ConfigSource::File(p) => Some(p.as_path()),
                    ConfigSource::Builtin => None,
                };
                output
                    .check(input)
                    .map_err(|e| InputError::Flag(e.to_string()))?;
                if let Some(audio) = &a.audio {
                    export::check_output(audio, Kind::Wav, input)
                        .map_err(|e| InputError::Flag(e.to_string()))?;
                }
                Self::Render {
                    config,
                    time: a.time,
                    output,
                    audio: a.audio,
                    input: input.map(std::path::Path::to_path_buf),
                }
            }
            Some(Command::Bench(cmd)) => Self::bench(cmd, &common)?,
        })
    }

    /// `bench render`'s job: its flags checked, then the config `asset` loads.
    fn bench_render(
        a: &BenchRenderArgs,
        asset: impl FnOnce() -> Result<Config, InputError>,
    ) -> Result<Self, InputError> {
        let frames = a.frames as u32;
        if !a.without.is_empty() && a.mode != BenchMode::Full {
            return Err(InputError::Flag(
                "--without applies to full frames: add --mode full (incremental frames \
                 always use every skip)"
                    .to_owned(),
            ));
        }
        let config = asset()?;
        let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
        let threads = if config.render.threads > 0 {
            vec![config.render.threads]
        } else {
            (1..=cores).collect()
        };
        let modes = match a.mode {
            BenchMode::Full => vec!["full"],
            BenchMode::Incremental => vec!["incremental"],
            BenchMode::Both => vec!["full", "incremental"],
            BenchMode::Orbit => vec!["orbit"],
        };
        let on = |s: Skip| !a.without.contains(&s);
        let options = crate::trace::RenderOptions {
            tile_culling: on(Skip::Tiles),
            shadow_culling: on(Skip::Shadows),
            bvh: on(Skip::Bvh),
            packets: on(Skip::Packets),
        };
        Ok(Self::BenchRender {
            config,
            threads,
            frames,
            modes,
            options,
            json: a.json,
        })
    }

    /// The `bench` subcommands' jobs.
    fn bench(cmd: BenchCommand, common: &Common) -> Result<Self, InputError> {
        let asset = || load(common).map(|(config, _)| config);
        Ok(match cmd {
            BenchCommand::Render(a) => Self::bench_render(&a, asset)?,
            BenchCommand::Physics(a) => {
                let dts = bench_physics_dts(&a);
                let config = asset()?;
                ignored(
                    common,
                    &["--angle"],
                    "bench physics runs its own cradle (5 touching balls, 1 lifted, ideal impacts, every integrator and step) with the asset's geometry",
                );
                check_plot(a.plot.as_deref(), common)?;
                Self::BenchPhysics {
                    plan: Plan {
                        params: config.cradle_params(),
                        angles_deg: common.angle.map_or(vec![30.0, 170.0], |a| vec![a]),
                        duration: a.duration,
                        dts,
                        sample_every: 0.01,
                    },
                    json: a.json,
                    plot: a.plot,
                }
            }
            BenchCommand::Stress(a) => {
                let scale = a.scale;
                ignored(
                    common,
                    &[],
                    "bench stress runs its fixed scenarios with the exact engine",
                );
                // The scenarios are fixed, but a bad asset or flag is still refused.
                asset()?;
                Self::BenchStress {
                    scale,
                    json: a.json,
                }
            }
            BenchCommand::Rocking(a) => {
                let duration = a.duration;
                check_plot(a.plot.as_deref(), common)?;
                let config = asset()?;
                if config.contact.model != crate::config::ContactModel::Hertz {
                    // Its restitution and losses are measured from Hertz contacts;
                    // ideal impacts would print a made-up restitution and no loss.
                    return Err(InputError::Flag(
                        "bench rocking measures Hertz contacts: contact.model is ideal; \
                         allowed: hertz (`--contact hertz`, or an asset such as \
                         assets/presets/realistic.ron)"
                            .to_owned(),
                    ));
                }
                Self::BenchRocking {
                    config,
                    duration,
                    json: a.json,
                    plot: a.plot,
                }
            }
            BenchCommand::RenderQuality(a) => {
                let frames = a.frames as u32;
                let used: Vec<&str> = common
                    .given_flags()
                    .into_iter()
                    .filter(|f| !matches!(*f, "--samples" | "--aa"))
                    .collect();
                ignored(
                    common,
                    &used,
                    "bench render-quality compares its own sampling schemes",
                );
                check_plot(a.plot.as_deref(), common)?;
                Self::BenchQuality {
                    config: asset()?,
                    frames,
                    json: a.json,
                    plot: a.plot,
                }
            }
        })
    }
}

/// Warns about override flags a command does not use (all but `used`).
fn ignored(common: &Common, used: &[&str], why: &str) {
    let unused: Vec<&str> = common
        .given_flags()
        .into_iter()
        .filter(|f| !used.contains(f))
        .collect();
    if !unused.is_empty() {
        tracing::warn!("{why}: {} not used", unused.join(", "));
    }
}

/// The config the common flags name, with their overrides; the log says which.
fn load(common: &Common) -> Result<(Config, ConfigSource), InputError> {
    let (config, source) = common.load()?;
    tracing::info!("config: {source}");
    Ok((config, source))
}

/// Checks a `--plot` path before the benchmark runs ([`export::check_output`]).
fn check_plot(plot: Option<&std::path::Path>, common: &Common) -> Result<(), InputError> {
    let Some(path) = plot else { return Ok(()) };
    export::check_output(path, Kind::Svg, common.config.as_deref())
        .map_err(|e| InputError::Flag(e.to_string()))
}

/// Checks `simulate`'s own flags.
///
/// # Errors
/// A flag out of range, with its range.
fn check_simulate(a: &SimulateArgs) -> Result<(), InputError> {
    if a.duration / a.every > 1e8 {
        return Err(InputError::Flag(format!(
            "--every {}: too small for --duration {}; allowed: at most 1e8 samples (every >= duration / 1e8)",
            a.every.short(),
            a.duration.short()
        )));
    }
    Ok(())
}

/// Checks `render`'s flags and says what to write.
///
/// # Errors
/// A flag out of range or a missing output, with what is allowed.
fn render_output(a: &RenderArgs) -> Result<crate::headless::Output, InputError> {
    use crate::headless::Output;
    // (The ranges were checked as the flags were parsed.)
    let frames = a.frames.map(|n| n as u32);
    let first = a.first.map_or(0, |k| k as u32);
    let animation = match (&a.gif, &a.apng) {
        (Some(_), Some(_)) => {
            return Err(InputError::Flag(
                "give either --gif or --apng, not both".into(),
            ));
        }
        (gif, apng) => gif.is_some() || apng.is_some(),
    };
    if a.first.is_some() && (frames.is_none() || animation) {
        return Err(InputError::Flag(
            "--first K: allowed with --frames N --out DIR/ (a PNG sequence) only".into(),
        ));
    }
    // Every frame's time is capped, not just the first one's.
    let last = a.time + f64::from(first + frames.unwrap_or(1).saturating_sub(1)) / a.fps;
    if last > 1e6 {
        // Name only what was given: the start time where it is not 0, the first
        // frame where a sequence starts later.
        let start = if a.time == 0.0 {
            String::new()
        } else {
            format!("--time {} + ", a.time.short())
        };
        let n = first + frames.unwrap_or(1).saturating_sub(1);
        return Err(InputError::Flag(format!(
            "the last frame, {start}frame {n} at --fps {}, is at {} s; allowed: every frame at \
             most 1e6 s (a smaller --first or --frames, or a higher --fps)",
            a.fps.short(),
            last.short()
        )));
    }
    if a.audio.is_some() && frames.is_none() && !animation {
        return Err(InputError::Flag(
            "--audio FILE.wav: allowed with --frames N --out DIR/, --gif FILE.gif or --apng \
             FILE.png (a soundtrack needs frames; one picture has none)"
                .into(),
        ));
    }
    if let Some(apng) = &a.apng {
        if a.out.is_some() {
            return Err(InputError::Flag(
                "give either --out or --apng, not both".into(),
            ));
        }
        return Ok(Output::Apng {
            path: apng.clone(),
            frames: frames.unwrap_or(60),
            fps: a.fps,
        });
    }
    match (&a.out, &a.gif, frames) {
        (Some(_), Some(_), _) => Err(InputError::Flag(
            "give either --out or --gif, not both".into(),
        )),
        (None, Some(gif), frames) => Ok(Output::Gif {
            path: gif.clone(),
            frames: frames.unwrap_or(60),
            fps: a.fps,
        }),
        (Some(dir), None, Some(frames)) => {
            // A sequence goes into a folder: `--out k.png` would make a folder
            // named like a picture.
            let picture = dir.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                ["png", "gif", "jpg", "jpeg"].contains(&e.to_ascii_lowercase().as_str())
            });
            if picture {
                return Err(InputError::Flag(format!(
                    "--out {} with --frames: a sequence goes into a folder; allowed: --out DIR/ \
                     (or --out FILE.png without --frames for one picture, --gif FILE.gif or \
                     --apng FILE.png for an animation)",
                    dir.display()
                )));
            }
            Ok(Output::Sequence {
                dir: dir.clone(),
                first,
                frames,
                fps: a.fps,
            })
        }
        (Some(png), None, None) => Ok(Output::Png(png.clone())),
        (None, None, _) => Err(InputError::Flag(
            "say where to write: --out FILE.png, --frames N --out DIR/, --gif FILE.gif or --apng \
             FILE.png"
                .into(),
        )),
    }
}

/// Checks `bench physics`' flags; returns the steps of the sweep.
///
/// # Errors
/// A flag out of range.
fn bench_physics_dts(a: &BenchPhysicsArgs) -> Vec<f64> {
    // Three steps per decade from 1e-2 down to min_dt.
    let mut dts = Vec::new();
    for i in 0.. {
        let dt = 1e-2 * 10f64.powf(-f64::from(i) / 3.0);
        if dt < a.min_dt * (1.0 - 1e-9) {
            break;
        }
        dts.push(dt);
    }
    dts
}
