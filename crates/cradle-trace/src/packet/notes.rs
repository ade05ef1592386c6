//! The motion record of a tracked frame's packets ([`LaneNotes`]): each lane
//! notes the cells its rays pass through and their segments inside the motion
//! box, exactly what the scalar path's `Motion::segment` notes for the lane's
//! pixel; an untracked frame's notes keep nothing. The packet code is built
//! twice, for tracked and untracked frames (the views' `const T: bool`, chosen
//! per packet by [`LaneNotes::tracked`]): the untracked build's notes compile
//! to nothing, so full frames pay nothing for them. The box's slabs
//! are cut over the lanes (the divisions and products of `MotionGrid::clip`, the
//! same IEEE operations per lane); the rest of the clip, and the cells, per lane.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::LANES;
use super::spare;
use super::vec::{L3, store3};
use crate::geometry::Ray;
use crate::motion::{Cells, Motion, MotionGrid, Seg};
use crate::prepared::Prepared;
use crate::simd::Simd;
use glam::Vec3;
use std::cell::{Cell, RefCell};

/// What each lane of a packet's rays passed through, in a tracked frame.
pub(crate) struct LaneNotes {
    /// The motion grid of a tracked frame (`None`: nothing is noted).
    motion: Option<MotionGrid>,
    /// The cells each lane's rays passed through.
    marks: Cell<[Cells; LANES]>,
    /// The segments of each lane's rays inside the motion box, in the order
    /// traced.
    segs: RefCell<[Vec<Seg>; LANES]>,
    /// Per lane, the first object the last shadow test found blocking it.
    first: Cell<[u32; LANES]>,
    /// Per lane, where the last [`Self::note`] put its segment in the lane's
    /// buffer (`u32::MAX`: none).
    last: Cell<[u32; LANES]>,
}

impl Drop for LaneNotes {
    /// Gives the lanes' segment buffers back to the thread's spares.
    fn drop(&mut self) {
        spare::give(std::mem::take(self.segs.get_mut()));
    }
}

impl LaneNotes {
    /// Notes for a frame tracked on `motion` (`None`: untracked), in the
    /// thread's spare segment buffers.
    pub(crate) fn new(motion: Option<MotionGrid>) -> Self {
        Self {
            motion,
            marks: Cell::new([0; LANES]),
            segs: RefCell::new(spare::take(motion.is_some())),
            first: Cell::new([u32::MAX; LANES]),
            last: Cell::new([u32::MAX; LANES]),
        }
    }

    /// Per lane, the first object the shadow test since the last
    /// [`Self::first_blockers`]'s reset found blocking it.
    pub(super) fn first_blockers(&self) -> &Cell<[u32; LANES]> {
        &self.first
    }

    /// Whether the frame is tracked.
    #[inline(always)]
    pub(super) fn tracked(&self) -> bool {
        self.motion.is_some()
    }

    /// Forgets the last packet's cells and segments (in a tracked frame).
    pub(super) fn fresh(&self) {
        if self.motion.is_some() {
            self.marks.set([0; LANES]);
            self.segs.borrow_mut().iter_mut().for_each(Vec::clear);
        }
    }

    /// The cells each lane's rays passed through in the last packet (in a
    /// tracked frame).
    pub(crate) fn marks(&self) -> [Cells; LANES] {
        self.marks.get()
    }

    /// The segments lane `i` noted in the last packet.
    pub(crate) fn lane(&self, i: usize) -> std::cell::Ref<'_, [Seg]> {
        std::cell::Ref::map(self.segs.borrow(), |segs| segs[i].as_slice())
    }

    /// What `f` returns, given a `Motion` for lane `i` (lent the lane's
    /// segments, to append to) whose cells then go to the lane's in a tracked
    /// frame: the scalar path's tracing of one lane.
    pub(super) fn in_lane(&self, i: usize, f: impl FnOnce(&mut Motion) -> Vec3) -> Vec3 {
        let lent = std::mem::take(&mut self.segs.borrow_mut()[i]);
        let mut motion = Motion::with(self.motion, lent);
        let c = f(&mut motion);
        if self.motion.is_some() {
            let m = &self.marks.as_array_of_cells()[i];
            m.set(m.get() | motion.mask);
        }
        self.segs.borrow_mut()[i] = motion.segs;
        c
    }

    /// In a tracked frame (and a tracked build, `T`: the untracked one
    /// compiles to nothing), after the shadow test of the rays [`Self::note`]
    /// noted last: the lanes of `stopped`, whose rays were blocked, keep
    /// their segment (flagged) where the first blocker the test found moves,
    /// with the blocker's shadow bit for a ball and its hit bit for another
    /// object, and nothing where it is still (a blocked shadow ray stays
    /// blocked but for its blocker moving away). A ray that never enters the
    /// motion box has no moving blocker.
    #[inline(always)]
    pub(super) fn after_shadows<const T: bool>(&self, stopped: u8, p: &Prepared<'_>) {
        if T && self.motion.is_some() && stopped != 0 {
            self.blocked(stopped, p);
        }
    }

    /// [`Self::after_shadows`] of the lanes `stopped`.
    #[cold]
    #[inline(never)]
    fn blocked(&self, stopped: u8, p: &Prepared<'_>) {
        let (ids, last) = (self.first.get(), self.last.get());
        let marks = self.marks.as_array_of_cells();
        let mut segs = self.segs.borrow_mut();
        for i in (0..LANES).filter(|i| stopped >> i & 1 != 0) {
            let at = last[i] as usize;
            if last[i] == u32::MAX || at >= segs[i].len() {
                continue;
            }
            let by = if ids[i] == u32::MAX {
                0
            } else {
                p.blocker_bits(ids[i] as usize)
            };
            if by == 0 {
                segs[i].truncate(at);
                continue;
            }
            segs[i][at].flag();
            marks[i].set(marks[i].get() | by);
        }
    }

    /// [`Self::note`] of rays that end on a hit (`t`, then the lanes' hits'
    /// [`Self::hit_lanes`] bits).
    #[inline(always)]
    pub(super) fn note_met<const T: bool, S: Simd>(
        &self,
        s: S,
        (on, free): (u8, u8),
        rays: (&L3<S::F>, &L3<S::F>),
        (t, bits): (S::F, impl FnOnce() -> Cells),
    ) {
        if T {
            self.note::<T, S>(s, (on, free), rays, t);
            self.hit_lanes(on, bits);
        }
    }

    /// In a tracked frame, notes `bits` (moving objects met, [`crate::motion::HITS`])
    /// in each lane of `on`.
    #[inline(always)]
    pub(super) fn hit_lanes(&self, on: u8, bits: impl FnOnce() -> Cells) {
        if self.motion.is_none() {
            return;
        }
        let bits = bits();
        if bits == 0 {
            return;
        }
        let marks = self.marks.as_array_of_cells();
        for (i, m) in marks.iter().enumerate() {
            if on >> i & 1 != 0 {
                m.set(m.get() | bits);
            }
        }
    }

    /// In a tracked frame (and a tracked build, `T`: the untracked one
    /// compiles to nothing), notes for each lane of `on` the segment of its ray
    /// from `origin` along `dir` up to `t`: its cells (but not in the lanes of
    /// `free`, as `Record::segment` takes it), and its part in the motion box (lane by
    /// lane, in order).
    #[inline(always)]
    pub(super) fn note<const T: bool, S: Simd>(
        &self,
        s: S,
        (on, free): (u8, u8),
        (origin, dir): (&L3<S::F>, &L3<S::F>),
        t: S::F,
    ) {
        let Some(g) = self.motion.as_ref().filter(|_| T) else {
            return;
        };
        if on == 0 {
            return;
        }
        self.first.set([u32::MAX; LANES]);
        let mut last = [u32::MAX; LANES];
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
            if let Some(mut seg) = MotionGrid::clip_slabs(&ray, (lo.lane(i), hi.lane(i)), t[i]) {
                if free >> i & 1 == 0 {
                    let m = &marks[i];
                    m.set(m.get() | g.segment_cells(seg.a, seg.b));
                } else {
                    seg.set_free();
                }
                last[i] = segs[i].len() as u32;
                segs[i].push(seg);
            }
        }
        self.last.set(last);
    }
}
