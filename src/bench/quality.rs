//! `newtons-cradle bench render-quality`: picture error against render time. For
//! each anti-aliasing mode (1, 4 and 16 samples per pixel, adaptive 4 and 16) and each
//! reflection depth 0..=5, one frame of the swinging cradle is timed and compared
//! with a reference traced at 64 samples per pixel and depth 8.

use super::median;
use crate::config::Config;
use crate::scene::CradleWorld;
use crate::trace::{self, Image, Scene};
use serde::Serialize;
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// An anti-aliasing mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Name in tables and JSON.
    pub name: &'static str,
    /// Samples per pixel (at edges only when adaptive).
    pub samples: u32,
    /// Adaptive: supersample only edge pixels.
    pub adaptive: bool,
}

/// The modes compared; adaptive ones at the asset's threshold (the default
/// asset: adaptive 4 at 0.1, the app's default).
pub const MODES: [Mode; 5] = [
    Mode {
        name: "1 spp",
        samples: 1,
        adaptive: false,
    },
    Mode {
        name: "4 spp",
        samples: 4,
        adaptive: false,
    },
    Mode {
        name: "16 spp",
        samples: 16,
        adaptive: false,
    },
    Mode {
        name: "adaptive 4",
        samples: 4,
        adaptive: true,
    },
    Mode {
        name: "adaptive 16",
        samples: 16,
        adaptive: true,
    },
];

/// Reflection depths compared.
pub const DEPTHS: std::ops::RangeInclusive<u32> = 0..=5;

/// One measured frame; as JSON, one line of `bench render-quality --json` (an
/// infinite PSNR, an exact match, is written as null).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Anti-aliasing mode.
    pub mode: &'static str,
    /// Reflection depth.
    pub depth: u32,
    /// Median ms per frame.
    pub ms_median: f64,
    /// Root mean square error against the reference, in 8-bit sRGB levels.
    pub rmse: f64,
    /// `20 log10(255 / rmse)` (dB); infinite for an exact match.
    pub psnr: f64,
    /// PSNR against 16 samples per pixel at the same depth (dB).
    pub psnr_vs_16: f64,
}

/// RMSE (8-bit levels) of `a` against `b` over the RGB channels.
#[must_use]
pub fn rmse(a: &Image, b: &Image) -> f64 {
    let (sum, n) = a
        .rgba
        .chunks_exact(4)
        .zip(b.rgba.chunks_exact(4))
        .flat_map(|(p, q)| p[..3].iter().zip(&q[..3]))
        .fold((0.0, 0usize), |(s, n), (x, y)| {
            let d = f64::from(*x) - f64::from(*y);
            (s + d * d, n + 1)
        });
    (sum / n.max(1) as f64).sqrt()
}

/// PSNR (dB) from an RMSE in 8-bit levels.
#[must_use]
pub fn psnr(rmse: f64) -> f64 {
    20.0 * (255.0 / rmse).log10()
}

fn with(scene: &Scene, samples: u32, adaptive: Option<f32>, depth: u32) -> Scene {
    Scene {
        samples,
        adaptive,
        max_depth: depth,
        ..scene.clone()
    }
}

/// Runs the comparison on the frame at t = 0.5 s of the swinging cradle,
/// timing `frames` renders per row on `threads` threads; calls `each` per row.
///
/// # Errors
/// When a thread pool cannot be built.
pub fn run(
    config: &Config,
    threads: usize,
    frames: u32,
    mut each: impl FnMut(&Row),
) -> anyhow::Result<Vec<Row>> {
    let pool = trace::pool(threads)?;
    let mut world = CradleWorld::new(config);
    world.set_running(true);
    world.show_at(0.5);
    let scene = world.scene().clone();
    let threshold = config.render.adaptive_threshold as f32;
    let mut work = Work::new(&scene, threshold, frames);
    let reference = work.render(&pool, &with(&scene, 64, None, 8));
    let mut rows = Vec::new();
    for depth in DEPTHS {
        let sixteen = work.render(&pool, &with(&scene, 16, None, depth));
        for mode in MODES {
            let s = with(
                &scene,
                mode.samples,
                mode.adaptive.then_some(threshold),
                depth,
            );
            let mut times = Vec::new();
            let mut img = None;
            for _ in 0..frames {
                let start = Instant::now();
                img = Some(pool.install(|| trace::render(&s)));
                times.push(start.elapsed().as_secs_f64() * 1e3);
                work.rendered(&s);
            }
            let img = img.expect("at least one frame");
            let e = rmse(&img, &reference);
            let row = Row {
                mode: mode.name,
                depth,
                ms_median: median(times),
                rmse: e,
                psnr: psnr(e),
                psnr_vs_16: psnr(rmse(&img, &sixteen)),
            };
            each(&row);
            rows.push(row);
        }
    }
    work.bar.finish_and_clear();
    Ok(rows)
}

/// The benchmark's renders as shares of its whole work, for a progress bar on
/// a terminal and an estimate in the log: at 8192x8192 the 64-sample reference
/// alone takes minutes.
struct Work {
    total: f64,
    done: f64,
    bar: indicatif::ProgressBar,
    estimate: super::Estimate,
}

impl Work {
    /// The work of the reference, and per depth the 16-sample render and
    /// `frames` of each mode.
    fn new(scene: &trace::Scene, threshold: f32, frames: u32) -> Self {
        let mut total = cost(&with(scene, 64, None, 8));
        for depth in DEPTHS {
            total += cost(&with(scene, 16, None, depth));
            for mode in MODES {
                let s = with(
                    scene,
                    mode.samples,
                    mode.adaptive.then_some(threshold),
                    depth,
                );
                total += f64::from(frames) * cost(&s);
            }
        }
        Self {
            total,
            done: 0.0,
            bar: super::progress_bar(1000, "thousandths"),
            estimate: super::Estimate::new("bench render-quality"),
        }
    }

    /// Traces `scene`, showing its progress within the whole.
    fn render(&mut self, pool: &rayon::ThreadPool, scene: &trace::Scene) -> trace::Image {
        let (before, share) = (self.done, cost(scene) / self.total);
        let img = super::traced_watching(pool, scene, |rows| self.show(before + rows * share));
        self.rendered(scene);
        img
    }

    /// `scene` was traced (a timed frame traces without watching: no thread
    /// beside it to disturb the timing).
    fn rendered(&mut self, scene: &trace::Scene) {
        self.done += cost(scene) / self.total;
        self.show(self.done);
    }

    fn show(&mut self, done: f64) {
        self.bar.set_position((1000.0 * done.min(1.0)) as u64);
        self.estimate.done(done);
    }
}

/// The rough cost of tracing `scene`: its rows, times the samples a pixel
/// takes (adaptive: one, and the samples at about 15% of pixels, the edges),
/// times its bounces.
fn cost(scene: &trace::Scene) -> f64 {
    let extra = f64::from(scene.samples.max(1) - 1);
    let samples = if scene.adaptive.is_some() {
        1.0 + 0.15 * extra
    } else {
        1.0 + extra
    };
    f64::from(scene.size.1) * samples * (1.0 + 0.5 * f64::from(scene.max_depth))
}

/// Draws RMSE against ms per frame, one line per mode through depths 0..=5.
///
/// # Errors
/// When the file cannot be written.
pub fn plot(rows: &[Row], path: &Path, title: &str) -> anyhow::Result<()> {
    use super::plot::{Axes, Panel, Series, log_log_svg};
    let series = MODES
        .iter()
        .map(|m| Series {
            name: format!("{} (depth 0..5)", m.name),
            points: rows
                .iter()
                .filter(|r| r.mode == m.name)
                .map(|r| (r.ms_median, r.rmse))
                .collect(),
        })
        .collect();
    log_log_svg(
        path,
        &[Panel {
            title: title.to_owned(),
            series,
        }],
        Axes {
            x: "ms per frame",
            y: "RMSE vs 64 spp, depth 8 (8-bit levels)",
            legend_lower_left: true,
        },
    )
}

/// `bench render-quality`: the table (or JSON Lines) on `out`, a row as each
/// finishes, and the plot at `plot_to`.
///
/// # Errors
/// When a thread pool cannot be built, or `out` or the plot cannot be written.
pub fn report(
    config: &Config,
    frames: u32,
    json: bool,
    plot_to: Option<&Path>,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let threads = config.render.threads;
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
    if !json {
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
    let mut written = Ok(());
    let rows = run(config, threads, frames, |r| {
        let line = if json {
            serde_json::to_string(r).expect("a row of numbers and names serializes")
        } else {
            format!(
                "{:<11}  {:>5}  {:>8.1}  {:>6.3}  {:>7.2}  {:>14.2}",
                r.mode, r.depth, r.ms_median, r.rmse, r.psnr, r.psnr_vs_16
            )
        };
        if written.is_ok() {
            written = writeln!(out, "{line}");
        }
    })?;
    written?;
    if let Some(path) = plot_to {
        plot(&rows, path, &title)?;
        tracing::info!("wrote {}", path.display());
    }
    Ok(())
}
