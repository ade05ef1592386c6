//! Tests of a row's motion record: its segment buffer's room and compaction.

use super::RowMotion;
use crate::motion::Seg;
use glam::Vec3;

#[test]
fn a_filled_row_takes_as_many_segments_again_without_moving_its_buffer() {
    let seg = Seg {
        a: Vec3::ZERO,
        b: Vec3::ONE,
    };
    let mut rm = RowMotion::new(100, true);
    for _ in 0..100 {
        rm.begin(true);
        rm.segs.extend([seg; 3]);
    }
    rm.begin(true);
    rm.seal();
    rm.room();
    let (len, at) = (rm.segs.len(), rm.segs.as_ptr());
    // Every pixel traced again, three quarters of them with one segment
    // more: theirs are appended (the others' fit where the old ones were),
    // and the garbage stays under half the segments, so `compact` keeps it.
    for k in 0..100 {
        let n = if k % 4 == 0 { 3 } else { 4 };
        rm.retrace(k, |out| {
            out.extend(std::iter::repeat_n(seg, n));
            (1, ())
        });
    }
    assert_eq!(rm.segs.len(), len + 300);
    assert_eq!(rm.garbage, 225);
    assert_eq!(rm.segs.as_ptr(), at, "the buffer grew");
    // An untracked record takes no room.
    let mut bare = RowMotion::new(100, false);
    bare.room();
    assert_eq!(bare.segs.capacity(), 0);
}

#[test]
fn compaction_keeps_each_pixels_segments_and_drops_the_rest() {
    // Pixel k's segments are told apart by their start point (k, j, 0).
    let seg = |k: usize, j: usize| Seg {
        a: Vec3::new(k as f32, j as f32, 0.0),
        b: Vec3::ONE,
    };
    let mut rm = RowMotion::new(10, true);
    for k in 0..10 {
        rm.begin(true);
        rm.segs.extend((0..=k % 3).map(|j| seg(k, j)));
    }
    rm.begin(true);
    rm.seal();
    // Traced again: pixels 2, 3, 4, 7 and 8 (now with 1, 4, 0, 0 and 1
    // segments), and pixel 5 cleared; pixels 0, 1, 6 and 9 keep theirs where
    // they were.
    let again = [(2, 1), (3, 4), (4, 0), (7, 0), (8, 1)];
    for &(k, n) in &again {
        rm.retrace(k, |out| {
            out.extend((0..n).map(|j| seg(k, 10 + j)));
            (1, ())
        });
    }
    rm.clear(5);
    let before = rm.segs.len();
    rm.compact();
    let want = |k: usize| -> Vec<Seg> {
        match again.iter().find(|a| a.0 == k) {
            Some(&(_, n)) => (0..n).map(|j| seg(k, 10 + j)).collect(),
            None if k == 5 => Vec::new(),
            None => (0..=k % 3).map(|j| seg(k, j)).collect(),
        }
    };
    for k in 0..10 {
        assert_eq!(rm.of(k), &want(k)[..], "pixel {k}");
    }
    // Only pixel 3's four segments are appended: the others' fit where their
    // old ones were. Garbage: the 2 + 1 + 2 + 3 + 2 + 2 segments that pixels
    // 2, 3, 4, 5, 7 and 8 no longer refer to, more than half of the 19 + 4:
    // compacted to the 11 live.
    assert_eq!(before, 23);
    assert_eq!(rm.garbage, 0);
    assert_eq!(rm.segs.len(), 11);
}

#[test]
fn segments_replaced_from_elsewhere_land_where_a_retrace_puts_them() {
    // Pixel k's segments are told apart by their start point (k, j, 0).
    let seg = |k: usize, j: usize| Seg {
        a: Vec3::new(k as f32, j as f32, 0.0),
        b: Vec3::ONE,
    };
    let fresh = || {
        let mut rm = RowMotion::new(6, true);
        for k in 0..6 {
            rm.begin(true);
            rm.segs.extend((0..2).map(|j| seg(k, j)));
        }
        rm.begin(true);
        rm.seal();
        rm
    };
    let (mut traced, mut replaced) = (fresh(), fresh());
    // Fewer, as many and more segments than before (the last appended),
    // and none.
    for (k, n) in [(1, 1), (2, 2), (4, 3), (5, 0)] {
        let new: Vec<Seg> = (0..n).map(|j| seg(k, 10 + j)).collect();
        traced.retrace(k, |out| {
            out.extend_from_slice(&new);
            (1 << k, ())
        });
        replaced.replace(k, 1 << k, &new);
        assert_eq!(replaced.of(k), &new[..], "pixel {k}");
    }
    assert_eq!(replaced.segs, traced.segs);
    assert_eq!(replaced.span, traced.span);
    assert_eq!(replaced.cells, traced.cells);
    // 1 + 0 + 2 + 2 segments no pixel refers to: pixel 4's old two among them.
    assert_eq!(replaced.garbage, 5);
    assert_eq!(traced.garbage, 5);
    assert_eq!(replaced.segs.len(), 15);
    // A record whose segments were dropped keeps cells only.
    let mut bare = fresh();
    bare.untrack();
    bare.replace(3, 8, &[seg(3, 0)]);
    assert_eq!((bare.cells[3], bare.segs.len()), (8, 0));
}
