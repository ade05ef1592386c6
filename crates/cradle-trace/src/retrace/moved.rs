//! What moved since the last frame, and which pixels of a row it may have
//! changed: the motion filter of incremental frames (cells first, then the
//! segments of the pixels they leave, eight at a time, against the moved shapes).

use super::{BLOCK, RowMotion};
use crate::bits::BitRoom;
use crate::motion::{Batch, Cells, NearSet};
#[cfg(target_arch = "x86_64")]
use crate::simd::Avx2;
use crate::simd::{Portable, Simd};
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
        let mut room = BitRoom::new();
        let mut hit = room.row(n);
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
                    hit.set(k);
                    continue;
                }
                for seg in rm.of(k) {
                    if hit.has(k) {
                        break;
                    }
                    let near_box = seg.a.max(seg.b).cmpge(self.lo).all()
                        && seg.a.min(seg.b).cmple(self.hi).all();
                    if near_box && batch.push(k as u32, cells, seg) {
                        batch.test(s, &self.near, &mut hit);
                    }
                }
            }
        }
        batch.test(s, &self.near, &mut hit);
        let mut out = Vec::with_capacity(hit.count());
        out.extend(hit.iter().map(|k| k as u32));
        (!out.is_empty()).then_some(out)
    }
}
