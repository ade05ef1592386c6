//! What moved since the last frame, and which pixels of a row it may have
//! changed: the motion filter of incremental frames (cells and the screen's
//! runs first, `screen`, then the segments of the pixels they leave, eight at a
//! time, against the moved shapes).

use super::Spans;
use crate::bits::BitRoom;
use crate::motion::{BLOCK, RowMotion, SUPER};
use crate::motion::{Batch, Cells, NearSet};
use crate::simd::{Build, Kernel, Simd};
use crate::tuning::PREFETCH_AHEAD;
use glam::Vec3;

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
    /// Per row, where the moved shapes may meet pixels' free segments, which
    /// leave no cells (`Record::segment`'s `free`).
    pub(crate) spans: Spans,
}

impl Moved {
    /// Whether the moved shapes may reach a pixel of row `y`, whose record is
    /// `rm` (sealed).
    pub(crate) fn reaches(&self, y: usize, rm: &RowMotion) -> bool {
        rm.meets(self.cells) || !self.spans.row(y).is_empty()
    }

    /// Into `out` (emptied first), the pixels of row `y`, whose record is `rm`
    /// (sealed), that may have changed, in order; false when no pixel may. A
    /// pixel may have changed when its cells meet the moved ones or it lies in
    /// the row's [`Spans`], and (in a tracked record of a frame without a
    /// moved plane) one of its segments near the moved shapes' box comes within
    /// a moved shape whose cells meet its own, or any moved shape for a pixel
    /// in the spans ([`crate::motion::Near::meets`]), unless it passes well
    /// through a moved ball where it was and where it is (a shadow ray blocked
    /// both times, [`NearSet::with_balls`]). Blocks neither reaches are skipped
    /// whole; the segments are tested eight at a time ([`Batch`]). With
    /// `sure`, a pixel in the row's sure runs ([`Spans::sure_row`]: its centre
    /// well inside a moved ball's image) is taken without its segments: its
    /// centre ray meets the ball unless something hides it, and a pixel taken
    /// needlessly is only traced again, so the frame keeps its bytes either
    /// way (the base layer, one centre sample, asks for it; the edge layer's
    /// samples lie anywhere in the pixel and each costs three, so it does not).
    /// The pixels `taken` (ascending: those the caller traces again anyway)
    /// are in `out` as they are, their segments not tested.
    pub(crate) fn dirty(
        &self,
        y: usize,
        rm: &RowMotion,
        (sure, taken): (bool, &[u32]),
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        if !self.reaches(y, rm) {
            out.extend_from_slice(taken);
            return !out.is_empty();
        }
        Build::detect().run(Dirty {
            moved: self,
            at: (y, rm, sure, taken),
            out,
        })
    }

    /// [`Self::dirty`] after its row test, in lane build `s`.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn dirty_with<S: Simd>(
        &self,
        s: S,
        (y, rm, sure, taken): (usize, &RowMotion, bool, &[u32]),
        out: &mut Vec<u32>,
    ) -> bool {
        let n = rm.cells.len();
        let mut room = BitRoom::new();
        let mut hit = room.row(n);
        // A pixel already in `hit` has its segments skipped.
        for &x in taken {
            hit.set(x as usize);
        }
        let mut batch = Batch::default();
        let runs = self.spans.row(y);
        let sure = if sure { self.spans.sure_row(y) } else { &[] };
        // The first run that ends after the pixel at hand (pixels ascend).
        let (mut r, mut sr) = (0, 0);
        for (i, &c) in rm.supers.iter().enumerate() {
            let (b0, b1) = (i * SUPER, ((i + 1) * SUPER).min(rm.blocks.len()));
            if !may_hold(
                runs,
                &mut r,
                c & self.cells,
                (b0 * BLOCK, (b1 * BLOCK).min(n)),
            ) {
                continue;
            }
            for b in b0..b1 {
                let (x0, x1) = (b * BLOCK, ((b + 1) * BLOCK).min(n));
                if !may_hold(runs, &mut r, rm.blocks[b] & self.cells, (x0, x1)) {
                    continue;
                }
                self.block(
                    s,
                    (rm, x0..x1),
                    (runs, &mut r),
                    (sure, &mut sr),
                    (&mut batch, &mut hit),
                );
            }
        }
        batch.test(s, &self.near, &mut hit);
        out.extend(hit.iter().map(|k| k as u32));
        !out.is_empty()
    }

    /// The candidates among pixels `xs` of `rm` (a block), their segments
    /// tested in `batch`, the pixels met noted in `hit`; `r`: the first of
    /// `runs` that ends after `xs.start`, kept so for the next block.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn block<S: Simd>(
        &self,
        s: S,
        (rm, xs): (&RowMotion, std::ops::Range<usize>),
        (runs, r): (&[(u32, u32)], &mut usize),
        (sure, sr): (&[(u32, u32)], &mut usize),
        (batch, hit): (&mut Batch, &mut crate::bits::RowBits<'_>),
    ) {
        let cells_only = !rm.tracked() || self.coarse;
        for k in xs {
            // The segments of a pixel further on, on their way (every pixel
            // of the block: the candidates among them are not known yet).
            if !cells_only {
                rm.prefetch(s, k + PREFETCH_AHEAD);
            }
            while *r < runs.len() && runs[*r].1 as usize <= k {
                *r += 1;
            }
            // In a run, any moved shape may meet a free segment.
            let in_run = runs.get(*r).is_some_and(|run| run.0 as usize <= k);
            let cells = if in_run {
                Cells::MAX
            } else {
                rm.cells[k] & self.cells
            };
            if cells == 0 {
                continue;
            }
            if cells_only {
                hit.set(k);
                continue;
            }
            while *sr < sure.len() && sure[*sr].1 as usize <= k {
                *sr += 1;
            }
            if sure.get(*sr).is_some_and(|run| run.0 as usize <= k) {
                hit.set(k);
                continue;
            }
            for seg in rm.of(k) {
                if hit.has(k) {
                    break;
                }
                let near_box =
                    seg.a.max(seg.b).cmpge(self.lo).all() && seg.a.min(seg.b).cmple(self.hi).all();
                if near_box && batch.push(k as u32, cells, seg) {
                    batch.test(s, &self.near, hit);
                }
            }
        }
    }
}

/// Whether pixels `x0..x1`, whose cells meeting the moved ones are `met`, may
/// hold a candidate: `met` is not empty or a run meets them (`r`: the first of
/// `runs` that ends after the last pixels asked about, ascending; moved on to
/// the first that ends after `x0`).
#[inline(always)]
#[expect(
    clippy::inline_always,
    reason = "a few compares, inlined into each build"
)]
fn may_hold(runs: &[(u32, u32)], r: &mut usize, met: Cells, (x0, x1): (usize, usize)) -> bool {
    while *r < runs.len() && runs[*r].1 as usize <= x0 {
        *r += 1;
    }
    met != 0 || runs.get(*r).is_some_and(|run| (run.0 as usize) < x1)
}

/// [`Moved::dirty`] after its row test, as a lane kernel.
struct Dirty<'k> {
    moved: &'k Moved,
    at: (usize, &'k RowMotion, bool, &'k [u32]),
    out: &'k mut Vec<u32>,
}

#[expect(
    clippy::inline_always,
    reason = "a kernel inlines into its build's entry point, which compiles it for AVX2 in the AVX2 build"
)]
impl Kernel for Dirty<'_> {
    type Output = bool;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> bool {
        self.moved.dirty_with(s, self.at, self.out)
    }
}
