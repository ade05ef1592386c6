//! Shadow rays from a plane (the floor, most of the picture) test only the objects
//! whose shadow can fall where they start.
//!
//! Seen from a point light, an object's box projects onto the plane as the convex
//! hull of its eight projected corners (a directional light projects in parallel).
//! A shadow ray from a point of the plane to the light runs along the line that
//! projects onto that point, so only objects whose projected rectangle holds the
//! point can block it. A rod goes in by the rectangles of its pieces' boxes
//! (`casters::piece_boxes`), whose union holds it: a slanted string or a post
//! shadows a thin diagonal, which its whole box's rectangle would cover many
//! times over. The rectangles are binned in a grid over the plane; a query
//! looks up its cell. The answer is a yes/no of "anything in the way", so testing
//! a superset of the blockers in any order gives the same bits as testing them all.

use super::geometry::Aabb;
use super::scene::Light;
use glam::{Vec2, Vec3};

/// A cell of the grid: column and row.
type Cell2 = (usize, usize);

/// Where the light shines from, for projecting onto the plane.
#[derive(Debug, Clone, Copy)]
enum Source {
    Point(Vec3),
    /// Direction the light travels.
    Directional(Vec3),
}

/// Where a shadow ray's start finds its candidates ([`Footprints::lookup`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Lookup {
    /// Behind the plane or level with the light: every object is a candidate.
    #[default]
    Unlit,
    /// Off the grid: only the objects that can shadow any point.
    Always,
    /// In this cell (row-major index).
    Cell(usize),
}

impl Lookup {
    /// [`Lookup::Unlit`] as a lane's number ([`Lookup::of`]).
    pub(crate) const UNLIT: u32 = u32::MAX;
    /// [`Lookup::Always`] as a lane's number.
    pub(crate) const ALWAYS: u32 = u32::MAX - 1;

    /// The lookup a lane's number stands for: a cell's index (grids have at
    /// most 256 x 256 cells), [`Self::UNLIT`] or [`Self::ALWAYS`]. Packets
    /// keep numbers, which compare eight at a time.
    pub(crate) fn of(code: u32) -> Self {
        match code {
            Self::UNLIT => Self::Unlit,
            Self::ALWAYS => Self::Always,
            k => Self::Cell(k as usize),
        }
    }
}

/// [`Footprints::lookup`]'s numbers: the plane, the light (a point, or a
/// direction of travel), the light's height over the plane (point) or the
/// direction's component along the normal, and the grid.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GridView {
    pub origin: Vec3,
    pub normal: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
    pub light: Result<Vec3, Vec3>,
    pub scale: f32,
    pub min: Vec2,
    pub inv_cell: Vec2,
    pub n: (usize, usize),
    pub gridded: bool,
}

/// The objects that can shadow each cell of one plane from one light.
#[derive(Debug, Clone)]
pub struct Footprints {
    /// A point of the plane and its unit normal (the lit side).
    origin: Vec3,
    normal: Vec3,
    /// Unit vectors spanning the plane.
    e1: Vec3,
    e2: Vec3,
    source: Source,
    /// Grid over the rectangles: corner, cell size, cells per axis.
    min: Vec2,
    inv_cell: Vec2,
    n: (usize, usize),
    /// Per cell, object indices in query order: cell `k` holds
    /// `items[starts[k]..starts[k + 1]]` (one flat list, built in two passes,
    /// not a vector per cell). Empty when there is no grid.
    starts: Vec<u32>,
    items: Vec<usize>,
    /// Objects reaching up to the light's height or beyond: they can shadow any
    /// point, so every query tests them.
    always: Vec<usize>,
    /// The binned objects (in the query order of the grid's first build),
    /// each with the rectangle holding its pieces' and their cells, and the
    /// rectangle holding them all (the grid's bounds): what
    /// [`Self::with_moved`] starts from.
    placed: Vec<Placed>,
    bounds: (Vec2, Vec2),
}

/// An object in the grid: its index, the rectangle holding its pieces'
/// rectangles, and the cells each of those reaches (first and last).
#[derive(Debug, Clone)]
struct Placed {
    object: usize,
    rect: (Vec2, Vec2),
    spans: Vec<(Cell2, Cell2)>,
}

impl Footprints {
    /// The footprints on the plane through `origin` with unit `normal` of the
    /// bounded objects `bounded` (index, box, in query order) lit by `light`.
    /// `pieces` gives an object's pieces' boxes (empty: its box whole), which
    /// bin it only in the cells the pieces' rectangles reach: a slanted rod's
    /// footprint is a thin diagonal, its box's rectangle a wide one.
    /// `None` for ambient light, or a light on the other side of the plane (its
    /// shadow rays from the lit side never start).
    #[must_use]
    pub fn new(
        origin: Vec3,
        normal: Vec3,
        light: &Light,
        bounded: &[(usize, Aabb)],
        pieces: impl Fn(usize) -> Vec<Aabb>,
    ) -> Option<Self> {
        let source = match *light {
            Light::Ambient { .. } => return None,
            Light::Point { position, .. } => {
                if (position - origin).dot(normal) <= 0.0 {
                    return None;
                }
                Source::Point(position)
            }
            Light::Directional { direction, .. } => {
                if direction.dot(normal) >= 0.0 {
                    return None;
                }
                Source::Directional(direction)
            }
        };
        let e1 = normal.any_orthonormal_vector();
        let e2 = normal.cross(e1);
        let mut fp = Self {
            origin,
            normal,
            e1,
            e2,
            source,
            min: Vec2::ZERO,
            inv_cell: Vec2::ZERO,
            n: (0, 0),
            starts: Vec::new(),
            items: Vec::new(),
            always: Vec::new(),
            placed: Vec::new(),
            bounds: (Vec2::ZERO, Vec2::ZERO),
        };
        // Per object, its pieces' rectangles (or its box's, where a piece's
        // corner does not project; where that does not, it is always tested).
        let mut rects: Vec<(usize, Vec<(Vec2, Vec2)>)> = Vec::new();
        for &(i, b) in bounded {
            match fp.rects(b, &pieces(i)) {
                Some(r) => rects.push((i, r)),
                None => fp.always.push(i),
            }
        }
        if rects.is_empty() {
            return Some(fp);
        }
        let (lo, hi) = hull(rects.iter().flat_map(|(_, r)| r));
        // About four cells per object along each axis, at most 256.
        let per_axis = ((rects.len() as f32).sqrt() * 8.0).clamp(8.0, 256.0) as usize;
        let size = (hi - lo).max(Vec2::splat(1e-6));
        fp.min = lo;
        fp.n = (per_axis, per_axis);
        fp.inv_cell = Vec2::splat(per_axis as f32) / size;
        fp.bounds = (lo, hi);
        fp.placed = rects
            .into_iter()
            .map(|(object, r)| fp.placed(object, &r))
            .collect();
        // Count each cell's objects, turn the counts into starts, then place
        // the objects (each cell keeps `placed`'s order, the query order; an
        // object whose pieces reach a cell twice is placed there once).
        let cells = per_axis * per_axis;
        let mut last = vec![u32::MAX; cells];
        let mut fill = vec![0u32; cells + 1];
        for (n, p) in fp.placed.iter().enumerate() {
            Self::cells_once(fp.n.0, &p.spans, (&mut last, n as u32), |k| {
                fill[k + 1] += 1;
            });
        }
        for k in 0..cells {
            fill[k + 1] += fill[k];
        }
        fp.items = vec![0; fill[cells] as usize];
        fp.starts.clone_from(&fill);
        last.fill(u32::MAX);
        for (n, p) in fp.placed.iter().enumerate() {
            let items = &mut fp.items;
            let object = p.object;
            Self::cells_once(fp.n.0, &p.spans, (&mut last, n as u32), |k| {
                items[fill[k] as usize] = object;
                fill[k] += 1;
            });
        }
        Some(fp)
    }

    /// These footprints after the objects `moved` took the boxes `bounded`
    /// gives them now (every other object as before): the moved objects'
    /// cells found again, the others' kept. Each cell then lists the objects
    /// [`Self::new`] would list afresh, those that stayed in their order
    /// before and those that moved after them, in the order of `moved`
    /// (the query order may have changed; a shadow ray's answer does not
    /// depend on it). `None` where that asks for more: the grid's bounds
    /// changed, the objects differ, or a moved object is not binned before or
    /// after.
    pub(crate) fn with_moved(
        mut self,
        moved: &[usize],
        bounded: &[(usize, Aabb)],
        pieces: impl Fn(usize) -> Vec<Aabb>,
    ) -> Option<Self> {
        if self.placed.is_empty() || self.placed.len() + self.always.len() != bounded.len() {
            return None;
        }
        // Each object's place in `placed` (`u32::MAX`: always tested), and
        // its box now.
        let top = bounded.iter().map(|&(i, _)| i + 1).max().unwrap_or(0);
        let mut at = vec![u32::MAX; top];
        for (n, p) in self.placed.iter().enumerate() {
            *at.get_mut(p.object)? = n as u32;
        }
        let mut boxes = vec![None; top];
        for &(i, b) in bounded {
            boxes[i] = Some(b);
        }
        if self.placed.iter().any(|p| boxes[p.object].is_none())
            || self
                .always
                .iter()
                .any(|&i| boxes.get(i).is_none_or(Option::is_none))
        {
            return None;
        }
        // The moved objects' rectangles; the grid's bounds must stay.
        let mut is_moved = vec![false; top];
        let mut news = Vec::with_capacity(moved.len());
        for &i in moved {
            let n = *at.get(i)?;
            if n == u32::MAX {
                return None;
            }
            if !std::mem::replace(&mut is_moved[i], true) {
                let rects = self.rects((*boxes.get(i)?)?, &pieces(i))?;
                news.push((n, self.placed(i, &rects)));
            }
        }
        let mut rect: Vec<(Vec2, Vec2)> = self.placed.iter().map(|p| p.rect).collect();
        for (n, p) in &news {
            rect[*n as usize] = p.rect;
        }
        if hull(&rect) != self.bounds {
            return None;
        }
        // The cells the moved objects reach now, bucketed by cell; the cells
        // they reached before or reach now change.
        let cells = self.n.0 * self.n.1;
        let mut last = vec![u32::MAX; cells];
        let mut changed = vec![false; cells];
        let mut adds = Vec::new();
        for (n, p) in news {
            let was = &self.placed[n as usize].spans;
            Self::cells_once(self.n.0, was, (&mut last, 2 * n), |k| changed[k] = true);
            Self::cells_once(self.n.0, &p.spans, (&mut last, 2 * n + 1), |k| {
                changed[k] = true;
                adds.push((k, p.object));
            });
            self.placed[n as usize] = p;
        }
        let mut from = vec![0u32; cells + 1];
        for &(k, _) in &adds {
            from[k + 1] += 1;
        }
        for k in 0..cells {
            from[k + 1] += from[k];
        }
        let mut added = vec![0; adds.len()];
        for (k, i) in adds {
            added[from[k] as usize] = i;
            from[k] += 1;
        }
        // Each cell's list again: its objects that did not move, then those
        // that moved there; a run of cells that did not change is copied
        // whole.
        let mut starts = Vec::with_capacity(cells + 1);
        let mut items = Vec::with_capacity(self.items.len() + added.len());
        starts.push(0);
        let mut k = 0;
        while k < cells {
            if changed[k] {
                let a = if k == 0 { 0 } else { from[k - 1] as usize };
                items.extend(self.cell(k).iter().copied().filter(|&i| !is_moved[i]));
                items.extend_from_slice(&added[a..from[k] as usize]);
                starts.push(items.len() as u32);
                k += 1;
                continue;
            }
            let run = k + changed[k..].iter().position(|&c| c).unwrap_or(cells - k);
            let (s0, s1) = (self.starts[k] as usize, self.starts[run] as usize);
            let shift = items.len() as i64 - s0 as i64;
            items.extend_from_slice(&self.items[s0..s1]);
            starts.extend(
                self.starts[k + 1..=run]
                    .iter()
                    .map(|&v| (i64::from(v) + shift) as u32),
            );
            k = run;
        }
        (self.starts, self.items) = (starts, items);
        Some(self)
    }

    /// The rectangles of an object with box `b` and pieces `pieces` (empty:
    /// its box whole): its pieces', or its box's where a piece's corner does
    /// not project; `None` where its box's does not (it can shadow any
    /// point).
    fn rects(&self, b: Aabb, pieces: &[Aabb]) -> Option<Vec<(Vec2, Vec2)>> {
        let whole = self.rect(&b)?;
        let parts: Option<Vec<_>> = pieces.iter().map(|p| self.rect(p)).collect();
        Some(parts.filter(|p| !p.is_empty()).unwrap_or(vec![whole]))
    }

    /// Object `object` with rectangles `rects` placed in the grid.
    fn placed(&self, object: usize, rects: &[(Vec2, Vec2)]) -> Placed {
        Placed {
            object,
            rect: hull(rects),
            spans: rects
                .iter()
                .map(|&(a, b)| (self.cell_of(a), self.cell_of(b)))
                .collect(),
        }
    }

    /// Calls `visit` with each cell (row-major, rows of `row`) that `spans`
    /// reach, once: `last` holds per cell the stamp of the last visit, and
    /// this one's is `stamp`.
    fn cells_once(
        row: usize,
        spans: &[(Cell2, Cell2)],
        (last, stamp): (&mut [u32], u32),
        mut visit: impl FnMut(usize),
    ) {
        for &((x0, y0), (x1, y1)) in spans {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let k = y * row + x;
                    if last[k] != stamp {
                        last[k] = stamp;
                        visit(k);
                    }
                }
            }
        }
    }

    /// Plane coordinates of a point on (or projected onto) the plane.
    fn coords(&self, p: Vec3) -> Vec2 {
        let d = p - self.origin;
        Vec2::new(d.dot(self.e1), d.dot(self.e2))
    }

    /// Where the line from the light through `x` meets the plane; `None` when `x`
    /// is level with the light or beyond it.
    fn project(&self, x: Vec3) -> Option<Vec2> {
        match self.source {
            Source::Point(l) => {
                let down = (l - x).dot(self.normal);
                // A margin of a millionth of the light's height keeps the division
                // well away from 0.
                let height = (l - self.origin).dot(self.normal);
                if down <= 1e-6 * height {
                    return None;
                }
                let s = height / down;
                Some(self.coords(l + (x - l) * s))
            }
            Source::Directional(d) => {
                let s = -(x - self.origin).dot(self.normal) / d.dot(self.normal);
                Some(self.coords(x + d * s))
            }
        }
    }

    /// The rectangle holding the box's shadow, padded for the rounding of the
    /// projections (1e-4 of the coordinates' size, and 1e-5 m).
    fn rect(&self, b: &Aabb) -> Option<(Vec2, Vec2)> {
        let mut lo = Vec2::splat(f32::INFINITY);
        let mut hi = Vec2::splat(f32::NEG_INFINITY);
        for c in b.corners() {
            let p = self.project(c)?;
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let pad = 1e-5 + 1e-4 * lo.abs().max(hi.abs()).max_element();
        Some((lo - Vec2::splat(pad), hi + Vec2::splat(pad)))
    }

    /// The cell holding `p`, clamped to the grid.
    fn cell_of(&self, p: Vec2) -> (usize, usize) {
        let c = (p - self.min) * self.inv_cell;
        let clamp = |v: f32, n: usize| (v.max(0.0) as usize).min(n - 1);
        (clamp(c.x, self.n.0), clamp(c.y, self.n.1))
    }

    /// The objects that can block a shadow ray from `start` (a point on the lit
    /// side of the plane, or lifted off it): its cell's, and the ones that can
    /// shadow any point. `None` when `start` projects nowhere useful (behind the
    /// plane, or level with the light): test everything then.
    #[must_use]
    pub fn candidates(&self, start: Vec3) -> Option<(&[usize], &[usize])> {
        self.list(self.lookup(start))
    }

    /// Where `start`'s candidates are, as a value: equal lookups give the same
    /// lists, so a packet's lanes can share one.
    #[inline]
    #[must_use]
    pub(crate) fn lookup(&self, start: Vec3) -> Lookup {
        if (start - self.origin).dot(self.normal) < 0.0 {
            return Lookup::Unlit;
        }
        let Some(q) = self.project(start) else {
            return Lookup::Unlit;
        };
        if self.starts.is_empty() {
            return Lookup::Always;
        }
        let c = (q - self.min) * self.inv_cell;
        let inside = c.x >= 0.0 && c.y >= 0.0 && c.x < self.n.0 as f32 && c.y < self.n.1 as f32;
        if !inside {
            return Lookup::Always;
        }
        let (x, y) = self.cell_of(q);
        Lookup::Cell(y * self.n.0 + x)
    }

    /// What [`Self::lookup`] computes with, for the lanes' build of it.
    #[must_use]
    pub(crate) fn view(&self) -> GridView {
        let (light, scale) = match self.source {
            // project: height = (l - origin).dot(normal), the same every time.
            Source::Point(l) => (Ok(l), (l - self.origin).dot(self.normal)),
            // project: s = -(x - origin).dot(normal) / d.dot(normal).
            Source::Directional(d) => (Err(d), d.dot(self.normal)),
        };
        GridView {
            origin: self.origin,
            normal: self.normal,
            e1: self.e1,
            e2: self.e2,
            light,
            scale,
            min: self.min,
            inv_cell: self.inv_cell,
            n: self.n,
            gridded: !self.starts.is_empty(),
        }
    }

    /// The objects of cell `k`.
    #[inline]
    fn cell(&self, k: usize) -> &[usize] {
        &self.items[self.starts[k] as usize..self.starts[k + 1] as usize]
    }

    /// The lists a [`Self::lookup`] names.
    #[inline]
    #[must_use]
    pub(crate) fn list(&self, at: Lookup) -> Option<(&[usize], &[usize])> {
        match at {
            Lookup::Unlit => None,
            Lookup::Always => Some((&[], &self.always)),
            Lookup::Cell(k) => Some((self.cell(k), &self.always)),
        }
    }
}

/// The rectangle holding `rects`.
fn hull<'a>(rects: impl IntoIterator<Item = &'a (Vec2, Vec2)>) -> (Vec2, Vec2) {
    rects.into_iter().fold(
        (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
        |(lo, hi), &(a, b)| (lo.min(a), hi.max(b)),
    )
}

#[cfg(test)]
mod tests;
