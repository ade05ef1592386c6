//! The `newtons-cradle` binary: parses the command line, loads the config, and hands
//! over to the library. Exit codes: 0 success, 2 bad input, 1 anything else.

use clap::Parser;
use newtons_cradle::cli::{self, Cli, Command, InputError};
use newtons_cradle::{preview, simulate};
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

fn run(cli: &Cli) -> Result<(), Failure> {
    if let Some(Command::Simulate(args)) = &cli.command {
        cli::check_simulate(args)?;
    }
    let (config, source) = cli.common.load()?;
    tracing::info!("config: {source}");
    match &cli.command {
        None | Some(Command::Run) => {
            let mut out = io::stdout().lock();
            writeln!(
                out,
                "newtons-cradle: the window is not built yet; here is a text preview of {} balls, {} lifted to {} degrees.",
                config.cradle.balls, config.start.lift, config.start.angle_deg
            )?;
            preview::preview(&config, 3.0, &mut out)?;
            writeln!(
                out,
                "For the numbers: `newtons-cradle simulate --duration 10 --every 0.01` prints the state as JSON Lines."
            )?;
        }
        Some(Command::Simulate(args)) => {
            let mut out = io::BufWriter::new(io::stdout().lock());
            simulate::simulate(&config, args.duration, args.every, &mut out)?;
        }
    }
    Ok(())
}
