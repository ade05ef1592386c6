//! The packet's lanes whose primary rays meet a bounded object (the cradle)
//! before the floor. Lanes that meet the same object with a plain colour are
//! shaded together, as the floor lanes are (`shade_lanes`): the lights, the
//! Lambert and Phong terms and the shadow rays over the lanes, each shadow ray
//! tested against the object's casters (`Prepared::occluded_towards`' list, per
//! piece of the object and per side); each lane's mirror ray goes through the
//! scalar `reflect`. A lone lane, or an object with a checker, goes through the
//! scalar `shade`. Every lane starts from the scalar hit test of its object (the
//! `t` the lanes found, and the normal).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::lanes::Met;
use super::occlusion::{Rays, recip};
use super::{L3, LANES, Packet, Surface, V8, lanes, load3, store3};
use crate::casters::clear_of;
use crate::geometry::Ray;
use crate::prepared::Hit;
use crate::scene::Material;
use crate::shade::{SURFACE_OFFSET, reflect, shade};
use crate::simd::Simd;

/// Fewer lanes than this on one object are shaded one by one.
const SHARED: u32 = 2;

/// The lanes' rays: from `origin` along `d`, a bounce at `depth` with path
/// weight `weight` (the eye's rays: 0 and 1).
pub(super) struct Bounce<'a, F> {
    pub(super) origin: &'a L3<F>,
    pub(super) d: &'a L3<F>,
    pub(super) depth: u32,
    pub(super) weight: f32,
}

impl Packet<'_, '_> {
    /// `color` with the lanes of `on` (bits) replaced by what `shade` gives
    /// their rays (`ray`), whose nearest hit is object `which` (per lane, as
    /// `f32`), met by the scalar test for its normal (the same `t`): the eye's
    /// rays that meet the cradle before the floor (`trace_primary`), or the
    /// floor's mirror rays (`reflect` through the tile's list).
    #[inline(always)]
    pub(super) fn objects_lanes<S: Simd>(
        &self,
        s: S,
        (x0, y, on): (u32, u32, u8),
        ray: &Bounce<'_, S::F>,
        which: S::F,
        color: L3<S::F>,
    ) -> L3<S::F> {
        let (origin, dir, which) = (store3::<S>(ray.origin), store3::<S>(ray.d), S::store(which));
        let lane_ray = |i: usize| Ray {
            origin: origin.lane(i),
            dir: dir.lane(i),
        };
        let mut out = store3::<S>(&color);
        let mut todo = on;
        while todo != 0 {
            let k = which[todo.trailing_zeros() as usize] as usize;
            let mut group = 0u8;
            for (i, &w) in which.iter().enumerate() {
                if w as usize == k {
                    group |= 1 << i;
                }
            }
            group &= todo;
            todo &= !group;
            let material = &self.p.scene.objects[k].material;
            let mut hits = [None; LANES];
            for i in (0..LANES).filter(|i| group >> i & 1 != 0) {
                let r = lane_ray(i);
                hits[i] = (self.p.hit_object(k, &r)).map(|(t, n)| Hit::facing(&r, t, k, n));
            }
            let all_hit = hits.iter().flatten().count() == group.count_ones() as usize;
            if group.count_ones() < SHARED || material.checker.is_some() || !all_hit {
                for i in (0..LANES).filter(|i| group >> i & 1 != 0) {
                    let r = lane_ray(i);
                    let tile = (ray.depth == 0).then_some((self.tiles, x0 + i as u32, y));
                    let (depth, weight, bound) = (ray.depth, ray.weight, self.bound);
                    let c = self.in_lane(i, |motion| {
                        shade(self.p, &r, hits[i], depth, weight, bound, motion, tile)
                    });
                    (out.x[i], out.y[i], out.z[i]) = (c.x, c.y, c.z);
                }
                continue;
            }
            let c = self.object_lanes(s, (x0, y, group), ray, &hits, material);
            let c = store3::<S>(&c);
            for i in (0..LANES).filter(|i| group >> i & 1 != 0) {
                (out.x[i], out.y[i], out.z[i]) = (c.x[i], c.y[i], c.z[i]);
            }
        }
        load3(s, &out)
    }

    /// `shade` of the lanes of `group`, whose rays (`ray`) all meet one object
    /// with a plain `material` at `hits`.
    #[inline(always)]
    fn object_lanes<S: Simd>(
        &self,
        s: S,
        (x0, y, group): (u32, u32, u8),
        ray: &Bounce<'_, S::F>,
        hits: &[Option<Hit>; LANES],
        material: &Material,
    ) -> L3<S::F> {
        let mut object = 0;
        let (mut t, mut n, mut outside) = ([0.0; LANES], V8::ZERO, 0u8);
        let (origin, dir) = (store3::<S>(ray.origin), store3::<S>(ray.d));
        for (i, h) in hits.iter().enumerate() {
            if let Some(h) = h {
                object = h.object;
                t[i] = h.t;
                (n.x[i], n.y[i], n.z[i]) = (h.normal.x, h.normal.y, h.normal.z);
                outside |= u8::from(h.outside) << i;
                if self.motion.is_some() {
                    // `shade` notes its ray up to the hit.
                    let r = Ray {
                        origin: origin.lane(i),
                        dir: dir.lane(i),
                    };
                    self.note(i, &r, h.t);
                }
            }
        }
        let nn = load3(s, &n);
        // point = ray.at(t): origin + dir * t; start = point + n * SURFACE_OFFSET
        let point = ray.origin.add(&ray.d.scale(s.load(&t)));
        let start = point.add(&nn.scale(s.splat(SURFACE_OFFSET)));
        let hit = Surface {
            d: *ray.d,
            point,
            start,
            nn,
        };
        let met = Met::Object {
            object,
            material,
            outside,
            bounce: (ray.depth, ray.weight),
        };
        self.shade_lanes(s, met, (x0, y), group, &hit)
    }

    /// Per lane (bits), `Prepared::occluded_towards` for the shadow rays of
    /// the lanes in `want` from `start` along `dir` to `dist`, towards light `li`
    /// from points of `object` met from outside in the lanes of `outside`: the
    /// planes, then the casters of the piece each lane starts from (lanes with
    /// the same list tested together), or every bounded object where there are
    /// no lists. An "any hit" answer, so the order of the tests does not matter.
    #[inline(always)]
    pub(super) fn object_shadows<S: Simd>(
        &self,
        s: S,
        (object, li, outside): (usize, usize, u8),
        (start, dir, dist): (&L3<S::F>, &L3<S::F>, S::F),
        want: u8,
    ) -> u8 {
        let p = self.p;
        let mut out = 0;
        for &k in p.planes() {
            out |= want & S::bits(S::lt(self.plane_hits(s, k, start, dir), dist));
        }
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
        // Per lane: its piece, and whether it starts clearly outside the object.
        let at = store3::<S>(start);
        let key: [(usize, bool); LANES] = lanes(|i| match casters {
            Some(c) if todo >> i & 1 != 0 => {
                let o = at.lane(i);
                let clear = outside >> i & 1 != 0 && clear_of(p.geom(object), o);
                (c.piece(o), clear)
            }
            _ => (0, false),
        });
        while todo != 0 {
            let first = key[todo.trailing_zeros() as usize];
            let mut group = 0;
            for (i, &kk) in key.iter().enumerate() {
                if kk == first {
                    group |= 1 << i;
                }
            }
            group &= todo;
            match casters.and_then(|c| c.list(li, first.0, first.1)) {
                Some(list) => {
                    for k in list.items() {
                        out |= self.blocks(s, k, &rays, group & !out);
                    }
                }
                None => {
                    for &(k, _) in &p.bounded {
                        out |= self.blocks(s, k, &rays, group & !out);
                    }
                }
            }
            todo &= !group;
        }
        out
    }

    /// Per lane, the radiance the mirror rays of the lanes of `on` bring back
    /// (`reflect` with weight `weight` after a bounce at `depth`, lane by lane)
    /// from points of `object` met from outside in the lanes of `outside`; the
    /// background in the other lanes.
    #[inline(always)]
    pub(super) fn object_mirrors<S: Simd>(
        &self,
        s: S,
        (x0, y, on): (u32, u32, u8),
        (object, outside, depth): (usize, u8, u32),
        Surface { d, start, nn, .. }: &Surface<S::F>,
        weight: f32,
    ) -> L3<S::F> {
        // dir - 2.0 * dir.dot(n) * n
        let dir = store3::<S>(&d.sub(&nn.scale(s.splat(2.0) * d.dot(nn))));
        let start = store3::<S>(start);
        let mut out = V8::ZERO;
        for i in (0..LANES).filter(|i| on >> i & 1 != 0) {
            let mirror = Ray {
                origin: start.lane(i),
                dir: dir.lane(i),
            };
            let from = (object, outside >> i & 1 != 0);
            let tile = (depth == 0).then_some((self.tiles, x0 + i as u32, y));
            let c = self.in_lane(i, |motion| {
                reflect(
                    self.p,
                    &mirror,
                    from,
                    depth + 1,
                    weight,
                    self.bound,
                    motion,
                    tile,
                )
            });
            (out.x[i], out.y[i], out.z[i]) = (c.x, c.y, c.z);
        }
        load3(s, &out)
    }
}
