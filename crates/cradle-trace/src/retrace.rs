//! The motion record of a row (each pixel's cells and ray segments in the motion
//! box) and the re-trace of the pixels an incremental frame must change: those
//! whose cells meet the moved objects' and one of whose segments comes near a
//! moved object, where it was or where it is.

use super::motion::{Cells, NearSet, Seg};
use super::packet::LANES;
use super::render::Frame;
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
pub(crate) const BLOCK: usize = 8;

impl RowMotion {
    /// A record of `width` pixels to fill; `track`: with segments.
    pub(crate) fn new(width: usize, track: bool) -> Self {
        Self {
            cells: vec![0; width],
            span: if track {
                Vec::with_capacity(width)
            } else {
                Vec::new()
            },
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
        let mut segs = Vec::with_capacity(self.segs.len() - self.garbage);
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
    /// Per pixel of `rm` (sealed), whether it may have changed ([`Self::touches`]);
    /// `None` when no pixel may. Blocks no moved cell reaches are skipped whole.
    pub(crate) fn dirty(&self, rm: &RowMotion) -> Option<Vec<bool>> {
        if !rm.meets(self.cells) {
            return None;
        }
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            // SAFETY: the CPU has AVX2, checked just above.
            #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
            return unsafe { self.dirty_avx2(rm) };
        }
        self.dirty_with::<false>(rm)
    }

    /// [`Self::dirty`] compiled for AVX2, the segment tests inlined.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn dirty_avx2(&self, rm: &RowMotion) -> Option<Vec<bool>> {
        self.dirty_with::<true>(rm)
    }

    /// [`Self::dirty`] after its row test; `AVX2` (set only where the CPU has
    /// it): the AVX2 build.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn dirty_with<const AVX2: bool>(&self, rm: &RowMotion) -> Option<Vec<bool>> {
        let mut out = vec![false; rm.cells.len()];
        let mut any = false;
        for ((b, &c), block) in rm.blocks.iter().enumerate().zip(out.chunks_mut(BLOCK)) {
            if c & self.cells == 0 {
                continue;
            }
            for (i, dirty) in block.iter_mut().enumerate() {
                *dirty = self.touches::<AVX2>(rm, b * BLOCK + i);
                any |= *dirty;
            }
        }
        any.then_some(out)
    }

    /// Whether pixel `k` of `rm` may have changed.
    /// `AVX2`: as in [`Self::dirty_with`].
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn touches<const AVX2: bool>(&self, rm: &RowMotion, k: usize) -> bool {
        let cells = rm.cells[k] & self.cells;
        if cells == 0 {
            return false;
        }
        if !rm.tracked() || self.coarse {
            return true;
        }
        // A segment near the moved shapes' box, tested against the shapes in
        // cells the pixel's rays passed.
        rm.of(k).iter().any(|s| {
            s.a.max(s.b).cmpge(self.lo).all()
                && s.a.min(s.b).cmple(self.hi).all()
                && self.near.meets_with::<AVX2>(s, cells)
        })
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
        let packets = self.packets(offsets);
        let mut traced = 0;
        let mut x = 0;
        while x < width {
            let end = (x + LANES).min(width);
            if !dirty[x..end].contains(&true) {
                x = end;
                continue;
            }
            let done = match &packets {
                Some(pk)
                    if end - x == LANES
                        && dirty[x..end].iter().filter(|&&d| d).count() >= PACKET_AT_LEAST =>
                {
                    let span = &mut row[x * 4..end * 4];
                    let before: [u8; 4 * LANES] = span.try_into().expect("a run of LANES");
                    let (done, marks) = pk.run(x as u32, y, span);
                    let colors = pk.colors.get();
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
                            n.note(k, dirty[k], bytes, colors[k - x]);
                        }
                        traced += 1;
                    }
                    done
                }
                _ => 0,
            };
            for k in (x..end).filter(|&k| dirty[k] && done & (1 << (k - x)) == 0) {
                let px = &mut row[k * 4..k * 4 + 4];
                let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
                let at = (k as u32, y);
                let c = rm.retrace(k, |segs| self.put(at, px, (None, offsets), segs));
                if let Some(n) = notes.as_deref_mut() {
                    n.note(k, true, (&before, px), c);
                }
                traced += 1;
            }
            x = end;
        }
        rm.compact();
        rm.seal();
        traced
    }
}
