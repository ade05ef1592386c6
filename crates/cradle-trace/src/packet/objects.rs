//! The shadow rays of lanes on a bounded object (the cradle), over the lanes:
//! each tested against the object's casters (`Prepared::occluded_towards`'
//! list, per piece of the object and per side).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::occlusion::{Rays, recip};
use super::{L3, LANES, Packet, lanes, store3};
use crate::casters::clear_of;
use crate::simd::Simd;

impl Packet<'_, '_> {
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
}
