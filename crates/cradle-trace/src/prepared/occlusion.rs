//! Shadow rays' queries on a frame's [`Prepared`] scene: whether anything
//! lies between a point and a light (any hit), through the casters' or the
//! footprints' lists where shadow culling is on, or through every object (the
//! reference). A plane's own shadow rays do not test it (`closest_from`).

use super::Prepared;
use crate::casters::clear_of;
use crate::geometry::Ray;
use crate::shadow::Footprints;
use crate::wide::WIDE_AT_MOST;

impl Prepared<'_> {
    /// Whether anything lies on the ray before `t_max` (shadow rays: any hit ends them).
    #[must_use]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.occluded_by(usize::MAX, ray, t_max, None)
    }

    /// [`Self::occluded`] for a shadow ray towards light `light` from a point of
    /// object `from` (a plane's own rays do not test it): with shadow culling,
    /// from a plane only the objects whose shadow can fall there are tested.
    /// The same answer either way.
    #[must_use]
    pub fn occluded_towards(
        &self,
        (from, outside): (usize, bool),
        light: usize,
        ray: &Ray,
        t_max: f32,
    ) -> bool {
        if let Some(list) = self.casters.as_ref().and_then(|c| {
            let clear = outside && clear_of(self.geom(from), ray.origin);
            c.get(from)?.as_ref()?.at(light, ray.origin, clear)
        }) {
            if self.occluded_by_planes(from, ray, t_max) {
                return true;
            }
            let inv = ray.dir.recip();
            return list.scan(
                ray,
                inv,
                || t_max,
                |i, _, _| self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max),
            );
        }
        self.occluded_by(from, ray, t_max, self.footprints(from, light))
    }

    /// [`Self::occluded`] for a shadow ray from a point of object `from` that
    /// only a plane can block (its start is where no bounded object casts a
    /// shadow: [`Footprints::region_clear`]). A plane's own shadow rays do not
    /// test it ([`Self::closest_from`]).
    #[must_use]
    pub fn occluded_by_planes(&self, from: usize, ray: &Ray, t_max: f32) -> bool {
        let own = self.own_plane(Some(from));
        self.planes
            .iter()
            .any(|&i| i != own && self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max))
    }

    /// `from` where it is a plane, else `usize::MAX`: the plane a ray leaving
    /// `from` does not test.
    #[must_use]
    pub fn own_plane(&self, from: Option<usize>) -> usize {
        from.filter(|&i| self.plane_slot.get(i).is_some_and(Option::is_some))
            .unwrap_or(usize::MAX)
    }

    /// Any hit before `t_max` on a plane (but `from`'s own), or, inside the box
    /// around them all, on a bounded object (each tested through its own box):
    /// all of them, or those `footprints` leaves for the ray's start.
    fn occluded_by(
        &self,
        from: usize,
        ray: &Ray,
        t_max: f32,
        footprints: Option<&Footprints>,
    ) -> bool {
        if self.occluded_by_planes(from, ray, t_max) {
            return true;
        }
        let blocks = |i: usize| self.hit_object(i, ray).is_some_and(|(t, _)| t < t_max);
        let inv = ray.dir.recip();
        if !self.group.hit(ray, inv, t_max) {
            return false;
        }
        let test = |i: usize| self.boxes[i].hit(ray, inv, t_max) && blocks(i);
        match (
            footprints.and_then(|fp| fp.candidates(ray.origin)),
            &self.bvh,
        ) {
            (Some((cell, always)), _) => cell.iter().chain(always).any(|&i| test(i)),
            (None, Some(_)) if self.bounded.len() <= WIDE_AT_MOST => {
                self.wide
                    .list()
                    .scan(ray, inv, || t_max, |i, _, _| blocks(i))
            }
            (None, Some(bvh)) => bvh.traverse(
                ray,
                inv,
                || t_max,
                |k| {
                    let (i, b) = self.bounded[k];
                    b.hit(ray, inv, t_max) && blocks(i)
                },
            ),
            (None, None) => self
                .bounded
                .iter()
                .any(|&(i, ref b)| b.hit(ray, inv, t_max) && blocks(i)),
        }
    }
}

#[cfg(test)]
mod tests;
