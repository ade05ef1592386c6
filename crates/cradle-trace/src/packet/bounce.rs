//! The packet's rays past the floor's own shading, over the lanes: the eye's
//! rays that meet the cradle before the floor, and the floor's mirror rays.
//! Level by level (one bounce each) instead of `shade`'s recursion: each
//! level finds every lane's nearest hit as `closest` does (`Scan::nearest_all`; a
//! plane's own mirror rays skip it, `Bounce::from`), groups the lanes by
//! the object met, shades each group's lights and shadows over the lanes
//! (`Lights::local`) and makes the mirror rays of the next level for the lanes
//! that reflect. Then the levels are blended from the deepest up,
//! `color * (1 - r) + reflected * r` per lane, as the recursion returns.
//!
//! Each group starts its shading from where the nearest-hit scan met the object
//! (`Found::at`: the `t` and the part of it) with the normal there
//! (`normal_at`; `Prepared::hit_object`'s per lane). Where the scan gave no `t`
//! (each lane walked the hierarchy), the object's hit test over the lanes
//! gives it (`hit_normal`); a lane that test were not to meet is traced by the
//! scalar path instead (`shade` from `Prepared::closest_from`).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::LANES;
use super::hits::{hit_normal, normal_at};
use super::lights::Lights;
use super::nearest::Found;
use super::rays::{Bounce, Bounce8, Met, leaving};
use super::vec::{F8, L3, Surface, V8, load3, select3, splat3, store3};
use crate::geometry::Ray;
use crate::geometry::{Hit, SURFACE_OFFSET};
use crate::material::BAILOUT;
use crate::scene::Shape;
use crate::shade::shade_from;
use crate::simd::{Kernel, Simd};
use crate::tuning::SHARED;
use glam::Vec3;

/// Levels a packet's rays can pass through: depths 0 to 16 (the most
/// `max_depth` allows).
const LEVELS: usize = 17;

/// One level's result per lane: the local colour, the reflectivity of what
/// was met, and the lanes that reflect (bits).
type Level<F> = (L3<F>, F, u8);

/// The bounces of the lanes' rays: the lights of what they meet, and the
/// radiance bound that ends a path whose weight cannot matter any more.
#[derive(Clone, Copy)]
pub(super) struct Bounces<'a, 'p, const T: bool> {
    pub(super) lights: Lights<'a, 'p, T>,
    pub(super) bound: f32,
}

/// [`Bounces::lanes`] of the rays `first` in lane build `s`, through
/// the build's one compiled copy: not inlined into each caller (the floor's
/// kernel and its mirrors), which made the crate slow to compile; the AVX2
/// copy is compiled for AVX2. Lane values cross the call as arrays.
#[inline(never)]
pub(super) fn bounce_copy<S: Simd, const T: bool>(
    s: S,
    bounces: Bounces<'_, '_, T>,
    first: &Bounce8,
    live: u8,
    found: Option<Found<F8>>,
) -> V8 {
    s.enter(BounceKernel {
        bounces,
        first,
        live,
        found,
    })
}

/// [`Bounces::lanes`] as a lane kernel.
struct BounceKernel<'k, 'p, const T: bool> {
    bounces: Bounces<'k, 'p, T>,
    first: &'k Bounce8,
    live: u8,
    found: Option<Found<F8>>,
}

impl<const T: bool> Kernel for BounceKernel<'_, '_, T> {
    type Output = V8;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> V8 {
        self.bounces.arrays(s, self.first, self.live, self.found)
    }
}

impl<const T: bool> Bounces<'_, '_, T> {
    /// [`Self::lanes`] through build `S`'s own copy.
    #[inline(always)]
    pub(super) fn trace<S: Simd>(
        &self,
        s: S,
        first: &Bounce<S::F>,
        live: u8,
        found: Option<Found<S::F>>,
    ) -> L3<S::F> {
        let arrays = Bounce8 {
            origin: store3::<S>(&first.origin),
            d: store3::<S>(&first.d),
            depth: first.depth,
            weight: S::store(first.weight),
            free: first.free,
            from: S::store(first.from),
        };
        // (No closure here: one left as a call is not compiled for AVX2.)
        let mut known = None;
        if let Some(f) = found {
            known = Some(f.store::<S>());
        }
        load3(s, &bounce_copy(s, *self, &arrays, live, known))
    }

    /// [`Self::lanes`] from and to arrays.
    #[inline(always)]
    fn arrays<S: Simd>(&self, s: S, b: &Bounce8, live: u8, found: Option<Found<F8>>) -> V8 {
        let first = Bounce {
            origin: load3(s, &b.origin),
            d: load3(s, &b.d),
            depth: b.depth,
            weight: s.load(&b.weight),
            free: b.free,
            from: s.load(&b.from),
        };
        let mut known = None;
        if let Some(f) = found {
            known = Some(f.load(s));
        }
        store3::<S>(&self.lanes(s, first, live, known))
    }

    /// Per lane, the radiance of the rays `first` of the lanes of `live`
    /// (`shade` of their nearest hit; other lanes: anything). `found`: their
    /// nearest hits where already known, the lanes that meet nothing and the
    /// object per lane (as `f32`).
    #[inline(always)]
    fn lanes<S: Simd>(
        &self,
        s: S,
        first: Bounce<S::F>,
        live: u8,
        found: Option<Found<S::F>>,
    ) -> L3<S::F> {
        // `None`s: only their tags are written (17 whole levels of zeros cost
        // 85 stores of a register a call).
        let mut levels: [Option<Level<S::F>>; LEVELS] = [None; LEVELS];
        let mut n = 0;
        let (mut ray, mut live, mut found) = (first, live, found);
        loop {
            let f = match found.take() {
                Some(f) => f,
                None => self.lights.scan.nearest_all(s, &ray, live),
            };
            let (level, next) = self.level(s, &ray, (live & !f.missed, live & f.missed), &f);
            levels[n] = Some(level);
            n += 1;
            if level.2 == 0 || n == LEVELS {
                break;
            }
            (ray, live) = (next, level.2);
        }
        let mut acc = splat3(s, Vec3::ZERO);
        if let Some(last) = levels[n - 1] {
            acc = last.0;
        }
        for &(c, r, m) in levels[..n - 1].iter().rev().flatten() {
            // color * (1.0 - r) + reflected * r
            let blended = c.scale(s.splat(1.0) - r).add(&acc.scale(r));
            acc = select3::<S>(s.mask(m), &blended, &c);
        }
        acc
    }

    /// One level: the lanes of `hitting` met what `found` says, those of
    /// `missed` nothing. Their local colours, reflectivities and the lanes
    /// that reflect, and the mirror rays of those.
    #[inline(always)]
    fn level<S: Simd>(
        &self,
        s: S,
        ray: &Bounce<S::F>,
        (hitting, missed): (u8, u8),
        found: &Found<S::F>,
    ) -> (Level<S::F>, Bounce<S::F>) {
        let p = self.lights.scan.p;
        let (origin, dir, which) = (
            store3::<S>(&ray.origin),
            store3::<S>(&ray.d),
            S::store(found.which),
        );
        let lane_ray = |i: usize| Ray {
            origin: origin.lane(i),
            dir: dir.lane(i),
        };
        // Free lanes (`Record::segment`'s `free`): camera rays, and mirror rays of camera
        // rays off a plane.
        let free = if ray.depth == 0 { 0xFF } else { ray.free };
        // `shade` of no hit notes the ray to infinity.
        let (origin, d, inf) = (&ray.origin, &ray.d, s.splat(f32::INFINITY));
        (self.lights.notes).note::<T, S>(s, (missed, free), (origin, d), inf);
        let mut color = splat3(s, p.scene.background);
        let (mut reflectivity, mut reflect) = (s.splat(0.0), 0u8);
        let mut next = Bounce {
            origin: color,
            d: color,
            depth: ray.depth + 1,
            weight: s.splat(0.0),
            free: 0,
            from: s.splat(-1.0),
        };
        let mut scalar = (0u8, V8::ZERO);
        let mut todo = hitting;
        while todo != 0 {
            let first = which[todo.trailing_zeros() as usize];
            let k = first as usize;
            // The lanes of `todo` on the same object: which == first.
            let same = S::le(found.which, s.splat(first)) & S::le(s.splat(first), found.which);
            let mut group = todo & S::bits(same);
            todo &= !group;
            if group.count_ones() < SHARED {
                // A lone lane: the scalar `shade` from its hit (or `trace`).
                for i in (0..LANES).filter(|i| group >> i & 1 != 0) {
                    let r = lane_ray(i);
                    let hit = p.hit_object(k, &r).map(|(t, n)| Hit::facing(&r, t, k, n));
                    self.lane_scalar::<S>((i, free), (ray, &r), hit, &mut scalar);
                }
                continue;
            }
            // Where the lanes meet object k, and its normal turned to face the
            // ray (`Hit::facing`: inside where n.dot(dir) > 0).
            let (t, n) = self.meeting(s, k, ray, found);
            let inside = S::lt(s.splat(0.0), n.dot(&ray.d));
            let nn = select3::<S>(inside, &n.neg(), &n);
            let outside = !S::bits(inside);
            let lost = group & !S::bits(S::lt(t, s.splat(f32::INFINITY)));
            // `shade` notes its ray up to the hit.
            let met = (t, || p.moving_bit(k));
            let rays = (&ray.origin, &ray.d);
            (self.lights.notes).note_met::<T, S>(s, (group & !lost, free), rays, met);
            for i in (0..LANES).filter(|i| lost >> i & 1 != 0) {
                // Not met by the hit test after all: the scalar path.
                self.lane_scalar::<S>((i, free), (ray, &lane_ray(i)), None, &mut scalar);
            }
            group &= !lost;
            if group == 0 {
                continue;
            }
            // point = ray.at(t): origin + dir * t; start = point + n * SURFACE_OFFSET
            let point = ray.origin.add(&ray.d.scale(t));
            let start = point.add(&nn.scale(s.splat(SURFACE_OFFSET)));
            let object = &p.scene.objects[k];
            let plane = matches!(object.shape, Shape::Plane { .. });
            let met = Met::Object {
                object: k,
                material: &object.material,
                outside,
                plane,
            };
            // A camera ray met a plane: its shadow and mirror rays are free.
            let from_eye = if plane && ray.depth == 0 { group } else { 0 };
            let hit = Surface {
                d: ray.d,
                point,
                start,
                nn,
            };
            let here = self.lights.local(s, met, (group, from_eye), &hit);
            color = select3::<S>(s.mask(group), &here, &color);
            let r = object.material.reflective;
            if r > 0.0 && ray.depth < p.scene.max_depth {
                // weight * r * bound >= BAILOUT
                let w = ray.weight * s.splat(r);
                let go = group & S::bits(S::le(s.splat(BAILOUT), w * s.splat(self.bound)));
                if go != 0 {
                    let m = s.mask(go);
                    // dir - 2.0 * dir.dot(n) * n
                    let d = ray.d.sub(&nn.scale(s.splat(2.0) * ray.d.dot(&nn)));
                    next.origin = select3::<S>(m, &start, &next.origin);
                    next.d = select3::<S>(m, &d, &next.d);
                    next.weight = S::select(m, w, next.weight);
                    next.free |= go & from_eye;
                    if plane {
                        next.from = S::select(m, s.splat(k as f32), next.from);
                    }
                    reflectivity = S::select(m, s.splat(r), reflectivity);
                    reflect |= go;
                }
            }
        }
        if scalar.0 != 0 {
            color = select3::<S>(s.mask(scalar.0), &load3(s, &scalar.1), &color);
        }
        ((color, reflectivity, reflect), next)
    }

    /// Where the lanes of `ray` meet object `k` and its outward normal there:
    /// as `found` says, else by its hit test over the lanes (the same `t`).
    #[inline(always)]
    fn meeting<S: Simd>(
        &self,
        s: S,
        k: usize,
        ray: &Bounce<S::F>,
        found: &Found<S::F>,
    ) -> (S::F, L3<S::F>) {
        let g = self.lights.scan.p.geom(k);
        match found.at {
            Some(at) => (at.0, normal_at(s, g, (&ray.origin, &ray.d), at)),
            None => hit_normal(s, g, &ray.origin, &ray.d),
        }
    }

    /// Lane `i` of `ray` (`r`) by [`Self::scalar_lane`], from `hit` where
    /// known: its colour and bit go to `scalar`.
    #[inline(always)]
    fn lane_scalar<S: Simd>(
        &self,
        (i, free): (usize, u8),
        (ray, r): (&Bounce<S::F>, &Ray),
        hit: Option<Hit>,
        scalar: &mut (u8, V8),
    ) {
        let w = S::store(ray.weight)[i];
        let from = leaving::<S>(ray.from, i);
        let c = self.scalar_lane((i, free), (r, from), hit, (ray.depth, w));
        (scalar.1.x[i], scalar.1.y[i], scalar.1.z[i]) = (c.x, c.y, c.z);
        scalar.0 |= 1 << i;
    }

    /// Lane `i`'s ray `r` (leaving plane `from`, if any), a bounce at `depth`
    /// with path weight `weight`, by the scalar path: `shade` from `hit` where
    /// known, else from the nearest hit (`trace`, but not testing `from`).
    fn scalar_lane(
        &self,
        (i, free): (usize, u8),
        (r, from): (&Ray, Option<(usize, bool)>),
        hit: Option<Hit>,
        (depth, weight): (u32, f32),
    ) -> Vec3 {
        let (p, b) = (self.lights.scan.p, self.bound);
        self.lights.notes.in_lane(i, |motion| {
            let hit = hit.or_else(|| p.closest_from(from, r, f32::INFINITY));
            shade_from(p, r, hit, (depth, weight), b, (motion, free >> i & 1 != 0))
        })
    }
}
