//! The shadow rays of lanes on a bounded object (the cradle), over the lanes:
//! each tested against the object's casters (`Prepared::occluded_towards`'
//! list, per piece of the object and per side).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::occlusion::{Rays, recip};
use super::{L3, LANES, Packet, lanes_with, store3};
use crate::casters::clear_of;
use crate::simd::Simd;

impl Packet<'_, '_> {
    /// Per lane (bits), `Prepared::occluded_towards` for the shadow rays of
    /// the lanes in `want` from `start` along `dir` to `dist`, towards light `li`
    /// from points of `object` met from outside in the lanes of `outside`: the
    /// planes, then the casters of the piece each lane starts from (lanes with
    /// the same list tested together), or every bounded object where there are
    /// no lists. An "any hit" answer, so the order of the tests does not matter.
    /// `key`: each lane's piece and side ([`Self::caster_keys`]).
    #[inline(always)]
    pub(super) fn object_shadows<S: Simd>(
        &self,
        s: S,
        (object, li, key): (usize, usize, &[(usize, bool); LANES]),
        (start, dir, dist): (&L3<S::F>, &L3<S::F>, S::F),
        want: u8,
    ) -> u8 {
        let p = self.p;
        let mut out = self.planes_before(s, (start, dir), dist, want);
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
        &self,
        object: usize,
        (outside, on): (u8, u8),
        start: &L3<S::F>,
    ) -> [(usize, bool); LANES] {
        let p = self.p;
        let Some(c) = p.casters(object) else {
            return [(0, false); LANES];
        };
        let at = store3::<S>(start);
        let mut key = [(0, false); LANES];
        for i in (0..LANES).filter(|i| on >> i & 1 != 0) {
            let o = at.lane(i);
            let clear = outside >> i & 1 != 0 && clear_of(p.geom(object), o);
            key[i] = (c.piece(o), clear);
        }
        key
    }
}
