//! `bench rocking`: a dissipative cradle (`assets/presets/realistic.ron`) over a long
//! run: each ball's amplitude against time, when the balls end up swinging in
//! phase, where the energy went, and the restitution its contact law gives at
//! 0.1, 0.5 and 1 m/s. `--plot` draws the amplitudes (docs/rocking.svg).

use super::plot::{Series, line_svg};
use crate::config::Config;
use crate::physics::{CradleParams, hertz};
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// Samples per second of the run (the in-phase test looks at every one).
const RATE: f64 = 100.0;

/// The balls are in phase while, over one swing, the spread of their angles
/// stays below this fraction of their common amplitude.
pub const IN_PHASE: f64 = 0.05;

/// Impact speeds (m/s) whose restitution is reported.
pub const SPEEDS: [f64; 3] = [0.1, 0.5, 1.0];

/// What a run showed.
#[derive(Debug, Clone, Serialize)]
pub struct Rocking {
    /// Simulated seconds.
    pub duration: f64,
    /// From when on (s) the balls stay in phase to the end; `None` if they are
    /// not by then.
    pub in_phase_from: Option<f64>,
    /// Over the last swing: the largest spread of the angles (rad)...
    pub final_spread: f64,
    /// ...and the largest angle of their mean (rad).
    pub final_amplitude: f64,
    /// Energy at the start and the end (J).
    pub energy: [f64; 2],
    /// Energy lost in contacts and to drag (J).
    pub lost: [f64; 2],
    /// Contacts (onsets).
    pub collisions: u64,
    /// CPU seconds of the simulation.
    pub cpu_seconds: f64,
    /// `(speed m/s, restitution)` of two of these balls meeting at the bottom.
    pub restitution: Vec<(f64, f64)>,
    /// Each ball's amplitude every 0.1 s (deg): its largest angle over the swing
    /// before.
    #[serde(skip)]
    pub amplitudes: Vec<(f64, Vec<f64>)>,
}

/// The restitution of ball 0 of `p` striking ball 1 at rest at `speed` (m/s),
/// both hanging at the bottom: minus their relative normal speed after the
/// contact over before it.
#[must_use]
pub fn restitution(p: &CradleParams, speed: f64) -> f64 {
    let two = CradleParams { balls: 2, ..*p };
    let k = two.hertz.unwrap_or(0.0);
    let w = speed / two.length;
    let end = hertz::run_phase(&two, k, 0.0, &[0.0; 2], &[w, 0.0], f64::INFINITY);
    (end.omega[1] - end.omega[0]) / w
}

/// Runs `config`'s cradle for `duration` (s).
#[must_use]
pub fn run(config: &Config, duration: f64) -> Rocking {
    let p = config.cradle_params();
    let cpu = super::thread_cpu_seconds();
    let mut cradle = config.build_cradle();
    let samples = (duration * RATE).round() as u64;
    let swing = (std::f64::consts::TAU / p.w0() * RATE).ceil() as usize;
    let mut window: std::collections::VecDeque<(f64, f64)> = std::collections::VecDeque::new();
    let (mut in_phase_from, mut last) = (None, (0.0, 0.0));
    let mut amplitudes = Vec::new();
    let mut reach: std::collections::VecDeque<Vec<f64>> = std::collections::VecDeque::new();
    let mut s = cradle.snapshot(0.0);
    // A long row takes minutes: a bar on a terminal, an estimate in the log.
    let bar = super::progress_bar(duration.ceil() as u64, "s simulated");
    let mut estimate = super::Estimate::new("bench rocking");
    for n in 0..=samples {
        let t = n as f64 / RATE;
        s = cradle.snapshot(t);
        if n % RATE as u64 == 0 {
            bar.set_position(t as u64);
            estimate.done(t / duration);
        }
        let (lo, hi) = s
            .theta
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let mean = s.theta.iter().sum::<f64>() / s.theta.len() as f64;
        window.push_back((hi - lo, mean.abs()));
        if window.len() > swing {
            window.pop_front();
        }
        if window.len() == swing {
            let spread = window.iter().map(|w| w.0).fold(0.0, f64::max);
            let common = window.iter().map(|w| w.1).fold(0.0, f64::max);
            let now = spread <= IN_PHASE * common;
            in_phase_from = match (now, in_phase_from) {
                (true, None) => Some(t),
                (true, since) => since,
                (false, _) => None,
            };
            last = (spread, common);
        }
        reach.push_back(s.theta.iter().map(|th| th.abs().to_degrees()).collect());
        if reach.len() > swing {
            reach.pop_front();
        }
        if n % 10 == 0 {
            let most = (0..s.theta.len())
                .map(|i| reach.iter().map(|r| r[i]).fold(0.0, f64::max))
                .collect();
            amplitudes.push((t, most));
        }
    }
    bar.finish_and_clear();
    let cpu_seconds = super::thread_cpu_seconds() - cpu;
    Rocking {
        duration,
        in_phase_from,
        final_spread: last.0,
        final_amplitude: last.1,
        energy: [cradle.initial_energy(), cradle.energy(&s)],
        lost: s.lost,
        collisions: s.collisions,
        cpu_seconds,
        restitution: SPEEDS.iter().map(|&v| (v, restitution(&p, v))).collect(),
        amplitudes,
    }
}

/// Runs `bench rocking`: a table (or one JSON line) to `out`, the plot to `plot`.
///
/// # Errors
/// Writing `out` or the plot fails.
pub fn report(
    config: &Config,
    duration: f64,
    json: bool,
    plot: Option<&Path>,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let r = run(config, duration);
    if json {
        serde_json::to_writer(&mut *out, &r)?;
        writeln!(out)?;
    } else {
        let since = r
            .in_phase_from
            .map_or_else(|| "not by the end".to_owned(), |t| format!("from {t:.1} s"));
        writeln!(
            out,
            "simulated {:.0} s in {:.2} s of CPU, {} contacts",
            r.duration, r.cpu_seconds, r.collisions
        )?;
        writeln!(
            out,
            "in phase (spread < {:.0}% of the amplitude over a swing): {since}",
            IN_PHASE * 100.0
        )?;
        writeln!(
            out,
            "last swing: spread {:.3} deg, amplitude {:.2} deg",
            r.final_spread.to_degrees(),
            r.final_amplitude.to_degrees()
        )?;
        writeln!(
            out,
            "energy {:.4e} J -> {:.4e} J; lost {:.4e} J in contacts, {:.4e} J to drag",
            r.energy[0], r.energy[1], r.lost[0], r.lost[1]
        )?;
        for (v, e) in &r.restitution {
            writeln!(out, "restitution at {v} m/s: {e:.4}")?;
        }
    }
    if let Some(path) = plot {
        let balls = r.amplitudes.first().map_or(0, |a| a.1.len());
        let series: Vec<Series> = (0..balls)
            .map(|i| Series {
                name: format!("ball {}", i + 1),
                points: r.amplitudes.iter().map(|(t, a)| (*t, a[i])).collect(),
            })
            .collect();
        line_svg(
            path,
            "Amplitude of each ball",
            &series,
            ("time (s)", "amplitude (deg)"),
        )?;
    }
    Ok(())
}
