//! The nearest hit of each lane's ray in a bounce past the eye's first hit,
//! as `Prepared::closest_from` finds it: the planes (but the one a lane's ray
//! leaves), then the bounded objects in runs of up to eight behind their chunk's
//! hull, or, in a large scene, each lane through the hierarchy.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::hits::{box8, hit_part, recip};
use super::rays::{Bounce, leaving};
use super::{F8, L3, LANES, Packet, store3};
use crate::geometry::Geom;
use crate::geometry::Ray;
use crate::simd::Simd;
use crate::tuning::SCAN_AT_MOST;

/// The nearest hits of a level's lanes: the lanes that meet nothing (bits),
/// the object each other lane meets (its index as `f32`), and where the scan
/// over the lanes found them, where (`t`) and on which part of it
/// (`hits::hit_part`): the shading then need not test it again.
#[derive(Clone, Copy)]
pub(super) struct Found<F> {
    pub(super) missed: u8,
    pub(super) which: F,
    pub(super) at: Option<(F, F)>,
}

impl<F: Copy> Found<F> {
    /// The lanes as arrays, to cross a call.
    #[inline(always)]
    pub(super) fn store<S: Simd<F = F>>(&self) -> Found<F8> {
        Found {
            missed: self.missed,
            which: S::store(self.which),
            at: self.at.map(|(t, part)| (S::store(t), S::store(part))),
        }
    }
}

impl Found<F8> {
    /// The arrays back as lanes.
    #[inline(always)]
    pub(super) fn load<S: Simd>(&self, s: S) -> Found<S::F> {
        Found {
            missed: self.missed,
            which: s.load(&self.which),
            at: self.at.map(|(t, part)| (s.load(&t), s.load(&part))),
        }
    }
}

/// A scan's nearest hit so far per lane: where, the object (its index as
/// `f32`) and the part of it (`hits::hit_part`; 0 for a plane), which change
/// together.
#[derive(Clone, Copy)]
pub(super) struct Nearest<F> {
    pub(super) best: F,
    which: F,
    part: F,
}

impl<F: Copy> Nearest<F> {
    /// Nothing met before `limit` yet.
    #[inline(always)]
    pub(super) fn before<S: Simd<F = F>>(s: S, limit: F) -> Self {
        Self {
            best: limit,
            which: s.splat(0.0),
            part: s.splat(0.0),
        }
    }

    /// Object `k`, met at `t` on part `part`, where nearer than the nearest so
    /// far in the lanes of `offered`.
    #[inline(always)]
    pub(super) fn offer<S: Simd<F = F>>(
        &mut self,
        s: S,
        offered: S::M,
        (t, part): (F, F),
        k: usize,
    ) {
        let take = offered & S::lt(t, self.best);
        self.best = S::select(take, t, self.best);
        self.which = S::select(take, s.splat(k as f32), self.which);
        self.part = S::select(take, part, self.part);
    }

    /// Bounded object `k` (`g`), tested by its hit test in the lanes of
    /// `inside` (those within its box; the test need be right only there),
    /// offered where nearer ([`Self::offer`]).
    #[inline(always)]
    pub(super) fn offer_object<S: Simd<F = F>>(
        &mut self,
        s: S,
        inside: S::M,
        (g, k): (&Geom, usize),
        (o, d): (&L3<F>, &L3<F>),
    ) {
        let hit = hit_part(s, g, (o, d), S::bits(inside));
        self.offer(s, inside, hit, k);
    }

    /// As [`Found`], the lanes of `missed` meeting nothing.
    #[inline(always)]
    pub(super) fn found(self, missed: u8) -> Found<F> {
        Found {
            missed,
            which: self.which,
            at: Some((self.best, self.part)),
        }
    }
}

impl Packet<'_, '_> {
    /// Per lane of `live`, the nearest hit of its ray as `closest_from` finds
    /// it (the planes but the one the lane's ray leaves, `Bounce::from`, then
    /// inside the box around them the bounded objects in
    /// order, each box tested with the nearest hit so far as its limit, a hit
    /// taken only where nearer), as [`Found`].
    /// Beyond [`SCAN_AT_MOST`] bounded objects each lane walks the hierarchy
    /// instead (`Prepared::closest_from`, the same hit; `Found::at` then
    /// unknown).
    #[inline(always)]
    pub(super) fn nearest_all<S: Simd>(&self, s: S, ray: &Bounce<S::F>, live: u8) -> Found<S::F> {
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
}
