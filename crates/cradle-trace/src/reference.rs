//! The reference: Whitted shading as the model defines it, ray by ray: the
//! ambient, Lambert diffuse and Phong specular terms per light, one shadow ray
//! per light (any hit ends it), mirror reflections to `max_depth` blended by
//! the material's `reflective` weight, cut by the bailout (`material`).
//!
//! It is the oracle every renderer is tested against, byte for byte: it knows
//! no tiles, no packets and no motion. The one shading function, [`shade`],
//! asks the rays it spawns of a [`Paths`]: the reference's own ([`Plain`])
//! scans the prepared scene; the scalar fast path (`shade`) answers from the
//! tiles' lists and notes what the incremental frames need, and must give the
//! same hits.

use super::geometry::{Hit, Ray, SURFACE_OFFSET};
use super::material::{BAILOUT, base_color, highlight, radiance_bound};
use super::prepared::Prepared;
use super::scene::Light;
use glam::Vec3;

/// How the rays that shading spawns find what they meet.
pub(crate) trait Paths {
    /// `ray`, traced at bounce `depth`, ends at `t_max` on object `met` (its
    /// hit), or meets nothing (`None`, infinity).
    fn traced(&mut self, p: &Prepared<'_>, ray: &Ray, end: (f32, Option<usize>), depth: u32);
    /// Whether the shadow ray `shadow` from the point of a hit (met at a
    /// bounce) towards a light, `from = (hit, light, depth)`, is blocked
    /// before `dist`.
    fn blocked(
        &mut self,
        p: &Prepared<'_>,
        shadow: &Ray,
        dist: f32,
        from: (Hit, usize, u32),
    ) -> bool;
    /// The nearest hit of the mirror ray `mirror` from the point of `hit` (met
    /// at bounce `depth`).
    fn mirror(&mut self, p: &Prepared<'_>, mirror: &Ray, hit: Hit, depth: u32) -> Option<Hit>;
}

/// The reference's paths: every query scans the prepared scene.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Plain;

impl Paths for Plain {
    #[inline]
    fn traced(&mut self, _: &Prepared<'_>, _: &Ray, _: (f32, Option<usize>), _: u32) {}

    #[inline]
    fn blocked(
        &mut self,
        p: &Prepared<'_>,
        shadow: &Ray,
        dist: f32,
        (hit, light, _): (Hit, usize, u32),
    ) -> bool {
        p.occluded_towards((hit.object, hit.outside), light, shadow, dist)
    }

    #[inline]
    fn mirror(&mut self, p: &Prepared<'_>, mirror: &Ray, hit: Hit, _: u32) -> Option<Hit> {
        p.closest_from(Some((hit.object, hit.outside)), mirror, f32::INFINITY)
    }
}

/// Radiance (linear RGB) along the camera ray `ray`, the reference's.
#[must_use]
pub fn trace(p: &Prepared<'_>, ray: &Ray) -> Vec3 {
    let hit = p.closest(ray, f32::INFINITY);
    shade(p, ray, hit, (0, 1.0), radiance_bound(p.scene), &mut Plain)
}

/// The radiance of `hit` (or the background for none) seen along `ray`, a
/// bounce at `depth` with path weight `weight`; `bound` from
/// [`radiance_bound`]; the spawned rays through `paths`.
#[inline]
pub(crate) fn shade(
    p: &Prepared<'_>,
    ray: &Ray,
    hit: Option<Hit>,
    (depth, weight): (u32, f32),
    bound: f32,
    paths: &mut impl Paths,
) -> Vec3 {
    let end = hit.map_or((f32::INFINITY, None), |h| (h.t, Some(h.object)));
    paths.traced(p, ray, end, depth);
    let Some(hit) = hit else {
        return p.scene.background;
    };
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
        if paths.blocked(p, &shadow, dist, (hit, li, depth)) {
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
        let h = paths.mirror(p, &mirror, hit, depth);
        let reflected = shade(p, &mirror, h, (depth + 1, weight * r), bound, paths);
        color = color * (1.0 - r) + reflected * r;
    }
    color
}
