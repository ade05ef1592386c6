//! Whitted shading: ambient + Lambert diffuse + Phong specular per light, one
//! shadow ray per light (any hit ends it), mirror reflections to `max_depth`
//! blended by the material's `reflective` weight.
//! The shading model's pieces are in `material`.

use super::geometry::{Hit, Ray, SURFACE_OFFSET};
use super::material::{BAILOUT, base_color, highlight};
use super::motion::Motion;
use super::prepared::Prepared;
use super::scene::{Light, Shape};
use super::tiles::Tiles;
use glam::Vec3;

/// Radiance (linear RGB) along `ray`; `depth` bounces so far, `weight` the product
/// of reflective factors so far, `bound` from [`radiance_bound`]; `motion` notes
/// whether the rays entered the moving objects' box.
#[must_use]
pub fn trace(
    p: &Prepared<'_>,
    ray: &Ray,
    depth: u32,
    weight: f32,
    bound: f32,
    motion: &mut Motion,
) -> Vec3 {
    let hit = p.closest(ray, f32::INFINITY);
    shade(p, ray, hit, depth, weight, bound, motion, None)
}

/// [`trace`] for the primary ray of pixel `(x, y)`: it tests only its tile's
/// candidates, and a plane's mirror ray only the tile's mirror candidates.
#[must_use]
pub fn trace_primary(
    p: &Prepared<'_>,
    ray: &Ray,
    (tiles, x, y): (&Tiles, u32, u32),
    bound: f32,
    motion: &mut Motion,
) -> Vec3 {
    let hit = p.closest_among(ray, f32::INFINITY, (tiles.at(x, y), usize::MAX));
    shade(p, ray, hit, 0, 1.0, bound, motion, Some((tiles, x, y)))
}

/// The radiance of `hit` (or the background for none) seen along `ray`; `tile`
/// is the primary ray's pixel, whose tile lists the candidates of mirror rays.
#[expect(
    clippy::too_many_arguments,
    reason = "the recursion's state, passed down"
)]
pub(crate) fn shade(
    p: &Prepared<'_>,
    ray: &Ray,
    hit: Option<Hit>,
    depth: u32,
    weight: f32,
    bound: f32,
    motion: &mut Motion,
    tile: Option<(&Tiles, u32, u32)>,
) -> Vec3 {
    // A camera ray's segment is free (`Motion::free`), and so are the shadow
    // and mirror rays from where it met a plane.
    motion.free |= depth == 0;
    motion.segment(ray, hit.map_or(f32::INFINITY, |h| h.t));
    let Some(hit) = hit else {
        return p.scene.background;
    };
    let from_eye_on_plane =
        depth == 0 && matches!(p.scene.objects[hit.object].shape, Shape::Plane { .. });
    let m = &p.scene.objects[hit.object].material;
    let point = ray.at(hit.t);
    let n = hit.normal;
    let start = point + n * SURFACE_OFFSET;
    let base = base_color(m, point);
    let mut color = Vec3::ZERO;
    for (li, light) in p.scene.lights.iter().enumerate() {
        let (to_light, dist, light_color) = match *light {
            Light::Ambient { color: c } => {
                color += base * c;
                continue;
            }
            Light::Point { position, color: c } => {
                let d = position - point;
                let len = d.length();
                (d / len, len, c)
            }
            Light::Directional {
                direction,
                color: c,
            } => (-direction, f32::INFINITY, c),
        };
        let lambert = n.dot(to_light);
        if lambert <= 0.0 {
            continue;
        }
        let shadow = Ray {
            origin: start,
            dir: to_light,
        };
        motion.free = from_eye_on_plane;
        if blocked(p, &shadow, dist, (hit, li), tile, motion) {
            continue;
        }
        color += base * light_color * lambert;
        if let Some(phong) = p.phong(hit.object) {
            let mirrored = 2.0 * lambert * n - to_light;
            let facing = mirrored.dot(-ray.dir);
            if facing > 0.0 {
                color += light_color * highlight(facing, phong);
            }
        }
    }
    let r = m.reflective;
    if r > 0.0 && depth < p.scene.max_depth && weight * r * bound >= BAILOUT {
        let dir = ray.dir - 2.0 * ray.dir.dot(n) * n;
        let mirror = Ray { origin: start, dir };
        motion.free = from_eye_on_plane;
        let reflected = reflect(
            p,
            &mirror,
            (hit.object, hit.outside),
            depth + 1,
            weight * r,
            bound,
            motion,
            tile,
        );
        color = color * (1.0 - r) + reflected * r;
    }
    color
}

/// Whether the shadow ray from a point of `hit` towards light `li` is blocked
/// before `dist`: a tile no caster can shadow (`tile`) tests only the planes.
pub(crate) fn blocked(
    p: &Prepared<'_>,
    shadow: &Ray,
    dist: f32,
    (hit, li): (Hit, usize),
    tile: Option<(&Tiles, u32, u32)>,
    motion: &mut Motion,
) -> bool {
    motion.segment(shadow, dist);
    if tile.is_some_and(|(t, x, y)| t.shadow_clear(p, (hit.object, li), x, y)) {
        p.occluded_by_planes(hit.object, shadow, dist)
    } else {
        p.occluded_towards((hit.object, hit.outside), li, shadow, dist)
    }
}

/// The radiance the mirror ray `mirror` from `object` (met from outside or
/// not) brings back, traced as a bounce at `depth` with path weight `weight`: a
/// plane's mirror ray from a primary pixel (`tile`) tests only its tile's
/// mirror candidates.
#[expect(
    clippy::too_many_arguments,
    reason = "the recursion's state, passed down"
)]
pub(crate) fn reflect(
    p: &Prepared<'_>,
    mirror: &Ray,
    (object, outside): (usize, bool),
    depth: u32,
    weight: f32,
    bound: f32,
    motion: &mut Motion,
    tile: Option<(&Tiles, u32, u32)>,
) -> Vec3 {
    let h = match tile.and_then(|(t, x, y)| t.mirror_at(object, x, y)) {
        Some(c) => p.closest_among(mirror, f32::INFINITY, (c, object)),
        None => p.closest_from(Some((object, outside)), mirror, f32::INFINITY),
    };
    shade(p, mirror, h, depth, weight, bound, motion, None)
}
