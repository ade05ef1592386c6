//! The `run` subcommand until the window exists: the ECS frame schedule drives the
//! cradle at 60 frames per second and a line of text shows where the balls are.

use crate::config::Config;
use crate::scene::{Control, CradleWorld, SimState, spawn::Layout};
use std::io::{self, IsTerminal, Write};
use std::time::Duration;

/// Columns of the text picture.
const COLUMNS: usize = 64;

/// One line: the balls' centres along the frame, `O` for each.
#[must_use]
pub fn draw(config: &Config, theta: &[f64]) -> String {
    let layout = Layout::new(config);
    let mut row = vec![' '; COLUMNS];
    for (i, &th) in theta.iter().enumerate() {
        let x = layout.pivot(i).x + config.cradle.length * th.sin();
        let col =
            ((x + layout.half_width) / (2.0 * layout.half_width) * (COLUMNS - 1) as f64).round();
        row[col.clamp(0.0, (COLUMNS - 1) as f64) as usize] = 'O';
    }
    format!("|{}|", row.into_iter().collect::<String>())
}

/// Runs `seconds` of simulated time through the ECS schedule, printing a line every
/// tenth of a second; in a terminal it keeps to real time and redraws in place.
///
/// # Errors
/// When writing to `out` fails.
pub fn preview(config: &Config, seconds: f64, out: &mut impl Write) -> io::Result<()> {
    let live = io::stdout().is_terminal();
    let mut world = CradleWorld::new(config);
    if world.state() == SimState::Paused {
        world.send(Control::TogglePause);
    }
    let fps = 60.0;
    for n in 0..=(seconds * fps) as u32 {
        world.frame(if n == 0 { 0.0 } else { 1.0 / fps });
        if n % 6 == 0 {
            let s = &world.cradle().snapshot;
            let err = world.cradle().cradle.energy_rel_error(s);
            let line = format!(
                "{} t={:5.2} s  impacts={:<4} energy err={err:+.1e}",
                draw(config, &s.theta),
                s.t,
                s.collisions
            );
            if live {
                write!(out, "\r{line}")?;
                out.flush()?;
                std::thread::sleep(Duration::from_millis(100));
            } else {
                writeln!(out, "{line}")?;
            }
        }
    }
    if live {
        writeln!(out)?;
    }
    Ok(())
}
