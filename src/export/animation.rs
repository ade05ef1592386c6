//! What the animation writers share: the rectangle of a frame that changed
//! since the last one (the only part a later frame stores), and frame delays
//! that follow the frame times.

/// A rectangle of a picture (pixels).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

/// The smallest rectangle holding every element where `a` and `b` differ:
/// both are rows of `width` elements of `bytes` bytes each (4 for RGBA8, 1
/// for palette indices). `None` when they are equal.
#[must_use]
pub fn changed(a: &[u8], b: &[u8], width: u32, bytes: usize) -> Option<Rect> {
    let row = width as usize * bytes;
    let mut rows = a.chunks_exact(row).zip(b.chunks_exact(row)).enumerate();
    let mut found: Option<(usize, usize, usize, usize)> = None;
    for (y, (ra, rb)) in &mut rows {
        if ra == rb {
            continue;
        }
        let differs = |x: &usize| ra[x * bytes..(x + 1) * bytes] != rb[x * bytes..(x + 1) * bytes];
        let pixels = width as usize;
        let left = (0..pixels).find(differs).unwrap_or(0);
        let right = (0..pixels).rev().find(differs).unwrap_or(0);
        found = Some(match found {
            None => (left, right, y, y),
            Some((l, r, top, _)) => (l.min(left), r.max(right), top, y),
        });
    }
    found.map(|(l, r, top, bottom)| Rect {
        x: l as u32,
        y: top as u32,
        width: (r - l + 1) as u32,
        height: (bottom - top + 1) as u32,
    })
}

/// The elements of `rect` out of rows of `width` elements of `bytes` bytes.
#[must_use]
pub fn crop(data: &[u8], width: u32, bytes: usize, rect: Rect) -> Vec<u8> {
    let row = width as usize * bytes;
    let (x0, x1) = (
        rect.x as usize * bytes,
        (rect.x + rect.width) as usize * bytes,
    );
    data.chunks_exact(row)
        .skip(rect.y as usize)
        .take(rect.height as usize)
        .flat_map(|r| &r[x0..x1])
        .copied()
        .collect()
}

/// The RGBA8 pixels of `rect` in `next` (rows of `width` pixels), with those
/// equal to `last`'s transparent: put over `last` they give `next`.
#[must_use]
pub fn changes_over(last: &[u8], next: &[u8], width: u32, rect: Rect) -> Vec<u8> {
    let row = width as usize * 4;
    let mut out = Vec::with_capacity(rect.width as usize * rect.height as usize * 4);
    for y in rect.y..rect.y + rect.height {
        let at = y as usize * row + rect.x as usize * 4;
        let span = at..at + rect.width as usize * 4;
        for (a, b) in last[span.clone()]
            .chunks_exact(4)
            .zip(next[span].chunks_exact(4))
        {
            out.extend_from_slice(if a == b { &[0; 4] } else { b });
        }
    }
    out
}

/// Frame delays in units of `1 / unit` s whose sum follows the frame times,
/// so that 30 fps in centiseconds plays at 30 fps on average (3, 3, 4, 3, 3,
/// 4, ..), not 33.3.
#[derive(Debug, Clone, Copy)]
pub struct Delays {
    fps: f64,
    unit: f64,
    frames: u64,
}

impl Delays {
    /// Delays in centiseconds (GIF's unit) for `fps` frames per second.
    #[must_use]
    pub fn new(fps: f64) -> Self {
        Self::in_units(fps, 100.0)
    }

    /// Delays in `1 / unit` s for `fps` frames per second.
    #[must_use]
    pub fn in_units(fps: f64, unit: f64) -> Self {
        Self {
            fps,
            unit,
            frames: 0,
        }
    }

    /// The next frame's delay: the units from its start to the next one's,
    /// both rounded, at least 1.
    pub fn next_delay(&mut self) -> u16 {
        let at = |n: u64| (n as f64 * self.unit / self.fps).round();
        let d = at(self.frames + 1) - at(self.frames);
        self.frames += 1;
        d.clamp(1.0, 65535.0) as u16
    }
}

#[cfg(test)]
mod tests {
    use super::{Rect, changed, changes_over, crop};

    #[test]
    fn the_changed_rectangle_holds_every_difference_and_no_more() {
        // 5x4 pixels of one byte each: two differences, at (1, 1) and (3, 2).
        let a = vec![0u8; 20];
        let mut b = a.clone();
        b[5 + 1] = 9;
        b[2 * 5 + 3] = 7;
        let r = changed(&a, &b, 5, 1).expect("they differ");
        assert_eq!(
            r,
            Rect {
                x: 1,
                y: 1,
                width: 3,
                height: 2
            }
        );
        assert_eq!(crop(&b, 5, 1, r), [9, 0, 0, 0, 0, 7]);
        assert_eq!(changed(&a, &a, 5, 1), None);
        // RGBA: a change in one channel of the last pixel of the last row.
        let (p, mut q) = (vec![1u8; 4 * 6], vec![1u8; 4 * 6]);
        q[4 * 6 - 1] = 0;
        let r = changed(&p, &q, 3, 4).expect("they differ");
        assert_eq!((r.x, r.y, r.width, r.height), (2, 1, 1, 1));
    }

    /// Puts `changes` (from [`changes_over`]) over `canvas` (rows of `width`
    /// RGBA8 pixels): its transparent pixels keep the canvas's.
    fn put_over(canvas: &mut [u8], width: u32, rect: Rect, changes: &[u8]) {
        let row = width as usize * 4;
        let span = rect.width as usize * 4;
        for (k, src) in changes.chunks_exact(span).enumerate() {
            let at = (rect.y as usize + k) * row + rect.x as usize * 4;
            for (dst, px) in canvas[at..at + span]
                .chunks_exact_mut(4)
                .zip(src.chunks_exact(4))
            {
                if px[3] != 0 {
                    dst.copy_from_slice(px);
                }
            }
        }
    }

    #[test]
    fn changes_put_over_the_last_frame_give_the_next() {
        // 3x2 opaque pixels; the middle of the top row and the last changed.
        let last: Vec<u8> = (0..6).flat_map(|k| [k, k, k, 255]).collect();
        let mut next = last.clone();
        next[4..8].copy_from_slice(&[9, 9, 9, 255]);
        next[20..24].copy_from_slice(&[7, 7, 7, 255]);
        let rect = changed(&last, &next, 3, 4).expect("they differ");
        let changes = changes_over(&last, &next, 3, rect);
        // The unchanged pixels in the rectangle are transparent.
        assert_eq!(&changes[8..12], &[0, 0, 0, 0]);
        let mut canvas = last.clone();
        put_over(&mut canvas, 3, rect, &changes);
        assert_eq!(canvas, next);
    }
}
