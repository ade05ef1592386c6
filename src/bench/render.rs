//! `newtons-cradle bench render`: milliseconds per frame of a swinging cradle for
//! each thread count from 1 to every core, the course project's experiment done
//! with medians.

use super::median;
use super::quality::{psnr, rmse};
use crate::config::Config;
use crate::scene::CradleWorld;
use crate::scene::components::Quality;
use crate::trace;
use serde::Serialize;
use std::io::Write;
use std::time::Instant;

/// One row of the table; as JSON, one line of the contract (docs/contracts.md) (its keys in
/// this order).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Worker threads.
    pub threads: usize,
    /// `full`: every pixel traced each frame; `incremental`: only what motion can change.
    pub mode: &'static str,
    /// Picture size.
    pub width: u32,
    /// Picture size.
    pub height: u32,
    /// Median milliseconds per frame.
    pub ms_median: f64,
    /// Frames timed.
    pub frames: u32,
    /// Mean share of the pixels traced per timed frame (1 for full frames).
    pub traced: f64,
    /// `orbit`: the median PSNR (dB) of its frames against the frames at rest
    /// (the asset's anti-aliasing, every pixel); `null` otherwise.
    pub psnr: Option<f64>,
}

/// Times `frames` frames of the swinging cradle (60 fps of simulated time, after two
/// warm-up frames) with each thread count in `threads`, in each of `modes`
/// (`full`: every pixel traced afresh with the skips of `options`;
/// `incremental`: only what motion changed, with every skip; `orbit`: the
/// view turning a degree a frame, at [`Quality::MOVING`]); calls `each` per
/// row.
///
/// # Errors
/// When a thread pool cannot be built.
pub fn bench_render(
    config: &Config,
    threads: &[usize],
    (frames, options): (u32, trace::RenderOptions),
    modes: &[&'static str],
    mut each: impl FnMut(&Row),
) -> anyhow::Result<Vec<Row>> {
    let mut rows = Vec::new();
    for &n in threads {
        let pool = trace::pool(n)?;
        for &mode in modes {
            let mut world = CradleWorld::new(config);
            world.set_running(true);
            let mut inc = trace::Incremental::new();
            let mut times = Vec::new();
            let mut traced = 0.0;
            let mut psnrs = Vec::new();
            let home = world.scene().camera;
            // Two warm-up frames (the first incremental one is traced in full).
            for f in 0..frames + 2 {
                if mode == "orbit" {
                    world.set_quality(Quality::MOVING);
                    world.set_camera(turned(home, f as f32));
                }
                world.show_at(0.5 + f64::from(f) / 60.0);
                let change = world.take_change();
                let start = Instant::now();
                if mode == "full" {
                    std::hint::black_box(
                        pool.install(|| trace::render_with(world.scene(), options)),
                    );
                } else {
                    std::hint::black_box(
                        pool.install(|| inc.render_changed(world.scene(), &change).rgba.len()),
                    );
                }
                let ms = start.elapsed().as_secs_f64() * 1e3;
                if f >= 2 && mode == "orbit" {
                    psnrs.push(psnr_at_rest(&pool, world.scene(), inc.image(), config));
                }
                if f >= 2 {
                    times.push(ms);
                    traced += if mode == "full" {
                        1.0
                    } else {
                        inc.dynamic_share()
                    };
                }
            }
            let row = Row {
                threads: n,
                mode,
                width: config.render.width,
                height: config.render.height,
                ms_median: median(times),
                frames,
                traced: traced / f64::from(frames),
                psnr: (!psnrs.is_empty()).then(|| median(psnrs)),
            };
            each(&row);
            rows.push(row);
        }
    }
    Ok(rows)
}

/// `home` turned by `deg` degrees about the vertical through what it looks at.
fn turned(home: trace::Camera, deg: f32) -> trace::Camera {
    let back = home.position - home.look_at;
    trace::Camera {
        position: home.look_at + glam::Quat::from_rotation_y(deg.to_radians()) * back,
        ..home
    }
}

/// The PSNR (dB) of `shown`, a moving view's frame of `scene`, against the
/// frame at rest there (every pixel, at `config`'s anti-aliasing).
fn psnr_at_rest(
    pool: &rayon::ThreadPool,
    scene: &trace::Scene,
    shown: Option<&trace::Image>,
    config: &Config,
) -> f64 {
    let mut rest = scene.clone();
    Quality::at_rest(&config.render).set_on(&mut rest);
    let still = pool.install(|| trace::render(&rest));
    shown.map_or(0.0, |img| psnr(rmse(img, &still)))
}

/// `bench render`: the table (or JSON Lines) on `out`, a row as each finishes.
///
/// # Errors
/// When a thread pool cannot be built or `out` cannot be written.
pub fn report(
    config: &Config,
    threads: &[usize],
    (frames, options): (u32, trace::RenderOptions),
    modes: &[&'static str],
    json: bool,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    if !json {
        writeln!(
            out,
            "{}x{}, {} balls, median of {frames} frames of a swinging cradle",
            config.render.width, config.render.height, config.cradle.balls
        )?;
        writeln!(
            out,
            "threads  mode         ms/frame  vs 1 thread full  pixels traced"
        )?;
    }
    let mut base = None;
    let mut written = Ok(());
    bench_render(config, threads, (frames, options), modes, |row| {
        let line = if json {
            serde_json::to_string(row).expect("a row of numbers and names serializes")
        } else {
            let b = *base.get_or_insert(row.ms_median);
            let psnr = row.psnr.map_or(String::new(), |p| {
                format!("  PSNR {p:.1} dB against the frame at rest")
            });
            format!(
                "{:>7}  {:<11}  {:>8.2}  {:>15.2}x  {:>12.1}%{psnr}",
                row.threads,
                row.mode,
                row.ms_median,
                b / row.ms_median,
                100.0 * row.traced
            )
        };
        if written.is_ok() {
            written = writeln!(out, "{line}");
        }
    })?;
    Ok(written?)
}
