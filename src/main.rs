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
                writeln!(out, "threads  mode         ms/frame  vs 1 thread full")?;
            }
            let mut base = None;
            bench::bench_render(&config, &threads, frames, |row| {
                let line = if args.json {
                    row.json()
                } else {
                    let b = *base.get_or_insert(row.ms_median);
                    format!(
                        "{:>7}  {:<11}  {:>8.2}  {:>7.2}x",
                        row.threads,
                        row.mode,
                        row.ms_median,
                        b / row.ms_median
                    )
                };
                let _ = writeln!(out, "{line}");
            })?;
        }
    }
    Ok(())
}
