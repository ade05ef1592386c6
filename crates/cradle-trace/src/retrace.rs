//! The motion record of a row (each pixel's cells, the moving objects its rays
//! met, and its ray segments in the motion box) and the re-trace of the pixels
//! an incremental frame must change: those whose rays met a moved object
//! where it was, and those one of whose segments comes near a moved object
//! where it is now.

use super::color::srgb8;
use super::frame::Frame;
use super::motion::{BLOCK, RowMotion};
use super::packet::{LANES, Packet};
use glam::Vec3;

mod moved;
mod screen;
use super::tuning::PACKET_AT_LEAST;
pub(crate) use moved::{Layer, Moved};
pub(crate) use screen::{Piece, Spans};

// A packet's run of pixels is one block, so resealing the blocks of a row's
// dirty pixels covers the clean lanes a packet traced beside them.
const _: () = assert!(BLOCK == LANES);

/// What the base layer of an adaptive frame notes as [`retrace_row`]
/// traces its pixels again.
#[derive(Debug)]
pub(crate) struct Notes<'r> {
    /// The x of each pixel the motion may have changed (its colour traced
    /// again), as [`Moved::dirty`] finds them.
    pub(crate) dirty: Vec<u32>,
    /// The x of each traced pixel whose bytes changed.
    pub(crate) changed: Vec<u32>,
    /// The row's linear colours, written where traced.
    pub(crate) lin: &'r mut [Vec3],
}

impl Notes<'_> {
    /// Notes traced pixel `k`: its bytes `before` and `after`, its colour `c`.
    fn note(&mut self, k: usize, (before, after): (&[u8], &[u8]), c: Vec3) {
        self.lin[k] = c;
        if before != after {
            self.changed.push(k as u32);
        }
    }
}

/// Re-traces the pixels of row `y` that `moved` may have changed, at samples
/// `offsets`, in packets where eight pixels in a row hold at least
/// [`PACKET_AT_LEAST`] such: a packet's bytes, cells and segments are the
/// scalar path's, and a pixel that did not change would get its own again.
/// Returns how many pixels it traced; with `notes`, notes each one there.
pub(crate) fn retrace_row(
    frame: &Frame<'_>,
    y: u32,
    row: &mut [u8],
    rm: &mut RowMotion,
    (moved, offsets): (&Moved, &[(f32, f32)]),
    mut notes: Option<&mut Notes<'_>>,
) -> usize {
    // The dirty pixels go to the notes' buffer (kept from frame to frame).
    let mut dirty = notes
        .as_deref_mut()
        .map(|n| std::mem::take(&mut n.dirty))
        .unwrap_or_default();
    let mut traced = 0;
    if moved.dirty(y as usize, rm, Layer::Base, &mut dirty) {
        traced = retrace_dirty(frame, (y, row, rm), (&dirty, offsets), notes.as_deref_mut());
    }
    if let Some(n) = notes {
        n.dirty = dirty;
    }
    traced
}

/// [`retrace_row`] of the pixels `dirty` (ascending, not empty).
fn retrace_dirty(
    frame: &Frame<'_>,
    (y, row, rm): (u32, &mut [u8], &mut RowMotion),
    (dirty, offsets): (&[u32], &[(f32, f32)]),
    mut notes: Option<&mut Notes<'_>>,
) -> usize {
    let width = frame.width() as usize;
    if let Some(n) = notes.as_deref_mut() {
        // `changed` holds at most the traced pixels (up to a run of eight
        // each), seldom more than twice as many as the dirty ones.
        n.changed.reserve(dirty.len() * 2);
    }
    let packets = frame.packets(offsets);
    let mut traced = 0;
    // Dirty pixels no floor packet traced, for the eye rays' lanes.
    let (mut left, mut n_left) = ([0; LANES], 0);
    // Run by run of LANES pixels holding a dirty one: `mask` a bit per
    // dirty pixel of the run.
    let mut rest = dirty;
    while let Some(&first) = rest.first() {
        let x = first as usize / LANES * LANES;
        let end = (x + LANES).min(width);
        let count = rest.iter().take_while(|&&k| (k as usize) < end).count();
        let mask = rest[..count]
            .iter()
            .fold(0u8, |m, &k| m | 1 << (k as usize - x));
        rest = &rest[count..];
        let done = match &packets {
            Some(pk) if end - x == LANES && count >= PACKET_AT_LEAST => {
                let span = &mut row[x * 4..end * 4];
                let before: [u8; 4 * LANES] = span.try_into().expect("a run of LANES");
                let done = pk.run(x as u32, y, span);
                let marks = pk.notes.marks();
                for k in (x..end).filter(|k| done & (1 << (k - x)) != 0) {
                    rm.replace(k, marks[k - x], &pk.notes.lane(k - x));
                    if let Some(n) = notes.as_deref_mut() {
                        let i = (k - x) * 4;
                        let bytes = (&before[i..i + 4], &span[i..i + 4]);
                        n.note(k, bytes, pk.color(k - x));
                    }
                    traced += 1;
                }
                done
            }
            _ => 0,
        };
        for k in (x..end).filter(|&k| (mask & !done) & (1 << (k - x)) != 0) {
            traced += 1;
            if let Some(pk) = &packets {
                // Eight at a time over the lanes, as eye rays.
                left[n_left] = k;
                n_left += 1;
                if n_left == LANES {
                    eye_rays(pk, (y, &left, offsets[0]), (row, rm), notes.as_deref_mut());
                    n_left = 0;
                }
                continue;
            }
            let px = &mut row[k * 4..k * 4 + 4];
            let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
            let at = (k as u32, y);
            let c = rm.retrace(k, |segs| frame.put(at, px, (None, offsets), segs));
            if let Some(n) = notes.as_deref_mut() {
                n.note(k, (&before, px), c);
            }
        }
    }
    if let Some(pk) = &packets
        && n_left > 0
    {
        eye_rays(pk, (y, &left[..n_left], offsets[0]), (row, rm), notes);
    }
    rm.compact();
    // Only pixels of dirty runs changed their cells.
    rm.reseal(dirty.iter().map(|&k| k as usize));
    traced
}

/// Re-traces pixels `ks` (at most [`LANES`]) of row `y` at their one
/// sample's offset (packets trace the centre only) over the packet's lanes, each as `trace_primary` traces its ray: the
/// bytes, cells and segments the scalar `put` gives (its colour is the
/// one sample's, over 1).
fn eye_rays(
    pk: &Packet<'_, '_>,
    (y, ks, (dx, dy)): (u32, &[usize], (f32, f32)),
    (row, rm): (&mut [u8], &mut RowMotion),
    mut notes: Option<&mut Notes<'_>>,
) {
    let mut at = [(0.0, 0.0); LANES];
    for (a, &k) in at.iter_mut().zip(ks) {
        *a = (k as f32 + dx, y as f32 + dy);
    }
    let colors = pk.camera_samples(&at[..ks.len()]);
    let marks = pk.notes.marks();
    for (i, &k) in ks.iter().enumerate() {
        // `pixel`: the sum from zero over the one sample, divided by 1.
        let c = (Vec3::ZERO + colors[i]) / 1.0;
        let px = &mut row[k * 4..k * 4 + 4];
        let before: [u8; 4] = (&*px).try_into().expect("4 bytes");
        px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        rm.replace(k, marks[i], &pk.notes.lane(i));
        if let Some(n) = notes.as_deref_mut() {
            n.note(k, (&before, px), c);
        }
    }
}
