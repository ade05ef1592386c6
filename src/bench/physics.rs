//! `newtons-cradle bench physics`: the work-precision benchmark. Each integrator
//! runs the same cradle (5 balls, 1 lifted, touching, ideal elastic impacts) for
//! the same simulated time over a sweep of steps; its error is the largest angle
//! error against the closed-form solution, its cost the CPU seconds of the run.
//!
//! The reference: with one ball lifted, an ideal cradle moves exactly one
//! pendulum at a time, the one released from `-A`, carried by the first ball left
//! of the vertical and by the last one right of it; the others stay at 0. Its angle
//! is the closed form `2 asin(k sn(w0 t - K, k^2))` (checked against mpmath in
//! `tests/elliptic.rs`), so the exact engine's own error is measured too.

use super::median;
use crate::physics::params::lifted_start;
use crate::physics::{Cradle, CradleParams, Flight, Integrator};
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// One point of the diagram; as JSON, one line of the contract (docs/contracts.md) (`dt`
/// null for `exact`, which has no step).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Point {
    /// Integrator.
    pub integrator: Integrator,
    /// Lift angle (degrees).
    pub angle_deg: f64,
    /// Step (s); `None` for the exact engine, which has none.
    pub dt: Option<f64>,
    /// Largest angle error over the run (rad).
    pub error: f64,
    /// CPU seconds to simulate the run (median of repeats when short).
    pub cpu_seconds: f64,
}

/// What to run.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The cradle's geometry (its ball count, gap and contact are overridden:
    /// 5 balls, touching, ideal elastic impacts).
    pub params: CradleParams,
    /// Lift angles (degrees).
    pub angles_deg: Vec<f64>,
    /// Simulated seconds per run.
    pub duration: f64,
    /// Steps of the fixed-step integrators (s).
    pub dts: Vec<f64>,
    /// The error is read every this many seconds.
    pub sample_every: f64,
}

impl Plan {
    /// The benchmark's cradle: `params`' geometry with 5 touching balls and ideal
    /// elastic impacts.
    #[must_use]
    pub fn cradle(&self) -> CradleParams {
        CradleParams {
            balls: 5,
            gap: 0.0,
            restitution: 1.0,
            hertz: None,
            dissipation: 0.0,
            drag: 0.0,
            ..self.params
        }
    }

    /// Runs counted: one per angle for `exact`, one per angle and step for each
    /// fixed-step integrator.
    #[must_use]
    pub fn runs(&self) -> usize {
        let stepped = Integrator::ALL.len() - 1;
        self.angles_deg.len() * (1 + stepped * self.dts.len())
    }
}

/// The closed-form angles at `t` of the benchmark cradle released from `-angle`.
fn reference(p: &CradleParams, flight: &Flight, t: f64) -> Vec<f64> {
    let (phi, _) = flight.state_at(t);
    let mut theta = vec![0.0; p.balls];
    theta[0] = phi.min(0.0);
    theta[p.balls - 1] = phi.max(0.0);
    theta
}

/// Largest angle error over `[0, duration]`, read every `sample_every`.
fn max_error(plan: &Plan, integrator: Integrator, dt: f64, angle: f64) -> f64 {
    let p = plan.cradle();
    let mut c = Cradle::new(p, integrator, dt, 1, angle);
    let (theta0, omega0) = lifted_start(p.balls, 1, angle);
    let flight = Flight::new(0.0, theta0[0], omega0[0], p.w0());
    let samples = (plan.duration / plan.sample_every).round() as u64;
    let mut worst: f64 = 0.0;
    for n in 0..=samples {
        let t = n as f64 * plan.sample_every;
        let s = c.snapshot(t);
        let want = reference(&p, &flight, t);
        for (a, b) in s.theta.iter().zip(&want) {
            let e = (a - b).abs();
            // A NaN (a blown-up integrator) counts as the worst possible error.
            worst = if e.is_nan() {
                f64::INFINITY
            } else {
                worst.max(e)
            };
        }
    }
    worst
}

/// CPU seconds to simulate the run once, sampled only at its end; short runs are
/// repeated (at least 0.2 s in all) and their median taken.
fn cpu_cost(plan: &Plan, integrator: Integrator, dt: f64, angle: f64) -> f64 {
    let p = plan.cradle();
    let mut times = Vec::new();
    let mut total = 0.0;
    while times.len() < 3 || (total < 0.2 && times.len() < 1000) {
        let start = super::thread_cpu_seconds();
        let mut c = Cradle::new(p, integrator, dt, 1, angle);
        std::hint::black_box(c.snapshot(plan.duration));
        let spent = super::thread_cpu_seconds() - start;
        total += spent;
        times.push(spent);
        if spent > 1.0 {
            break;
        }
    }
    median(times)
}

/// Runs the plan, calling `each` after every point (for progress and streaming).
pub fn run(plan: &Plan, mut each: impl FnMut(&Point)) -> Vec<Point> {
    let mut points = Vec::new();
    for &angle_deg in &plan.angles_deg {
        let angle = angle_deg.to_radians();
        for integrator in Integrator::ALL {
            let dts: Vec<Option<f64>> = if integrator == Integrator::Exact {
                vec![None]
            } else {
                plan.dts.iter().copied().map(Some).collect()
            };
            for dt in dts {
                let step = dt.unwrap_or(1e-3);
                let point = Point {
                    angle_deg,
                    integrator,
                    dt,
                    error: max_error(plan, integrator, step, angle),
                    cpu_seconds: cpu_cost(plan, integrator, step, angle),
                };
                each(&point);
                points.push(point);
            }
        }
    }
    points
}

/// Observed order between consecutive steps of one integrator and angle:
/// `log(e1 / e2) / log(dt1 / dt2)`, for each consecutive pair of points.
#[must_use]
pub fn orders(points: &[Point], integrator: Integrator, angle_deg: f64) -> Vec<(f64, f64)> {
    let line: Vec<&Point> = points
        .iter()
        .filter(|p| p.integrator == integrator && p.angle_deg == angle_deg && p.dt.is_some())
        .collect();
    line.windows(2)
        .filter_map(|w| {
            let (a, b) = (w[0], w[1]);
            let (da, db) = (a.dt?, b.dt?);
            Some((db, (a.error / b.error).ln() / (da / db).ln()))
        })
        .collect()
}

/// The cheapest point of any integrator (at `angle_deg`) whose error is at most
/// `error`.
#[must_use]
pub fn cheapest_within(points: &[Point], angle_deg: f64, error: f64) -> Option<&Point> {
    points
        .iter()
        .filter(|p| p.angle_deg == angle_deg && p.error <= error)
        .min_by(|a, b| a.cpu_seconds.total_cmp(&b.cpu_seconds))
}

/// Draws the work-precision diagram: one panel per angle, one line per integrator,
/// log error against log CPU seconds.
///
/// # Errors
/// When the file cannot be written.
pub fn plot(points: &[Point], plan: &Plan, path: &Path) -> anyhow::Result<()> {
    use super::plot::{Axes, Panel, Series, log_log_svg};
    let panels: Vec<Panel> = plan
        .angles_deg
        .iter()
        .map(|&a| Panel {
            title: format!("lift {a} deg, 5 balls, {} s", plan.duration),
            series: Integrator::ALL
                .iter()
                .map(|&m| Series {
                    name: m.name().to_owned(),
                    points: points
                        .iter()
                        .filter(|p| p.integrator == m && p.angle_deg == a)
                        .map(|p| (p.cpu_seconds, p.error))
                        .collect(),
                })
                .collect(),
        })
        .collect();
    log_log_svg(
        path,
        &panels,
        Axes {
            x: "CPU seconds",
            y: "max angle error (rad)",
            legend_lower_left: false,
        },
    )
}

/// `bench physics`: rows on `out` as they finish (a table, or JSON Lines), then the
/// observed orders, and the diagram at `plot`.
///
/// # Errors
/// When `out` or the plot cannot be written.
pub fn report(
    plan: &Plan,
    json: bool,
    plot_to: Option<&Path>,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    if !json {
        writeln!(
            out,
            "5 balls, 1 lifted, {} s simulated; error: max angle error (rad) against the closed form",
            plan.duration
        )?;
        writeln!(out, "angle  integrator  dt (s)     error (rad)  CPU (s)")?;
    }
    let bar = super::progress_bar(plan.runs() as u64, "runs");
    let mut written = Ok(());
    let points = run(plan, |pt| {
        let line = if json {
            serde_json::to_string(pt).expect("a point of numbers and names serializes")
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
        if written.is_ok() {
            written = bar.suspend(|| writeln!(out, "{line}"));
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    written?;
    if !json {
        for &a in &plan.angles_deg {
            writeln!(
                out,
                "observed order at {a} deg (between consecutive steps, finest last):"
            )?;
            for m in &Integrator::ALL[1..] {
                let o: Vec<String> = orders(&points, *m, a)
                    .iter()
                    .map(|(_, o)| format!("{o:.2}"))
                    .collect();
                writeln!(out, "  {:<9} {}", m.name(), o.join(" "))?;
            }
        }
    }
    if let Some(path) = plot_to {
        plot(&points, plan, path)?;
        tracing::info!("wrote {}", path.display());
    }
    Ok(())
}
