//! The motion record of a tracked frame's packets: each lane notes the cells its
//! rays pass through and their segments inside the motion box, exactly what the
//! scalar path's `Motion::segment` notes for the lane's pixel. The box's slabs
//! are cut over the lanes (the divisions and products of `MotionGrid::clip`, the
//! same IEEE operations per lane); the rest of the clip, and the cells, per lane.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::vec::{L3, store3};
use super::{LANES, Packet};
use crate::geometry::Ray;
use crate::motion::MotionGrid;
use crate::simd::Simd;
use glam::Vec3;

impl Packet<'_, '_> {
    /// In a tracked frame, notes for each lane of `on` the segment of its ray
    /// from `origin` along `dir` up to `t`: its cells (but not in the lanes of
    /// `free`, as `Record::segment` takes it), and its part in the motion box (lane by
    /// lane, in order).
    #[inline(always)]
    pub(super) fn note_lanes<S: Simd>(
        &self,
        s: S,
        (on, free): (u8, u8),
        (origin, dir): (&L3<S::F>, &L3<S::F>),
        t: S::F,
    ) {
        let Some(g) = &self.motion else {
            return;
        };
        if on == 0 {
            return;
        }
        // clip: inv = dir.recip(); t1 = (min - origin) * inv; t2 = (max -
        // origin) * inv; then t1.min(t2) and t1.max(t2).
        let one = s.splat(1.0);
        let inv = L3 {
            x: one / dir.x,
            y: one / dir.y,
            z: one / dir.z,
        };
        let b = g.outer();
        let slab = |m: Vec3| L3 {
            x: (s.splat(m.x) - origin.x) * inv.x,
            y: (s.splat(m.y) - origin.y) * inv.y,
            z: (s.splat(m.z) - origin.z) * inv.z,
        };
        let (t1, t2) = (slab(b.min), slab(b.max));
        let lo = store3::<S>(&L3 {
            x: S::min(t1.x, t2.x),
            y: S::min(t1.y, t2.y),
            z: S::min(t1.z, t2.z),
        });
        let hi = store3::<S>(&L3 {
            x: S::max(t1.x, t2.x),
            y: S::max(t1.y, t2.y),
            z: S::max(t1.z, t2.z),
        });
        let (o, d, t) = (store3::<S>(origin), store3::<S>(dir), S::store(t));
        let marks = self.marks.as_array_of_cells();
        let mut segs = self.segs.borrow_mut();
        for i in 0..LANES {
            if on >> i & 1 == 0 {
                continue;
            }
            let ray = Ray {
                origin: o.lane(i),
                dir: d.lane(i),
            };
            if let Some(seg) = MotionGrid::clip_slabs(&ray, (lo.lane(i), hi.lane(i)), t[i]) {
                if free >> i & 1 == 0 {
                    let m = &marks[i];
                    m.set(m.get() | g.cells(seg.a.min(seg.b), seg.a.max(seg.b)));
                }
                segs[i].push(seg);
            }
        }
    }
}
