//! Adaptive anti-aliasing's edge pixels (after the one-sample base layer):
//! their other samples, several pixels' at a time over the packets' lanes
//! where the frame has packets, else pixel by pixel (the scalar reference).
//! Either way each pixel gets the same bytes, motion cells and segments: each
//! lane traces what `trace_primary` traces, and the pixel's samples are summed
//! in the scalar order (its centre first, then the others in order).

use super::color::srgb8;
use super::frame::Frame;
use super::motion::{Cells, Seg};
use super::packet::LANES;
use glam::Vec3;
use std::ops::Range;

/// An edge pixel's result: its RGBA bytes and its samples' motion cells.
pub(crate) type Sampled = ([u8; 4], Cells);

/// The pixel being summed: column, sum so far, cells, where its segments start.
type Open = (usize, Vec3, Cells, usize);

/// What [`supersampled`] gives: per pixel its result and where its
/// other samples' segments (in a tracked frame) lie in `segs`. Kept by the
/// caller from row to row, so the buffers are not made anew for each.
#[derive(Debug, Default)]
pub(crate) struct Supersamples {
    pub(crate) done: Vec<(Sampled, Range<usize>)>,
    pub(crate) segs: Vec<Seg>,
}

/// Supersamples the edge pixels `xs` (ascending) of row `y`, whose centre
/// samples' linear colours `centre` gives, into `into` (emptied first): per
/// pixel of `xs`, in order, its result and its segments.
pub(crate) fn supersampled(
    frame: &Frame<'_>,
    y: u32,
    xs: &[usize],
    centre: impl Fn(usize) -> Vec3,
    into: &mut Supersamples,
) {
    let others = &frame.offsets()[1..];
    let Supersamples { done: out, segs } = into;
    out.clear();
    segs.clear();
    let Some(pk) = frame.packets(&[(0.5, 0.5)]).filter(|_| !others.is_empty()) else {
        for &x in xs {
            let (from, mut px) = (segs.len(), [0; 4]);
            let (cells, _) = frame.put((x as u32, y), &mut px, (Some(centre(x)), others), segs);
            out.push(((px, cells), from..segs.len()));
        }
        return;
    };
    let n = others.len() + 1;
    let finish = |(_, sum, cells, from): Open, to: usize| -> (Sampled, Range<usize>) {
        // `pixel`: the sum over the samples divided by their count.
        let c = sum / n as f32;
        (([srgb8(c.x), srgb8(c.y), srgb8(c.z), 255], cells), from..to)
    };
    let mut pairs = xs
        .iter()
        .flat_map(|&x| others.iter().map(move |&o| (x, o)))
        .peekable();
    let mut open: Option<Open> = None;
    let (mut batch, mut at) = ([0; LANES], [(0.0, 0.0); LANES]);
    while pairs.peek().is_some() {
        let mut len = 0;
        for (x, (dx, dy)) in pairs.by_ref().take(LANES) {
            // `pixel`: camera.ray(x + dx, y + dy).
            (batch[len], at[len]) = (x, (x as f32 + dx, y as f32 + dy));
            len += 1;
        }
        let colors = pk.camera_samples(&at[..len]);
        let marks = pk.notes.marks();
        for (i, &x) in batch[..len].iter().enumerate() {
            if open.is_none_or(|o| o.0 != x) {
                if let Some(done) = open.take() {
                    out.push(finish(done, segs.len()));
                }
                open = Some((x, Vec3::ZERO + centre(x), 0, segs.len()));
            }
            if let Some(o) = open.as_mut() {
                o.1 += colors[i];
                o.2 |= marks[i];
            }
            segs.extend_from_slice(&pk.notes.lane(i));
        }
    }
    if let Some(done) = open {
        out.push(finish(done, segs.len()));
    }
}
