//! Whitted shading: ambient + Lambert diffuse + Phong specular per light, one
//! shadow ray per light (any hit ends it), mirror reflections to `max_depth`
//! blended by the material's `reflective` weight.
//!
//! The reflection bailout is part of the model and applied identically everywhere:
//! a reflection is not traced when its weight (the product of `reflective` along the
//! path) times the brightest radiance the scene can produce times 12.92 (the
//! steepest slope of the sRGB curve) is below half an 8-bit step, 0.5/255. Its
//! contribution is then 0.

use super::geometry::Ray;
use super::motion::Motion;
use super::prepared::{Hit, Prepared};
use super::scene::{Light, Material, Shape};
use super::tiles::Tiles;
use glam::Vec3;

/// Secondary rays start this far (m) off the surface, along its normal.
pub(crate) const SURFACE_OFFSET: f32 = 2e-5;

/// Half an 8-bit step, divided by the steepest slope of the sRGB encoding.
pub(crate) const BAILOUT: f32 = 0.5 / 255.0 / 12.92;

/// The scene's brightest possible radiance per channel: every light at full
/// diffuse and full specular, or the background.
#[must_use]
pub fn radiance_bound(p: &Prepared<'_>) -> f32 {
    let lights: Vec3 = p
        .scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Ambient { color } => color,
            Light::Point { color, .. } | Light::Directional { color, .. } => 2.0 * color,
        })
        .sum();
    lights.max(p.scene.background).max_element()
}

/// `v.floor() as i64`, exactly (saturating, NaN to 0), without a call to libm's
/// `floorf` (the portable x86-64 build has no rounding instruction): truncate,
/// then step down where truncation went up.
#[inline]
#[must_use]
pub fn floor_i64(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `x` to the power `n` (at least 1) by repeated squaring, lowest bits first:
/// the same multiplications in the same order for a float and for lanes of
/// floats. (Plain loops, no closure: inlined into the AVX2 build of the lanes.)
#[expect(
    clippy::inline_always,
    reason = "inlined into the lanes' AVX2 build, which a call would leave"
)]
#[inline(always)]
pub(crate) fn powi<T: Copy + std::ops::Mul<Output = T>>(x: T, n: u32) -> T {
    let mut base = x;
    for _ in 0..n.trailing_zeros() {
        base = base * base;
    }
    let mut out = base;
    let mut rest = n.checked_shr(n.trailing_zeros() + 1).unwrap_or(0);
    while rest != 0 {
        base = base * base;
        if rest & 1 != 0 {
            out = out * base;
        }
        rest >>= 1;
    }
    out
}

/// A whole-number Phong exponent (1..=10000, as every asset's is), for
/// [`powi`]; `None` for the others, which take `powf`.
#[inline]
#[must_use]
pub(crate) fn whole(exponent: f32) -> Option<u32> {
    // A conversion and back, not `fract` (a libm call in the portable build).
    let n = exponent as u32;
    ((1..=10_000).contains(&n) && n as f32 == exponent).then_some(n)
}

/// A material's Phong exponent made ready for [`highlight`]: whole (by
/// [`powi`]) or not, and the least `facing` whose highlight is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Phong {
    /// The exponent.
    pub(crate) exponent: f32,
    /// It as a whole number, where it is one ([`whole`]).
    pub(crate) whole: Option<u32>,
    /// `(2^-100)^(1 / exponent)`: below it the highlight, under 2^-100, is 0.
    pub(crate) least: f32,
}

impl Phong {
    /// Exponent `exponent` made ready.
    #[must_use]
    pub(crate) fn new(exponent: f32) -> Self {
        let least = (2f64.powi(-100)).powf(1.0 / f64::from(exponent)) as f32;
        Self {
            exponent,
            whole: whole(exponent),
            least,
        }
    }
}

/// The Phong highlight `facing^exponent`: by [`powi`] for a whole-number
/// exponent (vectorizable, the same bits in lanes), else `powf`; 0 where
/// `facing` is below `least` (the highlight would be below 2^-100, far under
/// half an ulp of any lit colour). That cut keeps subnormal numbers out of the
/// squarings: an operation on them takes a slow microcode path on x86 CPUs.
#[inline]
#[must_use]
pub(crate) fn highlight(facing: f32, phong: Phong) -> f32 {
    if facing < phong.least {
        return 0.0;
    }
    match phong.whole {
        Some(n) => powi(facing, n),
        None => facing.powf(phong.exponent),
    }
}

/// The surface colour at `point`: plain, or a checker on the x-z grid.
pub(crate) fn base_color(m: &Material, point: Vec3) -> Vec3 {
    match m.checker {
        Some((other, size)) => {
            let cell = floor_i64(point.x / size) + floor_i64(point.z / size);
            if cell.rem_euclid(2) == 0 {
                m.color
            } else {
                other
            }
        }
        None => m.color,
    }
}

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
