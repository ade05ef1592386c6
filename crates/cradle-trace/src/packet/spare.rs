//! The lanes' segment buffers a thread's packets reuse: a packet takes a set
//! when made (`Frame::packets`) and gives it back when dropped, so the rows an
//! incremental frame traces again (hundreds a frame, each with a packet or
//! two) allocate no new buffers. Nothing else is shared: each thread keeps
//! its own sets.

use super::LANES;
use crate::motion::Seg;
use crate::tuning::LANE_SEGMENTS as ROOM;
use std::cell::RefCell;

/// A packet's segment buffers, one per lane.
pub(crate) type LaneSegs = [Vec<Seg>; LANES];

thread_local! {
    /// The sets given back on this thread (more than one only while packets
    /// are alive at once).
    static SPARE: RefCell<Vec<LaneSegs>> = const { RefCell::new(Vec::new()) };
}

/// A set of empty buffers: one given back on this thread, else new ones with
/// room for [`ROOM`] segments each where `track`.
pub(crate) fn take(track: bool) -> LaneSegs {
    SPARE.with_borrow_mut(Vec::pop).unwrap_or_else(|| {
        std::array::from_fn(|_| Vec::with_capacity(if track { ROOM } else { 0 }))
    })
}

/// Gives `segs` back for the next packet on this thread, emptied.
pub(crate) fn give(mut segs: LaneSegs) {
    segs.iter_mut().for_each(Vec::clear);
    // (During a thread's teardown the spare sets are gone: the buffers are
    // freed instead.)
    let _ = SPARE.try_with(|s| s.borrow_mut().push(segs));
}

#[cfg(test)]
mod tests {
    use super::{give, take};
    use crate::motion::Seg;
    use glam::Vec3;

    #[test]
    fn a_set_given_back_comes_back_empty_with_its_buffers() {
        let mut set = take(true);
        let seg = Seg {
            a: Vec3::ZERO,
            b: Vec3::ONE,
        };
        set[3].extend([seg; 40]);
        let (at, room) = (set[3].as_ptr(), set[3].capacity());
        give(set);
        let again = take(true);
        assert!(again.iter().all(Vec::is_empty));
        assert_eq!(
            again[3].as_ptr(),
            at,
            "a new buffer, not the one given back"
        );
        assert_eq!(again[3].capacity(), room);
        // None given back: fresh buffers.
        let other = take(true);
        assert_ne!(other[3].as_ptr(), at);
        assert!(other.iter().all(|v| v.capacity() >= 16));
    }
}
