//! Incremental frames with adaptive anti-aliasing. A full adaptive frame traces
//! one centre sample per pixel (the base), then every sample where a pixel's base
//! colour differs from a 4-neighbour's by more than the threshold (an edge). The
//! incremental twin keeps both layers with their ray segments:
//! 1. the base pixels a moved object may have changed are re-traced (as in a
//!    frame without anti-aliasing);
//! 2. the edge test is redone where a base pixel or a 4-neighbour changed bytes;
//! 3. an edge pixel is supersampled again when it just became an edge or one of
//!    its samples' segments comes near a moved object; any other pixel shows its
//!    base colour.
//!
//! So each frame equals the full adaptive render byte for byte (tested).

use super::color::Image;
use super::render::{Frame, for_rows};
use super::retrace::{BLOCK, Moved, RowMotion};
use rayon::prelude::*;

/// The centre sample of the base layer.
const CENTRE: [(f32, f32); 1] = [(0.5, 0.5)];

/// What an adaptive incremental frame keeps besides the picture.
#[derive(Debug)]
pub(crate) struct Layers {
    /// The one-sample picture.
    base: Image,
    /// Its rows' motion record.
    base_rows: Vec<RowMotion>,
    /// Per pixel (row-major), whether it is an edge of `base`.
    edge: Vec<bool>,
    /// Per row, the motion record of the edge pixels' samples (others: none).
    edge_rows: Vec<RowMotion>,
}

impl Frame<'_> {
    /// Whether each pixel of `base` is an edge at `threshold`, row-major.
    fn edges(&self, base: &[u8], threshold: f32) -> Vec<bool> {
        let w = self.width();
        (0..self.height())
            .into_par_iter()
            .flat_map_iter(|y| (0..w).map(move |x| self.is_edge(base, x, y, threshold)))
            .collect()
    }

    /// A full adaptive frame at `threshold`, and its layers.
    pub(crate) fn adaptive_full(&self, threshold: f32) -> (Image, Layers) {
        let (w, h) = (self.width(), self.height());
        let mut base = Image {
            width: w,
            height: h,
            rgba: vec![0; w as usize * h as usize * 4],
        };
        let base_rows = for_rows(&mut base, true, |y, row| self.row_with(y, row, &CENTRE));
        let edge = self.edges(&base.rgba, threshold);
        let mut img = base.clone();
        let n = w as usize;
        let edge_rows = for_rows(&mut img, true, |y, row| {
            let flags = &edge[y as usize * n..(y as usize + 1) * n];
            let mut rm = RowMotion::new(n, true);
            for (x, px) in row.chunks_exact_mut(4).enumerate() {
                rm.begin(true);
                if flags[x] {
                    rm.cells[x] = self.put(x as u32, y, px, &mut rm.segs);
                }
            }
            rm.begin(true);
            rm.seal();
            rm
        });
        let layers = Layers {
            base,
            base_rows,
            edge,
            edge_rows,
        };
        (img, layers)
    }

    /// The next adaptive frame into `img`, from `layers` after `moved`: returns
    /// how many pixels it traced (base and supersampled).
    pub(crate) fn adaptive_next(
        &self,
        threshold: f32,
        layers: &mut Layers,
        img: &mut Image,
        moved: &Moved,
    ) -> usize {
        let (w, h) = (self.width() as usize, self.height() as usize);
        let stride = w * 4;
        // The base layer, noting per row the pixels whose bytes changed.
        let (counts, xs): (Vec<usize>, Vec<Vec<u32>>) = layers
            .base
            .rgba
            .par_chunks_exact_mut(stride)
            .zip(layers.base_rows.par_iter_mut())
            .enumerate()
            .map(|(y, (row, rm))| {
                let mut xs = Vec::new();
                let n = self.retrace_row(y as u32, row, rm, (moved, &CENTRE), Some(&mut xs));
                (n, xs)
            })
            .unzip();
        let mut traced: usize = counts.iter().sum();
        let mut changed = vec![false; w * h];
        for (y, row) in xs.iter().enumerate() {
            for &x in row {
                changed[y * w + x as usize] = true;
            }
        }
        let base = &layers.base.rgba;
        // The edge test again at each changed pixel and its 4-neighbours.
        let old_edge = &layers.edge;
        let mut edge = old_edge.clone();
        edge.par_chunks_exact_mut(w)
            .enumerate()
            .for_each(|(y, flags)| {
                let mut again = |x: usize| {
                    flags[x] = self.is_edge(base, x as u32, y as u32, threshold);
                };
                for &x in &xs[y] {
                    let x = x as usize;
                    (x.saturating_sub(1)..(x + 2).min(w)).for_each(&mut again);
                }
                let beside = [y.checked_sub(1), Some(y + 1).filter(|&v| v < h)];
                for v in beside.into_iter().flatten() {
                    xs[v].iter().for_each(|&x| again(x as usize));
                }
            });
        traced += img
            .rgba
            .par_chunks_exact_mut(stride)
            .zip(layers.edge_rows.par_iter_mut())
            .enumerate()
            .map(|(y, (row, rm))| {
                let span = y * w..(y + 1) * w;
                let rows = (&base[y * stride..(y + 1) * stride], &xs[y][..]);
                let flags = (&old_edge[span.clone()], &edge[span]);
                self.final_row(y as u32, (row, rm), rows, flags, moved)
            })
            .sum::<usize>();
        layers.edge = edge;
        traced
    }

    /// Row `y` of the picture (`row`, with its edge record `rm`): base colours
    /// where not an edge, samples kept or traced again where an edge. `changed`:
    /// the pixels whose base bytes changed.
    fn final_row(
        &self,
        y: u32,
        (row, rm): (&mut [u8], &mut RowMotion),
        (base, changed): (&[u8], &[u32]),
        (was, is): (&[bool], &[bool]),
        moved: &Moved,
    ) -> usize {
        let w = is.len();
        let same = was == is;
        if same && changed.is_empty() && !rm.meets(moved.cells) {
            return 0;
        }
        let show_base = |row: &mut [u8], x: usize| {
            row[x * 4..x * 4 + 4].copy_from_slice(&base[x * 4..x * 4 + 4]);
        };
        for &x in changed {
            if !is[x as usize] {
                show_base(row, x as usize);
            }
        }
        if !same {
            for x in (0..w).filter(|&x| was[x] && !is[x]) {
                show_base(row, x);
            }
        }
        // Only edge pixels have cells in `rm`, so its blocks skip the others.
        let touched = moved.dirty(rm);
        let redo: Vec<bool> = (0..w)
            .map(|x| is[x] && (!was[x] || touched.as_ref().is_some_and(|t| t[x])))
            .collect();
        if same && !redo.contains(&true) {
            return 0;
        }
        // The new record reuses the old one's cells: kept where the pixel stays
        // an edge and is not traced again, cleared where it is no edge. Blocks
        // with nothing to change keep their segments in one copy.
        let mut old = std::mem::replace(rm, RowMotion::new(0, true));
        rm.cells = std::mem::take(&mut old.cells);
        rm.start.reserve(w + 1);
        let mut traced = 0;
        for x0 in (0..w).step_by(BLOCK) {
            let end = (x0 + BLOCK).min(w);
            if !redo[x0..end].contains(&true) && was[x0..end] == is[x0..end] {
                rm.keep(&old, x0..end);
                continue;
            }
            for x in x0..end {
                rm.begin(true);
                if redo[x] {
                    let px = &mut row[x * 4..x * 4 + 4];
                    rm.cells[x] = self.put(x as u32, y, px, &mut rm.segs);
                    traced += 1;
                } else if is[x] {
                    rm.segs.extend_from_slice(old.of(x));
                } else {
                    rm.cells[x] = 0;
                }
            }
        }
        rm.begin(true);
        rm.seal();
        traced
    }
}
