//! The scalar fast path: the reference's shading (`reference::shade`) with
//! its rays answered from the tiles' lists where a primary pixel has them (a
//! plane's mirror ray tests only its tile's mirror candidates; shadow rays the
//! casters' or footprints' lists, `Prepared::occluded_towards`), and each ray's segment noted for incremental
//! frames through a [`Record`] (nothing at all for [`NoRecord`]). It gives the
//! reference's hits, so the reference's bytes (tested).

use super::geometry::{Hit, Ray};
use super::motion::Record;
use super::prepared::Prepared;
use super::reference::{Paths, shade};
use super::scene::Shape;
use super::tiles::Tiles;
use glam::Vec3;

/// The fast path's [`Paths`]: the primary pixel's tile, if any (its lists
/// serve the rays from the primary hit), and the recorder of segments.
struct Tiled<'t, R> {
    tile: Option<(&'t Tiles, u32, u32)>,
    record: &'t mut R,
    /// Whether the next ray traced is free: a mirror ray from where a camera
    /// ray met a plane (camera rays are free by their depth).
    next_free: bool,
}

impl<R: Record> Tiled<'_, R> {
    /// Whether the rays from the point of `hit`, met at `depth`, are free: it
    /// is where a camera ray met a plane.
    #[inline]
    fn from_eye_on_plane(p: &Prepared<'_>, hit: Hit, depth: u32) -> bool {
        depth == 0 && matches!(p.scene.objects[hit.object].shape, Shape::Plane { .. })
    }

    /// The tile, for the rays from a primary hit (`depth` 0).
    #[inline]
    fn tile(&self, depth: u32) -> Option<(&Tiles, u32, u32)> {
        self.tile.filter(|_| depth == 0)
    }
}

impl<R: Record> Paths for Tiled<'_, R> {
    #[inline]
    fn traced(
        &mut self,
        p: &Prepared<'_>,
        ray: &Ray,
        (t_max, met): (f32, Option<usize>),
        depth: u32,
    ) {
        let free = std::mem::take(&mut self.next_free) || depth == 0;
        if self.record.tracks() {
            self.record.segment(ray, t_max, free);
            if let Some(o) = met {
                self.record.hit(p.moving_bit(o));
            }
        }
    }

    #[inline]
    fn blocked(
        &mut self,
        p: &Prepared<'_>,
        shadow: &Ray,
        dist: f32,
        (hit, light, depth): (Hit, usize, u32),
    ) -> bool {
        let from = (hit.object, hit.outside);
        if !self.record.tracks() {
            return p.occluded_towards(from, light, shadow, dist);
        }
        let free = Self::from_eye_on_plane(p, hit, depth);
        self.record.segment(shadow, dist, free);
        let Some(k) = p.blocker_towards(from, light, shadow, dist) else {
            return false;
        };
        // A blocked shadow ray stays blocked whatever comes near it, but for
        // its blocker moving away (a still one never does).
        self.record.blocked(p.blocker_bits(k));
        true
    }

    #[inline]
    fn mirror(&mut self, p: &Prepared<'_>, mirror: &Ray, hit: Hit, depth: u32) -> Option<Hit> {
        self.next_free = Self::from_eye_on_plane(p, hit, depth);
        match self
            .tile(depth)
            .and_then(|(t, x, y)| t.mirror_at(hit.object, x, y))
        {
            Some(c) => p.closest_among(mirror, f32::INFINITY, (c, hit.object)),
            None => p.closest_from(Some((hit.object, hit.outside)), mirror, f32::INFINITY),
        }
    }
}

/// The radiance of a camera ray (`depth` 0), by the fast path without tiles:
/// noting its segments in `record`.
#[must_use]
pub(crate) fn trace(p: &Prepared<'_>, ray: &Ray, bound: f32, record: &mut impl Record) -> Vec3 {
    let hit = p.closest(ray, f32::INFINITY);
    shade_from(p, ray, hit, (0, 1.0), bound, (record, false))
}

/// The radiance of the primary ray of pixel `(x, y)`: it tests only its
/// tile's candidates, and a plane's mirror ray only the tile's mirror
/// candidates; its segments noted in `record`.
#[must_use]
pub(crate) fn trace_primary(
    p: &Prepared<'_>,
    ray: &Ray,
    (tiles, x, y): (&Tiles, u32, u32),
    bound: f32,
    record: &mut impl Record,
) -> Vec3 {
    let hit = p.closest_among(ray, f32::INFINITY, (tiles.at(x, y), usize::MAX));
    let mut paths = Tiled {
        tile: Some((tiles, x, y)),
        record,
        next_free: false,
    };
    shade(p, ray, hit, (0, 1.0), bound, &mut paths)
}

/// The radiance of `hit` (or the background) seen along `ray`, a bounce at
/// `depth` with path weight `weight`, without tiles; its segments noted in
/// `record`, the first one free where `free` says so (a packet's lane
/// handing a ray on).
pub(crate) fn shade_from<R: Record>(
    p: &Prepared<'_>,
    ray: &Ray,
    hit: Option<Hit>,
    (depth, weight): (u32, f32),
    bound: f32,
    (record, free): (&mut R, bool),
) -> Vec3 {
    let mut paths = Tiled {
        tile: None,
        record,
        next_free: free,
    };
    shade(p, ray, hit, (depth, weight), bound, &mut paths)
}
