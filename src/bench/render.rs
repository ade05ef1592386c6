//! `newtons-cradle bench render`: milliseconds per frame of a swinging cradle for
//! each thread count from 1 to every core, the course project's experiment done
//! with medians.

use super::median;
use crate::config::Config;
use crate::scene::{Control, CradleWorld};
use crate::trace;
use serde_json::json;
use std::time::Instant;

/// One row of the table.
#[derive(Debug, Clone, PartialEq)]
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
}

impl Row {
    /// The row as the JSON Lines contract of DESIGN.md.
    #[must_use]
    pub fn json(&self) -> String {
        json!({"threads": self.threads, "mode": self.mode, "width": self.width, "height": self.height,
               "ms_median": self.ms_median, "frames": self.frames, "traced": self.traced})
        .to_string()
    }
}

/// Times `frames` frames of the swinging cradle (60 fps of simulated time, after two
/// warm-up frames) with each thread count in `threads`; calls `each` per row.
///
/// # Errors
/// When a thread pool cannot be built.
pub fn bench_render(
    config: &Config,
    threads: &[usize],
    frames: u32,
    mut each: impl FnMut(&Row),
) -> anyhow::Result<Vec<Row>> {
    let mut rows = Vec::new();
    for &n in threads {
        let pool = trace::pool(n)?;
        for mode in ["full", "incremental"] {
            let mut world = CradleWorld::new(config);
            world.send(Control::TogglePause);
            let mut inc = trace::Incremental::new();
            let mut times = Vec::new();
            let mut traced = 0.0;
            // Two warm-up frames (the first incremental one is traced in full).
            for f in 0..frames + 2 {
                world.show_at(0.5 + f64::from(f) / 60.0);
                let start = Instant::now();
                if mode == "full" {
                    std::hint::black_box(pool.install(|| trace::render(world.scene())));
                } else {
                    std::hint::black_box(pool.install(|| inc.render(world.scene()).rgba.len()));
                }
                let ms = start.elapsed().as_secs_f64() * 1e3;
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
            };
            each(&row);
            rows.push(row);
        }
    }
    Ok(rows)
}
