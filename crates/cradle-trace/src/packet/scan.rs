//! What the lanes' rays meet in the prepared scene, eight rays at once in
//! lane build `S` (the hit tests are in `hits`, the footprint lookups of
//! shadow rays in `lookup`): the nearest hits of the eye's rays in front of
//! the floor, of the floor's mirror rays among the tile's candidates and of
//! any bounce (as `Prepared::closest_from`: the planes but the one a lane's
//! ray leaves, then the bounded objects in runs of up to eight behind their
//! chunk's hull, or, in a large scene, each lane through the hierarchy); and
//! the shadow rays of the floor (`Prepared::blocker_by`: the planes, the
//! group box, then the objects the lane's footprint cell lists) and of a
//! bounded object (`Prepared::occluded_towards`: the casters of the piece and
//! side each lane starts from).
//!
//! Each lane computes the scalar test's operations in the scalar order
//! (`Aabb::hit`, `hit_sphere`, `Cylinder::hit`, `Footprints::lookup`; glam's
//! dot is `(x*x' + y*y') + z*z'`, its `min` and `max` are `a < b ? a : b` and
//! `a > b ? a : b`), a nearest hit is taken only where nearer (so the first
//! of equally near ones, as the scalar scan), and an "any hit" answer does
//! not depend on the order the objects are tested in, so every lane's answer
//! is the scalar one. Answers are lane masks, or bits (bit `i` for lane `i`).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::LANES;
use super::hits::{blocks8, box8, plane8, recip};
use super::lookup::lookup;
use super::nearest::{Found, Nearest};
use super::rays::{Bounce, leaving};
use super::vec::{L3, lanes_with, splat3, store3};
use crate::casters::MARGIN;
use crate::geometry::{Geom, Ray};
use crate::prepared::Prepared;
use crate::scene::Shape;
use crate::shadow::Lookup;
use crate::simd::Simd;
use crate::tuning::SCAN_AT_MOST;
use glam::Vec3;

/// The lanes' shadow rays: from `start` along `dir` (`inv` its inverse) up to
/// `dist`.
pub(super) struct Rays<'a, F> {
    pub(super) start: &'a L3<F>,
    pub(super) dir: &'a L3<F>,
    pub(super) inv: L3<F>,
    pub(super) dist: F,
}

/// The prepared scene as the lanes see it: each query answers for eight
/// rays at once what `Prepared`'s scalar query answers for each.
#[derive(Clone, Copy)]
pub(super) struct Scan<'a, 'p, const T: bool> {
    pub(super) p: &'a Prepared<'p>,
    /// In a tracked frame (`T`), per lane the first object a shadow test
    /// found blocking its ray (`u32::MAX`: none, or a plane), for its notes.
    pub(super) first: &'a std::cell::Cell<[u32; LANES]>,
}

impl<const T: bool> Scan<'_, '_, T> {
    /// Per lane of `live`, the nearest hit of its ray as `closest_from` finds
    /// it (the planes but the one the lane's ray leaves, `Bounce::from`, then
    /// inside the box around them the bounded objects in
    /// order, each box tested with the nearest hit so far as its limit, a hit
    /// taken only where nearer), as [`Found`].
    /// Beyond [`SCAN_AT_MOST`] bounded objects each lane walks the hierarchy
    /// instead (`Prepared::closest_from`, the same hit; `Found::at` then
    /// unknown).
    #[inline(always)]
    pub(super) fn nearest_all<S: Simd>(self, s: S, ray: &Bounce<S::F>, live: u8) -> Found<S::F> {
        let p = self.p;
        if p.bounded.len() > SCAN_AT_MOST {
            let (origin, dir) = (store3::<S>(&ray.origin), store3::<S>(&ray.d));
            let (mut missed, mut which) = (!live, [0.0; LANES]);
            for i in (0..LANES).filter(|i| live >> i & 1 != 0) {
                let r = Ray {
                    origin: origin.lane(i),
                    dir: dir.lane(i),
                };
                match p.closest_from(leaving::<S>(ray.from, i), &r, f32::INFINITY) {
                    Some(h) => which[i] = h.object as f32,
                    None => missed |= 1 << i,
                }
            }
            return Found {
                missed,
                which: s.load(&which),
                at: None,
            };
        }
        let inf = s.splat(f32::INFINITY);
        let mut near = Nearest::before(s, inf);
        for &k in p.planes() {
            let t = self.plane_hits(s, k, &ray.origin, &ray.d);
            // Not the plane the lane's ray leaves.
            let own = S::le(ray.from, s.splat(k as f32)) & S::le(s.splat(k as f32), ray.from);
            near.offer(s, !own, (t, s.splat(0.0)), k);
        }
        let inv = recip(s, &ray.d);
        let within = live & S::bits(box8(s, &p.group, &ray.origin, &inv, inf));
        if within != 0 {
            let within = s.mask(within);
            // A run of up to eight objects at a time behind its chunk's hull:
            // lanes that miss it before their nearest hit so far miss each of
            // the run's objects (`Chunk::hull`).
            for chunk in p.wide.chunks() {
                let hull = within & box8(s, chunk.hull(), &ray.origin, &inv, near.best);
                if S::bits(hull) == 0 {
                    continue;
                }
                for &k in chunk.items() {
                    let k = k as usize;
                    let inside = hull & box8(s, &p.boxes[k], &ray.origin, &inv, near.best);
                    if S::bits(inside) == 0 {
                        continue;
                    }
                    near.offer_object(s, inside, (p.geom(k), k), (&ray.origin, &ray.d));
                }
            }
        }
        near.found(!S::bits(S::lt(near.best, inf)))
    }

    /// Per lane, which of the objects `others` its primary ray (from `eye`
    /// along `d`) meets first before `t` (the floor's hit), as `closest_among`
    /// finds it after the floor: each box tested with the nearest hit so far as
    /// its limit, a hit taken only where nearer. The lanes that meet one (bits)
    /// and their hits (valid in those lanes).
    #[inline(always)]
    pub(super) fn nearest_of<S: Simd>(
        self,
        s: S,
        others: &[usize],
        (eye, d): (Vec3, &L3<S::F>),
        t: S::F,
    ) -> (u8, Found<S::F>) {
        let eye = splat3(s, eye);
        let inv = recip(s, d);
        let mut near = Nearest::before(s, t);
        for &k in others {
            let inside = box8(s, &self.p.boxes[k], &eye, &inv, near.best);
            if S::bits(inside) == 0 {
                continue;
            }
            near.offer_object(s, inside, (self.p.geom(k), k), (&eye, d));
        }
        (S::bits(S::lt(near.best, t)), near.found(0))
    }

    /// Per lane, the nearest of the objects `list` (but not `from`, the plane
    /// the rays leave) its ray from `start` along `dir` meets, as
    /// `closest_among` finds it: the candidates in order, each box tested with
    /// the nearest hit so far as its limit (bounded objects only in the lanes
    /// of `on`), a hit taken only where nearer. Lanes that meet none are
    /// `Found::missed`.
    #[inline(always)]
    pub(super) fn nearest_in<S: Simd>(
        self,
        s: S,
        (list, from): (&[usize], usize),
        (start, dir): (&L3<S::F>, &L3<S::F>),
        on: u8,
    ) -> Found<S::F> {
        let inf = s.splat(f32::INFINITY);
        let inv = recip(s, dir);
        let mut near = Nearest::before(s, inf);
        for &k in list.iter().filter(|&&k| k != from) {
            if matches!(self.p.scene.objects[k].shape, Shape::Plane { .. }) {
                let t = self.plane_hits(s, k, start, dir);
                near.offer(s, s.mask(0xFF), (t, s.splat(0.0)), k);
                continue;
            }
            let inside = box8(s, &self.p.boxes[k], start, &inv, near.best);
            if S::bits(inside) & on == 0 {
                continue;
            }
            near.offer_object(s, inside, (self.p.geom(k), k), (start, dir));
        }
        near.found(!S::bits(S::lt(near.best, inf)))
    }

    /// The lanes of `live` (bits) whose rays object `k` meets before `dist`.
    /// (A method, not a closure: a closure left as a call is not compiled for
    /// AVX2.)
    #[inline(always)]
    pub(super) fn blocks<S: Simd>(self, s: S, k: usize, r: &Rays<'_, S::F>, live: u8) -> u8 {
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
        inside & S::bits(blocks8(s, self.p.geom(k), (start, dir), dist, inside))
    }

    /// The lanes of `want` (bits) whose rays from `start` on object `from`
    /// along `dir` meet a plane (not `from` itself,
    /// `Prepared::occluded_by_planes`) before `dist`.
    #[inline(always)]
    pub(super) fn planes_before<S: Simd>(
        self,
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
        self,
        s: S,
        ks: impl Iterator<Item = usize>,
        r: &Rays<'_, S::F>,
        live: u8,
    ) -> u8 {
        let mut out = 0;
        if !T {
            for k in ks {
                out |= self.blocks(s, k, r, live & !out);
                if out == live {
                    break;
                }
            }
            return out;
        }
        for k in ks {
            let new = self.blocks(s, k, r, live & !out);
            if new != 0 {
                let mut ids = self.first.get();
                for (i, id) in ids.iter_mut().enumerate() {
                    if new >> i & 1 != 0 {
                        *id = k as u32;
                    }
                }
                self.first.set(ids);
            }
            out |= new;
            if out == live {
                break;
            }
        }
        out
    }

    /// Per lane (bits), whether `Prepared::blocker_by(ray, dist, footprints)`
    /// finds a blocker of the shadow rays from `start` along `dir` towards
    /// light `li` of floor object `plane`, for the lanes in `want` (the others
    /// answer false).
    #[inline(always)]
    pub(super) fn occluded_lanes<S: Simd>(
        self,
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

    /// Per lane, where the ray from `origin` along `dir` meets plane object `k`
    /// (`hit_plane`), or infinity for a miss.
    #[inline(always)]
    pub(super) fn plane_hits<S: Simd>(
        self,
        s: S,
        k: usize,
        origin: &L3<S::F>,
        dir: &L3<S::F>,
    ) -> S::F {
        let Shape::Plane { point, normal } = self.p.scene.objects[k].shape else {
            unreachable!("planes() lists planes")
        };
        plane8(s, (point, normal), origin, dir)
    }

    /// Per lane (bits), `Prepared::occluded_towards` for the shadow rays of
    /// the lanes in `want` from `start` along `dir` to `dist`, towards light `li`
    /// from points of `object` met from outside in the lanes of `outside`: the
    /// planes, then the casters of the piece each lane starts from (lanes with
    /// the same list tested together), or every bounded object where there are
    /// no lists. An "any hit" answer, so the order of the tests does not matter.
    /// `key`: each lane's piece and side ([`Self::caster_keys`]).
    #[inline(always)]
    pub(super) fn object_shadows<S: Simd>(
        self,
        s: S,
        (object, li, key): (usize, usize, &[(usize, bool); LANES]),
        (start, dir, dist): (&L3<S::F>, &L3<S::F>, S::F),
        want: u8,
    ) -> u8 {
        let p = self.p;
        let mut out = self.planes_before(s, (object, start, dir), dist, want);
        let mut todo = want & !out;
        if todo == 0 {
            return out;
        }
        let rays = Rays {
            start,
            dir,
            inv: recip(s, dir),
            dist,
        };
        let casters = p.casters(object);
        while todo != 0 {
            let first = key[todo.trailing_zeros() as usize];
            let group = lanes_with(key, &first, todo);
            out |= match casters.and_then(|c| c.list(li, first.0, first.1)) {
                Some(list) => self.blocked_by(s, list.items(), &rays, group & !out),
                None => self.blocked_by(s, p.bounded.iter().map(|b| b.0), &rays, group & !out),
            };
            todo &= !group;
        }
        out
    }

    /// Per lane of `on`, the piece of `object` its shadow rays start from (at
    /// `start`) and whether they start clearly outside it, having met it from
    /// outside (`outside`): which of the object's caster lists it takes, for
    /// every light.
    #[inline(always)]
    pub(super) fn caster_keys<S: Simd>(
        self,
        s: S,
        object: usize,
        (outside, on): (u8, u8),
        start: &L3<S::F>,
    ) -> [(usize, bool); LANES] {
        let p = self.p;
        let Some(c) = p.casters(object) else {
            return [(0, false); LANES];
        };
        let pieces = piece_lanes(s, c.axis(), start);
        let clear = outside & S::bits(clear_lanes(s, p.geom(object), start));
        let mut key = [(0, false); LANES];
        for (i, k) in key.iter_mut().enumerate() {
            if on >> i & 1 != 0 {
                *k = (pieces[i] as usize, clear >> i & 1 != 0);
            }
        }
        key
    }
}

/// `Casters::piece` per lane, with the same operations: `s = (at - a).dot(u)
/// / len * pieces`, then `(s.max(0.0) as usize).min(pieces - 1)`, here as
/// `max(s, 0)` (0 for NaN, as `f32::max`), `min` with `pieces - 1` (exact in
/// `f32`) and a truncation of a value in `0..=pieces - 1`.
#[inline(always)]
fn piece_lanes<S: Simd>(
    s: S,
    (a, u, len, pieces): (Vec3, Vec3, f32, usize),
    at: &L3<S::F>,
) -> [i32; LANES] {
    if pieces == 1 {
        return [0; LANES];
    }
    let k = |v: f32| s.splat(v);
    let along = at.sub(&splat3(s, a)).dot(&splat3(s, u)) / k(len) * k(pieces as f32);
    S::trunc(S::min(S::max(along, k(0.0)), k((pieces - 1) as f32)))
}

/// `casters::clear_of` per lane, with the same operations: a sphere's
/// `(p - centre).length_squared() > (radius + MARGIN)^2`; a cylinder's axial
/// position beyond either cap by more than `MARGIN`, or the offset from the
/// axis, `p - a - u * s`, longer than `radius + MARGIN`; planes: always.
#[inline(always)]
fn clear_lanes<S: Simd>(s: S, g: &Geom, p: &L3<S::F>) -> S::M {
    let k = |v: f32| s.splat(v);
    match *g {
        Geom::Sphere { centre, radius } => {
            let d = p.sub(&splat3(s, centre));
            S::lt(k((radius + MARGIN) * (radius + MARGIN)), d.dot(&d))
        }
        Geom::Cylinder(ref c) => {
            let (a, _, u, len, radius) = c.parts();
            let pa = p.sub(&splat3(s, a));
            let along = pa.dot(&splat3(s, u));
            let beyond = S::lt(along, k(-MARGIN)) | S::lt(k(len + MARGIN), along);
            let off = pa.sub(&splat3(s, u).scale(along));
            beyond | S::lt(k((radius + MARGIN) * (radius + MARGIN)), off.dot(&off))
        }
        Geom::Plane { .. } => s.mask(0xFF),
    }
}

#[cfg(test)]
mod tests {
    use super::{clear_lanes, piece_lanes};
    use crate::casters::{Casters, clear_of};
    use crate::geometry::Geom;
    use crate::packet::vec::L3;
    use crate::scene::{Light, Shape};
    use crate::simd::{Portable, Simd};
    use glam::Vec3;

    /// Both lane builds' pieces and sides equal `Casters::piece` and
    /// `clear_of` point by point, around a sphere and a tilted rod: points
    /// just inside and outside the 1e-5 m margin, beyond the caps, on the axis,
    /// far away, and NaN.
    #[test]
    fn lane_keys_equal_the_scalar_ones() {
        let shapes = [
            Shape::Sphere {
                centre: Vec3::new(0.1, 0.2, -0.05),
                radius: 0.02,
            },
            Shape::Cylinder {
                a: Vec3::new(-0.2, 0.05, 0.0),
                b: Vec3::new(0.25, 0.3, 0.1),
                radius: 0.005,
            },
        ];
        let light = [Light::Point {
            position: Vec3::new(0.0, 1.0, 1.0),
            color: Vec3::ONE,
        }];
        let mut seed = 7u32;
        let mut rnd = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for shape in shapes {
            let geom = Geom::new(&shape);
            let casters = Casters::new((0, &shape), &light, &[], None).expect("bounded");
            let (centre, axis, len, radius) = match shape {
                Shape::Sphere { centre, radius } => (centre, Vec3::X, 0.0, radius),
                Shape::Cylinder { a, b, radius } => {
                    ((a + b) * 0.5, (b - a).normalize(), (b - a).length(), radius)
                }
                Shape::Plane { .. } => unreachable!(),
            };
            let side = axis.any_orthonormal_vector();
            let mut points = vec![Vec3::NAN, centre, centre + Vec3::splat(1e3)];
            for _ in 0..4000 {
                // Along the axis to past the caps, at a distance from it near
                // the radius plus the margin (a few ulps either side).
                let s = (rnd() * 1.2 - 0.6) * len;
                let around = radius + 1e-5 + (rnd() - 0.5) * 4e-7;
                let turn = glam::Quat::from_axis_angle(axis, rnd() * 6.3) * side;
                points.push(centre + axis * s + turn * around);
            }
            for chunk in points.chunks(8) {
                let mut pts = [centre; 8];
                pts[..chunk.len()].copy_from_slice(chunk);
                let want_clear: u8 =
                    (0..8).fold(0, |m, i| m | u8::from(clear_of(&geom, pts[i])) << i);
                let want_piece: [i32; 8] = std::array::from_fn(|i| casters.piece(pts[i]) as i32);
                let want = (want_clear, want_piece);
                assert_eq!(build(Portable, &geom, &casters, &pts), want, "{pts:?}");
                #[cfg(target_arch = "x86_64")]
                if let Some(a) = crate::simd::Avx2::detect() {
                    assert_eq!(build(a, &geom, &casters, &pts), want, "AVX2 {pts:?}");
                }
            }
        }
    }

    fn build<S: Simd>(s: S, geom: &Geom, casters: &Casters, p: &[Vec3; 8]) -> (u8, [i32; 8]) {
        let at = L3 {
            x: s.load(&p.map(|v| v.x)),
            y: s.load(&p.map(|v| v.y)),
            z: s.load(&p.map(|v| v.z)),
        };
        (
            S::bits(clear_lanes(s, geom, &at)),
            piece_lanes(s, casters.axis(), &at),
        )
    }
}
