//! `newtons-cradle simulate`: the cradle's state as JSON Lines (docs/contracts.md).
//!
//! Line 1 `{"params":{..}}`; then one line per sample at `t = n * every` (a
//! product, never a running sum) up to the duration; last `{"summary":{..}}`.

use crate::config::Config;
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;

/// What a run measured, as printed in the summary line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Simulated seconds.
    pub duration: f64,
    /// Impacts in the run.
    pub collisions: u64,
    /// Energy at t = 0 (J).
    pub energy_initial: f64,
    /// Energy at the last sample (J).
    pub energy_final: f64,
    /// Largest |E(t) - E(0)| / E(0) over the samples; with dissipation, of the
    /// energy balance |E(t) + lost(t) - E(0)| / E(0).
    pub max_energy_rel_error: f64,
    /// With dissipation: energy lost in viscoelastic contacts by the end (J).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lost_contact: Option<f64>,
    /// With dissipation: energy lost to air drag by the end (J).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lost_drag: Option<f64>,
    /// Wall-clock seconds spent.
    pub wall_seconds: f64,
}

/// The run's parameters, as printed in the first line (SI units).
#[derive(Debug, Serialize)]
struct Params<'a> {
    balls: usize,
    radius: f64,
    length: f64,
    gap: f64,
    gravity: f64,
    mass: f64,
    lift: usize,
    angle_deg: f64,
    contact: &'a str,
    integrator: &'a str,
    dt: f64,
    restitution: f64,
    density: f64,
    /// The dissipation keys, only when the cradle loses energy (so elastic runs
    /// print what they always printed).
    #[serde(skip_serializing_if = "Option::is_none")]
    dissipation: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    air_density: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    drag_coefficient: Option<f64>,
}

/// One sample line.
#[derive(Debug, Serialize)]
struct Sample<'a> {
    t: f64,
    theta: &'a [f64],
    omega: &'a [f64],
    energy: f64,
    /// Total horizontal momentum of the balls (kg m/s).
    momentum: f64,
    collisions: u64,
    /// With dissipation: energy lost so far in contacts and to drag (J).
    #[serde(skip_serializing_if = "Option::is_none")]
    lost: Option<[f64; 2]>,
}

/// One impact, with `--impacts`.
#[derive(Debug, Serialize)]
struct ImpactLine {
    /// When the balls met (s).
    t: f64,
    /// The two balls (from 0, left to right).
    balls: [usize; 2],
    /// How fast they approached along the line of centres (m/s).
    speed: f64,
    /// The contact point (m): along the row from the first pivot, and up from
    /// the pivots.
    x: f64,
    y: f64,
    /// Hertz contact: how long the pair touched (s), its peak force (N) and
    /// the impulse it passed (N s).
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    peak_force: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    impulse: Option<f64>,
}

impl From<&crate::physics::Impact> for ImpactLine {
    fn from(i: &crate::physics::Impact) -> Self {
        Self {
            t: i.t,
            balls: [i.pair, i.pair + 1],
            speed: i.speed,
            x: i.at.0,
            y: i.at.1,
            contact_s: i.contact.map(|c| c.duration),
            peak_force: i.contact.map(|c| c.peak_force),
            impulse: i.contact.map(|c| c.impulse),
        }
    }
}

/// The first and last lines: `{"params":{..}}` and `{"summary":{..}}`; with
/// `--impacts`, `{"impact":{..}}` lines between the samples.
#[derive(Debug, Serialize)]
#[serde(rename_all = "lowercase")]
enum Framing<'a> {
    Params(Params<'a>),
    Impact(ImpactLine),
    Summary(&'a Summary),
}

/// Writes `value` as one JSON line.
fn line(out: &mut impl Write, value: &impl Serialize) -> io::Result<()> {
    serde_json::to_writer(&mut *out, value)?;
    writeln!(out)
}

/// How long the physics works between looks at its progress.
const PROBE: std::time::Duration = std::time::Duration::from_secs(1);

/// Keeps a long run talking: its lines leave the buffer at least every 0.1 s
/// of wall time, and once it is clear that the run will take more than 10 s
/// longer, stderr says about how long.
struct Feedback {
    start: Instant,
    flushed: Instant,
    duration: f64,
    warned: bool,
}

impl Feedback {
    fn new(start: Instant, duration: f64) -> Self {
        Self {
            start,
            flushed: start,
            duration,
            warned: false,
        }
    }

    /// After the sample at simulated time `t`.
    fn after(&mut self, t: f64, out: &mut impl Write) -> io::Result<()> {
        if self.flushed.elapsed().as_secs_f64() < 0.1 {
            return Ok(());
        }
        let spent = self.start.elapsed().as_secs_f64();
        if !self.warned && spent >= 1.0 && t > 0.0 {
            let left = spent * (self.duration / t - 1.0);
            if left > 10.0 {
                tracing::warn!(
                    "this run will take about {} more (from its first {spent:.0} s); Ctrl-C stops it",
                    human(left)
                );
                self.warned = true;
            }
        }
        // After the warning, so a reader of the lines has seen it by then.
        out.flush()?;
        self.flushed = Instant::now();
        Ok(())
    }
}

/// Seconds as a person reads them.
fn human(s: f64) -> String {
    match s {
        s if s < 120.0 => format!("{s:.0} s"),
        s if s < 7200.0 => format!("{:.0} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.0} h", s / 3600.0),
        s if s < 6.3e7 => format!("{:.0} days", s / 86_400.0),
        s => format!("{:.0} years", s / 3.156e7),
    }
}

/// Number of samples `n = 0..=count` with `n * every <= duration` (within 1e-9).
#[must_use]
pub fn sample_count(duration: f64, every: f64) -> u64 {
    (duration / every * (1.0 + 1e-9)).floor() as u64
}

/// Runs the simulation, writing JSON Lines to `out`; with `impacts`, each
/// impact too, before the first sample at or after it (a Hertz contact once
/// it has ended).
///
/// # Errors
/// When writing to `out` fails.
pub fn simulate(
    config: &Config,
    duration: f64,
    every: f64,
    impacts: bool,
    out: &mut impl Write,
) -> io::Result<Summary> {
    let start = Instant::now();
    let p = config.cradle_params();
    let damped = p.dissipative();
    let params = Params {
        balls: p.balls,
        radius: p.radius,
        length: p.length,
        gap: p.gap,
        gravity: p.gravity,
        mass: p.mass,
        lift: config.start.lift,
        angle_deg: config.start.angle_deg,
        contact: config.contact.model.name(),
        integrator: config.physics.integrator.name(),
        dt: config.physics.dt,
        restitution: p.restitution,
        density: config.cradle.density,
        dissipation: damped.then_some(config.contact.dissipation),
        air_density: damped.then_some(config.cradle.air_density),
        drag_coefficient: damped.then_some(config.cradle.drag_coefficient),
    };
    line(out, &Framing::Params(params))?;
    let mut cradle = config.build_cradle();
    if impacts {
        cradle.record_impacts();
    }
    let e0 = cradle.initial_energy();
    let (mut max_err, mut e_last, mut collisions) = (0.0_f64, e0, 0);
    let mut lost = [0.0; 2];
    let mut feedback = Feedback::new(start, duration);
    let bar = crate::bench::progress_bar(duration.ceil().max(1.0) as u64, "s simulated");
    for n in 0..=sample_count(duration, every) {
        let t = n as f64 * every;
        // A second of work at a time: a sample far ahead (a coarse --every)
        // still shows progress and its estimate. Stopping and going on leaves
        // the engines' steps and events as they are.
        let s = loop {
            let s = cradle.snapshot_by(t, Instant::now() + PROBE);
            if s.t >= t {
                break s;
            }
            bar.set_position(s.t as u64);
            feedback.after(s.t, out)?;
        };
        bar.set_position(t as u64);
        for i in &cradle.take_impacts(t) {
            line(out, &Framing::Impact(i.into()))?;
        }
        let e = cradle.energy(&s);
        if !(e.is_finite() && s.theta.iter().chain(&s.omega).all(|x| x.is_finite())) {
            // Never a null in the JSON: stop, and say where.
            return Err(io::Error::other(format!(
                "the state stopped being finite at t = {t} s; this is a bug: please report it with the config"
            )));
        }
        max_err = max_err.max(cradle.energy_rel_error(&s).abs());
        e_last = e;
        collisions = s.collisions;
        lost = s.lost;
        let sample = Sample {
            t,
            theta: &s.theta,
            omega: &s.omega,
            energy: e,
            momentum: p.momentum(&s.theta, &s.omega),
            collisions: s.collisions,
            lost: damped.then_some(s.lost),
        };
        line(out, &sample)?;
        feedback.after(t, out)?;
    }
    bar.finish_and_clear();
    let summary = Summary {
        duration,
        collisions,
        energy_initial: e0,
        energy_final: e_last,
        max_energy_rel_error: max_err,
        lost_contact: damped.then_some(lost[0]),
        lost_drag: damped.then_some(lost[1]),
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    line(out, &Framing::Summary(&summary))?;
    out.flush()?;
    Ok(summary)
}
