//! The motion record of a row (each pixel's cells and ray segments in the motion
//! box) and the re-trace of the pixels an incremental frame must change: those
//! whose cells meet the moved objects' and one of whose segments comes near a
//! moved object, where it was or where it is.

use super::motion::{Cells, Near, Seg};
use super::packet::LANES;
use super::render::Frame;
use glam::Vec3;

/// What a row's rays passed: per pixel its motion cells, and its segments in the
/// motion box, `segs[start[k]..start[k + 1]]` for pixel `k`. Without `start`
/// (untracked frames, adaptive frames) only the cells count.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowMotion {
    pub(crate) cells: Vec<Cells>,
    pub(crate) start: Vec<u32>,
    pub(crate) segs: Vec<Seg>,
}

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
        }
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
}

/// What moved since the last frame: the cells of the moved objects, where they
/// were and where they are, and those shapes grown a little.
#[derive(Debug, Clone, Default)]
pub(crate) struct Moved {
    pub(crate) cells: Cells,
    /// Each shape with its own cells.
    pub(crate) near: Vec<(Cells, Near)>,
    /// The box around every `near`.
    pub(crate) lo: Vec3,
    pub(crate) hi: Vec3,
    /// A moved shape has no [`Near`] (a plane): the cells alone decide.
    pub(crate) coarse: bool,
}

impl Moved {
    /// Whether pixel `k` of `rm` may have changed.
    pub(crate) fn touches(&self, rm: &RowMotion, k: usize) -> bool {
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
                && self.near.iter().any(|(c, n)| c & cells != 0 && n.meets(s))
        })
    }
}

impl Frame<'_> {
    /// Re-traces the pixels of row `y` that `moved` may have changed, at samples
    /// `offsets`, in packets where eight pixels in a row hold one such: a
    /// packet's bytes, cells and segments are the scalar path's, and a pixel that
    /// did not change would get its own again. Returns how many pixels it traced.
    pub(crate) fn retrace_row(
        &self,
        y: u32,
        row: &mut [u8],
        rm: &mut RowMotion,
        (moved, offsets): (&Moved, &[(f32, f32)]),
    ) -> usize {
        let width = self.width() as usize;
        let dirty: Vec<bool> = (0..width).map(|k| moved.touches(rm, k)).collect();
        if !dirty.contains(&true) {
            return 0;
        }
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
                for k in x..end {
                    rm.begin(track);
                    if track {
                        rm.segs.extend_from_slice(old.of(k));
                    }
                }
                x = end;
                continue;
            }
            let done = match &packets {
                Some(pk) if end - x == LANES => {
                    let span = &mut row[x * 4..end * 4];
                    let (done, marks) = pk.run(x as u32, y, span);
                    for k in x..end {
                        if done & (1 << (k - x)) != 0 {
                            rm.cells[k] = marks[k - x];
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
                        rm.cells[k] = self.put_with((k as u32, y), px, offsets, &mut rm.segs);
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
        traced
    }
}
