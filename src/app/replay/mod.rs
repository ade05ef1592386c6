//! The last 10 seconds the window showed (V): every frame presented while the
//! swing runs, as shown (the picture with the HUD; egui's windows are drawn
//! apart and not kept), and the clicks heard with them. The frame loop finds
//! what it drew; a thread of its own keeps of that the runs of pixels that
//! changed since the frame before (deflated when there are many, as when the
//! view moves), and a whole frame every second (`ring`). V hands a copy to
//! another thread, which writes an animated PNG at the frame times the window
//! ran at and, when clicks were heard, a WAV of the same name (`kept`): the
//! frame loop never waits for either. Paused time is not kept: the frame
//! after a pause follows the one before it by one frame's time. This module
//! is the window's side and the recording thread.

mod kept;
mod ring;

pub use kept::Saved;
pub use ring::SPAN;

use crate::sound::synth::{Click, Timbre};
use kept::Kept;
use ring::{Ring, Span};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, SyncSender, TrySendError, sync_channel};
use std::time::Instant;

/// A gap between two presented frames longer than this (s) is a stall (the
/// window hidden, a pause): the frame after it follows by one frame's time.
const STALL: f64 = 0.25;

/// Frames are kept at most this often (s): 100 a second, more than a screen
/// shows; a small window can present several hundred.
const MIN_INTERVAL: f64 = 0.01;

/// Frames waiting for the recording thread; more are dropped (and counted).
const QUEUE: usize = 8;

/// Buffers the recording thread hands back for the next frames' bytes.
const SPARE: usize = 4;

/// What the recording thread is told.
enum Msg {
    /// A presented frame: its time on the recording's clock (s), its size,
    /// and what changed since the frame sent before: the spans and, one after
    /// another, their bytes (BGRA when `bgra`). The first frame and every
    /// frame after a size change or a dropped one send every row whole.
    Frame {
        at: f64,
        size: (u32, u32),
        bgra: bool,
        spans: Vec<Span>,
        data: Vec<u8>,
    },
    /// Clicks heard, on the recording's clock.
    Clicks(Vec<Click>),
    /// Write what is kept to `png` (and a WAV beside it), then call `done`.
    Save {
        png: PathBuf,
        timbre: Timbre,
        done: Box<dyn FnOnce(Result<Saved, String>) + Send>,
    },
}

/// The window's side: it hands each presented frame and the clicks heard to
/// the recording thread.
pub struct Replay {
    tx: Option<SyncSender<Msg>>,
    /// The recording thread: joined when the window closes, after the saves
    /// it started have finished (no half-written file is left behind).
    thread: Option<std::thread::JoinHandle<()>>,
    /// Buffers handed back by the recording thread.
    spare: Receiver<Vec<u8>>,
    /// The recording's clock at the last frame (s), and when that frame was
    /// presented (`None` after a pause: the next frame follows by `typical`).
    clock: f64,
    last: Option<Instant>,
    /// A frame's time, averaged over the recent frames (s).
    typical: f64,
    /// The size of the frames sent, and whether the next must go whole (the
    /// first, one after a frame the thread missed, or after a frame that may
    /// have written anywhere).
    sent_size: (u32, u32),
    whole_next: bool,
    /// Per row, the pixels written since the frame last sent (`x0 >= x1`:
    /// none): frames not kept (paused, hidden, too soon) write too.
    pending: Vec<(u32, u32)>,
    /// Frames the recording thread could not take in time.
    pub dropped: u64,
}

impl Replay {
    /// Starts the recording thread; without it (it could not start) nothing
    /// is kept and V says so.
    pub fn start() -> Self {
        let (tx, rx) = sync_channel(QUEUE);
        let (back, spare) = sync_channel(SPARE);
        let started = std::thread::Builder::new()
            .name("replay".into())
            .spawn(move || record(&rx, &back));
        if let Err(e) = &started {
            tracing::warn!("no replay (V): {e}");
        }
        let (tx, thread) = match started {
            Ok(thread) => (Some(tx), Some(thread)),
            Err(_) => (None, None),
        };
        Self {
            tx,
            thread,
            spare,
            clock: 0.0,
            last: None,
            typical: 1.0 / 60.0,
            sent_size: (0, 0),
            whole_next: true,
            pending: Vec::new(),
            dropped: 0,
        }
    }

    /// The framebuffer was written at `now`: `pixels` of `size`, BGRA when
    /// `bgra`, of which the frame wrote only the `touched` pixels of each row
    /// (`x0..x1`; `None`: any may have changed). `keep`: the frame was
    /// presented while the swing runs (else it is not kept, and the next kept
    /// one follows the last by one frame's time).
    pub fn frame(
        &mut self,
        now: Instant,
        (size, bgra, pixels): ((u32, u32), bool, &[u8]),
        touched: Option<&[(u32, u32)]>,
        keep: bool,
    ) {
        let Some(tx) = self.tx.clone() else {
            return;
        };
        self.note(size, touched);
        if !keep {
            self.last = None;
            return;
        }
        let gap = self
            .last
            .map(|l| now.saturating_duration_since(l).as_secs_f64())
            .filter(|&g| g < STALL);
        if gap.is_some_and(|g| g < MIN_INTERVAL) {
            return;
        }
        let step = gap.unwrap_or(self.typical);
        if let Some(g) = gap {
            self.typical = 0.9 * self.typical + 0.1 * g;
        }
        let at = if self.last.is_none() && self.clock == 0.0 {
            0.0
        } else {
            self.clock + step
        };
        let (spans, data) = self.changes(size, pixels);
        let msg = Msg::Frame {
            at,
            size,
            bgra,
            spans,
            data,
        };
        match tx.try_send(msg) {
            Ok(()) => {
                self.clock = at;
                self.last = Some(now);
            }
            Err(TrySendError::Full(_)) => {
                // The thread missed these changes: the next frame goes whole.
                self.whole_next = true;
                self.dropped += 1;
            }
            Err(TrySendError::Disconnected(_)) => self.tx = None,
        }
    }

    /// Adds a frame's `touched` pixels (of a framebuffer of `size`) to what
    /// was written since the frame last sent.
    fn note(&mut self, size: (u32, u32), touched: Option<&[(u32, u32)]>) {
        match touched.filter(|t| t.len() == size.1 as usize && size == self.sent_size) {
            Some(t) if self.pending.len() == t.len() => {
                for (p, &(a, b)) in self.pending.iter_mut().zip(t) {
                    if a < b {
                        *p = if p.0 < p.1 {
                            (p.0.min(a), p.1.max(b))
                        } else {
                            (a, b)
                        };
                    }
                }
            }
            Some(t) => self.pending = t.to_vec(),
            None => self.whole_next = true,
        }
    }

    /// What to send of `pixels` (of `size`): the pixels written since the
    /// frame last sent, or every row whole when that is not known or the
    /// thread needs it.
    fn changes(&mut self, size: (u32, u32), pixels: &[u8]) -> (Vec<Span>, Vec<u8>) {
        let width = size.0;
        let pending = std::mem::take(&mut self.pending);
        match pending {
            touched if !self.whole_next && self.sent_size == size && !touched.is_empty() => {
                let spans: Vec<Span> = touched
                    .iter()
                    .zip(0..)
                    .filter(|((x0, x1), _)| x0 < x1.min(&width))
                    .map(|(&(x0, x1), y)| Span {
                        y,
                        x0,
                        x1: x1.min(width),
                    })
                    .collect();
                let mut data = self.spare.try_recv().unwrap_or_default();
                data.clear();
                data.reserve(spans.iter().map(|s| s.len()).sum());
                for s in &spans {
                    data.extend_from_slice(&pixels[s.bytes(width)]);
                }
                (spans, data)
            }
            _ => {
                self.whole_next = false;
                self.sent_size = size;
                let whole = (0..size.1).map(|y| Span {
                    y,
                    x0: 0,
                    x1: width,
                });
                (whole.collect(), pixels.to_vec())
            }
        }
    }

    /// Clicks heard with the last frame, their times from it (s, as the live
    /// sound has them).
    pub fn clicks(&mut self, clicks: Vec<Click>) {
        let clicks: Vec<Click> = clicks
            .into_iter()
            .map(|c| Click {
                at: self.clock + c.at,
                ..c
            })
            .collect();
        if let (false, Some(tx)) = (clicks.is_empty(), &self.tx) {
            // Clicks are few and small: wait for room rather than lose them.
            let _ = tx.send(Msg::Clicks(clicks));
        }
    }

    /// Writes what is kept to `png` (and a WAV of the same name with the
    /// clicks of `timbre`) on a thread of its own; `done` hears how it went.
    pub fn save(
        &mut self,
        png: PathBuf,
        timbre: Timbre,
        done: impl FnOnce(Result<Saved, String>) + Send + 'static,
    ) {
        let Some(tx) = &self.tx else {
            done(Err("nothing is kept: the recording could not start".into()));
            return;
        };
        let msg = Msg::Save {
            png,
            timbre,
            done: Box::new(done),
        };
        if let Err(e) = tx.send(msg) {
            let Msg::Save { done, .. } = e.0 else {
                unreachable!("sent a save");
            };
            done(Err("nothing is kept: the recording has stopped".into()));
        }
    }
}

/// Lowers the calling thread's priority (on Linux, nice 10): the frame loop,
/// the tracer and the sound come first; the replay takes what they leave.
fn behind_the_others() {
    #[cfg(target_os = "linux")]
    if let Err(e) = rustix::process::setpriority_process(Some(rustix::thread::gettid()), 10) {
        tracing::debug!("the replay thread keeps its priority: {e}");
    }
}

impl Drop for Replay {
    /// Ends the recording thread, once the saves it started have finished.
    fn drop(&mut self) {
        self.tx = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The recording thread: keeps the frames it is sent, saves on request.
fn record(rx: &Receiver<Msg>, back: &SyncSender<Vec<u8>>) {
    behind_the_others();
    let mut ring = Ring::default();
    let mut saves: Vec<std::thread::JoinHandle<()>> = Vec::new();
    while let Ok(msg) = rx.recv() {
        match msg {
            Msg::Frame {
                at,
                size,
                bgra,
                spans,
                data,
            } => {
                ring.push(at, (size, bgra), &spans, &data);
                // For the next frame's bytes: no fresh allocation a frame.
                let _ = back.try_send(data);
            }
            Msg::Clicks(clicks) => ring.clicks.extend(clicks),
            Msg::Save { png, timbre, done } => {
                let kept = Kept::of(&ring);
                let spawned = std::thread::Builder::new()
                    .name("replay-save".into())
                    .spawn(move || {
                        behind_the_others();
                        done(kept.write(&png, timbre));
                    });
                match spawned {
                    Ok(save) => saves.push(save),
                    Err(e) => tracing::error!("cannot start saving the replay: {e}"),
                }
                saves.retain(|s| !s.is_finished());
            }
        }
    }
    // The window has closed: a save under way finishes first.
    for save in saves {
        if !save.is_finished() {
            tracing::info!("finishing the replay being saved");
        }
        let _ = save.join();
    }
}

/// A free name for a replay: `newtons-cradle-STAMP.png`, numbered so that
/// neither it nor its WAV replaces a file.
#[must_use]
pub fn free_name(stamp: &str) -> PathBuf {
    let name = super::screenshot::free_named(stamp, "png", |n| {
        Path::new(n).exists() || Path::new(n).with_extension("wav").exists()
    });
    PathBuf::from(name)
}

#[cfg(test)]
mod tests {
    use super::kept::tests::{H, W, animation_frames, frame};
    use super::{Replay, Saved, Timbre};
    use std::path::Path;
    use std::time::{Duration, Instant};

    /// What `replay`'s save to `png` answered, waited for.
    fn saved(replay: &mut Replay, png: &Path) -> Result<Saved, String> {
        let (tx, rx) = std::sync::mpsc::channel();
        replay.save(
            png.to_path_buf(),
            Timbre::new(2e11, 0.29, 0.02, 0.26),
            move |r| tx.send(r).expect("the test waits"),
        );
        rx.recv_timeout(Duration::from_secs(30)).expect("answered")
    }

    #[test]
    fn the_window_s_frames_keep_their_times_and_a_pause_adds_none() {
        let dir = std::env::temp_dir().join(format!("nc-replay-w-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut replay = Replay::start();
        let t0 = Instant::now();
        let ms = |n: u64| t0 + Duration::from_millis(n);
        let f = frame(0);
        // 20 frames 20 ms apart, a pause of 5 s, 20 more.
        for k in 0..40u64 {
            let at = if k < 20 {
                ms(20 * k)
            } else {
                ms(5000 + 20 * k)
            };
            let touched: Vec<(u32, u32)> = (0..H).map(|_| (0, W)).collect();
            if k == 20 {
                // A frame presented while paused: not kept.
                replay.frame(ms(2000), ((W, H), false, &f), Some(&touched), false);
            }
            replay.frame(at, ((W, H), false, &f), Some(&touched), true);
            // As a window presents: the thread keeps up between frames.
            std::thread::sleep(Duration::from_millis(2));
        }
        assert_eq!(replay.dropped, 0);
        let png = dir.join("w.png");
        let saved = saved(&mut replay, &png).expect("saved");
        assert_eq!(saved.frames, 40);
        // 40 frames of 20 ms each: the pause took no time.
        assert!((saved.seconds - 0.8).abs() < 0.01, "{}", saved.seconds);
        assert_eq!(animation_frames(&png), 40);
        std::fs::remove_dir_all(&dir).ok();
    }

    /// The last frame of an animated PNG as shown (dispose "none"; blend
    /// "source", or "over" with transparent pixels keeping what was there).
    fn last_frame(path: &std::path::Path) -> Vec<u8> {
        let file = std::io::BufReader::new(std::fs::File::open(path).expect("written"));
        let mut reader = png::Decoder::new(file).read_info().expect("a PNG");
        let (w, h) = reader.info().size();
        let n = reader
            .info()
            .animation_control
            .expect("animated")
            .num_frames;
        let mut canvas = vec![0u8; (w * h * 4) as usize];
        let mut buf = vec![0; reader.output_buffer_size().expect("sized")];
        for _ in 0..n {
            let info = reader.next_frame(&mut buf).expect("a frame");
            let fc = reader.info().frame_control.expect("a frame control");
            for y in 0..fc.height {
                for x in 0..fc.width {
                    let src = y as usize * info.line_size + x as usize * 4;
                    let px = &buf[src..src + 4];
                    let dst = (((fc.y_offset + y) * w + fc.x_offset + x) * 4) as usize;
                    if fc.blend_op == png::BlendOp::Source || px[3] != 0 {
                        canvas[dst..dst + 4].copy_from_slice(px);
                    }
                }
            }
        }
        canvas
    }

    #[test]
    fn what_frames_not_kept_wrote_reaches_the_next_kept_one() {
        let dir = std::env::temp_dir().join(format!("nc-replay-p-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut replay = Replay::start();
        let t0 = Instant::now();
        let ms = |n: u64| t0 + Duration::from_millis(n);
        let whole: Vec<(u32, u32)> = (0..H).map(|_| (0, W)).collect();
        let only = |row: usize| -> Vec<(u32, u32)> {
            (0..H as usize)
                .map(|y| if y == row { (0, W) } else { (0, 0) })
                .collect()
        };
        let mut f = frame(0);
        replay.frame(ms(0), ((W, H), false, &f), Some(&whole), true);
        std::thread::sleep(Duration::from_millis(2));
        // Paused: row 2 changes (a HUD line, say), not kept.
        f[(2 * W * 4) as usize] = 77;
        replay.frame(ms(20), ((W, H), false, &f), Some(&only(2)), false);
        // Running again, too soon after the last kept frame: row 9, not kept.
        f[(9 * W * 4) as usize] = 99;
        replay.frame(ms(25), ((W, H), false, &f), Some(&only(9)), true);
        std::thread::sleep(Duration::from_millis(2));
        replay.frame(ms(26), ((W, H), false, &f), Some(&only(9)), true);
        std::thread::sleep(Duration::from_millis(2));
        // Kept: row 5 changes; rows 2 and 9 must come with it.
        f[(5 * W * 4) as usize] = 55;
        replay.frame(ms(60), ((W, H), false, &f), Some(&only(5)), true);
        std::thread::sleep(Duration::from_millis(2));
        let png = dir.join("p.png");
        assert!(saved(&mut replay, &png).expect("saved").frames >= 2);
        assert!(last_frame(&png) == f, "the last frame is the framebuffer");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn closing_the_window_lets_a_save_under_way_finish() {
        let dir = std::env::temp_dir().join(format!("nc-replay-d-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut replay = Replay::start();
        let t0 = Instant::now();
        let whole: Vec<(u32, u32)> = (0..H).map(|_| (0, W)).collect();
        for k in 0..50u64 {
            let f = frame(k as usize);
            let at = t0 + Duration::from_millis(20 * k);
            replay.frame(at, ((W, H), false, &f), Some(&whole), true);
            std::thread::sleep(Duration::from_millis(1));
        }
        let png = dir.join("d.png");
        replay.save(png.clone(), Timbre::new(2e11, 0.29, 0.02, 0.26), |_| {});
        // Closed at once: the file is there, whole, with no temporary left.
        drop(replay);
        assert!(animation_frames(&png) >= 2);
        let names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["d.png"]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
