//! A frame's scene made ready to trace: world-space bounds per object, one box
//! around everything but the planes, the culling structures built for it
//! (shadow footprints per plane and light, shadow casters per object, the
//! hierarchy), and the queries the shading needs: the nearest hit, and
//! whether anything lies between a point and a light (through the casters' or
//! the footprints' lists where shadow culling is on, or through every object,
//! the reference; a plane's own rays never test it).

use super::bvh::{Bvh, runs};
use super::casters::{Casters, clear_of, piece_boxes};
use super::geometry::{Aabb, Geom, Hit, Ray, bounds, hit_plane, hit_sphere};
use super::material::Phong;
use super::motion::{Cells, blocker_bits, moving_bits};
use super::scene::{Scene, Shape};
use super::shadow::Footprints;
use super::wide::{W, WIDE_AT_MOST, WideBoxes};
use glam::Vec3;
use rayon::prelude::*;
use std::cell::Cell;

/// The scene with its acceleration data.
#[derive(Debug, Clone)]
pub struct Prepared<'a> {
    /// The flat scene.
    pub scene: &'a Scene,
    geoms: Vec<Geom>,
    /// Per object: its material's Phong exponent made ready (`None`: matt).
    phong: Vec<Option<Phong>>,
    /// Per object: its box (planes: empty, never used).
    pub(crate) boxes: Vec<Aabb>,
    /// Per object: its slot in `footprints` if it is a plane.
    plane_slot: Vec<Option<usize>>,
    /// Per plane, per light: which objects can shadow which part of it; built
    /// only when shadow culling is turned on.
    footprints: Option<PerPlane>,
    /// Per object (`None` for planes): the objects that can block its shadow
    /// rays ([`Casters`]); built only when shadow culling is turned on.
    casters: Option<Vec<Option<Casters>>>,
    /// Over `bounded`; built only when the hierarchy is turned on.
    bvh: Option<Bvh>,
    /// `bounded`'s boxes eight at a time, for scans that skip nothing.
    pub(crate) wide: WideBoxes,
    pub(crate) bounded: Vec<(usize, Aabb)>,
    pub(crate) group: Aabb,
    pub(crate) planes: Vec<usize>,
    /// Per object, its bit among the moving objects ([`moving_bits`]).
    moving_bits: Vec<Cells>,
}

/// Per plane, per light: the footprints of the bounded objects.
pub(crate) type PerPlane = Vec<Vec<Option<Footprints>>>;

/// The shadow casters of the frame before, for the next one
/// ([`Prepared::with_shadow_culling_kept`]): per object, with the objects that
/// moved since and their boxes where they were and where they are. The scene
/// is the same but for those objects' shapes (its lights too).
#[derive(Debug)]
pub(crate) struct Kept {
    pub(crate) casters: Vec<Option<Casters>>,
    /// The footprints, where the frame before had them.
    pub(crate) footprints: Option<PerPlane>,
    pub(crate) moved: Vec<usize>,
    pub(crate) boxes: Vec<Aabb>,
}

impl<'a> Prepared<'a> {
    /// Bounds for every object of `scene`.
    #[must_use]
    pub fn new(scene: &'a Scene) -> Self {
        let mut bounded = Vec::new();
        let mut planes = Vec::new();
        let mut group = Aabb::EMPTY;
        for (i, o) in scene.objects.iter().enumerate() {
            match bounds(&o.shape) {
                Some(b) => {
                    group = group.union(b);
                    bounded.push((i, b));
                }
                None => planes.push(i),
            }
        }
        // Query order: runs of up to W objects close together, each a chunk
        // of `wide`, so that the scans' hull tests pass over whole runs.
        let runs: Vec<Vec<(usize, Aabb)>> =
            runs(&bounded.iter().map(|&(_, b)| b).collect::<Vec<_>>(), W)
                .into_iter()
                .map(|run| run.into_iter().map(|k| bounded[k]).collect())
                .collect();
        let bounded: Vec<(usize, Aabb)> = runs.iter().flatten().copied().collect();
        let mut plane_slot = vec![None; scene.objects.len()];
        for (slot, &i) in planes.iter().enumerate() {
            plane_slot[i] = Some(slot);
        }
        let mut boxes = vec![Aabb::EMPTY; scene.objects.len()];
        for &(i, b) in &bounded {
            boxes[i] = b;
        }
        Self {
            scene,
            boxes,
            plane_slot,
            footprints: None,
            casters: None,
            bvh: None,
            geoms: scene.objects.iter().map(|o| Geom::new(&o.shape)).collect(),
            phong: scene
                .objects
                .iter()
                .map(|o| o.material.specular.map(Phong::new))
                .collect(),
            wide: WideBoxes::in_runs(&runs),
            bounded,
            group,
            planes,
            moving_bits: moving_bits(&scene.objects),
        }
    }

    /// Object `i`'s bit among the moving objects (0 if it never moves).
    #[must_use]
    pub(crate) fn moving_bit(&self, i: usize) -> Cells {
        self.moving_bits[i]
    }

    /// What a shadow ray blocked first by object `i` notes
    /// ([`blocker_bits`]).
    #[must_use]
    pub(crate) fn blocker_bits(&self, i: usize) -> Cells {
        blocker_bits(&self.scene.objects[i], self.moving_bits[i])
    }

    /// Object `i`'s shape with what its hit test needs.
    pub(crate) fn geom(&self, i: usize) -> &Geom {
        &self.geoms[i]
    }

    /// Object `i`'s Phong exponent made ready (`None`: matt).
    pub(crate) fn phong(&self, i: usize) -> Option<Phong> {
        self.phong[i]
    }

    /// Distance and outward normal of the ray's hit on object `i`, if any.
    pub(crate) fn hit_object(&self, i: usize, ray: &Ray) -> Option<(f32, Vec3)> {
        match self.geoms[i] {
            Geom::Sphere { centre, radius } => {
                hit_sphere(ray, centre, radius).map(|t| (t, (ray.at(t) - centre) / radius))
            }
            Geom::Cylinder(c) => c.hit(ray),
            Geom::Plane { point, normal } => hit_plane(ray, point, normal).map(|t| (t, normal)),
        }
    }

    /// Every object in the order hit queries consider them (planes first, then the
    /// bounded ones), with its bounds (`None` for planes), so that ties in distance
    /// always resolve the same way.
    pub fn in_query_order(&self) -> impl Iterator<Item = (usize, Option<Aabb>)> + '_ {
        self.planes
            .iter()
            .map(|&i| (i, None))
            .chain(self.bounded.iter().map(|&(i, b)| (i, Some(b))))
    }

    /// The nearest hit before `t_max` among `candidates` (indices in query order),
    /// which must include every object the ray can hit: primary rays of a tile,
    /// or the mirror rays of plane `from`'s points there, which do not test it
    /// ([`Self::closest_from`]; `usize::MAX` for none).
    #[must_use]
    pub fn closest_among(
        &self,
        ray: &Ray,
        t_max: f32,
        (candidates, from): (&[usize], usize),
    ) -> Option<Hit> {
        let mut best: Option<(f32, usize, Vec3)> = None;
        let inv = ray.dir.recip();
        for &i in candidates.iter().filter(|&&i| i != from) {
            let limit = best.map_or(t_max, |b| b.0);
            // The box test first, as the full scan does: a hit that grazes a
            // shape's box can round either way, and must round the same way.
            let planar = self.plane_slot[i].is_some();
            if !planar && !self.boxes[i].hit(ray, inv, limit) {
                continue;
            }
            if let Some((t, n)) = self.hit_object(i, ray)
                && t < limit
            {
                best = Some((t, i, n));
            }
        }
        best.map(|(t, object, n)| Hit::facing(ray, t, object, n))
    }

    /// The nearest hit before `t_max`.
    #[must_use]
    pub fn closest(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.closest_from(None, ray, t_max)
    }

    /// [`Self::closest`] for the mirror ray of a point of object `from` that its
    /// ray met from `outside`. A plane's own rays never test it, in every
    /// renderer (the one rule of hits that the reference keeps too); a bounded
    /// object is tested again, in every renderer, even when the ray leaves it
    /// from outside: the mirror ray runs away from its surface, but a sphere's
    /// test can still round to a hit just past `T_MIN` when the direction is a
    /// little short of unit length (a reflection of a reflection), and every
    /// renderer must round the same way.
    #[must_use]
    pub fn closest_from(&self, from: Option<(usize, bool)>, ray: &Ray, t_max: f32) -> Option<Hit> {
        let own = self.own_plane(from.map(|f| f.0));
        if let Some(bvh) = &self.bvh {
            if self.bounded.len() > WIDE_AT_MOST {
                return self.closest_bvh(bvh, ray, t_max, own);
            }
            return self.closest_wide(ray, t_max, own);
        }
        let mut best: Option<(f32, usize, Vec3)> = None;
        let consider = |i: usize, best: &mut Option<(f32, usize, Vec3)>| {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some((t, n)) = self.hit_object(i, ray)
                && t < limit
            {
                *best = Some((t, i, n));
            }
        };
        for &i in self.planes.iter().filter(|&&i| i != own) {
            consider(i, &mut best);
        }
        let inv = ray.dir.recip();
        if self.group.hit(ray, inv, t_max) {
            for &(i, ref b) in &self.bounded {
                if b.hit(ray, inv, best.map_or(t_max, |x| x.0)) {
                    consider(i, &mut best);
                }
            }
        }
        best.map(|(t, object, n)| Hit::facing(ray, t, object, n))
    }

    /// [`Self::closest`] through the hierarchy: the same hit, since among equally
    /// near hits the one earliest in query order wins, as in the linear scan.
    /// Object `skip` is not tested.
    fn closest_bvh(&self, bvh: &Bvh, ray: &Ray, t_max: f32, skip: usize) -> Option<Hit> {
        // (t, place in query order, object, normal)
        let best: Cell<Option<(f32, usize, usize, Vec3)>> = Cell::new(None);
        let limit = || best.get().map_or(t_max, |b| b.0);
        let consider = |i: usize, key: usize| {
            if i == skip {
                return;
            }
            if let Some((t, n)) = self.hit_object(i, ray) {
                let better = match best.get() {
                    None => t < t_max,
                    Some((bt, bk, _, _)) => t < bt || (t == bt && key < bk),
                };
                if better {
                    best.set(Some((t, key, i, n)));
                }
            }
        };
        for (key, &i) in self.planes.iter().enumerate() {
            consider(i, key);
        }
        let inv = ray.dir.recip();
        if self.group.hit(ray, inv, t_max) {
            let first = self.planes.len();
            bvh.traverse(ray, inv, limit, |k| {
                let (i, b) = self.bounded[k];
                if b.hit(ray, inv, limit()) {
                    consider(i, first + k);
                }
                false
            });
        }
        best.get()
            .map(|(t, _, object, n)| Hit::facing(ray, t, object, n))
    }

    /// The linear scan of [`Prepared::closest`] (the planes, then the bounded
    /// objects in query order, each tested through its box with the nearest hit
    /// so far as the limit), eight boxes at a time: the same boxes pass, so it
    /// finds the same hit. Object `skip` is not tested.
    pub(crate) fn closest_wide(&self, ray: &Ray, t_max: f32, skip: usize) -> Option<Hit> {
        let best: Cell<Option<(f32, usize, Vec3)>> = Cell::new(None);
        let limit = || best.get().map_or(t_max, |b| b.0);
        let consider = |i: usize| {
            if i == skip {
                return;
            }
            if let Some((t, n)) = self.hit_object(i, ray)
                && t < limit()
            {
                best.set(Some((t, i, n)));
            }
        };
        for &i in &self.planes {
            consider(i);
        }
        let inv = ray.dir.recip();
        if self.group.hit(ray, inv, t_max) {
            self.wide.list().scan(ray, inv, limit, |i, b, chunk| {
                // A nearer hit found within this chunk: the box again, with it.
                let now = limit();
                if now >= chunk || b.hit(ray, inv, now) {
                    consider(i);
                }
                false
            });
        }
        best.get()
            .map(|(t, object, n)| Hit::facing(ray, t, object, n))
    }

    /// Turns the hierarchy on or off for secondary rays (off: each tests every
    /// object's box, the reference).
    #[must_use]
    pub fn with_bvh(mut self, on: bool) -> Self {
        self.bvh = on.then(|| Bvh::new(&self.bounded.iter().map(|(_, b)| *b).collect::<Vec<_>>()));
        self
    }

    /// The casters of object `i`'s shadow rays, when shadow culling is on and
    /// it is bounded.
    pub(crate) fn casters(&self, i: usize) -> Option<&Casters> {
        self.casters.as_ref()?.get(i)?.as_ref()
    }

    /// The footprints of the bounded objects on plane `plane` (an object index)
    /// from light `light`, when shadow culling is on.
    pub(crate) fn footprints(&self, plane: usize, light: usize) -> Option<&Footprints> {
        let slot = self.plane_slot.get(plane).copied().flatten()?;
        self.footprints.as_ref()?[slot].get(light)?.as_ref()
    }

    /// The planes of the scene (object indices, in query order).
    #[must_use]
    pub fn planes(&self) -> &[usize] {
        &self.planes
    }

    /// Turns shadow culling ([`Footprints`]) on or off (off: every shadow ray
    /// tests every object, the reference). The casters are found through the
    /// hierarchy where [`Self::with_bvh`] built it first.
    #[must_use]
    pub fn with_shadow_culling(self, on: bool) -> Self {
        self.with_shadow_culling_kept(on, None)
    }

    /// [`Self::with_shadow_culling`], keeping the casters of the frame before
    /// (`kept`) of the objects that did not move, as they are or patched
    /// ([`Casters::updated`]).
    #[must_use]
    pub(crate) fn with_shadow_culling_kept(mut self, on: bool, kept: Option<Kept>) -> Self {
        if !on {
            (self.footprints, self.casters) = (None, None);
            return self;
        }
        // The footprints and the casters are independent: built side by side.
        let (kept, old) = match kept {
            Some(mut k) => {
                let old = k.footprints.take().map(|f| (f, k.moved.clone()));
                (Some(k), old)
            }
            None => (None, None),
        };
        let this = &self;
        let (footprints, casters) =
            rayon::join(|| this.footprints_of(old), || this.casters_of(kept));
        (self.footprints, self.casters) = (Some(footprints), Some(casters));
        self
    }

    /// The casters, taken out for the next frame ([`Kept`]).
    pub(crate) fn take_casters(&mut self) -> Option<Vec<Option<Casters>>> {
        self.casters.take()
    }

    /// The footprints, taken out for the next frame ([`Kept`]).
    pub(crate) fn take_footprints(&mut self) -> Option<PerPlane> {
        self.footprints.take()
    }

    /// Per plane, per light, the footprints of the bounded objects: those of
    /// the frame before (`kept`, with the objects moved since) where the
    /// moved objects' cells can be found again in them
    /// ([`Footprints::with_moved`]), the others built afresh.
    fn footprints_of(&self, kept: Option<(PerPlane, Vec<usize>)>) -> PerPlane {
        let scene = self.scene;
        let pieces = |i: usize| piece_boxes(&scene.objects[i].shape);
        let (mut old, moved) = match kept {
            Some((f, moved)) if f.len() == self.planes.len() => (f, moved),
            _ => (Vec::new(), Vec::new()),
        };
        old.resize_with(self.planes.len(), Vec::new);
        self.planes
            .iter()
            .zip(old)
            .map(|(&i, old)| {
                let Shape::Plane { point, normal } = scene.objects[i].shape else {
                    unreachable!("only planes are unbounded")
                };
                let mut old = old.into_iter();
                scene
                    .lights
                    .iter()
                    .map(|l| {
                        old.next()
                            .flatten()
                            .and_then(|f| f.with_moved(&moved, &self.bounded, pieces))
                            .or_else(|| Footprints::new(point, normal, l, &self.bounded, pieces))
                    })
                    .collect()
            })
            .collect()
    }

    /// Per object, the objects that can block its shadow rays: those `kept`
    /// as they hold or patched ([`Casters::updated`]), found afresh for the
    /// moved objects.
    fn casters_of(&self, kept: Option<Kept>) -> Vec<Option<Casters>> {
        let scene = self.scene;
        let n = scene.objects.len();
        let mut moved = vec![false; n];
        let (old, moved_boxes) = match kept {
            Some(Kept {
                mut casters,
                moved: list,
                boxes,
                ..
            }) if casters.len() == n => {
                for &i in &list {
                    if let Some(c) = casters.get_mut(i) {
                        *c = None;
                        moved[i] = true;
                    }
                }
                (casters, boxes)
            }
            _ => ((0..n).map(|_| None).collect(), Vec::new()),
        };
        // The moved objects where they are, in query order.
        let now: Vec<(usize, Aabb)> = (self.bounded.iter().copied())
            .filter(|&(i, _)| moved[i])
            .collect();
        // Beyond a few dozen objects, find each piece's casters through a
        // hierarchy rather than by testing every object: the frame's own
        // where it has one (over the same boxes).
        let boxes: Vec<Aabb> = self.bounded.iter().map(|&(_, b)| b).collect();
        let own;
        let bvh = match &self.bvh {
            _ if boxes.len() <= 32 => None,
            Some(b) => Some(b),
            None => {
                own = Bvh::new(&boxes);
                Some(&own)
            }
        };
        // (Object by object over the pool: each takes a list per light and
        // piece, and a frame waits for them before it traces.)
        scene
            .objects
            .par_iter()
            .zip(old)
            .enumerate()
            .map(|(i, (o, old))| {
                let since = (&moved_boxes[..], &moved[..], &now[..]);
                if let Some(c) = old {
                    return Some(c.updated((i, &o.shape), &scene.lights, since));
                }
                let bvh = bvh.map(|b| (b, &boxes[..]));
                Casters::new((i, &o.shape), &scene.lights, &self.bounded, bvh)
            })
            .collect()
    }

    /// Whether anything lies on the ray before `t_max` (shadow rays: any hit ends them).
    #[must_use]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.blocker_by(usize::MAX, ray, t_max, None).is_some()
    }

    /// [`Self::occluded`] for a shadow ray towards light `light` from a point of
    /// object `from` (a plane's own rays do not test it): with shadow culling,
    /// from a plane only the objects whose shadow can fall there are tested.
    /// The same answer either way.
    #[must_use]
    pub fn occluded_towards(
        &self,
        from: (usize, bool),
        light: usize,
        ray: &Ray,
        t_max: f32,
    ) -> bool {
        self.blocker_towards(from, light, ray, t_max).is_some()
    }

    /// [`Self::occluded`] for a shadow ray from a point of object `from` that
    /// only a plane can block (its footprint cell holds no bounded object). A
    /// plane's own shadow rays do not test it ([`Self::closest_from`]).
    #[must_use]
    pub fn occluded_by_planes(&self, from: usize, ray: &Ray, t_max: f32) -> bool {
        self.blocking_plane(from, ray, t_max).is_some()
    }

    /// The object found blocking the shadow ray of [`Self::occluded_towards`]
    /// (the first of its tests to), if any: through the casters' list of
    /// `from` for `light` where there is one, else as [`Self::blocker_by`]
    /// finds it.
    #[must_use]
    pub(crate) fn blocker_towards(
        &self,
        (from, outside): (usize, bool),
        light: usize,
        ray: &Ray,
        t_max: f32,
    ) -> Option<usize> {
        if let Some(list) = self.casters.as_ref().and_then(|c| {
            let clear = outside && clear_of(self.geom(from), ray.origin);
            c.get(from)?.as_ref()?.at(light, ray.origin, clear)
        }) {
            if let Some(k) = self.blocking_plane(from, ray, t_max) {
                return Some(k);
            }
            let inv = ray.dir.recip();
            let mut found = None;
            list.scan(
                ray,
                inv,
                || t_max,
                |i, _, _| {
                    let b = self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max);
                    noted(&mut found, i, b)
                },
            );
            return found;
        }
        self.blocker_by(from, ray, t_max, self.footprints(from, light))
    }

    /// The first plane [`Self::occluded_by_planes`] finds blocking the ray.
    fn blocking_plane(&self, from: usize, ray: &Ray, t_max: f32) -> Option<usize> {
        let own = self.own_plane(Some(from));
        self.planes
            .iter()
            .copied()
            .find(|&i| i != own && self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max))
    }

    /// `from` where it is a plane, else `usize::MAX`: the plane a ray leaving
    /// `from` does not test.
    #[must_use]
    pub fn own_plane(&self, from: Option<usize>) -> usize {
        from.filter(|&i| self.plane_slot.get(i).is_some_and(Option::is_some))
            .unwrap_or(usize::MAX)
    }

    /// The first object found blocking the ray before `t_max` (any hit ends
    /// the search): the planes but `from`'s own, then, if the ray
    /// meets the box around them all, the bounded objects (each tested
    /// through its own box): all of them, or those `footprints` leaves for
    /// the ray's start.
    fn blocker_by(
        &self,
        from: usize,
        ray: &Ray,
        t_max: f32,
        footprints: Option<&Footprints>,
    ) -> Option<usize> {
        if let Some(k) = self.blocking_plane(from, ray, t_max) {
            return Some(k);
        }
        let blocks = |i: usize| self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max);
        let inv = ray.dir.recip();
        if !self.group.hit(ray, inv, t_max) {
            return None;
        }
        let test = |i: usize| self.boxes[i].hit(ray, inv, t_max) && blocks(i);
        match (
            footprints.and_then(|fp| fp.candidates(ray.origin)),
            &self.bvh,
        ) {
            (Some((cell, always)), _) => cell.iter().chain(always).copied().find(|&i| test(i)),
            (None, Some(_)) if self.bounded.len() <= WIDE_AT_MOST => {
                let mut found = None;
                self.wide.list().scan(
                    ray,
                    inv,
                    || t_max,
                    |i, _, _| noted(&mut found, i, blocks(i)),
                );
                found
            }
            (None, Some(bvh)) => {
                let mut found = None;
                bvh.traverse(
                    ray,
                    inv,
                    || t_max,
                    |k| {
                        let (i, b) = self.bounded[k];
                        noted(&mut found, i, b.hit(ray, inv, t_max) && blocks(i))
                    },
                );
                found
            }
            (None, None) => self
                .bounded
                .iter()
                .find(|&&(i, ref b)| b.hit(ray, inv, t_max) && blocks(i))
                .map(|&(i, _)| i),
        }
    }
}

/// A blocker scan's answer for object `i`, `blocks`, noting `i` in `found`
/// where it blocks (the scans stop at the first that does).
fn noted(found: &mut Option<usize>, i: usize, blocks: bool) -> bool {
    if blocks {
        *found = Some(i);
    }
    blocks
}

#[cfg(test)]
mod tests;
