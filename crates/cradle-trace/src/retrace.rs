//! The motion record of a row (each pixel's cells and ray segments in the motion
//! box) and the re-trace of the pixels an incremental frame must change: those
//! whose cells meet the moved objects' and one of whose segments comes near a
//! moved object, where it was or where it is.

use super::motion::{Cells, NearSet, Seg};
use super::packet::LANES;
use super::render::Frame;
use glam::Vec3;

/// What a row's rays passed: per pixel its motion cells, and its segments in the
/// motion box, `segs[start[k]..start[k + 1]]` for pixel `k`. Without `start`
/// (untracked frames, adaptive frames) only the cells count. `blocks` holds the
/// union of the cells of each [`BLOCK`] pixels and `any` of them all, so that a
/// frame skips the rows and blocks no moved cell reaches without reading every
/// pixel's; [`RowMotion::seal`] sets them once the cells are written.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowMotion {
    pub(crate) cells: Vec<Cells>,
    pub(crate) start: Vec<u32>,
    pub(crate) segs: Vec<Seg>,
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
            start: if track {
                Vec::with_capacity(width + 1)
            } else {
                Vec::new()
            },
            segs: Vec::new(),
            blocks: Vec::new(),
            any: 0,
        }
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

    /// Marks where the next pixel's segments begin (and, after the last, where
    /// they end).
    pub(crate) fn begin(&mut self, track: bool) {
        if track {
            self.start.push(self.segs.len() as u32);
        }
    }

    /// Pixel `k`'s segments.
    pub(crate) fn of(&self, k: usize) -> &[Seg] {
        &self.segs[self.start[k] as usize..self.start[k + 1] as usize]
    }

    /// Appends the segments of `old`'s pixels `range` (the next ones of this
    /// record, with segments) in one copy.
    pub(crate) fn keep(&mut self, old: &Self, range: std::ops::Range<usize>) {
        let (a, b) = (old.start[range.start], old.start[range.end]);
        let shift = self.segs.len() as u32;
        self.start
            .extend(old.start[range].iter().map(|&k| k - a + shift));
        self.segs
            .extend_from_slice(&old.segs[a as usize..b as usize]);
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
        let mut out = vec![false; rm.cells.len()];
        let mut any = false;
        for ((b, &c), block) in rm.blocks.iter().enumerate().zip(out.chunks_mut(BLOCK)) {
            if c & self.cells == 0 {
                continue;
            }
            for (i, dirty) in block.iter_mut().enumerate() {
                *dirty = self.touches(rm, b * BLOCK + i);
                any |= *dirty;
            }
        }
        any.then_some(out)
    }

    /// Whether pixel `k` of `rm` may have changed.
    fn touches(&self, rm: &RowMotion, k: usize) -> bool {
        let cells = rm.cells[k] & self.cells;
        if cells == 0 {
            return false;
        }
        if rm.start.is_empty() || self.coarse {
            return true;
        }
        // A segment near the moved shapes' box, tested against the shapes in
        // cells the pixel's rays passed.
        rm.of(k).iter().any(|s| {
            s.a.max(s.b).cmpge(self.lo).all()
                && s.a.min(s.b).cmple(self.hi).all()
                && self.near.meets(s, cells)
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
        let track = !rm.start.is_empty();
        let mut old = std::mem::replace(rm, RowMotion::new(0, track));
        rm.cells = std::mem::take(&mut old.cells);
        if track {
            rm.start.reserve(width + 1);
            rm.segs.reserve(old.segs.len() + old.segs.len() / 4);
        }
        let packets = self.packets(offsets);
        let mut traced = 0;
        let mut x = 0;
        while x < width {
            let end = (x + LANES).min(width);
            if !dirty[x..end].contains(&true) {
                if track {
                    // The clean pixels' segments, in one copy.
                    rm.keep(&old, x..end);
                }
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
                    for k in x..end {
                        if done & (1 << (k - x)) != 0 {
                            rm.cells[k] = marks[k - x];
                            let i = (k - x) * 4;
                            if let Some(n) = notes.as_deref_mut() {
                                let bytes = (&before[i..i + 4], &span[i..i + 4]);
                                n.note(k, dirty[k], bytes, colors[k - x]);
                            }
                        }
                    }
                    Some((pk, done))
                }
                _ => None,
            };
            for k in x..end {
                rm.begin(track);
                match done {
                    Some((pk, d)) if d & (1 << (k - x)) != 0 => {
                        if track {
                            pk.lane_segs(k - x, &mut rm.segs);
                        }
                        traced += 1;
                    }
                    _ if dirty[k] => {
                        let px = &mut row[k * 4..k * 4 + 4];
                        let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
                        let at = (k as u32, y);
                        let (cells, c) = self.put(at, px, (None, offsets), &mut rm.segs);
                        rm.cells[k] = cells;
                        if let Some(n) = notes.as_deref_mut() {
                            n.note(k, true, (&before, px), c);
                        }
                        traced += 1;
                    }
                    _ => {
                        if track {
                            rm.segs.extend_from_slice(old.of(k));
                        }
                    }
                }
            }
            x = end;
        }
        rm.begin(track);
        rm.seal();
        traced
    }
}
