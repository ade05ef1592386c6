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
    use super::{Rect, changed, crop};

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
}
