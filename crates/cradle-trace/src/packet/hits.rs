//! The hit tests over a packet's lanes, in lane build `S`: boxes, spheres,
//! cylinders and planes, each lane computing the scalar test's operations in
//! the scalar order (`Aabb::hit`, `hit_sphere`, `Cylinder::hit`, `hit_plane`;
//! glam's dot is `(x*x' + y*y') + z*z'`, its `min` and `max` are `a < b ? a :
//! b` and `a > b ? a : b`), so every lane's answer is the scalar one. The
//! queries that use them (nearest hits, shadow rays) are `Scan`'s.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::vec::select3;
use super::{L3, splat3};
use crate::geometry::Geom;
use crate::geometry::{Aabb, Cylinder, T_MIN};
use crate::simd::Simd;
use glam::Vec3;

/// Every lane (bits).
const LANES_ALL: u8 = 0xFF;

/// `1 / v` per component (`Vec3::recip`).
#[inline(always)]
pub(super) fn recip<S: Simd>(s: S, v: &L3<S::F>) -> L3<S::F> {
    let one = s.splat(1.0);
    L3 {
        x: one / v.x,
        y: one / v.y,
        z: one / v.z,
    }
}

/// The entry and exit of one slab of a box: `(lo - o) * inv`, `(hi - o) *
/// inv`, the smaller and the larger. (A function, not a closure: a closure left
/// as a call is not compiled for AVX2.)
#[inline(always)]
fn slab<S: Simd>(s: S, (lo, hi): (f32, f32), o: S::F, inv: S::F) -> (S::F, S::F) {
    let t1 = (s.splat(lo) - o) * inv;
    let t2 = (s.splat(hi) - o) * inv;
    (S::min(t1, t2), S::max(t1, t2))
}

/// `Aabb::hit` per lane (origins `o`, inverse directions `inv`): glam's vector
/// `min`/`max`, `max_element` is `max(x, max(y, z))`, then `f32::max(T_MIN)` and
/// `f32::min(t_max)`, which pick the same as `a > b ? a : b` and `a < b ? a : b`
/// here (`T_MIN` and `t_max` are never NaN).
#[inline(always)]
pub(super) fn box8<S: Simd>(s: S, b: &Aabb, o: &L3<S::F>, inv: &L3<S::F>, t_max: S::F) -> S::M {
    let (lx, hx) = slab(s, (b.min.x, b.max.x), o.x, inv.x);
    let (ly, hy) = slab(s, (b.min.y, b.max.y), o.y, inv.y);
    let (lz, hz) = slab(s, (b.min.z, b.max.z), o.z, inv.z);
    let near = S::max(S::max(lx, S::max(ly, lz)), s.splat(T_MIN));
    let far = S::min(S::min(hx, S::min(hy, hz)), t_max);
    S::le(near, far)
}

/// `hit_sphere`'s nearest hit per lane (+inf for none): `oc`, `b =
/// oc.dot(dir)`, `f = oc - dir * b`, `disc = r*r - |f|^2`, the first of `-b -
/// s`, `-b + s` beyond `T_MIN`.
#[inline(always)]
fn sphere<S: Simd>(s: S, (centre, radius): (glam::Vec3, f32), o: &L3<S::F>, d: &L3<S::F>) -> S::F {
    let oc = o.sub(&splat3(s, centre));
    let b = oc.dot(d);
    let f = oc.sub(&d.scale(b));
    let disc = s.splat(radius * radius) - f.dot(&f);
    let root = S::sqrt(disc);
    let (t0, t1) = (-b - root, -b + root);
    let t_min = s.splat(T_MIN);
    let first = S::select(S::lt(t_min, t0), t0, t1);
    let hit = !S::lt(disc, s.splat(0.0)) & S::lt(t_min, first);
    S::select(hit, first, s.splat(f32::INFINITY))
}

/// A ray's parts along and across a cylinder's axis `u` (from end `a`):
/// `du = dir.dot(u)`, `ou = (origin - a).dot(u)`, `dp = dir - u * du` and `op =
/// (origin - a) - u * ou`, as `Cylinder::hit` computes them.
struct Across<F> {
    du: F,
    ou: F,
    dp: L3<F>,
    op: L3<F>,
}

#[inline(always)]
fn across<S: Simd>(s: S, (a, u): (Vec3, Vec3), o: &L3<S::F>, d: &L3<S::F>) -> Across<S::F> {
    let uu = splat3(s, u);
    let ao = o.sub(&splat3(s, a));
    let (du, ou) = (d.dot(&uu), ao.dot(&uu));
    // dir - u * du, ao - u * ou: (u.x * du) is (du * u.x), the same product.
    Across {
        du,
        ou,
        dp: d.sub(&uu.scale(du)),
        op: ao.sub(&uu.scale(ou)),
    }
}

/// `Cylinder::hit`'s nearest hit per lane (+inf for none) and which part it
/// lies on: 0 the body, 1 and 2 the caps at `a` and `b`. "No hit yet" is +inf,
/// which takes and drops the same roots as the scalar `None` (a root of +inf
/// could never be nearer than another).
///
/// Only the lanes of `want` (bits) need be right, and of those only the ones
/// whose hit is not already below `enough`: a lane whose body hit lies below
/// it keeps that `t` without the caps, which could only lower it (an any-hit
/// query passes its `t_max`; a nearest-hit one -inf, so every lane looks at
/// the caps). Where every wanted lane misses the infinite cylinder, as the
/// scalar test returns early, the roots and caps are skipped.
#[inline(always)]
fn cylinder<S: Simd>(
    s: S,
    c: &Cylinder,
    (o, d): (&L3<S::F>, &L3<S::F>),
    (want, enough): (u8, S::F),
) -> (S::F, S::F) {
    let (a, b, u, len, radius) = c.parts();
    let k = |v: f32| s.splat(v);
    let Across { du, ou, dp, op } = across(s, (a, u), o, d);
    let (qa, qb) = (dp.dot(&dp), op.dot(&dp));
    let r2 = k(radius * radius);
    let t_min = k(T_MIN);
    let body = S::lt(k(1e-12), qa);
    let f = op.sub(&dp.scale(qb / qa));
    let disc = qa * (r2 - f.dot(&f));
    let miss_all = body & S::lt(disc, k(0.0));
    // Missing the infinite cylinder misses the caps too (`Cylinder::hit`).
    if S::bits(miss_all) & want == want {
        return (k(f32::INFINITY), k(0.0));
    }
    let root = S::sqrt(disc);
    let (mut best, mut part) = (k(f32::INFINITY), k(0.0));
    for root in [-qb - root, -qb + root] {
        let t = root / qa;
        let along = ou + t * du;
        let inside = S::le(k(0.0), along) & S::le(along, k(len));
        let take = body & inside & S::lt(t_min, t) & S::lt(t, best);
        best = S::select(take, t, best);
    }
    // Every wanted lane blocked before the caps: they could only come nearer.
    if S::bits(S::lt(best, enough) | miss_all) & want == want {
        return (S::select(miss_all, k(f32::INFINITY), best), part);
    }
    // |du| > 1e-12
    let caps = S::lt(k(1e-12), S::abs(du));
    for (end, along, cap) in [(a, 0.0, 1.0), (b, len, 2.0)] {
        let t = (k(along) - ou) / du;
        // ray.at(t) - end: (origin + dir * t) - end.
        let p = o.add(&d.scale(t)).sub(&splat3(s, end));
        let take = caps & S::le(p.dot(&p), r2) & S::lt(t_min, t) & S::lt(t, best);
        best = S::select(take, t, best);
        part = S::select(take, k(cap), part);
    }
    (S::select(miss_all, k(f32::INFINITY), best), part)
}

/// Per lane, where object `g` first meets the ray beyond `T_MIN` (+inf for
/// none) and its outward normal there: `Prepared::hit_object`.
#[inline(always)]
pub(super) fn hit_normal<S: Simd>(s: S, g: &Geom, o: &L3<S::F>, d: &L3<S::F>) -> (S::F, L3<S::F>) {
    if let Geom::Plane { point, normal } = *g {
        return (plane8(s, (point, normal), o, d), splat3(s, normal));
    }
    let (t, part) = hit_part(s, g, (o, d), LANES_ALL);
    (t, normal_at(s, g, (o, d), (t, part)))
}

/// Per lane, object `g`'s outward normal where the ray meets it at `t`, on
/// part `part` (a cylinder's, [`hit_part`]), as `Prepared::hit_object` gives
/// it: a sphere's `(ray.at(t) - centre) / radius`, a cylinder's body `(o_perp +
/// d_perp * t).normalize()` or a cap's `-u` or `u`, a plane's normal.
#[inline(always)]
pub(super) fn normal_at<S: Simd>(
    s: S,
    g: &Geom,
    (o, d): (&L3<S::F>, &L3<S::F>),
    (t, part): (S::F, S::F),
) -> L3<S::F> {
    match *g {
        Geom::Sphere { centre, radius } => {
            let at = o.add(&d.scale(t));
            at.sub(&splat3(s, centre)).div(s.splat(radius))
        }
        Geom::Cylinder(ref c) => {
            let (a, _, u, _, _) = c.parts();
            let Across { dp, op, .. } = across(s, (a, u), o, d);
            let v = op.add(&dp.scale(t));
            // normalize: v * (1 / sqrt(v.dot(v)))
            let body = v.scale(s.splat(1.0) / S::sqrt(v.dot(&v)));
            let u = splat3(s, u);
            let (cap_a, cap_b) = (S::lt(s.splat(0.5), part), S::lt(s.splat(1.5), part));
            let n = select3::<S>(cap_a, &u.neg(), &body);
            select3::<S>(cap_b, &u, &n)
        }
        Geom::Plane { normal, .. } => splat3(s, normal),
    }
}

/// `hit_plane` per lane (+inf for a miss): `denom = dir.dot(normal)`, a miss
/// below 1e-9 in magnitude; `t = (point - origin).dot(normal) / denom`, a hit
/// beyond `T_MIN`.
#[inline(always)]
pub(super) fn plane8<S: Simd>(
    s: S,
    (point, normal): (Vec3, Vec3),
    o: &L3<S::F>,
    d: &L3<S::F>,
) -> S::F {
    let nv = splat3(s, normal);
    let denom = d.dot(&nv);
    let t = splat3(s, point).sub(o).dot(&nv) / denom;
    let hit = S::le(s.splat(1e-9), S::abs(denom)) & S::lt(s.splat(T_MIN), t);
    S::select(hit, t, s.splat(f32::INFINITY))
}

/// Per lane, where bounded object `g` first meets the ray beyond `T_MIN` (the
/// `t` of `hit_sphere` or `Cylinder::hit`), or +inf (planes are tested
/// elsewhere: +inf here), and the part of the object met, for [`normal_at`]:
/// a cylinder's body (0) or caps (1 and 2); 0 for a sphere. Right in the
/// lanes of `want` (bits); the others' answers may differ.
#[inline(always)]
pub(super) fn hit_part<S: Simd>(
    s: S,
    g: &Geom,
    (o, d): (&L3<S::F>, &L3<S::F>),
    want: u8,
) -> (S::F, S::F) {
    match *g {
        Geom::Sphere { centre, radius } => (sphere(s, (centre, radius), o, d), s.splat(0.0)),
        Geom::Cylinder(ref c) => cylinder(s, c, (o, d), (want, s.splat(f32::NEG_INFINITY))),
        Geom::Plane { .. } => (s.splat(f32::INFINITY), s.splat(0.0)),
    }
}

/// Per lane of `want` (bits), whether bounded object `g` meets the ray before
/// `t_max`; the other lanes' answers may differ.
#[inline(always)]
pub(super) fn blocks8<S: Simd>(
    s: S,
    g: &Geom,
    (o, d): (&L3<S::F>, &L3<S::F>),
    t_max: S::F,
    want: u8,
) -> S::M {
    let t = match *g {
        Geom::Cylinder(ref c) => cylinder(s, c, (o, d), (want, t_max)).0,
        _ => hit_part(s, g, (o, d), want).0,
    };
    S::lt(t, t_max)
}
