//! The last 10 seconds the window showed (V): every frame presented while the
//! swing runs, as shown (the picture with the HUD; egui's windows are drawn
//! apart and not kept), and the clicks heard with them. The frame loop finds
//! what it drew; a thread of its own keeps of that the runs of pixels that
//! changed since the frame before (deflated when there are many, as when the
//! view moves), and a whole frame every second. V hands a
//! copy to another thread, which writes an animated PNG at the frame times the
//! window ran at and, when clicks were heard, a WAV of the same name: the
//! frame loop never waits for either. Paused time is not kept: the frame
//! after a pause follows the one before it by one frame's time.

use crate::export::{ApngWriter, WriteError};
use crate::sound::synth::{Click, Timbre};
use crate::sound::track::Soundtrack;
use crate::trace::Image;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, SyncSender, TrySendError, sync_channel};
use std::time::Instant;

/// How much of the past is kept (s).
pub const SPAN: f64 = 10.0;

/// What is kept stops at this many bytes (the oldest second goes first),
/// whatever the span.
const MAX_BYTES: usize = 256 << 20;

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

/// Pixels `x0..x1` of row `y` of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Span {
    y: u32,
    x0: u32,
    x1: u32,
}

impl Span {
    /// Its bytes.
    fn len(self) -> usize {
        (self.x1 - self.x0) as usize * 4
    }

    /// Its bytes' place in a frame of rows of `width` RGBA pixels.
    fn bytes(self, width: u32) -> std::ops::Range<usize> {
        let at = (self.y as usize * width as usize) * 4;
        at + self.x0 as usize * 4..at + self.x1 as usize * 4
    }
}

/// What a save wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Saved {
    /// The animated PNG, and the WAV when clicks were heard.
    pub png: PathBuf,
    pub wav: Option<PathBuf>,
    /// Frames and seconds.
    pub frames: usize,
    pub seconds: f64,
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
                let kept = ring.kept();
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

/// One kept frame after the first: when it was shown, and what changed.
#[derive(Debug, Clone)]
struct Delta {
    at: f64,
    spans: Arc<[Span]>,
    /// The spans' bytes, one after another; `deflated` (and filtered) when
    /// there were many (the view moving changes every pixel).
    data: Arc<[u8]>,
    deflated: bool,
}

/// A frame's changes of more bytes than this are deflated: a swing changes
/// about 55 KB a frame at 1200x600, kept as they are; a moving view every
/// pixel, 2.9 MB, deflated to about a quarter.
const DEFLATE_OVER: usize = 256 << 10;

/// A new whole frame is kept this often (s of the recording's clock): what
/// is kept starts at one, so between 10 and 11 s are kept and a save starts
/// its last 10 s from there.
const KEY_EVERY: f64 = 1.0;

/// A whole frame and the changes of the frames after it, up to the next one.
#[derive(Debug, Clone)]
struct Segment {
    at: f64,
    key: Arc<[u8]>,
    deltas: Vec<Delta>,
}

/// The kept frames: whole ones about a second apart, the rest as changes.
#[derive(Debug, Default)]
struct Ring {
    size: (u32, u32),
    /// The frames' bytes are BGRA (else RGBA): swapped when saved.
    bgra: bool,
    /// The newest frame, whole, kept up to date from the changes.
    newest: Vec<u8>,
    segments: VecDeque<Segment>,
    /// The whole frames' and the changes' bytes.
    bytes: usize,
    clicks: Vec<Click>,
}

impl Ring {
    /// Keeps the frame shown at `at` (s) of `size` (BGRA when `bgra`), given
    /// as `spans` that may have changed since the last and their bytes `data`
    /// one after another (every row whole for a first frame or a new size;
    /// until one comes, nothing is kept). Only what did change is kept.
    fn push(&mut self, at: f64, (size, bgra): ((u32, u32), bool), spans: &[Span], data: &[u8]) {
        let whole =
            spans.len() == size.1 as usize && data.len() == size.0 as usize * size.1 as usize * 4;
        if self.segments.is_empty() || size != self.size || bgra != self.bgra {
            if whole {
                *self = Self {
                    size,
                    bgra,
                    bytes: data.len(),
                    segments: VecDeque::from([Segment {
                        at,
                        key: data.into(),
                        deltas: Vec::new(),
                    }]),
                    newest: data.to_vec(),
                    ..Self::default()
                };
            }
            return;
        }
        let (spans, data) = narrowed(&mut self.newest, size.0, spans, data);
        let last = self.segments.back_mut().expect("one at least");
        if at - last.at >= KEY_EVERY {
            self.bytes += self.newest.len();
            self.segments.push_back(Segment {
                at,
                key: self.newest.as_slice().into(),
                deltas: Vec::new(),
            });
        } else {
            let deflated = data.len() > DEFLATE_OVER;
            let data: Arc<[u8]> = if deflated {
                fdeflate::compress_to_vec(&filter(&data, &spans)).into()
            } else {
                data.into()
            };
            self.bytes += data.len() + spans.len() * std::mem::size_of::<Span>();
            last.deltas.push(Delta {
                at,
                spans: spans.into(),
                data,
                deflated,
            });
        }
        while self.segments.len() > 1
            && (self.segments[1].at <= at - SPAN || self.bytes > MAX_BYTES)
        {
            let gone = self.segments.pop_front().expect("checked");
            self.bytes -= gone.key.len()
                + gone
                    .deltas
                    .iter()
                    .map(|d| d.data.len() + d.spans.len() * std::mem::size_of::<Span>())
                    .sum::<usize>();
        }
        let from = self.segments.front().map_or(at, |s| s.at);
        self.clicks.retain(|c| c.at >= from);
    }

    /// A copy of what is kept, for a save.
    fn kept(&self) -> Kept {
        let raw: usize = self
            .segments
            .iter()
            .flat_map(|s| s.deltas.iter().flat_map(|d| d.spans.iter()))
            .map(|s| (s.x1 - s.x0) as usize * 4)
            .sum();
        tracing::info!(
            "replay: {} frames kept in {:.1} MB ({} whole, and the changes of the rest: {:.1} MB of pixels, large ones deflated)",
            self.segments
                .iter()
                .map(|s| s.deltas.len() + 1)
                .sum::<usize>(),
            self.bytes as f64 / 1e6,
            self.segments.len(),
            raw as f64 / 1e6
        );
        Kept {
            size: self.size,
            bgra: self.bgra,
            segments: self.segments.iter().cloned().collect(),
            clicks: self.clicks.clone(),
        }
    }
}

/// What a save writes.
struct Kept {
    size: (u32, u32),
    bgra: bool,
    segments: Vec<Segment>,
    clicks: Vec<Click>,
}

impl Kept {
    /// The time of the newest frame (s).
    fn end(&self) -> f64 {
        self.segments
            .last()
            .map_or(0.0, |s| s.deltas.last().map_or(s.at, |d| d.at))
    }

    /// Every kept frame of the last [`SPAN`] seconds in order, each with its
    /// time (s on the recording's clock).
    fn frames(&self) -> impl Iterator<Item = (f64, Vec<u8>)> + '_ {
        let from = self.end() - SPAN;
        let width = self.size.0;
        self.segments
            .iter()
            .flat_map(move |s| {
                let mut canvas = s.key.to_vec();
                std::iter::once((s.at, canvas.clone())).chain(s.deltas.iter().map(move |d| {
                    apply(&mut canvas, width, d);
                    (d.at, canvas.clone())
                }))
            })
            .skip_while(move |(at, _)| *at < from)
            .map(move |(at, mut frame)| {
                if self.bgra {
                    for p in frame.chunks_exact_mut(4) {
                        p.swap(0, 2);
                    }
                }
                (at, frame)
            })
    }

    /// Writes the animated PNG (and the WAV when clicks were heard).
    fn write(&self, png: &Path, timbre: Timbre) -> Result<Saved, String> {
        if self.segments.is_empty() {
            return Err("nothing to save yet: the swing has not run".into());
        }
        let from = self.end() - SPAN;
        let times: Vec<f64> = self
            .segments
            .iter()
            .flat_map(|s| std::iter::once(s.at).chain(s.deltas.iter().map(|d| d.at)))
            .filter(|&t| t >= from)
            .collect();
        let (first, n) = (times[0], times.len());
        // The last frame is shown for as long as the frames before it were.
        let seconds = if n == 1 {
            1.0 / 60.0
        } else {
            (times[n - 1] - first) * n as f64 / (n - 1) as f64
        };
        let written = (|| -> Result<Option<PathBuf>, WriteError> {
            let mut apng = ApngWriter::create(png, self.size, n as u32, true)?;
            let mut frames = self.frames().peekable();
            let ms = |t: f64| ((t - first) * 1000.0).round();
            while let Some((t, rgba)) = frames.next() {
                let next = frames.peek().map_or(first + seconds, |f| f.0);
                let delay = (ms(next) - ms(t)).clamp(1.0, 65535.0) as u16;
                let img = Image {
                    width: self.size.0,
                    height: self.size.1,
                    rgba,
                };
                apng.push(&img, (delay, 1000))?;
            }
            apng.finish()?;
            let clicks: Vec<Click> = self
                .clicks
                .iter()
                .filter(|c| c.at >= first)
                .map(|c| Click {
                    at: c.at - first,
                    ..*c
                })
                .collect();
            if clicks.is_empty() {
                return Ok(None);
            }
            let wav = png.with_extension("wav");
            Soundtrack::laid(timbre, seconds, clicks).write(&wav)?;
            Ok(Some(wav))
        })();
        match written {
            Ok(wav) => Ok(Saved {
                png: png.to_path_buf(),
                wav,
                frames: n,
                seconds,
            }),
            Err(e) => Err(e.to_string()),
        }
    }
}

/// Each span's bytes as differences from the same byte of the pixel to their
/// left (PNG's "sub" filter): smooth shading deflates far better.
fn filter(data: &[u8], spans: &[Span]) -> Vec<u8> {
    let mut out = Vec::with_capacity(data.len());
    let mut at = 0;
    for s in spans {
        let span = &data[at..at + s.len()];
        out.extend_from_slice(&span[..4.min(span.len())]);
        out.extend(span[4..].iter().zip(span).map(|(a, b)| a.wrapping_sub(*b)));
        at += s.len();
    }
    out
}

/// Undoes [`filter`].
fn unfilter(data: &mut [u8], spans: &[Span]) {
    let mut at = 0;
    for s in spans {
        let end = at + (s.x1 - s.x0) as usize * 4;
        let span = &mut data[at..end];
        for i in 4..span.len() {
            span[i] = span[i].wrapping_add(span[i - 4]);
        }
        at = end;
    }
}

/// Unchanged pixels between two changed ones of a row, up to this many, are
/// kept with them: a span costs more than a few pixels.
const GAP: usize = 16;

/// Of `spans` and their bytes `data` (one after another), the runs of pixels
/// that differ from `newest` (rows of `width` pixels; runs closer than [`GAP`]
/// pixels joined), as spans and bytes; puts them into `newest`.
fn narrowed(newest: &mut [u8], width: u32, spans: &[Span], data: &[u8]) -> (Vec<Span>, Vec<u8>) {
    let (mut out, mut bytes) = (Vec::new(), Vec::new());
    let mut at = 0;
    for s in spans {
        let end = at + s.len();
        let (Some(old), Some(new)) = (newest.get_mut(s.bytes(width)), data.get(at..end)) else {
            break;
        };
        at = end;
        if old == new {
            continue;
        }
        for (x0, x1) in runs(old, new) {
            old[4 * x0..4 * x1].copy_from_slice(&new[4 * x0..4 * x1]);
            bytes.extend_from_slice(&new[4 * x0..4 * x1]);
            out.push(Span {
                y: s.y,
                x0: s.x0 + x0 as u32,
                x1: s.x0 + x1 as u32,
            });
        }
    }
    (out, bytes)
}

/// The runs `x0..x1` of RGBA pixels where `a` and `b` differ, joined across
/// gaps of at most [`GAP`] equal pixels.
fn runs(a: &[u8], b: &[u8]) -> Vec<(usize, usize)> {
    let px = a.len() / 4;
    let same = |i: usize| a[4 * i..4 * i + 4] == b[4 * i..4 * i + 4];
    let mut out: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < px {
        // Four equal pixels at a time while they last.
        if i + 4 <= px && a[4 * i..4 * i + 16] == b[4 * i..4 * i + 16] {
            i += 4;
            continue;
        }
        if same(i) {
            i += 1;
            continue;
        }
        match out.last_mut() {
            Some(run) if i - run.1 <= GAP => run.1 = i + 1,
            _ => out.push((i, i + 1)),
        }
        i += 1;
    }
    out
}

/// Puts the `spans`' bytes `data` (one after another) into `canvas` (rows of
/// `width` RGBA pixels).
fn put(canvas: &mut [u8], width: u32, spans: &[Span], data: &[u8]) {
    let mut at = 0;
    for s in spans {
        let place = s.bytes(width);
        let end = at + place.len();
        if let (Some(dst), Some(src)) = (canvas.get_mut(place), data.get(at..end)) {
            dst.copy_from_slice(src);
        }
        at = end;
    }
}

/// Puts a kept frame's changes into `canvas` (rows of `width` RGBA pixels).
fn apply(canvas: &mut [u8], width: u32, d: &Delta) {
    if !d.deflated {
        put(canvas, width, &d.spans, &d.data);
        return;
    }
    // Deflated here from spans of these sizes: it inflates to them.
    let Ok(mut data) = fdeflate::decompress_to_vec(&d.data) else {
        tracing::error!("a kept frame did not inflate; skipped");
        return;
    };
    unfilter(&mut data, &d.spans);
    put(canvas, width, &d.spans, &data);
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
    use super::{Click, Kept, Replay, Ring, SPAN, Span, Timbre};
    use std::time::{Duration, Instant};

    const W: u32 = 40;
    const H: u32 = 20;

    /// Frame `k`: a fixed pattern with a 3x3 block at x = k mod 37, y = 5, and
    /// pixel (0, 0) counting frames.
    fn frame(k: usize) -> Vec<u8> {
        let mut f: Vec<u8> = (0..W * H)
            .flat_map(|i| [(i % 251) as u8, (i / 7) as u8, 40, 255])
            .collect();
        let x0 = (k % 37) as u32;
        for y in 5..8 {
            for x in x0..x0 + 3 {
                let at = ((y * W + x) * 4) as usize;
                f[at..at + 4].copy_from_slice(&[255, 0, 0, 255]);
            }
        }
        f[0] = k as u8;
        f
    }

    /// Every row, whole: what may have changed when nothing narrower is known.
    fn rows() -> Vec<Span> {
        (0..H).map(|y| Span { y, x0: 0, x1: W }).collect()
    }

    /// Rows 0 and 5..8 whole: all that frame `k` changes after frame `k - 1`.
    fn touched() -> Vec<Span> {
        [0, 5, 6, 7].map(|y| Span { y, x0: 0, x1: W }).to_vec()
    }

    fn bytes_of(f: &[u8], spans: &[Span]) -> Vec<u8> {
        spans.iter().flat_map(|s| f[s.bytes(W)].to_vec()).collect()
    }

    #[test]
    fn a_ring_keeps_the_last_ten_seconds_of_frames_exactly() {
        let mut ring = Ring::default();
        let fps = 50.0;
        for k in 0..750 {
            let f = frame(k);
            let spans = if k == 0 { rows() } else { touched() };
            ring.push(
                k as f64 / fps,
                ((W, H), false),
                &spans,
                &bytes_of(&f, &spans),
            );
        }
        let kept = ring.kept();
        let frames: Vec<(f64, Vec<u8>)> = kept.frames().collect();
        // 14.98 s pushed: the frames from 4.98 s on, 501 of them.
        assert_eq!(frames.len(), (SPAN * fps) as usize + 1);
        for (t, f) in &frames {
            let k = (t * fps).round() as usize;
            assert!((t - k as f64 / fps).abs() < 1e-9);
            assert!(*f == frame(k), "frame {k}");
        }
        assert_eq!(frames[0].0, 4.98);
    }

    #[test]
    fn bgra_frames_and_frames_of_many_changes_come_back_as_shown() {
        // 400x200, every pixel changing each frame: deflated, BGRA.
        let (w, h) = (400u32, 200u32);
        let pic = |k: u32| -> Vec<u8> {
            (0..w * h)
                .flat_map(|i| [(i + k) as u8, (i * 3 + k) as u8, (i / 400) as u8, 255])
                .collect()
        };
        let bgra = |f: &[u8]| -> Vec<u8> {
            f.chunks_exact(4)
                .flat_map(|p| [p[2], p[1], p[0], p[3]])
                .collect()
        };
        let all: Vec<Span> = (0..h).map(|y| Span { y, x0: 0, x1: w }).collect();
        let mut ring = Ring::default();
        for k in 0..5 {
            ring.push(f64::from(k) / 30.0, ((w, h), true), &all, &bgra(&pic(k)));
        }
        let kept = ring.kept();
        assert!(kept.segments[0].deltas.iter().all(|d| d.deflated));
        let frames: Vec<(f64, Vec<u8>)> = kept.frames().collect();
        assert_eq!(frames.len(), 5);
        for (k, (_, f)) in frames.iter().enumerate() {
            assert!(*f == pic(k as u32), "frame {k}");
        }
    }

    /// A saved replay's frame count and length, read back from its file.
    fn animation_frames(path: &std::path::Path) -> u32 {
        let file = std::io::BufReader::new(std::fs::File::open(path).expect("written"));
        let reader = png::Decoder::new(file).read_info().expect("a PNG");
        reader
            .info()
            .animation_control
            .expect("animated")
            .num_frames
    }

    fn kept_with_clicks(clicks: Vec<Click>) -> Kept {
        let mut ring = Ring::default();
        for k in 0..100 {
            let f = frame(k);
            ring.push(k as f64 / 50.0, ((W, H), false), &rows(), &f);
        }
        ring.clicks = clicks;
        ring.kept()
    }

    #[test]
    fn a_save_writes_every_kept_frame_and_the_clicks_beside_them() {
        let dir = std::env::temp_dir().join(format!("nc-replay-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let timbre = Timbre::new(2e11, 0.29, 0.02, 0.26);
        let click = Click {
            at: 1.0,
            level: 0.5,
            pulse: 1e-4,
            pan: 0.0,
        };
        let png = dir.join("a.png");
        let saved = kept_with_clicks(vec![click])
            .write(&png, timbre)
            .expect("saved");
        assert_eq!(saved.frames, 100);
        assert_eq!(animation_frames(&png), 100);
        // 100 frames 20 ms apart: 2 s, the last shown as long as the others.
        assert!((saved.seconds - 2.0).abs() < 1e-9, "{}", saved.seconds);
        let wav = saved.wav.expect("a click was heard");
        assert_eq!(wav, dir.join("a.wav"));
        let reader = hound::WavReader::open(&wav).expect("a WAV");
        assert_eq!(reader.duration(), 96_000, "2 s at 48 kHz");
        // No click heard: no WAV.
        let silent = kept_with_clicks(Vec::new())
            .write(&dir.join("b.png"), timbre)
            .expect("saved");
        assert_eq!(silent.wav, None);
        assert!(!dir.join("b.wav").exists());
        std::fs::remove_dir_all(&dir).ok();
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
        let (tx, rx) = std::sync::mpsc::channel();
        let png = dir.join("w.png");
        replay.save(png.clone(), Timbre::new(2e11, 0.29, 0.02, 0.26), move |r| {
            tx.send(r).unwrap();
        });
        let saved = rx.recv_timeout(Duration::from_secs(30)).expect("answered");
        let saved = saved.expect("saved");
        assert_eq!(saved.frames, 40);
        // 40 frames of 20 ms each: the pause took no time.
        assert!((saved.seconds - 0.8).abs() < 0.01, "{}", saved.seconds);
        assert_eq!(animation_frames(&png), 40);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn nothing_kept_is_said_not_written() {
        let kept = Ring::default().kept();
        let path = std::env::temp_dir().join("nc-replay-none.png");
        let e = kept
            .write(&path, Timbre::new(2e11, 0.29, 0.02, 0.26))
            .expect_err("nothing to save");
        assert!(e.contains("nothing to save"), "{e}");
        assert!(!path.exists());
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
        let (tx, rx) = std::sync::mpsc::channel();
        let png = dir.join("p.png");
        replay.save(png.clone(), Timbre::new(2e11, 0.29, 0.02, 0.26), move |r| {
            tx.send(r).unwrap();
        });
        let saved = rx.recv_timeout(Duration::from_secs(30)).expect("answered");
        assert!(saved.expect("saved").frames >= 2);
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
