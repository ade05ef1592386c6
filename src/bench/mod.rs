//! The `bench` subcommands: what the program costs and how accurate it is.
//! - [`render`]: milliseconds per frame over thread counts, full and incremental.
//! - [`physics`]: the work-precision benchmark of the integrators.
//! - [`quality`]: picture error against render time (anti-aliasing, depth).
//! - [`stress`]: the stability stress suite, longer runs of `tests/stress.rs`.
//! - [`rocking`]: a dissipative cradle's drift into swinging in phase.
//! - [`plot`]: SVG line plots (plotters) for the benchmarks' `--plot`.

pub mod physics;
pub mod plot;
pub mod quality;
pub mod render;
pub mod rocking;
pub mod stress;

pub use render::{Row, bench_render};

/// A progress bar on stderr with the time left, for `total` steps of `unit`,
/// and its message (what runs now); hidden when stderr is not a terminal, so
/// pipes and logs stay clean.
#[must_use]
pub fn progress_bar(total: u64, unit: &str) -> indicatif::ProgressBar {
    let style = indicatif::ProgressStyle::with_template(&format!(
        "[{{bar:30}}] {{pos}}/{{len}} {unit}, {{eta}} left {{msg}}"
    ))
    .expect("a fixed, valid template")
    .progress_chars("#>-");
    indicatif::ProgressBar::new(total).with_style(style)
}

/// Says once, in the log, how long a piece of work will take, when that is
/// over 10 s: from the share of it done, once 2 s have passed (so that the
/// estimate has something to go on). Beside a progress bar, for the logs
/// that have no terminal.
#[derive(Debug)]
pub struct Estimate {
    what: String,
    start: std::time::Instant,
    said: bool,
}

impl Estimate {
    /// An estimate of `what` (e.g. "bench rocking"), from now.
    #[must_use]
    pub fn new(what: impl Into<String>) -> Self {
        Self {
            what: what.into(),
            start: std::time::Instant::now(),
            said: false,
        }
    }

    /// `done` (0..=1) of the work is done.
    pub fn done(&mut self, done: f64) {
        let spent = self.start.elapsed().as_secs_f64();
        if self.said || spent < 2.0 || done <= 0.0 {
            return;
        }
        let left = spent * (1.0 / done - 1.0);
        if left > 10.0 {
            self.said = true;
            tracing::info!(
                "{}: {spent:.0} s so far, about {:.0} s more",
                self.what,
                left.min(1e9)
            );
        }
    }
}

/// One frame of `scene` traced on `pool`, telling `rows` the share of its
/// rows done (0..=1) every 0.2 s while it traces: a frame of minutes (8K at
/// 64 samples) can show its progress. The same picture as `trace::render`.
pub fn traced_watching(
    pool: &rayon::ThreadPool,
    scene: &crate::trace::Scene,
    mut rows: impl FnMut(f64),
) -> crate::trace::Image {
    use std::sync::atomic::{AtomicU32, Ordering};
    let passes = if scene.adaptive.is_some() && scene.samples > 1 {
        2
    } else {
        1
    };
    let total = f64::from((passes * scene.size.1).max(1));
    let done = AtomicU32::new(0);
    std::thread::scope(|s| {
        let tracing = s.spawn(|| pool.install(|| crate::trace::render_counting(scene, &done)));
        while !tracing.is_finished() {
            std::thread::sleep(std::time::Duration::from_millis(200));
            rows(f64::from(done.load(Ordering::Relaxed)) / total);
        }
        tracing.join().expect("the tracer does not panic")
    })
}

/// Median of a non-empty list.
#[must_use]
pub fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// CPU seconds this thread has used (wall seconds where the platform has no
/// thread clock).
#[must_use]
pub fn thread_cpu_seconds() -> f64 {
    use std::sync::OnceLock;
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    match cpu_time::ThreadTime::try_now() {
        Ok(t) => t.as_duration().as_secs_f64(),
        Err(_) => START
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_secs_f64(),
    }
}
