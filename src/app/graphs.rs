//! The graphs window (G): `egui_plot` plots of what the physics recorded
//! ([`Recording`]) over the last 30 s of simulated time: energy, momentum,
//! angles and a phase portrait, amplitudes, and the last impacts (the last
//! one's course: Hertz's force per pair in microseconds, or an ideal impact's
//! velocities before and after). It follows the simulated time at any rate
//! and stands still while paused (nothing new is recorded then).

use crate::physics::{Course, CradleParams};
use crate::scene::record::{Recording, Sample};
use egui::Context;
use egui_plot::{Bar, BarChart, Legend, Line, Plot, PlotPoints};

/// At most this many points per line: more would not show at the window's
/// width and would cost the frame its time.
const POINTS: usize = 300;

/// At most this many balls get a line of their own (a long row's first).
const BALLS: usize = 12;

/// The graphs' own state between frames.
#[derive(Debug, Clone, Default)]
pub struct Graphs {
    /// The plots shown.
    pub tab: Tab,
    /// The ball of the phase portrait (from 0).
    pub ball: usize,
}

/// Which plots the window shows: one group at a time, so a frame draws only
/// what is seen.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Tab {
    /// Energy stacked by ball, and its error or where it went.
    #[default]
    Energy,
    /// Total and each ball's momentum.
    Momentum,
    /// Angles over time and a phase portrait.
    Angles,
    /// Swing amplitudes.
    Amplitudes,
    /// The last impacts.
    Impacts,
}

impl Tab {
    const ALL: [(Self, &'static str); 5] = [
        (Self::Energy, "energy"),
        (Self::Momentum, "momentum"),
        (Self::Angles, "angles"),
        (Self::Amplitudes, "amplitudes"),
        (Self::Impacts, "impacts"),
    ];
}

/// Every `stride`-th sample, and the last, so that at most [`POINTS`] are drawn.
fn thinned(rec: &Recording) -> Vec<&Sample> {
    let n = rec.samples.len();
    let stride = n.div_ceil(POINTS).max(1);
    let mut picked: Vec<&Sample> = rec.samples.iter().step_by(stride).collect();
    if let Some(last) = rec.samples.back()
        && picked.last().is_none_or(|p| p.t != last.t)
    {
        picked.push(last);
    }
    picked
}

/// A line through `(t, f(sample))`.
fn line<'a>(name: String, samples: &[&Sample], f: impl Fn(&Sample) -> f64) -> Line<'a> {
    let points: PlotPoints = samples.iter().map(|s| [s.t, f(s)]).collect();
    Line::new(name, points)
}

/// A plot of the recording's time span, `height` points tall.
fn plot(id: &str, y: &str, height: f32) -> Plot<'static> {
    Plot::new(id.to_owned())
        .height(height)
        .legend(Legend::default())
        .x_axis_label("t (s)")
        .y_axis_label(y.to_owned())
        .allow_scroll(false)
}

/// Shows the graphs window over `ctx` while `open`; the user may close it.
pub fn graphs_ui(ctx: &Context, rec: &Recording, state: &mut Graphs, open: &mut bool) {
    // Below the HUD's status band (the top 12% of the picture).
    let below_hud = 0.13 * ctx.content_rect().height();
    egui::Window::new("Graphs")
        .open(open)
        .anchor(egui::Align2::LEFT_TOP, [8.0, below_hud])
        .default_width(420.0)
        .vscroll(true)
        .show(ctx, |ui| {
            ui.horizontal(|ui| {
                for (tab, name) in Tab::ALL {
                    ui.selectable_value(&mut state.tab, tab, name);
                }
            });
            let Some(p) = rec.params else {
                ui.label("recording from the next frame that moves (Space runs the swing)");
                return;
            };
            let samples = thinned(rec);
            let n = p.balls.min(BALLS);
            if p.balls > BALLS {
                ui.label(format!(
                    "per-ball lines: the first {BALLS} of {} balls",
                    p.balls
                ));
            }
            match state.tab {
                Tab::Energy => energy(ui, &samples, &p, n),
                Tab::Momentum => momentum(ui, &samples, n),
                Tab::Angles => angles(ui, &samples, state, n, p.balls),
                Tab::Amplitudes => amplitudes(ui, &samples, &p, n),
                Tab::Impacts => impacts(ui, rec),
            }
        });
}

/// Each ball's energy stacked (the top line is the balls' total), and the
/// total's error, or for a lossy cradle where the energy went.
fn energy(ui: &mut egui::Ui, samples: &[&Sample], p: &CradleParams, n: usize) {
    plot("energy", "E (J), stacked", 150.0).show(ui, |pu| {
        for k in (0..n).rev() {
            let name = if k == 0 {
                "ball 1".to_owned()
            } else {
                format!("+ ball {}", k + 1)
            };
            let l = line(name, samples, |s| s.energy[..=k].iter().sum());
            pu.line(l);
        }
        if p.dissipative() {
            pu.line(line("left + lost in contacts".into(), samples, |s| {
                s.total + s.lost[0]
            }));
            pu.line(line("+ lost to drag".into(), samples, |s| {
                s.total + s.lost[0] + s.lost[1]
            }));
        }
    });
    let (name, label) = if p.dissipative() {
        ("balance error", "(E + lost - E0) / E0")
    } else {
        ("energy error", "(E - E0) / E0")
    };
    plot("energy error", label, 90.0)
        .y_axis_formatter(|mark, _| format!("{:.1e}", mark.value))
        .show(ui, |pu| {
            pu.line(line(name.into(), samples, |s| s.error));
        });
}

/// Total horizontal momentum and each ball's.
fn momentum(ui: &mut egui::Ui, samples: &[&Sample], n: usize) {
    plot("momentum", "p (kg m/s)", 150.0).show(ui, |pu| {
        pu.line(line("total".into(), samples, Sample::total_momentum).width(2.5));
        for k in 0..n {
            pu.line(line(format!("ball {}", k + 1), samples, |s| s.momentum[k]));
        }
    });
}

/// Each ball's angle, and the phase portrait of one.
fn angles(ui: &mut egui::Ui, samples: &[&Sample], state: &mut Graphs, n: usize, balls: usize) {
    plot("angles", "theta (deg)", 150.0).show(ui, |pu| {
        for k in 0..n {
            pu.line(line(format!("ball {}", k + 1), samples, |s| {
                s.theta[k].to_degrees()
            }));
        }
    });
    state.ball = state.ball.min(balls - 1);
    let mut shown = state.ball + 1;
    ui.add(egui::Slider::new(&mut shown, 1..=balls).text("ball of the portrait"));
    state.ball = shown - 1;
    let k = state.ball;
    let points: PlotPoints = samples
        .iter()
        .map(|s| [s.theta[k].to_degrees(), s.omega[k].to_degrees()])
        .collect();
    Plot::new("phase")
        .height(160.0)
        .x_axis_label("theta (deg)")
        .y_axis_label("omega (deg/s)")
        .allow_scroll(false)
        .show(ui, |pu| pu.line(Line::new(format!("ball {shown}"), points)));
}

/// Each ball's swing amplitude: the realistic cradle's slide into swinging in
/// phase shows here.
fn amplitudes(ui: &mut egui::Ui, samples: &[&Sample], p: &CradleParams, n: usize) {
    plot("amplitudes", "amplitude (deg)", 150.0).show(ui, |pu| {
        for k in 0..n {
            pu.line(line(format!("ball {}", k + 1), samples, |s| {
                s.amplitude(p, k).to_degrees()
            }));
        }
    });
}

/// The last impact's course, then the last impacts, newest first: time,
/// balls, speed, and for Hertz contact how long, how hard and the impulse.
fn impacts(ui: &mut egui::Ui, rec: &Recording) {
    if rec.impacts.is_empty() {
        ui.label("none yet");
        return;
    }
    match rec.strike.first() {
        Some(Course::Force { .. }) => contact_forces(ui, &rec.strike),
        Some(Course::Ideal { before, after, .. }) => velocities(ui, before, after),
        None => {}
    }
    egui::Grid::new("impacts").striped(true).show(ui, |ui| {
        for h in [
            "t (s)",
            "balls",
            "v (m/s)",
            "contact (us)",
            "F max (N)",
            "J (mN s)",
        ] {
            ui.strong(h);
        }
        ui.end_row();
        for i in rec.impacts.iter().rev() {
            ui.label(format!("{:.6}", i.t));
            ui.label(format!("{}-{}", i.pair + 1, i.pair + 2));
            ui.label(format!("{:.4}", i.speed));
            if let Some(c) = i.contact {
                ui.label(format!("{:.1}", c.duration * 1e6));
                ui.label(format!("{:.0}", c.peak_force));
                ui.label(format!("{:.3}", c.impulse * 1e3));
            } else {
                ui.label("ideal");
                ui.label("");
                ui.label("");
            }
            ui.end_row();
        }
    });
}

/// The last strike's Hertz contacts: each pair's force against time in
/// microseconds, as the contact integration stepped: from the strike's start
/// when its contacts overlap in time (a touching chain), from each contact's
/// own start when they come one after another (a chain with gaps).
fn contact_forces(ui: &mut egui::Ui, strike: &[Course]) {
    let span = |c: &Course| match c {
        Course::Force { impact, curve } => (impact.t, curve.last().map_or(0.0, |p| p.0)),
        Course::Ideal { t, .. } => (*t, 0.0),
    };
    let t0 = strike.first().map_or(0.0, Course::start);
    let end = strike
        .iter()
        .map(|c| span(c).0 + span(c).1)
        .fold(t0, f64::max);
    let longest = strike.iter().map(|c| span(c).1).fold(0.0, f64::max);
    let together = end - t0 <= 4.0 * longest;
    let x_label = if together {
        "t since the strike (us)"
    } else {
        "t since each contact began (us)"
    };
    Plot::new("contact")
        .height(150.0)
        .legend(Legend::default())
        .x_axis_label(x_label)
        .y_axis_label("F (N)")
        .allow_scroll(false)
        .show(ui, |pu| {
            for c in strike.iter().take(BALLS) {
                let Course::Force { impact, curve } = c else {
                    continue;
                };
                let from = if together { impact.t - t0 } else { 0.0 };
                let stride = curve.len().div_ceil(POINTS).max(1);
                let points: PlotPoints = curve
                    .iter()
                    .step_by(stride)
                    .chain(curve.last().filter(|_| stride > 1))
                    .map(|&(t, f)| [(from + t) * 1e6, f])
                    .collect();
                let balls = format!("balls {}-{}", impact.pair + 1, impact.pair + 2);
                let name = if together {
                    balls
                } else {
                    format!("{balls} at +{:.1} ms", (impact.t - t0) * 1e3)
                };
                pu.line(Line::new(name, points));
            }
        });
}

/// An ideal impact: each ball's velocity just before and just after it.
fn velocities(ui: &mut egui::Ui, before: &[f64], after: &[f64]) {
    let bars = |v: &[f64], shift: f64| -> Vec<Bar> {
        v.iter()
            .take(BALLS)
            .enumerate()
            .map(|(k, &v)| Bar::new(k as f64 + 1.0 + shift, v).width(0.35))
            .collect()
    };
    Plot::new("velocities")
        .height(150.0)
        .legend(Legend::default())
        .x_axis_label("ball")
        .y_axis_label("v (m/s)")
        .allow_scroll(false)
        .show(ui, |pu| {
            pu.bar_chart(BarChart::new("before", bars(before, -0.2)));
            pu.bar_chart(BarChart::new("after", bars(after, 0.2)));
        });
}
