//! The `newtons-cradle` binary: parses the command line once into a checked
//! [`Job`], then dispatches it to the library. Exit codes: 0 success, 2 bad input,
//! 1 anything else.

use clap::Parser;
use newtons_cradle::cli::{Cli, InputError, Job};
use newtons_cradle::{app, bench, headless, simulate};
use std::io;
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

impl From<anyhow::Error> for Failure {
    fn from(e: anyhow::Error) -> Self {
        // An output path the user gave that cannot be written is bad input.
        if headless::is_bad_path(&e) {
            Self::Input(InputError::Flag(e.to_string()))
        } else {
            Self::Other(e)
        }
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
    // Ctrl-C removes the temporary files of unfinished writes.
    newtons_cradle::export::clean_up_on_interrupt();
    match Job::from_cli(cli).map_err(Failure::from).and_then(run) {
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

/// Does the job; tables and JSON Lines go to stdout, logs to stderr.
fn run(job: Job) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    match job {
        // No display or adapter: said plainly (exit 1), not as a crash.
        Job::Run {
            config,
            source,
            overrides,
        } => app::run(config, source, overrides)?,
        Job::Simulate {
            config,
            duration,
            every,
            impacts,
        } => {
            let mut out = io::BufWriter::new(out);
            simulate::simulate(&config, duration, every, impacts, &mut out)?;
        }
        Job::Render {
            config,
            time,
            output,
            audio,
            input,
        } => headless::run(&config, time, &output, audio.as_deref(), input.as_deref())?,
        Job::BenchRender {
            config,
            threads,
            frames,
            modes,
            options,
            json,
        } => bench::render::report(&config, &threads, (frames, options), &modes, json, &mut out)?,
        Job::BenchPhysics { plan, json, plot } => {
            bench::physics::report(&plan, json, plot.as_deref(), &mut out)?;
        }
        Job::BenchStress { scale, json } => bench::stress::report(scale, json, &mut out)?,
        Job::BenchRocking {
            config,
            duration,
            json,
            plot,
        } => bench::rocking::report(&config, duration, json, plot.as_deref(), &mut out)?,
        Job::BenchQuality {
            config,
            frames,
            json,
            plot,
        } => bench::quality::report(&config, frames, json, plot.as_deref(), &mut out)?,
    }
    Ok(())
}
