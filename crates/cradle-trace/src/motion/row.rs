//! The motion record of a row: each pixel's motion cells and its ray segments
//! in the motion box, with the unions that let a frame skip what no moved cell
//! reaches. Filled as a frame traces its rows, read by the re-trace of an
//! incremental frame.

use super::{Cells, Seg};
use crate::simd::Simd;
/// Blocks per super-block of [`RowMotion::supers`] (`tuning`).
pub(crate) use crate::tuning::SUPER;

/// What a row's rays passed: per pixel its motion cells, and its segments in the
/// motion box, `segs[span[k][0]..span[k][1]]` for pixel `k`. Without spans
/// (untracked frames, full adaptive frames) only the cells count. A pixel traced
/// again writes its new segments over its old ones where they fit (what is left
/// over is garbage), else appends them and leaves its old ones as garbage, which
/// [`RowMotion::compact`] drops once it is half the row's, so a frame's work is in
/// the pixels it traces, not in copying the others'. `blocks` holds the union of
/// the cells of each [`BLOCK`] pixels, `supers` of each [`SUPER`] blocks and
/// `any` of them all, so that a frame skips the rows and blocks no moved cell
/// reaches without reading every pixel's (nor every block's);
/// [`RowMotion::seal`] sets them once the cells are written.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowMotion {
    pub(crate) cells: Vec<Cells>,
    pub(crate) span: Vec<[u32; 2]>,
    pub(crate) segs: Vec<Seg>,
    /// Segments in `segs` no pixel refers to.
    pub(crate) garbage: usize,
    pub(crate) blocks: Vec<Cells>,
    pub(crate) supers: Vec<Cells>,
    pub(crate) any: Cells,
}

/// Pixels per block of [`RowMotion::blocks`].
pub(crate) const BLOCK: usize = 8;

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
        // (No pixel changed: the unions hold.)
        let Some(s) = pending else {
            return;
        };
        self.supers[s] = union(chunk(&self.blocks, s, SUPER));
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

    /// Asks the CPU, in lane build `s`, for the first segment of each pixel
    /// of the block from pixel `x0` (none past the row): a hint, for a reader
    /// about to get there.
    #[expect(
        clippy::inline_always,
        reason = "inlined into the filter's build, so the AVX2 one prefetches"
    )]
    #[inline(always)]
    pub(crate) fn prefetch<S: Simd>(&self, s: S, x0: usize) {
        let span = self.span.get(x0..).unwrap_or_default();
        for i in 0..BLOCK {
            if let Some(&[a, _]) = span.get(i) {
                // (A hint at any address: one past the buffer's end, for a
                // pixel with no segments there, is asked for harmlessly.)
                s.prefetch(self.segs.as_ptr().wrapping_add(a as usize));
            }
        }
    }

    /// Pixel `k`'s segments.
    pub(crate) fn of(&self, k: usize) -> &[Seg] {
        let [a, b] = self.span[k];
        &self.segs[a as usize..b as usize]
    }

    /// Traces pixel `k` again: `trace` appends its segments and returns its cells
    /// (and what the caller wants back); they replace the old ones, in their
    /// place when they are no more.
    #[inline]
    pub(crate) fn retrace<R>(
        &mut self,
        k: usize,
        trace: impl FnOnce(&mut Vec<Seg>) -> (Cells, R),
    ) -> R {
        let start = self.segs.len();
        let (cells, out) = trace(&mut self.segs);
        self.cells[k] = cells;
        if k < self.span.len()
            && let Some(a) = self.place(k, start, self.segs.len() - start)
        {
            self.segs.copy_within(start.., a);
            self.segs.truncate(start);
        }
        out
    }

    /// Pixel `k` traced again elsewhere: its cells are `cells` and its
    /// segments `new`, which replace the old ones as [`Self::retrace`] would
    /// (written once, straight to where they go).
    #[inline]
    pub(crate) fn replace(&mut self, k: usize, cells: Cells, new: &[Seg]) {
        self.cells[k] = cells;
        if k < self.span.len() {
            let end = self.segs.len();
            match self.place(k, end, new.len()) {
                Some(a) => self.segs[a..a + new.len()].copy_from_slice(new),
                None => self.segs.extend_from_slice(new),
            }
        }
    }

    /// Where the `n` new segments of pixel `k` (a tracked pixel) go: their
    /// old place when they fit in it (`Some` of its start), else from `end`,
    /// the buffer's end (`None`); notes its span and the garbage left.
    fn place(&mut self, k: usize, end: usize, n: usize) -> Option<usize> {
        let span = &mut self.span[k];
        let (a, b) = (span[0] as usize, span[1] as usize);
        if n <= b - a {
            self.garbage += b - a - n;
            *span = [a as u32, (a + n) as u32];
            Some(a)
        } else {
            self.garbage += b - a;
            *span = [end as u32, (end + n) as u32];
            None
        }
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
        // traced again since the last compaction) are copied as one run, and
        // their spans moved by as much as their run.
        let n = self.span.len();
        let mut i = 0;
        while i < n {
            let [start, mut end] = self.span[i];
            let mut j = i + 1;
            while j < n && self.span[j][0] == end {
                end = self.span[j][1];
                j += 1;
            }
            let to = segs.len() as u32;
            segs.extend_from_slice(&self.segs[start as usize..end as usize]);
            // (Each span lies within the run: the sum is exact.)
            let by = to.wrapping_sub(start);
            for span in &mut self.span[i..j] {
                *span = span.map(|e| e.wrapping_add(by));
            }
            i = j;
        }
        self.segs = segs;
        self.garbage = 0;
    }
}

/// The union of `cells` (eight of them, a block's or a super-block's, unrolled).
fn union(cells: &[Cells]) -> Cells {
    match <&[Cells; 8]>::try_from(cells) {
        Ok(eight) => eight.iter().fold(0, |a, c| a | c),
        Err(_) => cells.iter().fold(0, |a, c| a | c),
    }
}
/// Chunk `i` of `n` of `all` (the last one shorter).
fn chunk(all: &[Cells], i: usize, n: usize) -> &[Cells] {
    &all[i * n..((i + 1) * n).min(all.len())]
}

#[cfg(test)]
mod tests;
