//! The motion record of a row (each pixel's cells and ray segments in the motion
//! box) and the re-trace of the pixels an incremental frame must change: those
//! whose cells meet the moved objects' and one of whose segments comes near a
//! moved object, where it was or where it is.

use super::color::srgb8;
use super::motion::{Cells, Seg};
use super::packet::{LANES, Packet};
use super::render::Frame;
use glam::Vec3;

mod moved;
mod screen;
pub(crate) use moved::Moved;
pub(crate) use screen::{Piece, Spans};

/// What a row's rays passed: per pixel its motion cells, and its segments in the
/// motion box, `segs[span[k][0]..span[k][1]]` for pixel `k`. Without spans
/// (untracked frames, full adaptive frames) only the cells count. A pixel traced
/// again appends its new segments and leaves its old ones as garbage, which
/// [`RowMotion::compact`] drops once it is half the row's, so a frame's work is in
/// the pixels it traces, not in copying the others'. `blocks` holds the union of
/// the cells of each [`BLOCK`] pixels, `supers` of each [`SUPER`] blocks and
/// `any` of them all, so that a frame skips the rows and blocks no moved cell
/// reaches without reading every pixel's (nor every block's);
/// [`RowMotion::seal`] sets them once the cells are written.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowMotion {
    pub(crate) cells: Vec<Cells>,
    span: Vec<[u32; 2]>,
    pub(crate) segs: Vec<Seg>,
    /// Segments in `segs` no pixel refers to.
    garbage: usize,
    blocks: Vec<Cells>,
    supers: Vec<Cells>,
    any: Cells,
}

/// Pixels per block of [`RowMotion::blocks`].
const BLOCK: usize = 8;
/// Blocks per super-block of [`RowMotion::supers`]: most blocks of a row meet
/// no moved cell, and scanning them all read 2.4 kB a row (a third of the
/// motion filter's cache misses).
const SUPER: usize = 8;
// A packet's run of pixels is one block, so resealing the blocks of a row's
// dirty pixels covers the clean lanes a packet traced beside them.
const _: () = assert!(BLOCK == LANES);

impl RowMotion {
    /// A record of `width` pixels to fill; `track`: with cells and segments.
    /// Without, it stays empty: a frame that tracks no motion has no cells.
    pub(crate) fn new(width: usize, track: bool) -> Self {
        if !track {
            return Self::default();
        }
        Self {
            cells: vec![0; width],
            span: Vec::with_capacity(width),
            ..Self::default()
        }
    }

    /// Whether the record holds segments.
    pub(crate) fn tracked(&self) -> bool {
        !self.span.is_empty()
    }

    /// Drops the segments, keeping the cells.
    pub(crate) fn untrack(&mut self) {
        self.span = Vec::new();
        self.segs = Vec::new();
        self.garbage = 0;
    }

    /// Notes the union of the cells of each block, of each super-block and of
    /// the row: call it once the cells are written (before the row is next
    /// tested against motion).
    pub(crate) fn seal(&mut self) {
        self.blocks.clear();
        self.blocks.extend(self.cells.chunks(BLOCK).map(union));
        self.supers.clear();
        self.supers.extend(self.blocks.chunks(SUPER).map(union));
        self.any = union(&self.supers);
    }

    /// [`Self::seal`] after the cells of pixels `xs` (in order) changed, and
    /// only theirs.
    pub(crate) fn reseal(&mut self, xs: impl IntoIterator<Item = usize>) {
        let (mut last, mut pending) = (usize::MAX, None);
        for b in xs.into_iter().map(|x| x / BLOCK) {
            if b == last {
                continue;
            }
            last = b;
            self.blocks[b] = union(chunk(&self.cells, b, BLOCK));
            // A super-block once its blocks in `xs` are done (they ascend).
            if let Some(s) = pending.filter(|&s| s != b / SUPER) {
                self.supers[s] = union(chunk(&self.blocks, s, SUPER));
            }
            pending = Some(b / SUPER);
        }
        if let Some(s) = pending {
            self.supers[s] = union(chunk(&self.blocks, s, SUPER));
        }
        self.any = union(&self.supers);
    }

    /// Gives a freshly filled record's segments room for as many again and a
    /// quarter (call it once the row is traced in full): the next frames
    /// append the segments of the pixels they trace until [`Self::compact`],
    /// which keeps the room, instead of growing the buffer by copying it (13
    /// rows a frame of the default swing did for its first seconds).
    pub(crate) fn room(&mut self) {
        if self.tracked() {
            self.segs.reserve(self.segs.len() + self.segs.len() / 4);
        }
    }

    /// Whether some pixel's cells meet `cells` (after [`Self::seal`]).
    pub(crate) fn meets(&self, cells: Cells) -> bool {
        self.any & cells != 0
    }

    /// While a fresh record is filled pixel by pixel: ends the last pixel's
    /// segments and begins the next one's (after the last pixel: ends it).
    pub(crate) fn begin(&mut self, track: bool) {
        if track {
            let n = self.segs.len() as u32;
            if let Some(last) = self.span.last_mut() {
                last[1] = n;
            }
            if self.span.len() < self.cells.len() {
                self.span.push([n, n]);
            }
        }
    }

    /// Pixel `k`'s segments.
    pub(crate) fn of(&self, k: usize) -> &[Seg] {
        let [a, b] = self.span[k];
        &self.segs[a as usize..b as usize]
    }

    /// Traces pixel `k` again: `trace` appends its segments and returns its cells
    /// (and what the caller wants back); they replace the old ones.
    pub(crate) fn retrace<R>(
        &mut self,
        k: usize,
        trace: impl FnOnce(&mut Vec<Seg>) -> (Cells, R),
    ) -> R {
        let start = self.segs.len() as u32;
        let (cells, out) = trace(&mut self.segs);
        self.cells[k] = cells;
        if let Some(span) = self.span.get_mut(k) {
            self.garbage += (span[1] - span[0]) as usize;
            *span = [start, self.segs.len() as u32];
        }
        out
    }

    /// Clears pixel `k`: no cells, no segments.
    pub(crate) fn clear(&mut self, k: usize) {
        self.cells[k] = 0;
        if let Some(span) = self.span.get_mut(k) {
            self.garbage += (span[1] - span[0]) as usize;
            *span = [0, 0];
        }
    }

    /// Drops the garbage once it is half the segments: copies each pixel's
    /// segments, in pixel order, into a fresh buffer.
    pub(crate) fn compact(&mut self) {
        if self.garbage * 2 <= self.segs.len() {
            return;
        }
        // As much room as before: the next frames' segments append without
        // growing it again.
        let mut segs = Vec::with_capacity(self.segs.capacity());
        // Pixels whose segments follow each other in the old buffer (those not
        // traced again since the last compaction) are copied as one run.
        let mut run = 0..0;
        for span in &mut self.span {
            let (a, b) = (span[0] as usize, span[1] as usize);
            if a != run.end {
                segs.extend_from_slice(&self.segs[run.clone()]);
                run = a..a;
            }
            run.end = b;
            // Where the pixel's segments land: after the runs copied, and
            // this one's segments before it.
            let start = (segs.len() + (a - run.start)) as u32;
            *span = [start, start + (b - a) as u32];
        }
        segs.extend_from_slice(&self.segs[run]);
        self.segs = segs;
        self.garbage = 0;
    }
}

/// The union of `cells`.
fn union(cells: &[Cells]) -> Cells {
    cells.iter().fold(0, |a, c| a | c)
}

/// Chunk `i` of `n` of `all` (the last one shorter).
fn chunk(all: &[Cells], i: usize, n: usize) -> &[Cells] {
    &all[i * n..((i + 1) * n).min(all.len())]
}

/// What the base layer of an adaptive frame notes as [`Frame::retrace_row`]
/// traces its pixels again.
#[derive(Debug)]
pub(crate) struct Notes<'r> {
    /// The x of each pixel the motion may have changed (its colour traced
    /// again), as [`Moved::dirty`] finds them.
    pub(crate) dirty: Vec<u32>,
    /// The x of each traced pixel whose bytes changed.
    pub(crate) changed: Vec<u32>,
    /// The row's linear colours, written where traced.
    pub(crate) lin: &'r mut [Vec3],
}

impl Notes<'_> {
    /// Notes traced pixel `k`: its bytes `before` and `after`, its colour `c`.
    fn note(&mut self, k: usize, (before, after): (&[u8], &[u8]), c: Vec3) {
        self.lin[k] = c;
        if before != after {
            self.changed.push(k as u32);
        }
    }
}

/// A run of eight pixels holding at least this many to re-trace goes as a packet
/// (which traces all eight); fewer go one by one. Chosen by callgrind on the
/// default swing: 1 (always a packet) 167M instructions an incremental frame at
/// one sample, 3 155M, 5 151M, 6 150M, never 159M; later, with the default
/// anti-aliasing, 4 1M more than 5 and 6 0.5M fewer (100.4M -> 99.9M).
const PACKET_AT_LEAST: usize = 6;

impl Frame<'_> {
    /// Re-traces the pixels of row `y` that `moved` may have changed, at samples
    /// `offsets`, in packets where eight pixels in a row hold at least
    /// [`PACKET_AT_LEAST`] such: a packet's bytes, cells and segments are the
    /// scalar path's, and a pixel that did not change would get its own again.
    /// Returns how many pixels it traced; with `notes`, notes each one there.
    pub(crate) fn retrace_row(
        &self,
        y: u32,
        row: &mut [u8],
        rm: &mut RowMotion,
        (moved, offsets): (&Moved, &[(f32, f32)]),
        mut notes: Option<&mut Notes<'_>>,
    ) -> usize {
        // The dirty pixels go to the notes' buffer (kept from frame to frame).
        let mut dirty = notes
            .as_deref_mut()
            .map(|n| std::mem::take(&mut n.dirty))
            .unwrap_or_default();
        let mut traced = 0;
        if moved.dirty(y as usize, rm, true, &mut dirty) {
            traced = self.retrace_dirty((y, row, rm), (&dirty, offsets), notes.as_deref_mut());
        }
        if let Some(n) = notes {
            n.dirty = dirty;
        }
        traced
    }

    /// [`Self::retrace_row`] of the pixels `dirty` (ascending, not empty).
    fn retrace_dirty(
        &self,
        (y, row, rm): (u32, &mut [u8], &mut RowMotion),
        (dirty, offsets): (&[u32], &[(f32, f32)]),
        mut notes: Option<&mut Notes<'_>>,
    ) -> usize {
        let width = self.width() as usize;
        let track = rm.tracked();
        if let Some(n) = notes.as_deref_mut() {
            // `changed` holds at most the traced pixels (up to a run of eight
            // each), seldom more than twice as many as the dirty ones.
            n.changed.reserve(dirty.len() * 2);
        }
        let packets = self.packets(offsets);
        let mut traced = 0;
        // Dirty pixels no floor packet traced, for the eye rays' lanes.
        let (mut left, mut n_left) = ([0; LANES], 0);
        // Run by run of LANES pixels holding a dirty one: `mask` a bit per
        // dirty pixel of the run.
        let mut rest = dirty;
        while let Some(&first) = rest.first() {
            let x = first as usize / LANES * LANES;
            let end = (x + LANES).min(width);
            let count = rest.iter().take_while(|&&k| (k as usize) < end).count();
            let mask = rest[..count]
                .iter()
                .fold(0u8, |m, &k| m | 1 << (k as usize - x));
            rest = &rest[count..];
            let done = match &packets {
                Some(pk) if end - x == LANES && count >= PACKET_AT_LEAST => {
                    let span = &mut row[x * 4..end * 4];
                    let before: [u8; 4 * LANES] = span.try_into().expect("a run of LANES");
                    let done = pk.run(x as u32, y, span);
                    let marks = pk.marks();
                    for k in (x..end).filter(|k| done & (1 << (k - x)) != 0) {
                        rm.retrace(k, |segs| {
                            if track {
                                pk.lane_segs(k - x, segs);
                            }
                            (marks[k - x], ())
                        });
                        if let Some(n) = notes.as_deref_mut() {
                            let i = (k - x) * 4;
                            let bytes = (&before[i..i + 4], &span[i..i + 4]);
                            n.note(k, bytes, pk.color(k - x));
                        }
                        traced += 1;
                    }
                    done
                }
                _ => 0,
            };
            for k in (x..end).filter(|&k| (mask & !done) & (1 << (k - x)) != 0) {
                traced += 1;
                if let Some(pk) = &packets {
                    // Eight at a time over the lanes, as eye rays.
                    left[n_left] = k;
                    n_left += 1;
                    if n_left == LANES {
                        Self::eye_rays(pk, (y, &left, offsets[0]), (row, rm), notes.as_deref_mut());
                        n_left = 0;
                    }
                    continue;
                }
                let px = &mut row[k * 4..k * 4 + 4];
                let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
                let at = (k as u32, y);
                let c = rm.retrace(k, |segs| self.put(at, px, (None, offsets), segs));
                if let Some(n) = notes.as_deref_mut() {
                    n.note(k, (&before, px), c);
                }
            }
        }
        if let Some(pk) = &packets
            && n_left > 0
        {
            Self::eye_rays(pk, (y, &left[..n_left], offsets[0]), (row, rm), notes);
        }
        rm.compact();
        // Only pixels of dirty runs changed their cells.
        rm.reseal(dirty.iter().map(|&k| k as usize));
        traced
    }

    /// Re-traces pixels `ks` (at most [`LANES`]) of row `y` at their one
    /// sample's offset (packets trace the centre only) over the packet's lanes, each as `trace_primary` traces its ray: the
    /// bytes, cells and segments the scalar `put` gives (its colour is the
    /// one sample's, over 1).
    fn eye_rays(
        pk: &Packet<'_, '_>,
        (y, ks, (dx, dy)): (u32, &[usize], (f32, f32)),
        (row, rm): (&mut [u8], &mut RowMotion),
        mut notes: Option<&mut Notes<'_>>,
    ) {
        let track = rm.tracked();
        let mut at = [(0.0, 0.0); LANES];
        for (a, &k) in at.iter_mut().zip(ks) {
            *a = (k as f32 + dx, y as f32 + dy);
        }
        let colors = pk.camera_samples(&at[..ks.len()]);
        let marks = pk.marks();
        for (i, &k) in ks.iter().enumerate() {
            // `pixel`: the sum from zero over the one sample, divided by 1.
            let c = (Vec3::ZERO + colors[i]) / 1.0;
            let px = &mut row[k * 4..k * 4 + 4];
            let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
            px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
            rm.retrace(k, |segs| {
                if track {
                    pk.lane_segs(i, segs);
                }
                (marks[i], ())
            });
            if let Some(n) = notes.as_deref_mut() {
                n.note(k, (&before, px), c);
            }
        }
    }
}

#[cfg(test)]
mod row_tests;
