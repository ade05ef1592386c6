//! What a packet's lanes meet on the way, all lanes at once in lane build `S`:
//! the box, sphere and cylinder tests (the footprint lookups of shadow rays are
//! in `lookup`), the objects in front of the floor, and the floor lanes' shadow rays (what
//! `Prepared::occluded_by` answers for each lane's ray: the planes, the group
//! box, then the objects the lane's footprint cell lists, each through its box).
//! Each lane computes the scalar test's operations in the scalar order
//! (`Aabb::hit`, `hit_sphere`, `Cylinder::hit`, `Footprints::lookup`; glam's dot
//! is `(x*x' + y*y') + z*z'`, its `min` and `max` are `a < b ? a : b` and
//! `a > b ? a : b`), and an "any hit" answer does not depend on the order the
//! objects are tested in, so every lane's answer is the scalar one. Answers are
//! lane masks, or bits (bit `i` for lane `i`).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::lookup::lookup;
use super::vec::select3;
use super::{L3, LANES, Packet, lanes_with, splat3};
use crate::geometry::{Aabb, Cylinder, T_MIN};
use crate::prepared::Geom;
use crate::shadow::Lookup;
use crate::simd::Simd;
use glam::Vec3;

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

/// `Cylinder::hit`'s nearest hit per lane (+inf for none). "No hit yet" is
/// +inf, which takes and drops the same roots as the scalar `None` (a root of
/// +inf could never be nearer than another).
#[inline(always)]
fn cylinder<S: Simd>(s: S, c: &Cylinder, o: &L3<S::F>, d: &L3<S::F>) -> S::F {
    cylinder_parts(s, c, o, d).t
}

/// A cylinder's hit per lane ([`cylinder_parts`]).
struct CylinderHit<F> {
    /// Where (+inf: none).
    t: F,
    /// 0 the body, 1 and 2 the caps at `a` and `b`.
    part: F,
    /// The ray's origin and direction across the axis.
    op: L3<F>,
    dp: L3<F>,
}

/// [`cylinder`]'s hit per lane, with where it lies and the ray's parts across
/// the axis (`o_perp`, `d_perp`), for the normal.
#[inline(always)]
fn cylinder_parts<S: Simd>(s: S, c: &Cylinder, o: &L3<S::F>, d: &L3<S::F>) -> CylinderHit<S::F> {
    let (a, b, u, len, radius) = c.parts();
    let k = |v: f32| s.splat(v);
    let uu = splat3(s, u);
    let ao = o.sub(&splat3(s, a));
    let (du, ou) = (d.dot(&uu), ao.dot(&uu));
    // dir - u * du, ao - u * ou: (u.x * du) is (du * u.x), the same product.
    let dp = d.sub(&uu.scale(du));
    let op = ao.sub(&uu.scale(ou));
    let (qa, qb) = (dp.dot(&dp), op.dot(&dp));
    let r2 = k(radius * radius);
    let t_min = k(T_MIN);
    let body = S::lt(k(1e-12), qa);
    let f = op.sub(&dp.scale(qb / qa));
    let disc = qa * (r2 - f.dot(&f));
    let miss_all = body & S::lt(disc, k(0.0));
    let root = S::sqrt(disc);
    let (mut best, mut part) = (k(f32::INFINITY), k(0.0));
    for root in [-qb - root, -qb + root] {
        let t = root / qa;
        let along = ou + t * du;
        let inside = S::le(k(0.0), along) & S::le(along, k(len));
        let take = body & inside & S::lt(t_min, t) & S::lt(t, best);
        best = S::select(take, t, best);
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
    CylinderHit {
        t: S::select(miss_all, k(f32::INFINITY), best),
        part,
        op,
        dp,
    }
}

/// Per lane, where object `g` first meets the ray beyond `T_MIN` (+inf for
/// none) and its outward normal there: `Prepared::hit_object` (a sphere's
/// `(ray.at(t) - centre) / radius`, a cylinder's body `(o_perp + d_perp *
/// t).normalize()` or a cap's `-u` or `u`, a plane's normal).
#[inline(always)]
pub(super) fn hit_normal<S: Simd>(s: S, g: &Geom, o: &L3<S::F>, d: &L3<S::F>) -> (S::F, L3<S::F>) {
    match *g {
        Geom::Sphere { centre, radius } => {
            let t = sphere(s, (centre, radius), o, d);
            let at = o.add(&d.scale(t));
            (t, at.sub(&splat3(s, centre)).div(s.splat(radius)))
        }
        Geom::Cylinder(ref c) => {
            let CylinderHit { t, part, op, dp } = cylinder_parts(s, c, o, d);
            let v = op.add(&dp.scale(t));
            // normalize: v * (1 / sqrt(v.dot(v)))
            let body = v.scale(s.splat(1.0) / S::sqrt(v.dot(&v)));
            let u = splat3(s, c.parts().2);
            let (cap_a, cap_b) = (S::lt(s.splat(0.5), part), S::lt(s.splat(1.5), part));
            let n = select3::<S>(cap_a, &u.neg(), &body);
            (t, select3::<S>(cap_b, &u, &n))
        }
        Geom::Plane { point, normal } => (plane8(s, (point, normal), o, d), splat3(s, normal)),
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
/// `t` of `hit_sphere` or `Cylinder::hit`), or +inf; planes are tested
/// elsewhere (+inf here).
#[inline(always)]
pub(super) fn hit8<S: Simd>(s: S, g: &Geom, o: &L3<S::F>, d: &L3<S::F>) -> S::F {
    match *g {
        Geom::Sphere { centre, radius } => sphere(s, (centre, radius), o, d),
        Geom::Cylinder(ref c) => cylinder(s, c, o, d),
        Geom::Plane { .. } => s.splat(f32::INFINITY),
    }
}

/// Per lane, whether bounded object `g` meets the ray before `t_max`.
#[inline(always)]
pub(super) fn blocks8<S: Simd>(s: S, g: &Geom, o: &L3<S::F>, d: &L3<S::F>, t_max: S::F) -> S::M {
    S::lt(hit8(s, g, o, d), t_max)
}

/// The lanes' shadow rays: from `start` along `dir` (`inv` its inverse) up to
/// `dist`.
pub(super) struct Rays<'a, F> {
    pub(super) start: &'a L3<F>,
    pub(super) dir: &'a L3<F>,
    pub(super) inv: L3<F>,
    pub(super) dist: F,
}

impl Packet<'_, '_> {
    /// Per lane, which of the objects `others` its primary ray (from the eye
    /// along `d`) meets first before `t` (the floor's hit), as `closest_among`
    /// finds it after the floor: each box tested with the nearest hit so far as
    /// its limit, a hit taken only where nearer. The lanes that meet one (bits)
    /// and the object per lane (as `f32`, valid in those lanes).
    #[inline(always)]
    pub(super) fn nearest_of<S: Simd>(
        &self,
        s: S,
        others: &[usize],
        d: &L3<S::F>,
        t: S::F,
    ) -> (u8, S::F) {
        let eye = splat3(s, self.cam.origin);
        let inv = recip(s, d);
        let (mut best, mut which) = (t, s.splat(0.0));
        for &k in others {
            let inside = box8(s, &self.p.boxes[k], &eye, &inv, best);
            if S::bits(inside) == 0 {
                continue;
            }
            let h = hit8(s, self.p.geom(k), &eye, d);
            let take = inside & S::lt(h, best);
            best = S::select(take, h, best);
            which = S::select(take, s.splat(k as f32), which);
        }
        (S::bits(S::lt(best, t)), which)
    }

    /// The lanes of `live` (bits) whose rays object `k` meets before `dist`.
    /// (A method, not a closure: a closure left as a call is not compiled for
    /// AVX2.)
    #[inline(always)]
    pub(super) fn blocks<S: Simd>(&self, s: S, k: usize, r: &Rays<'_, S::F>, live: u8) -> u8 {
        let Rays {
            start,
            dir,
            ref inv,
            dist,
        } = *r;
        if live == 0 {
            return 0;
        }
        let inside = live & S::bits(box8(s, &self.p.boxes[k], start, inv, dist));
        if inside == 0 {
            return 0;
        }
        inside & S::bits(blocks8(s, self.p.geom(k), start, dir, dist))
    }

    /// The lanes of `want` (bits) whose rays from `start` on object `from`
    /// along `dir` meet a plane (not `from` itself,
    /// `Prepared::occluded_by_planes`) before `dist`.
    #[inline(always)]
    pub(super) fn planes_before<S: Simd>(
        &self,
        s: S,
        (from, start, dir): (usize, &L3<S::F>, &L3<S::F>),
        dist: S::F,
        want: u8,
    ) -> u8 {
        let mut out = 0;
        for &k in self.p.planes().iter().filter(|&&k| k != from) {
            out |= want & S::bits(S::lt(self.plane_hits(s, k, start, dir), dist));
        }
        out
    }

    /// The lanes of `live` (bits) whose rays one of the objects `ks` meets
    /// before `dist` (an "any hit": each object tests the lanes still open).
    #[inline(always)]
    pub(super) fn blocked_by<S: Simd>(
        &self,
        s: S,
        ks: impl Iterator<Item = usize>,
        r: &Rays<'_, S::F>,
        live: u8,
    ) -> u8 {
        let mut out = 0;
        for k in ks {
            out |= self.blocks(s, k, r, live & !out);
            if out == live {
                break;
            }
        }
        out
    }

    /// Per lane (bits), `Prepared::occluded_by(ray, dist, footprints)` for the
    /// shadow rays from `start` along `dir` towards light `li` of floor object
    /// `plane`, for the lanes in `want` (the others answer false).
    #[inline(always)]
    pub(super) fn occluded_lanes<S: Simd>(
        &self,
        s: S,
        (plane, li): (usize, usize),
        (start, dir): (&L3<S::F>, &L3<S::F>),
        dist: S::F,
        want: u8,
    ) -> u8 {
        let p = self.p;
        // The planes first: a hit before dist on any of them.
        let mut out = self.planes_before(s, (plane, start, dir), dist, want);
        // inv = dir.recip(); the group box.
        let inv = recip(s, dir);
        let mut todo = want & !out & S::bits(box8(s, &p.group, start, &inv, dist));
        if todo == 0 {
            return out;
        }
        let fp = p.footprints(plane, li);
        // Lane by lane, where its footprint cell is (or no grid: every object);
        // lanes with the same lists are tested together.
        let at: [u32; LANES] = match fp {
            None => [Lookup::UNLIT; LANES],
            Some(f) => lookup(s, &f.view(), start),
        };
        let rays = Rays {
            start,
            dir,
            inv,
            dist,
        };
        while todo != 0 {
            let first = at[todo.trailing_zeros() as usize];
            let group = lanes_with(&at, &first, todo);
            out |= match fp.and_then(|f| f.list(Lookup::of(first))) {
                Some((cell, always)) => {
                    let list = cell.iter().chain(always).copied();
                    self.blocked_by(s, list, &rays, group & !out)
                }
                None => self.blocked_by(s, p.bounded.iter().map(|b| b.0), &rays, group & !out),
            };
            todo &= !group;
        }
        out
    }
}
