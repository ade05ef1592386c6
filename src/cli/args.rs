//! The clap schema of the command line (docs/contracts.md): subcommands, their
//! flags and the common overrides, as typed. A subcommand's number flags are
//! checked against their ranges here, as they are parsed ([`InRange`]); the
//! common overrides' ranges are the config's (`overrides`).

use clap::{Args, Parser, Subcommand, ValueEnum};

/// A whole-number flag: its value, or a message with what `allowed`. The
/// common overrides' ranges are the config's, checked when the config is
/// validated with them applied (a flag's error then names the flag).
fn whole(allowed: &'static str) -> impl Fn(&str) -> Result<i64, String> + Clone + Send + Sync {
    move |s: &str| {
        s.trim()
            .parse()
            .map_err(|_| format!("not a whole number; allowed: {allowed}"))
    }
}

/// A number flag: a finite number, or a message with what `allowed` (a
/// common override: see [`whole`]).
fn number(allowed: &'static str) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    move |s: &str| match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("not a finite number; allowed: {allowed}")),
    }
}

/// A subcommand's number flag, parsed and checked against its range in one
/// place: a value that is not a number, not finite or out of range is
/// refused with the flag, the value and what is allowed (exit code 2).
#[derive(Clone, Copy)]
struct InRange<T> {
    ok: fn(T) -> bool,
    allowed: &'static str,
}

/// [`InRange`] of the values `ok` takes, `allowed` saying which.
fn in_range<T>(ok: fn(T) -> bool, allowed: &'static str) -> InRange<T> {
    InRange { ok, allowed }
}

/// A number a flag can hold.
trait FlagNumber: std::str::FromStr + Short + Copy + Send + Sync + 'static {
    /// Not infinite nor NaN.
    fn finite(self) -> bool;
}

impl FlagNumber for f64 {
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl FlagNumber for i64 {
    fn finite(self) -> bool {
        true
    }
}

impl<T: FlagNumber> clap::builder::TypedValueParser for InRange<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &std::ffi::OsStr,
    ) -> Result<T, clap::Error> {
        let flag = arg
            .and_then(clap::Arg::get_long)
            .map_or_else(String::new, |l| format!("--{l} "));
        let text = value.to_string_lossy();
        let (why, shown) = match text.trim().parse::<T>() {
            Ok(v) if v.finite() && (self.ok)(v) => return Ok(v),
            Ok(v) => ("not allowed", v.short()),
            Err(_) => ("not a number", text.trim().to_owned()),
        };
        let message = format!("{flag}{shown}: {why}; allowed: {}\n", self.allowed);
        Err(clap::Error::raw(clap::error::ErrorKind::ValueValidation, message).with_cmd(cmd))
    }
}

/// A number as a message shows it: as typed for ordinary magnitudes, with an
/// exponent for extreme ones (1e300, not 301 digits).
pub trait Short {
    /// The text.
    fn short(&self) -> String;
}

impl Short for f64 {
    fn short(&self) -> String {
        let a = self.abs();
        if a != 0.0 && !(1e-5..1e16).contains(&a) {
            format!("{self:e}")
        } else {
            format!("{self}")
        }
    }
}

impl Short for i64 {
    fn short(&self) -> String {
        self.to_string()
    }
}
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
    /// Ray trace frames without a window: a PNG, a PNG sequence, a GIF or an animated PNG.
    Render(RenderArgs),
    /// Measure the program.
    #[command(subcommand)]
    Bench(BenchCommand),
}

/// `render`'s flags.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A PNG file (one frame), or with --frames a folder for `frame_0000.png`, ...
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Simulated time of the (first) frame (s), 0..=1e6.
    #[arg(value_parser = in_range(|v: f64| (0.0..=1e6).contains(&v), "0..=1e6 (s)"), 
        long,
        default_value_t = 0.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub time: f64,
    /// Number of frames of a sequence or animation, 1..=100000 (animation default 60).
    #[arg(value_parser = in_range(|v: i64| (1..=100_000).contains(&v), "1..=100000"), long, allow_negative_numbers = true, value_name = "N")]
    pub frames: Option<i64>,
    /// Frames per second of simulated time, > 0 and <= 1000.
    #[arg(value_parser = in_range(|v: f64| v > 0.0 && v <= 1000.0, "> 0 and <= 1000"), 
        long,
        default_value_t = 30.0,
        allow_negative_numbers = true,
        value_name = "F"
    )]
    pub fps: f64,
    /// Write an animated GIF here instead.
    #[arg(long, value_name = "FILE.gif")]
    pub gif: Option<PathBuf>,
    /// Write an animated PNG here instead (lossless; later frames hold only
    /// what changed).
    #[arg(long, value_name = "FILE.png")]
    pub apng: Option<PathBuf>,
    /// With --frames and --out DIR/: render frames K..K+N-1 (files numbered from
    /// K), so that a long sequence splits across processes, 0..=10000000.
    #[arg(value_parser = in_range(|v: i64| (0..=10_000_000).contains(&v), "0..=10000000"), long, allow_negative_numbers = true, value_name = "K")]
    pub first: Option<i64>,
    /// With a sequence or an animation: also write its soundtrack here (48 kHz,
    /// 16-bit stereo, as long as the frames).
    #[arg(long, value_name = "FILE.wav")]
    pub audio: Option<PathBuf>,
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
    /// A dissipative cradle (e.g. --config assets/presets/realistic.ron): amplitudes, the drift into swinging in phase, restitution.
    Rocking(BenchRockingArgs),
}

/// `bench rocking`'s flags.
#[derive(Debug, Args)]
pub struct BenchRockingArgs {
    /// One JSON line instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also draw each ball's amplitude against time here.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
    /// Simulated seconds, 1..=3600.
    #[arg(value_parser = in_range(|v: f64| (1.0..=3600.0).contains(&v), "1..=3600 (s)"),
        long,
        default_value_t = 90.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub duration: f64,
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
    #[arg(value_parser = in_range(|v: i64| (1..=1000).contains(&v), "1..=1000"), 
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
    #[arg(value_parser = in_range(|v: f64| (0.01..=1000.0).contains(&v), "0.01..=1000"), 
        long,
        default_value_t = 10.0,
        allow_negative_numbers = true,
        value_name = "X"
    )]
    pub scale: f64,
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
    #[arg(value_parser = in_range(|v: f64| (0.1..=3600.0).contains(&v), "0.1..=3600 (s)"), 
        long,
        default_value_t = 60.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub duration: f64,
    /// Smallest step of the sweep (s), 1e-7..=1e-2 (the sweep runs from 1e-2 down).
    #[arg(value_parser = in_range(|v: f64| (1e-7..=1e-2).contains(&v), "1e-7..=1e-2 (s)"), 
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
    #[arg(value_parser = in_range(|v: i64| (1..=10_000).contains(&v), "1..=10000"), 
        long,
        default_value_t = 15,
        allow_negative_numbers = true,
        value_name = "N"
    )]
    pub frames: i64,
    /// Which frames to time: every pixel traced afresh, only what motion changed,
    /// both, or the view turning.
    #[arg(long, value_enum, default_value_t = BenchMode::Both)]
    pub mode: BenchMode,
    /// With --mode full: trace without these skips, to see what each earns
    /// (the same picture, more work); a comma-separated list.
    #[arg(long, value_enum, value_delimiter = ',', value_name = "SKIP")]
    pub without: Vec<Skip>,
}

/// `bench render --without`: the tracer's work-skipping, each of which leaves
/// the picture as it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Skip {
    /// Primary rays test only the objects that cover their 16x16 tile (packets need it).
    Tiles,
    /// Shadow rays test only the objects whose shadow can fall there.
    Shadows,
    /// Secondary rays walk a bounding volume hierarchy past 64 objects.
    Bvh,
    /// Eight pixels' centre samples at a time in SIMD lanes.
    Packets,
}

/// `bench render --mode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BenchMode {
    /// Every pixel traced afresh each frame, nothing reused.
    Full,
    /// Only the pixels motion can change re-traced.
    Incremental,
    /// Full, then incremental.
    Both,
    /// The view turning a degree a frame around the cradle as it swings (a
    /// right-drag): one ray per 2x2 block, as the window traces a moving view;
    /// with the PSNR of those frames against the frame at rest.
    Orbit,
}

/// `simulate`'s flags.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Simulated time (s), 0..=1e7.
    #[arg(value_parser = in_range(|v: f64| (0.0..=1e7).contains(&v), "0..=1e7 (s)"), long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub duration: f64,
    /// Sampling interval (s), > 0, at most 1e8 samples in all.
    #[arg(value_parser = in_range(|v: f64| v > 0.0, "> 0 (s)"), long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub every: f64,
    /// Also print each impact as it happens: `{"impact":{..}}` lines between
    /// the samples.
    #[arg(long)]
    pub impacts: bool,
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

/// The common overrides (docs/contracts.md): each replaces one config field.
#[derive(Debug, Clone, Args, Default)]
pub struct Common {
    /// Config asset (default: ./assets/cradle.ron if present, else the built-in one).
    #[arg(long, global = true, value_name = "PATH")]
    pub config: Option<PathBuf>,
    /// Number of balls, 1..=200.
    #[arg(value_parser = whole("1..=200"), long, global = true, allow_negative_numbers = true, value_name = "N")]
    pub balls: Option<i64>,
    /// Balls lifted from the left, 0..=balls.
    #[arg(value_parser = whole("0..=balls"), long, global = true, allow_negative_numbers = true, value_name = "K")]
    pub lift: Option<i64>,
    /// Lift angle (degrees), 0..=179.999.
    #[arg(value_parser = number("0..=179.999"), long, global = true, allow_negative_numbers = true, value_name = "DEG")]
    pub angle: Option<f64>,
    /// Gap between neighbouring balls at rest (m), 0..=10.
    #[arg(value_parser = number("0..=10 (m)"), long, global = true, allow_negative_numbers = true, value_name = "M")]
    pub gap: Option<f64>,
    /// Contact model.
    #[arg(long, global = true, value_enum)]
    pub contact: Option<ContactFlag>,
    /// Integrator.
    #[arg(long, global = true, value_enum)]
    pub integrator: Option<IntegratorFlag>,
    /// Step of the fixed-step integrators (s), 1e-7..=0.1.
    #[arg(value_parser = number("1e-7..=0.1 (s)"), long, global = true, allow_negative_numbers = true, value_name = "S")]
    pub dt: Option<f64>,
    /// Tracing threads, 0..=256 (0 = every core).
    #[arg(value_parser = whole("0..=256 (0 = every core)"), long, global = true, allow_negative_numbers = true, value_name = "N")]
    pub threads: Option<i64>,
    /// Picture width (pixels), 16..=8192.
    #[arg(value_parser = whole("16..=8192"), long, global = true, allow_negative_numbers = true, value_name = "W")]
    pub width: Option<i64>,
    /// Picture height (pixels), 16..=8192.
    #[arg(value_parser = whole("16..=8192"), long, global = true, allow_negative_numbers = true, value_name = "H")]
    pub height: Option<i64>,
    /// Samples per pixel, 1..=64 (1 = no anti-aliasing).
    #[arg(value_parser = whole("1..=64 (1 = no anti-aliasing)"), long, global = true, allow_negative_numbers = true, value_name = "N")]
    pub samples: Option<i64>,
    /// Anti-aliasing: the samples in every pixel, or only at edges.
    #[arg(long, global = true, value_enum)]
    pub aa: Option<AaFlag>,
    /// Start the window muted (M unmutes).
    #[arg(long, global = true)]
    pub mute: bool,
}

/// Anti-aliasing schemes on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum AaFlag {
    /// Every pixel gets `samples` samples.
    Uniform,
    /// One sample, then `samples` where a neighbour differs (edges).
    Adaptive,
}
