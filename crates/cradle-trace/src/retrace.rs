//! The motion record of a row (each pixel's cells and ray segments in the motion
//! box) and the re-trace of the pixels an incremental frame must change: those
//! whose cells meet the moved objects' and one of whose segments comes near a
//! moved object, where it was or where it is.

use super::motion::{Batch, Cells, NearSet, Seg, has};
use super::packet::LANES;
use super::render::Frame;
#[cfg(target_arch = "x86_64")]
use super::simd::Avx2;
use super::simd::{Portable, Simd};
use glam::Vec3;

/// What a row's rays passed: per pixel its motion cells, and its segments in the
/// motion box, `segs[span[k][0]..span[k][1]]` for pixel `k`. Without spans
/// (untracked frames, full adaptive frames) only the cells count. A pixel traced
/// again appends its new segments and leaves its old ones as garbage, which
/// [`RowMotion::compact`] drops once it is half the row's, so a frame's work is in
/// the pixels it traces, not in copying the others'. `blocks` holds the union of
/// the cells of each [`BLOCK`] pixels and `any` of them all, so that a frame skips
/// the rows and blocks no moved cell reaches without reading every pixel's;
/// [`RowMotion::seal`] sets them once the cells are written.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowMotion {
    pub(crate) cells: Vec<Cells>,
    span: Vec<[u32; 2]>,
    pub(crate) segs: Vec<Seg>,
    /// Segments in `segs` no pixel refers to.
    garbage: usize,
    blocks: Vec<Cells>,
    any: Cells,
}

/// Pixels per block of [`RowMotion::blocks`].
const BLOCK: usize = 8;
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

    /// Notes the union of the cells of each block and of the row: call it once
    /// the cells are written (before the row is next tested against motion).
    pub(crate) fn seal(&mut self) {
        self.blocks.clear();
        self.blocks.extend(
            self.cells
                .chunks(BLOCK)
                .map(|b| b.iter().fold(0, |a, c| a | c)),
        );
        self.any = self.blocks.iter().fold(0, |a, c| a | c);
    }

    /// [`Self::seal`] after the cells of pixels `xs` (in order) changed, and
    /// only theirs.
    pub(crate) fn reseal(&mut self, xs: impl IntoIterator<Item = usize>) {
        let mut last = usize::MAX;
        for b in xs.into_iter().map(|x| x / BLOCK) {
            if b != last {
                let end = ((b + 1) * BLOCK).min(self.cells.len());
                self.blocks[b] = self.cells[b * BLOCK..end].iter().fold(0, |a, c| a | c);
                last = b;
            }
        }
        self.any = self.blocks.iter().fold(0, |a, c| a | c);
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
        for span in &mut self.span {
            let start = segs.len() as u32;
            segs.extend_from_slice(&self.segs[span[0] as usize..span[1] as usize]);
            *span = [start, segs.len() as u32];
        }
        self.segs = segs;
        self.garbage = 0;
    }
}

/// What moved since the last frame: the cells of the moved objects, where they
/// were and where they are, and those shapes grown a little.
#[derive(Debug, Clone, Default)]
pub(crate) struct Moved {
    pub(crate) cells: Cells,
    /// Each shape with its own cells.
    pub(crate) near: NearSet,
    /// The box around every `near`.
    pub(crate) lo: Vec3,
    pub(crate) hi: Vec3,
    /// A moved shape has no [`crate::motion::Near`] (a plane): the cells alone
    /// decide.
    pub(crate) coarse: bool,
}

impl Moved {
    /// The pixels of `rm` (sealed) that may have changed, in order; `None` when
    /// no pixel may. A pixel may have changed when its cells meet the moved
    /// ones and (in a tracked record of a frame without a moved plane) one of
    /// its segments near the moved shapes' box comes within a moved shape whose
    /// cells meet its own ([`crate::motion::Near::meets`]). Blocks no moved cell
    /// reaches are skipped whole; the segments are tested eight at a time
    /// ([`Batch`]).
    pub(crate) fn dirty(&self, rm: &RowMotion) -> Option<Vec<u32>> {
        if !rm.meets(self.cells) {
            return None;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(s) = Avx2::detect() {
            // SAFETY: the token proves the CPU has AVX2.
            #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
            return unsafe { self.dirty_avx2(s, rm) };
        }
        self.dirty_with(Portable, rm)
    }

    /// [`Self::dirty`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn dirty_avx2(&self, s: Avx2, rm: &RowMotion) -> Option<Vec<u32>> {
        self.dirty_with(s, rm)
    }

    /// [`Self::dirty`] after its row test, in lane build `s`.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn dirty_with<S: Simd>(&self, s: S, rm: &RowMotion) -> Option<Vec<u32>> {
        let n = rm.cells.len();
        let cells_only = !rm.tracked() || self.coarse;
        // A bit per pixel, on the stack for rows up to 4,096 pixels.
        let (mut stack, mut heap) = ([0u64; 64], Vec::new());
        let hit: &mut [u64] = if n <= 64 * 64 {
            &mut stack[..n.div_ceil(64)]
        } else {
            heap.resize(n.div_ceil(64), 0);
            &mut heap
        };
        let mut batch = Batch::default();
        for (b, &c) in rm.blocks.iter().enumerate() {
            if c & self.cells == 0 {
                continue;
            }
            // Plain loops: a closure would stay a call, outside the AVX2 build.
            for k in b * BLOCK..((b + 1) * BLOCK).min(n) {
                let cells = rm.cells[k] & self.cells;
                if cells == 0 {
                    continue;
                }
                if cells_only {
                    hit[k / 64] |= 1 << (k % 64);
                    continue;
                }
                for seg in rm.of(k) {
                    if has(hit, k as u32) {
                        break;
                    }
                    let near_box = seg.a.max(seg.b).cmpge(self.lo).all()
                        && seg.a.min(seg.b).cmple(self.hi).all();
                    if near_box && batch.push(k as u32, cells, seg) {
                        batch.test(s, &self.near, hit);
                    }
                }
            }
        }
        batch.test(s, &self.near, hit);
        let count = hit.iter().map(|w| w.count_ones() as usize).sum();
        let mut out = Vec::with_capacity(count);
        for (i, &word) in hit.iter().enumerate() {
            let mut w = word;
            while w != 0 {
                out.push((i * 64) as u32 + w.trailing_zeros());
                w &= w - 1;
            }
        }
        (!out.is_empty()).then_some(out)
    }
}

/// What the base layer of an adaptive frame notes as [`Frame::retrace_row`]
/// traces its pixels again.
#[derive(Debug)]
pub(crate) struct Notes<'r> {
    /// The x of each pixel the motion may have changed (its colour traced again).
    pub(crate) dirty: Vec<u32>,
    /// The x of each traced pixel whose bytes changed.
    pub(crate) changed: Vec<u32>,
    /// The row's linear colours, written where traced.
    pub(crate) lin: &'r mut [Vec3],
}

impl Notes<'_> {
    /// Notes traced pixel `k`: `dirty` whether motion may have changed it, its
    /// bytes `before` and `after`, its colour `c`.
    fn note(&mut self, k: usize, dirty: bool, (before, after): (&[u8], &[u8]), c: Vec3) {
        self.lin[k] = c;
        if dirty {
            self.dirty.push(k as u32);
        }
        if before != after {
            self.changed.push(k as u32);
        }
    }
}

/// A run of eight pixels holding at least this many to re-trace goes as a packet
/// (which traces all eight); fewer go one by one. Chosen by callgrind on the
/// default swing: 1 (always a packet) 167M instructions an incremental frame at
/// one sample, 3 155M, 5 151M, 6 150M, never 159M.
const PACKET_AT_LEAST: usize = 5;

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
        let width = self.width() as usize;
        let Some(dirty) = moved.dirty(rm) else {
            return 0;
        };
        let track = rm.tracked();
        if let Some(n) = notes.as_deref_mut() {
            // At most every pixel of the dirty ones' runs.
            n.dirty.reserve(dirty.len());
            n.changed.reserve(dirty.len() * 2);
        }
        let packets = self.packets(offsets);
        let mut traced = 0;
        // Run by run of LANES pixels holding a dirty one: `mask` a bit per
        // dirty pixel of the run.
        let mut rest = &dirty[..];
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
                            n.note(k, mask & (1 << (k - x)) != 0, bytes, pk.color(k - x));
                        }
                        traced += 1;
                    }
                    done
                }
                _ => 0,
            };
            for k in (x..end).filter(|&k| (mask & !done) & (1 << (k - x)) != 0) {
                let px = &mut row[k * 4..k * 4 + 4];
                let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
                let at = (k as u32, y);
                let c = rm.retrace(k, |segs| self.put(at, px, (None, offsets), segs));
                if let Some(n) = notes.as_deref_mut() {
                    n.note(k, true, (&before, px), c);
                }
                traced += 1;
            }
        }
        rm.compact();
        // Only pixels of dirty runs changed their cells.
        rm.reseal(dirty.iter().map(|&k| k as usize));
        traced
    }
}
