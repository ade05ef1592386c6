//! The `newtons-cradle` binary: parses the command line, loads the config, and hands
//! over to the library. Exit codes: 0 success, 2 bad input, 1 anything else.

use clap::Parser;
use newtons_cradle::cli::{self, BenchCommand, Cli, Command, InputError};
use newtons_cradle::{bench, headless, simulate};
use std::io::{self, Write};
use std::process::ExitCode;

/// Why the program stopped early.
enum Failure {
    /// Bad config or flag: exit code 2.
    Input(InputError),
    /// Anything else: exit code 1.
    Other(anyhow::Error),
}

impl From<InputError> for Failure {
    fn from(e: InputError) -> Self {
        Self::Input(e)
    }
}

impl From<io::Error> for Failure {
    fn from(e: io::Error) -> Self {
        Self::Other(e.into())
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    tracing_subscriber::fmt()
        .with_writer(io::stderr)
        .with_ansi(io::IsTerminal::is_terminal(&io::stderr()))
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .init();
    match run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Other(e)) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(Failure::Other(e)) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

/// Output cut short by a closed pipe (`| head`) is not a failure.
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.downcast_ref::<io::Error>()
        .is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe)
}

impl From<anyhow::Error> for Failure {
    fn from(e: anyhow::Error) -> Self {
        if headless::is_bad_path(&e) {
            Self::Input(InputError::Flag(e.to_string()))
        } else {
            Self::Other(e)
        }
    }
}

fn run(cli: &Cli) -> Result<(), Failure> {
    // Check the subcommand's own flags before loading anything.
    let render_output = match &cli.command {
        Some(Command::Simulate(args)) => {
            cli::check_simulate(args)?;
            None
        }
        Some(Command::Render(args)) => Some(cli::render_output(args)?),
        Some(Command::Bench(BenchCommand::Render(args))) => {
            cli::bench_frames(args)?;
            None
        }
        Some(Command::Bench(BenchCommand::Physics(args))) => {
            cli::bench_physics_dts(args)?;
            None
        }
        Some(Command::Bench(BenchCommand::Stress(args))) => {
            cli::bench_stress_scale(args)?;
            None
        }
        Some(Command::Bench(BenchCommand::RenderQuality(args))) => {
            cli::quality_frames(args)?;
            None
        }
        _ => None,
    };
    let (config, source) = cli.common.load()?;
    tracing::info!("config: {source}");
    match &cli.command {
        None | Some(Command::Run) => {
            newtons_cradle::app::run(config, source, cli.common.clone()).map_err(|e| {
                // No display or adapter: say so plainly (exit 1), not as a crash.
                Failure::Other(e)
            })?;
        }
        Some(Command::Simulate(args)) => {
            let mut out = io::BufWriter::new(io::stdout().lock());
            simulate::simulate(&config, args.duration, args.every, &mut out)?;
        }
        Some(Command::Render(args)) => {
            let output = render_output.expect("checked above for render");
            tracing::info!(
                "rendering {} at {}x{}",
                headless::describe(&output),
                config.render.width,
                config.render.height
            );
            let start = std::time::Instant::now();
            let files = headless::render(&config, args.time, &output)?;
            tracing::info!(
                "wrote {} file(s) in {:.2} s",
                files.len(),
                start.elapsed().as_secs_f64()
            );
        }
        Some(Command::Bench(BenchCommand::Render(args))) => {
            let frames = cli::bench_frames(args)?;
            let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
            let threads: Vec<usize> = if config.render.threads > 0 {
                vec![config.render.threads]
            } else {
                (1..=cores).collect()
            };
            let mut out = io::stdout().lock();
            if !args.json {
                writeln!(
                    out,
                    "{}x{}, {} balls, median of {frames} frames of a swinging cradle",
                    config.render.width, config.render.height, config.cradle.balls
                )?;
                writeln!(
                    out,
                    "threads  mode         ms/frame  vs 1 thread full  pixels traced"
                )?;
            }
            let mut base = None;
            bench::bench_render(&config, &threads, frames, |row| {
                let line = if args.json {
                    row.json()
                } else {
                    let b = *base.get_or_insert(row.ms_median);
                    format!(
                        "{:>7}  {:<11}  {:>8.2}  {:>15.2}x  {:>12.1}%",
                        row.threads,
                        row.mode,
                        row.ms_median,
                        b / row.ms_median,
                        100.0 * row.traced
                    )
                };
                let _ = writeln!(out, "{line}");
            })?;
        }
        Some(Command::Bench(BenchCommand::Physics(args))) => {
            let dts = cli::bench_physics_dts(args)?;
            bench_physics(&config, cli.common.angle, args, dts)?;
        }
        Some(Command::Bench(BenchCommand::Stress(args))) => {
            bench_stress(cli::bench_stress_scale(args)?, args.json)?;
        }
        Some(Command::Bench(BenchCommand::RenderQuality(args))) => {
            bench_quality(&config, args)?;
        }
    }
    Ok(())
}

/// `bench physics`: runs the sweep, prints rows as they come, then the observed
/// orders, and draws the plot.
fn bench_physics(
    config: &newtons_cradle::config::Config,
    angle: Option<f64>,
    args: &cli::BenchPhysicsArgs,
    dts: Vec<f64>,
) -> Result<(), Failure> {
    use newtons_cradle::bench::physics::{self, Plan};
    use newtons_cradle::physics::Integrator;
    let plan = Plan {
        params: config.cradle_params(),
        angles_deg: angle.map_or(vec![30.0, 170.0], |a| vec![a]),
        duration: args.duration,
        dts,
        sample_every: 0.01,
    };
    let mut out = io::stdout().lock();
    if !args.json {
        writeln!(
            out,
            "5 balls, 1 lifted, {} s simulated; error: max angle error (rad) against the closed form",
            plan.duration
        )?;
        writeln!(out, "angle  integrator  dt (s)     error (rad)  CPU (s)")?;
    }
    let total = plan.runs();
    let mut done = 0;
    let points = physics::run(&plan, |pt| {
        done += 1;
        let line = if args.json {
            pt.json()
        } else {
            format!(
                "{:>5}  {:<10}  {:<9}  {:>11.3e}  {:>9.3e}",
                pt.angle_deg,
                pt.integrator.name(),
                pt.dt.map_or("-".into(), |d| format!("{d:.2e}")),
                pt.error,
                pt.cpu_seconds
            )
        };
        let _ = writeln!(out, "{line}");
        tracing::debug!("bench physics: {done}/{total} runs");
    });
    if !args.json {
        for &a in &plan.angles_deg {
            writeln!(
                out,
                "observed order at {a} deg (between consecutive steps, finest last):"
            )?;
            for m in &Integrator::ALL[1..] {
                let o: Vec<String> = physics::orders(&points, *m, a)
                    .iter()
                    .map(|(_, o)| format!("{o:.2}"))
                    .collect();
                writeln!(out, "  {:<9} {}", m.name(), o.join(" "))?;
            }
        }
    }
    if let Some(path) = &args.plot {
        physics::plot(&points, &plan, path)?;
        tracing::info!("wrote {}", path.display());
    }
    Ok(())
}

/// `bench stress`: every scenario of the suite, `scale` times longer; exit 1 when
/// one fails its checks.
fn bench_stress(scale: f64, json: bool) -> Result<(), Failure> {
    use newtons_cradle::bench::stress;
    let mut out = io::stdout().lock();
    if !json {
        writeln!(
            out,
            "stress suite at {scale}x the test's durations (exact engine)"
        )?;
        writeln!(
            out,
            "{:<36} {:>8} {:>9} {:>10} {:>10} {:>9} {:>7}",
            "scenario", "sim s", "impacts", "drift", "overlap m", "angle/max", "CPU s"
        )?;
    }
    let mut failed = Vec::new();
    for s in stress::scenarios(scale) {
        let r = stress::run(&s);
        if json {
            writeln!(out, "{}", r.json())?;
        } else {
            writeln!(
                out,
                "{:<36} {:>8.0} {:>9} {:>10.2e} {:>10.2e} {:>9.6} {:>7.2}",
                r.name,
                r.duration,
                r.impacts,
                r.energy_drift,
                r.max_overlap.max(0.0),
                r.max_angle / r.angle_bound,
                r.cpu_seconds
            )?;
        }
        for f in r.failures(&s) {
            failed.push(format!("{}: {f}", s.name));
        }
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Failure::Other(anyhow::anyhow!(
            "stress suite failed:\n{}",
            failed.join("\n")
        )))
    }
}

/// `bench render-quality`: the table (or JSON Lines) and the plot.
fn bench_quality(
    config: &newtons_cradle::config::Config,
    args: &cli::BenchQualityArgs,
) -> Result<(), Failure> {
    use newtons_cradle::bench::quality;
    let frames = cli::quality_frames(args)?;
    let threads = config.render.threads;
    let mut out = io::stdout().lock();
    let title = format!(
        "{}x{}, {} threads, t = 0.5 s",
        config.render.width,
        config.render.height,
        if threads == 0 {
            "all".to_owned()
        } else {
            threads.to_string()
        }
    );
    if !args.json {
        writeln!(
            out,
            "{title}; reference: 64 spp, depth 8; adaptive threshold {}",
            config.render.adaptive_threshold
        )?;
        writeln!(
            out,
            "mode         depth  ms/frame    RMSE  PSNR dB  PSNR vs 16 spp"
        )?;
    }
    let rows = quality::run(config, threads, frames, |r| {
        let line = if args.json {
            r.json()
        } else {
            format!(
                "{:<11}  {:>5}  {:>8.1}  {:>6.3}  {:>7.2}  {:>14.2}",
                r.mode, r.depth, r.ms_median, r.rmse, r.psnr, r.psnr_vs_16
            )
        };
        let _ = writeln!(out, "{line}");
    })?;
    if let Some(path) = &args.plot {
        quality::plot(&rows, path, &title)?;
        tracing::info!("wrote {}", path.display());
    }
    Ok(())
}
