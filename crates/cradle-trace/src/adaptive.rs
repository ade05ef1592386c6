//! Incremental frames with adaptive anti-aliasing. A full adaptive frame traces
//! one centre sample per pixel (the base), then the other samples where a pixel's
//! base colour differs from a 4-neighbour's by more than the threshold (an edge):
//! sample 0 of the pattern is the centre, so an edge pixel takes the base's
//! linear colour for it and traces the rest, adding them in the same order as a
//! uniform render. The incremental twin keeps both layers with their ray segments
//! and the base's linear colours:
//! 1. the base pixels a moved object may have changed are re-traced (as in a
//!    frame without anti-aliasing);
//! 2. the edge test is redone where a base pixel or a 4-neighbour changed bytes;
//! 3. an edge pixel is supersampled again when it just became an edge, its base
//!    pixel was re-traced, or one of its other samples' segments comes near a
//!    moved object; any other pixel shows its base colour.
//!
//! So each frame equals the full adaptive render byte for byte (tested).

use super::bits::{BitRoom, ascending};
use super::color::Image;
use super::frame::{Edges, Frame, least_above};
use super::motion::RowMotion;
use super::retrace::{Layer, Moved, Notes, retrace_row};
use super::supersample::{Supersamples, supersampled};
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// The centre sample of the base layer.
const CENTRE: [(f32, f32); 1] = [(0.5, 0.5)];

/// A row of the base layer as the final row sees it after a frame's re-trace.
#[derive(Clone, Copy)]
struct Base<'r> {
    bytes: &'r [u8],
    lin: &'r [Vec3],
    /// The pixels traced again where motion may have changed them.
    dirty: &'r [u32],
    /// Those whose bytes changed.
    changed: &'r [u32],
}

/// What an adaptive incremental frame keeps besides the picture.
#[derive(Debug)]
pub(crate) struct Layers {
    /// The one-sample picture.
    base: Image,
    /// Its rows' motion record.
    base_rows: Vec<RowMotion>,
    /// Per row, per pixel, whether it is an edge of `base`.
    edge: Vec<Vec<bool>>,
    /// Per row, its linear colours: sample 0 of an edge pixel.
    lin: Vec<Vec<Vec3>>,
    /// Per row, the motion record of the edge pixels' other samples (others:
    /// none).
    edge_rows: Vec<RowMotion>,
    /// Per row, what the last frame noted (the buffers kept for the next):
    /// the base pixels traced again where motion may have changed them, those
    /// whose bytes changed, and the pixels whose edge flag flipped.
    dirty: Vec<Vec<u32>>,
    changed: Vec<Vec<u32>>,
    flips: Vec<Vec<u32>>,
}

/// Buffers a thread's rows of the picture use in turn ([`final_row`]).
#[derive(Default)]
struct Scratch {
    retest: Retest,
    redo: Vec<usize>,
    sorted: Vec<usize>,
    touched: Vec<u32>,
    samples: Supersamples,
}

/// The full adaptive frame at `threshold`, and its layers: the one-sample
/// base, then every sample at its edges. Rows in parallel or one after
/// another (the same bytes), adding 1 to `rows_done` as each row of each
/// pass is done (`2 * height` in all). Every adaptive picture is made here:
/// the full renders' and the first of a run of incremental frames.
pub(crate) fn adaptive_full(
    frame: &Frame<'_>,
    threshold: f32,
    (parallel, rows_done): (bool, Option<&AtomicU32>),
) -> (Image, Layers) {
    let count = || {
        if let Some(c) = rows_done {
            c.fetch_add(1, Ordering::Relaxed);
        }
    };
    let (w, h) = (frame.width(), frame.height());
    let track = frame.motion.is_some();
    let mut base = Image {
        width: w,
        height: h,
        rgba: vec![0; w as usize * h as usize * 4],
    };
    let n = w as usize;
    let (base_rows, lin): (Vec<RowMotion>, Vec<Vec<Vec3>>) = base
        .for_rows(parallel, |y, row| {
            let mut lin = vec![Vec3::ZERO; n];
            let rm = frame.row_with(y, row, &CENTRE, Some(&mut lin));
            count();
            (rm, lin)
        })
        .into_iter()
        .unzip();
    // The picture is the base's bytes but at the edges, copied row by row
    // beside the rows' supersampling.
    let mut img = Image {
        rgba: vec![0; base.rgba.len()],
        ..base
    };
    let stride = n * 4;
    let (edge_rows, edge): (Vec<RowMotion>, Vec<Vec<bool>>) = img
        .for_rows(parallel, |y, row| {
            let y_at = y as usize;
            row.copy_from_slice(&base.rgba[y_at * stride..(y_at + 1) * stride]);
            let flags = frame.edge_row(&base.rgba, y, threshold);
            let lin = &lin[y_at];
            let mut rm = RowMotion::new(n, track);
            let xs: Vec<usize> = (0..n).filter(|&x| flags[x]).collect();
            let mut samples = Supersamples::default();
            supersampled(frame, y, &xs, |x| lin[x], &mut samples);
            let Supersamples { done, segs } = samples;
            let mut done = done.into_iter();
            for (x, px) in row.chunks_exact_mut(4).enumerate() {
                rm.begin(track);
                if flags[x]
                    && let Some(((bytes, cells), span)) = done.next()
                {
                    px.copy_from_slice(&bytes);
                    if track {
                        rm.cells[x] = cells;
                        rm.segs.extend_from_slice(&segs[span]);
                    }
                }
            }
            rm.begin(track);
            rm.seal();
            rm.room();
            count();
            (rm, flags)
        })
        .into_iter()
        .unzip();
    let layers = Layers {
        base,
        base_rows,
        edge,
        lin,
        edge_rows,
        dirty: vec![Vec::new(); h as usize],
        changed: vec![Vec::new(); h as usize],
        flips: vec![Vec::new(); h as usize],
    };
    (img, layers)
}

impl Layers {
    /// Each row's motion cells, the base's and the edge samples' together,
    /// without segments: the record of a frame that is not reused.
    pub(crate) fn into_rows(self) -> Vec<RowMotion> {
        let mut rows = self.base_rows;
        for (m, e) in rows.iter_mut().zip(self.edge_rows) {
            m.cells.iter_mut().zip(e.cells).for_each(|(a, b)| *a |= b);
            m.untrack();
            m.seal();
        }
        rows
    }
}

/// The next adaptive frame into `img`, from `layers` after `moved`, noting
/// per row in `written` the pixels whose bytes it may have changed: returns
/// how many pixels it traced (base and supersampled).
pub(crate) fn adaptive_next(
    frame: &Frame<'_>,
    threshold: f32,
    layers: &mut Layers,
    (img, written): (&mut Image, &mut [[u32; 2]]),
    moved: &Moved,
) -> usize {
    let stride = frame.width() as usize * 4;
    // The base layer, noting per row the pixels motion may have changed and
    // those whose bytes changed.
    let mut traced: usize = layers
        .base
        .rgba
        .par_chunks_exact_mut(stride)
        .zip(layers.base_rows.par_iter_mut())
        .zip(layers.lin.par_iter_mut())
        .zip(
            layers
                .dirty
                .par_iter_mut()
                .zip(layers.changed.par_iter_mut()),
        )
        .enumerate()
        .map(|(y, (((row, rm), lin), (dirty, changed)))| {
            changed.clear();
            let mut notes = Notes {
                dirty: std::mem::take(dirty),
                changed: std::mem::take(changed),
                lin,
            };
            let n = retrace_row(frame, y as u32, row, rm, (moved, &CENTRE), Some(&mut notes));
            (*dirty, *changed) = (notes.dirty, notes.changed);
            n
        })
        .sum();
    let (base, lin, xs) = (&layers.base.rgba, &layers.lin, &layers.changed);
    let dirty = &layers.dirty;
    let least = least_above(threshold);
    // Row by row: the edge test again at each changed pixel of the row and
    // at the row's pixels beside a changed one (in place: the row's flags
    // and the pixels whose flag flipped), then the row of the picture. A
    // row's test reads the base rows above and below it, which the base
    // layer has finished, and writes only its own flags.
    traced += img
        .rgba
        .par_chunks_exact_mut(stride)
        .zip(layers.edge_rows.par_iter_mut())
        .zip(written.par_iter_mut())
        .zip(layers.edge.par_iter_mut().zip(layers.flips.par_iter_mut()))
        .enumerate()
        .map_init(
            Scratch::default,
            |scratch, (y, (((row, rm), written), (flags, flipped)))| {
                scratch
                    .retest
                    .row(frame, (base, y, least), xs, (flags, flipped));
                let base = Base {
                    bytes: &base[y * stride..(y + 1) * stride],
                    lin: &lin[y],
                    dirty: &dirty[y],
                    changed: &xs[y],
                };
                let at = (y as u32, row, rm);
                let (n, xs) = final_row(frame, at, &base, (flags, flipped), moved, scratch);
                *written = xs;
                n
            },
        )
        .sum::<usize>();
    traced
}

/// Runs this long or longer take [`Frame::edge_run`] in the edge test
/// again; shorter ones [`Frame::is_edge`] pixel by pixel.
const RUN_AT_LEAST: usize = 8;

/// The edge test again of runs of pixels, with the buffers it keeps.
#[derive(Default)]
struct Retest {
    run: Vec<bool>,
    edges: Edges,
}

impl Retest {
    /// The edge test of row `y` again, at each pixel of `changed[y]` and its
    /// neighbours in the row and at each pixel of `changed[y - 1]` and
    /// `changed[y + 1]` (`base`: the base layer's bytes, `least`: as
    /// [`Frame::is_edge`] takes it): each pixel whose flag in `flags` flips
    /// is flipped and noted in `flipped` (emptied first).
    fn row(
        &mut self,
        frame: &Frame<'_>,
        (base, y, least): (&[u8], usize, u16),
        changed: &[Vec<u32>],
        (flags, flipped): (&mut [bool], &mut Vec<u32>),
    ) {
        flipped.clear();
        let (w, h) = (flags.len(), changed.len());
        let beside = [y.checked_sub(1), Some(y + 1).filter(|&v| v < h)];
        let above_below = beside
            .into_iter()
            .flatten()
            .flat_map(|v| changed[v].iter().map(|&x| x as usize));
        let here = changed[y]
            .iter()
            .flat_map(|&x| x.saturating_sub(1) as usize..(x as usize + 2).min(w));
        let mut room = BitRoom::new();
        let mut bits = room.row(w);
        above_below.chain(here).for_each(|x| bits.set(x));
        for run in bits.runs() {
            self.retest(frame, (base, y as u32, least), run, (flags, flipped));
        }
    }

    /// Tests pixels `xs` of row `y` of `base` again (`least`: as
    /// [`Frame::is_edge`] takes it), and where a pixel's flag in `flags`
    /// flips, flips it and notes the pixel in `flipped`.
    fn retest(
        &mut self,
        frame: &Frame<'_>,
        (base, y, least): (&[u8], u32, u16),
        xs: std::ops::Range<usize>,
        (flags, flipped): (&mut [bool], &mut Vec<u32>),
    ) {
        let mut note = |x: usize, now: bool| {
            if now != flags[x] {
                flags[x] = now;
                flipped.push(x as u32);
            }
        };
        if xs.len() < RUN_AT_LEAST {
            for x in xs {
                note(x, frame.is_edge(base, x as u32, y, least));
            }
        } else {
            let edges = (&mut self.run, &mut self.edges);
            frame.edge_run(base, (y, xs.clone()), least, edges);
            for (x, &now) in xs.zip(&self.run) {
                note(x, now);
            }
        }
    }
}

/// Row `y` of the picture (`row`, with its edge record `rm`): base colours
/// where not an edge, samples kept or traced again where an edge. `is`: the
/// row's edge flags; `flips`: the pixels whose flag this frame flipped.
/// Returns how many pixels it supersampled, and the pixels `x0..x1` whose
/// bytes it may have changed (`[0, 0]`: none).
fn final_row(
    frame: &Frame<'_>,
    (y, row, rm): (u32, &mut [u8], &mut RowMotion),
    base: &Base<'_>,
    (is, flips): (&[bool], &[u32]),
    moved: &Moved,
    scratch: &mut Scratch,
) -> (usize, [u32; 2]) {
    let w = is.len();
    let Base {
        bytes,
        lin,
        dirty,
        changed,
    } = *base;
    if flips.is_empty() && dirty.is_empty() && changed.is_empty() && !moved.reaches(y as usize, rm)
    {
        return (0, [0, 0]);
    }
    // The pixels written: those whose base bytes changed (not in order),
    // whose flag flipped, and the edges supersampled again.
    let mut span = changed
        .iter()
        .chain(flips)
        .fold((u32::MAX, 0), |(a, b), &x| (a.min(x), b.max(x + 1)));
    let show_base = |row: &mut [u8], x: usize| {
        row[x * 4..x * 4 + 4].copy_from_slice(&bytes[x * 4..x * 4 + 4]);
    };
    for &x in changed {
        if !is[x as usize] {
            show_base(row, x as usize);
        }
    }
    // Pixels that stop being edges show the base colour and drop their
    // record; new edges are supersampled.
    let Scratch {
        redo,
        sorted,
        touched,
        samples,
        ..
    } = scratch;
    redo.clear();
    for &x in flips {
        let x = x as usize;
        if is[x] {
            redo.push(x);
        } else {
            show_base(row, x);
            rm.clear(x);
        }
    }
    // So are edges whose base pixel, sample 0, was traced again (taken as
    // they are) and those whose other samples' segments come near a moved
    // object (only edge pixels have cells in `rm`, so its blocks skip the
    // others).
    if moved.dirty(y as usize, rm, Layer::Edges { is, taken: dirty }, touched) {
        redo.extend(touched.iter().map(|&x| x as usize));
    }
    let written = |(a, b): (u32, u32)| if a < b { [a, b] } else { [0, 0] };
    if redo.is_empty() && flips.is_empty() {
        return (0, written(span));
    }
    ascending(w, redo.iter().copied(), sorted);
    if let (Some(&a), Some(&b)) = (sorted.first(), sorted.last()) {
        span = (span.0.min(a as u32), span.1.max(b as u32 + 1));
    }
    supersampled(frame, y, sorted, |x| lin[x], samples);
    for (&x, ((bytes, cells), span)) in sorted.iter().zip(&samples.done) {
        row[x * 4..x * 4 + 4].copy_from_slice(bytes);
        rm.replace(x, *cells, &samples.segs[span.clone()]);
    }
    let traced = sorted.len();
    rm.compact();
    // The blocks of the pixels whose cells changed: those traced again and
    // those that stopped being edges (each ascending).
    rm.reseal(sorted.iter().copied());
    rm.reseal(flips.iter().map(|&x| x as usize).filter(|&x| !is[x]));
    (traced, written(span))
}
