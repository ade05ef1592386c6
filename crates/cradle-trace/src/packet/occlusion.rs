//! What a packet's lanes meet on the way, all lanes at once in lane build `S`
//! (the hit tests are in `hits`, the footprint lookups of shadow rays in
//! `lookup`): the objects in front of the floor, and the floor lanes' shadow rays (what
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

use super::hits::{blocks8, box8, recip};
use super::lookup::lookup;
use super::nearest::{Found, Nearest};
use super::{L3, LANES, Packet, lanes_with, splat3};
use crate::shadow::Lookup;
use crate::simd::Simd;

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
    /// and their hits (valid in those lanes).
    #[inline(always)]
    pub(super) fn nearest_of<S: Simd>(
        &self,
        s: S,
        others: &[usize],
        d: &L3<S::F>,
        t: S::F,
    ) -> (u8, Found<S::F>) {
        let eye = splat3(s, self.cam.origin);
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
        inside & S::bits(blocks8(s, self.p.geom(k), (start, dir), dist, inside))
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
