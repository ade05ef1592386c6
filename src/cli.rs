//! The command line (DESIGN.md contract): subcommands, the common overrides, and
//! applying them to a config with errors that name the flag and its valid range.

use crate::config::{Config, ConfigSource, ContactModel, FieldError};
use crate::physics::Integrator;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// A Newton's cradle: ray traced on the CPU, driven by exact physics.
#[derive(Debug, Parser)]
#[command(name = "newtons-cradle", version, about, long_about = None)]
pub struct Cli {
    /// Overrides of the config asset, for every subcommand.
    #[command(flatten)]
    pub common: Common,
    /// What to do; `run` when left out.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the window (the default).
    Run,
    /// Print the cradle's state as JSON Lines: params, samples, summary.
    Simulate(SimulateArgs),
    /// Ray trace frames without a window: a PNG, a PNG sequence, or a GIF.
    Render(RenderArgs),
    /// Measure the program.
    #[command(subcommand)]
    Bench(BenchCommand),
}

/// `render`'s flags.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A PNG file (one frame), or with --frames a folder for frame_0000.png, ...
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Simulated time of the (first) frame (s), 0..=1e6.
    #[arg(
        long,
        default_value_t = 0.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub time: f64,
    /// Number of frames of a sequence or GIF, 1..=100000 (GIF default 60).
    #[arg(long, allow_negative_numbers = true, value_name = "N")]
    pub frames: Option<i64>,
    /// Frames per second of simulated time, > 0 and <= 1000.
    #[arg(
        long,
        default_value_t = 30.0,
        allow_negative_numbers = true,
        value_name = "F"
    )]
    pub fps: f64,
    /// Write an animated GIF here instead.
    #[arg(long, value_name = "FILE.gif")]
    pub gif: Option<PathBuf>,
}

/// What to measure.
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Milliseconds per frame of a swinging cradle for 1..=all threads.
    Render(BenchRenderArgs),
    /// Work-precision: each integrator's angle error against CPU time.
    Physics(BenchPhysicsArgs),
    /// The stability stress suite, longer than `cargo test` runs it.
    Stress(BenchStressArgs),
    /// Picture error (RMSE, PSNR) against ms per frame, per anti-aliasing mode and depth.
    RenderQuality(BenchQualityArgs),
}

/// `bench render-quality`'s flags.
#[derive(Debug, Args)]
pub struct BenchQualityArgs {
    /// JSON Lines instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also draw RMSE against ms per frame here.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
    /// Frames timed per row (the median is reported), 1..=1000.
    #[arg(
        long,
        default_value_t = 3,
        allow_negative_numbers = true,
        value_name = "N"
    )]
    pub frames: i64,
}

/// `bench stress`' flags.
#[derive(Debug, Args)]
pub struct BenchStressArgs {
    /// JSON Lines instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Run every scenario this many times longer than the test suite does, 0.01..=1000.
    #[arg(
        long,
        default_value_t = 10.0,
        allow_negative_numbers = true,
        value_name = "X"
    )]
    pub scale: f64,
}

/// Checks `bench stress`' flags.
///
/// # Errors
/// A flag out of range.
pub fn bench_stress_scale(a: &BenchStressArgs) -> Result<f64, InputError> {
    let ok = a.scale.is_finite() && (0.01..=1000.0).contains(&a.scale);
    flag_value("--scale", a.scale, ok, "0.01..=1000")
}

/// `bench physics`'s flags.
#[derive(Debug, Args)]
pub struct BenchPhysicsArgs {
    /// JSON Lines instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also draw the work-precision diagram (log error against log CPU time) here.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
    /// Simulated seconds per run, 0.1..=3600.
    #[arg(
        long,
        default_value_t = 60.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub duration: f64,
    /// Smallest step of the sweep (s), 1e-7..=1e-2 (the sweep runs from 1e-2 down).
    #[arg(
        long,
        default_value_t = 1e-5,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub min_dt: f64,
}

/// `bench render`'s flags.
#[derive(Debug, Args)]
pub struct BenchRenderArgs {
    /// JSON Lines instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Frames timed per thread count (the median is reported), 1..=10000.
    #[arg(
        long,
        default_value_t = 15,
        allow_negative_numbers = true,
        value_name = "N"
    )]
    pub frames: i64,
}

/// `simulate`'s flags.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Simulated time (s), 0..=1e7.
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub duration: f64,
    /// Sampling interval (s), > 0, at most 1e8 samples in all.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub every: f64,
}

/// Contact model names on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ContactFlag {
    /// Instantaneous impacts with restitution.
    Ideal,
    /// Soft Hertz spheres.
    Hertz,
}

/// Integrator names on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum IntegratorFlag {
    /// Closed-form flight, root-found impacts.
    Exact,
    /// Semi-implicit Euler.
    Euler,
    /// Stormer-Verlet.
    Verlet,
    /// Classic Runge-Kutta 4.
    Rk4,
    /// Yoshida 4th order.
    Yoshida4,
}

/// The common overrides (DESIGN.md): each replaces one config field.
#[derive(Debug, Clone, Args, Default)]
pub struct Common {
    /// Config asset (default: ./assets/cradle.ron if present, else the built-in one).
    #[arg(long, global = true, value_name = "PATH")]
    pub config: Option<PathBuf>,
    /// Number of balls, 1..=200.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "N")]
    pub balls: Option<i64>,
    /// Balls lifted from the left, 0..=balls.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "K")]
    pub lift: Option<i64>,
    /// Lift angle (degrees), 0 <= DEG < 180.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "DEG")]
    pub angle: Option<f64>,
    /// Gap between neighbouring balls at rest (m), >= 0.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "M")]
    pub gap: Option<f64>,
    /// Contact model.
    #[arg(long, global = true, value_enum)]
    pub contact: Option<ContactFlag>,
    /// Integrator.
    #[arg(long, global = true, value_enum)]
    pub integrator: Option<IntegratorFlag>,
    /// Step of the fixed-step integrators (s), 1e-7..=0.1.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "S")]
    pub dt: Option<f64>,
    /// Tracing threads, 0..=256 (0 = every core).
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "N")]
    pub threads: Option<i64>,
    /// Picture width (pixels), 16..=8192.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "W")]
    pub width: Option<i64>,
    /// Picture height (pixels), 16..=8192.
    #[arg(long, global = true, allow_negative_numbers = true, value_name = "H")]
    pub height: Option<i64>,
}

/// Bad input from a flag or the config: exit code 2.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The config asset.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// A flag out of range.
    #[error("{0}")]
    Flag(String),
}

/// A count flag as the config's integer type; a negative count becomes `fail`, a
/// value the field's check refuses, so that the flag's message shows its range.
fn count<T: TryFrom<i64>>(v: i64, fail: T) -> T {
    T::try_from(v).unwrap_or(fail)
}

impl Common {
    /// The flags given, as `(config field path, flag name, value as typed)`.
    fn given(&self) -> Vec<(&'static str, &'static str, String)> {
        let mut out = Vec::new();
        let mut add = |field, flag, v: Option<String>| {
            if let Some(v) = v {
                out.push((field, flag, v));
            }
        };
        add("cradle.balls", "--balls", self.balls.map(|v| v.to_string()));
        add("start.lift", "--lift", self.lift.map(|v| v.to_string()));
        add(
            "start.angle_deg",
            "--angle",
            self.angle.map(|v| v.to_string()),
        );
        add("cradle.gap", "--gap", self.gap.map(|v| v.to_string()));
        add(
            "contact.model",
            "--contact",
            self.contact.map(|v| format!("{v:?}").to_lowercase()),
        );
        add("physics.dt", "--dt", self.dt.map(|v| v.to_string()));
        add(
            "render.threads",
            "--threads",
            self.threads.map(|v| v.to_string()),
        );
        add("render.width", "--width", self.width.map(|v| v.to_string()));
        add(
            "render.height",
            "--height",
            self.height.map(|v| v.to_string()),
        );
        out
    }

    /// Loads the config this command line names and applies the overrides.
    ///
    /// # Errors
    /// A bad asset, or a flag out of range (with the flag's valid range).
    pub fn load(&self) -> Result<(Config, ConfigSource), InputError> {
        let source = ConfigSource::resolve(self.config.as_deref());
        let mut config = source.load()?;
        self.apply(&mut config)?;
        Ok((config, source))
    }

    /// Applies the overrides to `config` and validates the result.
    ///
    /// # Errors
    /// A flag out of range, named with its valid range; or a field of the asset that
    /// a flag made invalid (e.g. `--balls 2` with `lift: 3`).
    pub fn apply(&self, config: &mut Config) -> Result<(), InputError> {
        if let Some(v) = self.balls {
            config.cradle.balls = count(v, 0);
        }
        if let Some(v) = self.lift {
            config.start.lift = count(v, usize::MAX);
        }
        if let Some(v) = self.angle {
            config.start.angle_deg = v;
        }
        if let Some(v) = self.gap {
            config.cradle.gap = v;
        }
        if let Some(v) = self.contact {
            config.contact.model = match v {
                ContactFlag::Ideal => ContactModel::Ideal,
                ContactFlag::Hertz => ContactModel::Hertz,
            };
        }
        if let Some(v) = self.integrator {
            config.physics.integrator = match v {
                IntegratorFlag::Exact => Integrator::Exact,
                IntegratorFlag::Euler => Integrator::Euler,
                IntegratorFlag::Verlet => Integrator::Verlet,
                IntegratorFlag::Rk4 => Integrator::Rk4,
                IntegratorFlag::Yoshida4 => Integrator::Yoshida4,
            };
        }
        if let Some(v) = self.dt {
            config.physics.dt = v;
        }
        if let Some(v) = self.threads {
            config.render.threads = count(v, usize::MAX);
        }
        if let Some(v) = self.width {
            config.render.width = count(v, 0);
        }
        if let Some(v) = self.height {
            config.render.height = count(v, 0);
        }
        let Err(errors) = config.validate() else {
            return Ok(());
        };
        let given = self.given();
        Err(InputError::Flag(
            errors
                .iter()
                .map(|e| flag_message(e, &given))
                .collect::<Vec<_>>()
                .join("\n"),
        ))
    }
}

/// Names the flag that set a field, or says which field of the asset a flag broke.
fn flag_message(e: &FieldError, given: &[(&str, &str, String)]) -> String {
    match given.iter().find(|(field, _, _)| *field == e.path) {
        Some((_, flag, raw)) => format!("{flag} {raw}: not allowed; allowed: {}", e.allowed),
        None => {
            let flags: Vec<&str> = given.iter().map(|g| g.1).collect();
            format!("{e} (after applying {})", flags.join(", "))
        }
    }
}

/// Checks `simulate`'s own flags.
///
/// # Errors
/// A flag out of range, with its range.
pub fn check_simulate(a: &SimulateArgs) -> Result<(), InputError> {
    let ok = a.duration.is_finite() && (0.0..=1e7).contains(&a.duration);
    flag_value("--duration", a.duration, ok, "0..=1e7 (s)")?;
    let ok = a.every.is_finite() && a.every > 0.0;
    flag_value("--every", a.every, ok, "> 0 (s)")?;
    if a.duration / a.every > 1e8 {
        return Err(InputError::Flag(format!(
            "--every {}: too small for --duration {}; allowed: at most 1e8 samples (every >= duration / 1e8)",
            a.every, a.duration
        )));
    }
    Ok(())
}

/// Checks `render`'s flags and says what to write.
///
/// # Errors
/// A flag out of range or a missing output, with what is allowed.
pub fn render_output(a: &RenderArgs) -> Result<crate::headless::Output, InputError> {
    use crate::headless::Output;
    let ok = a.time.is_finite() && (0.0..=1e6).contains(&a.time);
    flag_value("--time", a.time, ok, "0..=1e6 (s)")?;
    let ok = a.fps.is_finite() && a.fps > 0.0 && a.fps <= 1000.0;
    flag_value("--fps", a.fps, ok, "> 0 and <= 1000")?;
    let frames = match a.frames {
        None => None,
        Some(n) => {
            Some(flag_value("--frames", n, (1..=100_000).contains(&n), "1..=100000")? as u32)
        }
    };
    match (&a.out, &a.gif, frames) {
        (Some(_), Some(_), _) => Err(InputError::Flag(
            "give either --out or --gif, not both".into(),
        )),
        (None, Some(gif), frames) => Ok(Output::Gif {
            path: gif.clone(),
            frames: frames.unwrap_or(60),
            fps: a.fps,
        }),
        (Some(dir), None, Some(frames)) => Ok(Output::Sequence {
            dir: dir.clone(),
            frames,
            fps: a.fps,
        }),
        (Some(png), None, None) => Ok(Output::Png(png.clone())),
        (None, None, _) => Err(InputError::Flag(
            "say where to write: --out FILE.png, --frames N --out DIR/, or --gif FILE.gif".into(),
        )),
    }
}

/// Checks `bench physics`' flags; returns the steps of the sweep.
///
/// # Errors
/// A flag out of range.
pub fn bench_physics_dts(a: &BenchPhysicsArgs) -> Result<Vec<f64>, InputError> {
    let ok = a.duration.is_finite() && (0.1..=3600.0).contains(&a.duration);
    flag_value("--duration", a.duration, ok, "0.1..=3600 (s)")?;
    let ok = a.min_dt.is_finite() && (1e-7..=1e-2).contains(&a.min_dt);
    flag_value("--min-dt", a.min_dt, ok, "1e-7..=1e-2 (s)")?;
    // Three steps per decade from 1e-2 down to min_dt.
    let mut dts = Vec::new();
    for i in 0.. {
        let dt = 1e-2 * 10f64.powf(-f64::from(i) / 3.0);
        if dt < a.min_dt * (1.0 - 1e-9) {
            break;
        }
        dts.push(dt);
    }
    Ok(dts)
}

/// Checks `bench render`'s flags.
///
/// # Errors
/// A flag out of range.
pub fn bench_frames(a: &BenchRenderArgs) -> Result<u32, InputError> {
    let ok = (1..=10_000).contains(&a.frames);
    flag_value("--frames", a.frames, ok, "1..=10000").map(|f| f as u32)
}

/// Checks `bench render-quality`'s flags; returns the frames per row.
///
/// # Errors
/// A flag out of range.
pub fn quality_frames(a: &BenchQualityArgs) -> Result<u32, InputError> {
    let ok = (1..=1000).contains(&a.frames);
    flag_value("--frames", a.frames, ok, "1..=1000").map(|f| f as u32)
}

/// `v` when `ok`; else the flag's error, naming what is allowed.
fn flag_value<T: std::fmt::Display>(
    flag: &str,
    v: T,
    ok: bool,
    allowed: &str,
) -> Result<T, InputError> {
    if ok {
        Ok(v)
    } else {
        Err(InputError::Flag(format!(
            "{flag} {v}: not allowed; allowed: {allowed}"
        )))
    }
}
