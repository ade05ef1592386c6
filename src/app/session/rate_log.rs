//! The frame rates: smoothed for the HUD, and while the swing runs one line
//! every 2 seconds with the frames per second and the median trace time of
//! those 2 seconds, for the session to write to the log (`58.7 fps, trace
//! 3.1 ms`). Window-free.

use std::time::{Duration, Instant};

/// How often a line is written.
pub const EVERY: Duration = Duration::from_secs(2);

/// Frames and trace times since the last line.
#[derive(Debug, Default)]
pub struct RateLog {
    /// When the current span started (its first frame).
    since: Option<Instant>,
    /// Frames after the first.
    frames: u32,
    /// Trace times (ms) of the span's frames.
    traces: Vec<f64>,
    /// Frames per second and trace milliseconds, smoothed over ~10 frames
    /// so that the HUD's numbers stay readable.
    fps: f64,
    trace_ms: f64,
}

/// Exponential smoothing over ~10 frames.
fn smooth(old: f64, new: f64) -> f64 {
    if old == 0.0 {
        new
    } else {
        0.9 * old + 0.1 * new
    }
}

impl RateLog {
    /// The smoothed frames per second and trace milliseconds.
    #[must_use]
    pub fn shown(&self) -> (f64, f64) {
        (self.fps, self.trace_ms)
    }

    /// A running frame `dt` seconds after the one before.
    pub fn shown_after(&mut self, dt: f64) {
        self.fps = smooth(self.fps, 1.0 / dt);
    }

    /// A frame traced in `trace_ms`, shown at `now` (`running`: the swing
    /// runs): the line to log, if one is due.
    pub fn traced(&mut self, now: Instant, trace_ms: f64, running: bool) -> Option<String> {
        self.trace_ms = smooth(self.trace_ms, trace_ms);
        running.then(|| self.frame(now, trace_ms)).flatten()
    }

    /// A frame shown at `now` that took `trace_ms` to trace; the line to log
    /// when the span has lasted [`EVERY`].
    pub fn frame(&mut self, now: Instant, trace_ms: f64) -> Option<String> {
        self.traces.push(trace_ms);
        let Some(since) = self.since else {
            self.since = Some(now);
            return None;
        };
        self.frames += 1;
        let span = now.saturating_duration_since(since);
        if span < EVERY {
            return None;
        }
        let fps = f64::from(self.frames) / span.as_secs_f64();
        let mut traces = std::mem::take(&mut self.traces);
        traces.sort_by(f64::total_cmp);
        let median = traces[traces.len() / 2];
        self.since = Some(now);
        self.frames = 0;
        Some(format!("{fps:.1} fps, trace {median:.1} ms"))
    }

    /// The swing stopped: the next frame starts a new span.
    pub fn pause(&mut self) {
        (self.since, self.frames) = (None, 0);
        self.traces.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::RateLog;
    use std::time::{Duration, Instant};

    #[test]
    fn a_line_every_two_seconds_with_the_rate_and_median_trace() {
        let t0 = Instant::now();
        let mut log = RateLog::default();
        let mut lines = Vec::new();
        // 50 frames a second for 4.5 s; trace times cycle 1, 2, .., 9 ms.
        for i in 0..=225u32 {
            let at = t0 + Duration::from_millis(u64::from(i) * 20);
            if let Some(l) = log.frame(at, f64::from(i % 9 + 1)) {
                lines.push(l);
            }
        }
        // Frames at exactly 2.00 s and 4.00 s close the spans: 100 frames in
        // 2 s each; the median of 1..=9 repeated is 5.
        assert_eq!(lines, ["50.0 fps, trace 5.0 ms", "50.0 fps, trace 5.0 ms"]);
    }

    #[test]
    fn a_pause_starts_a_new_span_and_nothing_is_logged_before_two_seconds() {
        let t0 = Instant::now();
        let mut log = RateLog::default();
        for i in 0..50u64 {
            assert_eq!(log.frame(t0 + Duration::from_millis(i * 30), 2.0), None);
        }
        log.pause();
        // The paused time (1.5 s to 10 s) does not count as slow frames.
        let t1 = t0 + Duration::from_secs(10);
        assert_eq!(log.frame(t1, 4.0), None);
        assert_eq!(
            log.frame(t1 + Duration::from_secs(2), 4.0).as_deref(),
            Some("0.5 fps, trace 4.0 ms")
        );
    }
}
