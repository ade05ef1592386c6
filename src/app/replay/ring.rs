//! What the replay keeps (`super`): whole frames a second apart and, between
//! them, the runs of pixels each frame changed, up to the last 10 seconds.

use crate::sound::synth::Click;
use std::collections::VecDeque;
use std::sync::Arc;

/// How much of the past is kept (s).
pub const SPAN: f64 = 10.0;

/// What is kept stops at this many bytes (the oldest second goes first),
/// whatever the span.
const MAX_BYTES: usize = 256 << 20;

/// Pixels `x0..x1` of row `y` of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Span {
    pub(super) y: u32,
    pub(super) x0: u32,
    pub(super) x1: u32,
}

impl Span {
    /// Its bytes.
    pub(super) fn len(self) -> usize {
        (self.x1 - self.x0) as usize * 4
    }

    /// Its bytes' place in a frame of rows of `width` RGBA pixels.
    pub(super) fn bytes(self, width: u32) -> std::ops::Range<usize> {
        let at = (self.y as usize * width as usize) * 4;
        at + self.x0 as usize * 4..at + self.x1 as usize * 4
    }
}

/// One kept frame after the first: when it was shown, and what changed.
#[derive(Debug, Clone)]
pub(super) struct Delta {
    pub(super) at: f64,
    pub(super) spans: Arc<[Span]>,
    /// The spans' bytes, one after another; `deflated` (and filtered) when
    /// there were many (the view moving changes every pixel).
    data: Arc<[u8]>,
    pub(super) deflated: bool,
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
pub(super) struct Segment {
    pub(super) at: f64,
    pub(super) key: Arc<[u8]>,
    pub(super) deltas: Vec<Delta>,
}

/// The kept frames: whole ones about a second apart, the rest as changes.
#[derive(Debug, Default)]
pub(super) struct Ring {
    pub(super) size: (u32, u32),
    /// The frames' bytes are BGRA (else RGBA): swapped when saved.
    pub(super) bgra: bool,
    /// The newest frame, whole, kept up to date from the changes.
    newest: Vec<u8>,
    pub(super) segments: VecDeque<Segment>,
    /// The whole frames' and the changes' bytes.
    pub(super) bytes: usize,
    pub(super) clicks: Vec<Click>,
}

impl Ring {
    /// Keeps the frame shown at `at` (s) of `size` (BGRA when `bgra`), given
    /// as `spans` that may have changed since the last and their bytes `data`
    /// one after another (every row whole for a first frame or a new size;
    /// until one comes, nothing is kept). Only what did change is kept.
    pub(super) fn push(
        &mut self,
        at: f64,
        (size, bgra): ((u32, u32), bool),
        spans: &[Span],
        data: &[u8],
    ) {
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
pub(super) fn apply(canvas: &mut [u8], width: u32, d: &Delta) {
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
