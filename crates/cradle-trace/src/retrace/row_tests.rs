//! Tests of a row's motion record: its segment buffer's room.

use super::{RowMotion, Seg};
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
    // Every pixel traced again with its three segments, and a quarter of
    // them with one more: as much garbage as live segments, the most a
    // row holds before `compact` drops the garbage.
    for k in 0..100 {
        let n = if k % 4 == 0 { 4 } else { 3 };
        rm.retrace(k, |out| {
            out.extend(std::iter::repeat_n(seg, n));
            (1, ())
        });
    }
    assert_eq!(rm.segs.len(), len + 325);
    assert_eq!(rm.segs.as_ptr(), at, "the buffer grew");
    // An untracked record takes no room.
    let mut bare = RowMotion::new(100, false);
    bare.room();
    assert_eq!(bare.segs.capacity(), 0);
}
