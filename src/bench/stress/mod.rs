//! The stability stress suite: extreme cradles run for a long time, each checked for
//! non-finite numbers, energy drift, overlap and angles beyond what the start's
//! energy allows. `tests/stress.rs` runs it at scale 1 (seconds of CPU) in
//! `cargo test`; `newtons-cradle bench stress --scale N` runs every scenario N
//! times longer.

mod cases;

pub use cases::scenarios;

use crate::physics::{Cradle, CradleParams, Integrator};
use serde::Serialize;
use std::io::Write;

/// One stress case.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// Short name.
    pub name: String,
    /// The cradle.
    pub params: CradleParams,
    /// Balls lifted.
    pub lift: usize,
    /// Lift angle (degrees).
    pub angle_deg: f64,
    /// Simulated seconds.
    pub duration: f64,
    /// The state is checked every this many seconds.
    pub sample_every: f64,
    /// Largest energy change allowed, relative to the start: drift either way
    /// with restitution 1, growth only below it.
    pub energy_tol: f64,
    /// Largest overlap of neighbours allowed (m); `None` for Hertz contact, where
    /// overlap is the physics.
    pub overlap_tol: Option<f64>,
    /// Energy just after the first strike as a fraction of the start's, where the
    /// model gives it in closed form.
    pub first_strike_energy: Option<f64>,
    /// The impacts must have stopped by this time (s), at any scale: restitution
    /// < 1 ends a touching chain in finitely many events. Unchecked in runs
    /// shorter than it.
    pub rest_by: Option<f64>,
}

/// What one scenario did; as JSON, one line of `bench stress --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Scenario name.
    #[serde(rename = "scenario")]
    pub name: String,
    /// Simulated seconds.
    pub duration: f64,
    /// Impacts (Hertz: contacts).
    pub impacts: u64,
    /// Every number stayed finite.
    pub finite: bool,
    /// Largest `|E - E0| / E0` (restitution 1) or largest growth over the lowest
    /// energy so far, relative to `E0` (restitution < 1).
    pub energy_drift: f64,
    /// Largest overlap of neighbours seen (m).
    pub max_overlap: f64,
    /// Largest `|theta|` seen (rad).
    pub max_angle: f64,
    /// The most any ball can swing with the start's energy (rad).
    pub angle_bound: f64,
    /// Energy just after the first strike over the start's.
    pub first_strike_energy: f64,
    /// Impacts after the scenario's `rest_by` time (0 once at rest; 0 when the
    /// run is shorter or there is none).
    pub late_impacts: u64,
    /// CPU seconds.
    pub cpu_seconds: f64,
}

impl Report {
    /// What went wrong, checked against the scenario's limits; empty when it passed.
    #[must_use]
    pub fn failures(&self, s: &Scenario) -> Vec<String> {
        let mut out = Vec::new();
        if !self.finite {
            out.push("a non-finite angle, speed or energy".to_owned());
        }
        if self.energy_drift.is_nan() || self.energy_drift > s.energy_tol {
            out.push(format!(
                "energy drift {:e} > {:e}",
                self.energy_drift, s.energy_tol
            ));
        }
        if let Some(tol) = s.overlap_tol
            && (self.max_overlap.is_nan() || self.max_overlap > tol)
        {
            out.push(format!("overlap {:e} m > {tol:e} m", self.max_overlap));
        }
        // The bound's own round-off: 1e-12 rad. A bound of pi means the energy
        // could carry a ball over the top: there is no angle to exceed.
        let over_the_top = self.angle_bound >= std::f64::consts::PI;
        if self.max_angle.is_nan() || (!over_the_top && self.max_angle > self.angle_bound + 1e-12) {
            out.push(format!(
                "angle {} rad beyond the energy's bound {} rad",
                self.max_angle, self.angle_bound
            ));
        }
        // NaN: the run ended before the first strike (a short `--scale`); a
        // non-finite state is caught above.
        if let Some(want) = s.first_strike_energy
            && !self.first_strike_energy.is_nan()
        {
            // The first strike is a handful of exact impulses: 1e-12 of round-off.
            if (self.first_strike_energy - want).abs() > 1e-12 {
                out.push(format!(
                    "first strike left {} of the energy, the model says {want}",
                    self.first_strike_energy
                ));
            }
        }
        if let Some(t) = s.rest_by
            && self.late_impacts > 0
        {
            out.push(format!(
                "{} impacts after {t} s: never came to rest",
                self.late_impacts
            ));
        }
        out
    }
}

/// Runs one scenario with the exact engine.
#[must_use]
pub fn run(s: &Scenario) -> Report {
    let start = super::thread_cpu_seconds();
    let p = s.params;
    let angle = s.angle_deg.to_radians();
    let mut c = Cradle::new(p, Integrator::Exact, 1e-3, s.lift, angle);
    let e0 = c.initial_energy();
    // With all the energy in one ball: sin^2(A_max/2) = k sin^2(A/2).
    let angle_bound = 2.0
        * ((s.lift as f64).sqrt() * (0.5 * angle).sin())
            .clamp(-1.0, 1.0)
            .asin();
    // The lifted balls reach the bottom a quarter period after release.
    let quarter = crate::physics::period_ratio(angle) * std::f64::consts::FRAC_PI_2 / p.w0();
    let mut report = Report {
        name: s.name.clone(),
        duration: s.duration,
        impacts: 0,
        finite: true,
        energy_drift: 0.0,
        max_overlap: f64::NEG_INFINITY,
        max_angle: 0.0,
        angle_bound,
        first_strike_energy: f64::NAN,
        late_impacts: 0,
        cpu_seconds: 0.0,
    };
    let samples = (s.duration / s.sample_every).round() as u64;
    let mut lowest = e0;
    let mut at_rest_by = None;
    let mut check = |c: &mut Cradle, t: f64, report: &mut Report| {
        let snap = c.snapshot(t);
        let e = c.energy(&snap);
        report.finite &=
            e.is_finite() && snap.theta.iter().chain(&snap.omega).all(|v| v.is_finite());
        // Kept energy: its drift; a lossy cradle's books: the error of the
        // balance E + lost - E0; ideal impacts that lose energy unbooked: any
        // rise above the lowest energy yet.
        let drift = if p.dissipative() {
            c.energy_rel_error(&snap).abs()
        } else if p.restitution == 1.0 {
            (e - e0).abs() / e0
        } else {
            (e - lowest) / e0
        };
        report.energy_drift = report.energy_drift.max(drift);
        lowest = lowest.min(e);
        for (a, w) in snap.theta.windows(2).enumerate() {
            let (x0, y0) = p.centre(a, w[0]);
            let (x1, y1) = p.centre(a + 1, w[1]);
            report.max_overlap = report
                .max_overlap
                .max(2.0 * p.radius - (x1 - x0).hypot(y1 - y0));
        }
        for th in &snap.theta {
            report.max_angle = report.max_angle.max(th.abs());
        }
        report.impacts = snap.collisions;
        e
    };
    for n in 0..=samples {
        let t = n as f64 * s.sample_every;
        // Just after the first strike (a thousandth of a period later).
        let probe = quarter * 1.004;
        if n > 0 && (n - 1) as f64 * s.sample_every < probe && probe <= t {
            let e = check(&mut c, probe, &mut report);
            report.first_strike_energy = e / e0;
        }
        let before = t - s.sample_every;
        match s.rest_by {
            // The impacts so far, at the last sample before `rest_by`.
            Some(r) if t >= r && before < r => at_rest_by = Some(report.impacts),
            _ => {}
        }
        check(&mut c, t, &mut report);
    }
    report.late_impacts = at_rest_by.map_or(0, |n| report.impacts - n);
    report.cpu_seconds = super::thread_cpu_seconds() - start;
    report
}

/// Simulated seconds for the table: short runs keep their decimals.
fn seconds(t: f64) -> String {
    if t < 10.0 {
        format!("{t:.2}")
    } else {
        format!("{t:.0}")
    }
}

/// `bench stress`: every scenario of the suite, `scale` times longer, a row on
/// `out` as each finishes.
///
/// # Errors
/// When `out` cannot be written, or a scenario fails its checks (listed).
pub fn report(scale: f64, json: bool, out: &mut impl Write) -> anyhow::Result<()> {
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
    let all = scenarios(scale);
    let count = all.len();
    let bar = super::progress_bar(count as u64, "scenarios");
    let mut passed = 0;
    for (i, s) in all.into_iter().enumerate() {
        // Some scenarios take a minute at large scales: say which one runs, on
        // the bar on a terminal (a log line there would break the table).
        if bar.is_hidden() {
            tracing::info!("stress {}/{count}: {}", i + 1, s.name);
        } else {
            bar.set_message(s.name.clone());
        }
        let r = run(&s);
        let line = if json {
            serde_json::to_string(&r)?
        } else {
            format!(
                "{:<36} {:>8} {:>9} {:>10.2e} {:>10.2e} {:>9.6} {:>7.2}",
                r.name,
                seconds(r.duration),
                r.impacts,
                r.energy_drift,
                r.max_overlap.max(0.0),
                r.max_angle / r.angle_bound,
                r.cpu_seconds
            )
        };
        bar.suspend(|| writeln!(out, "{line}"))?;
        bar.inc(1);
        let failures = r.failures(&s);
        passed += usize::from(failures.is_empty());
        failed.extend(failures.into_iter().map(|f| format!("{}: {f}", s.name)));
    }
    bar.finish_and_clear();
    if !json {
        writeln!(out, "stress suite: {passed} of {count} scenarios passed")?;
    }
    anyhow::ensure!(
        failed.is_empty(),
        "stress suite failed:\n{}",
        failed.join("\n")
    );
    Ok(())
}
