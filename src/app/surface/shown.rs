//! What the window's framebuffer shows, so that a new picture is put there by
//! copying only the pixels its frame may have changed ([`Changes`]), not every
//! byte: the copy (with the swap to BGRA) ran between taking a frame back from
//! the tracer and starting the next one, 0.8 ms of a 12 ms frame in the window.
//! The HUD's box, drawn over the picture, is put back from the picture first.
//! Window-free, so it is tested here.

use super::formats::put_bgra;
use crate::app::hud::Rect;
use crate::trace::{Changes, Image};

/// The framebuffer's picture: which one, and the HUD boxes drawn over it.
#[derive(Debug, Default)]
pub(super) struct Shown {
    /// The number of the picture the framebuffer holds (`None`: unknown, say
    /// after a resize).
    id: Option<u64>,
    /// The HUD boxes drawn over it last.
    hud: Vec<Rect>,
    /// Per row, the pixels `x0..x1` written since the last [`Self::put`]
    /// (`x0 >= x1`: none); empty: unknown (everything may have changed).
    touched: Vec<(u32, u32)>,
}

impl Shown {
    /// The framebuffer no longer holds a known picture.
    pub(super) fn forget(&mut self) {
        self.id = None;
        self.touched.clear();
    }

    /// Per row of the framebuffer, the pixels `x0..x1` the last frame wrote
    /// (picture and HUD; `x0 >= x1`: none); `None` when any may have changed.
    pub(super) fn touched(&self) -> Option<&[(u32, u32)]> {
        (!self.touched.is_empty()).then_some(&self.touched[..])
    }

    /// Notes that pixels `x0..x1` of rows `rows` were written.
    fn touch(&mut self, rows: std::ops::Range<usize>, (x0, x1): (usize, usize)) {
        for y in rows {
            if let Some(t) = self.touched.get_mut(y) {
                *t = if t.0 >= t.1 {
                    (x0 as u32, x1 as u32)
                } else {
                    (t.0.min(x0 as u32), t.1.max(x1 as u32))
                };
            }
        }
    }

    /// Makes `frame` (as many bytes as `img`, BGRA when `bgra`) hold `img`,
    /// which `changes` describes (`None`: unknown, copied whole); the HUD box
    /// drawn last is put back from `img`. Call [`Self::hud`] after drawing the
    /// new one.
    pub(super) fn put(
        &mut self,
        frame: &mut [u8],
        img: &Image,
        changes: Option<Changes<'_>>,
        bgra: bool,
    ) {
        let put = |to: &mut [u8], from: &[u8]| {
            if bgra {
                put_bgra(to, from);
            } else {
                to.copy_from_slice(from);
            }
        };
        let (w, h) = (img.width as usize, img.height as usize);
        let stride = w * 4;
        let id = changes.map(|c| c.id);
        self.touched.clear();
        self.touched.resize(h, (0, 0));
        match changes {
            // The same picture again: only the HUD box below.
            Some(c) if self.id == Some(c.id) => {}
            Some(c) if c.since.is_some() && c.since == self.id && c.rows.len() == h => {
                for (y, &[a, b]) in c.rows.iter().enumerate() {
                    let span = y * stride + a as usize * 4..y * stride + b as usize * 4;
                    put(&mut frame[span.clone()], &img.rgba[span]);
                    self.touch(y..y + 1, (a as usize, b as usize));
                }
            }
            _ => {
                put(frame, &img.rgba);
                self.touch(0..h, (0, w));
            }
        }
        for (x, y0, bw, bh) in std::mem::take(&mut self.hud) {
            let (x0, x1) = (x.min(w), (x + bw).min(w));
            for y in y0.min(h)..(y0 + bh).min(h) {
                let span = y * stride + x0 * 4..y * stride + x1 * 4;
                put(&mut frame[span.clone()], &img.rgba[span]);
            }
            self.touch(y0.min(h)..(y0 + bh).min(h), (x0, x1));
        }
        self.id = id;
    }

    /// The HUD boxes just drawn over the picture.
    pub(super) fn hud(&mut self, boxes: Vec<Rect>) {
        let h = self.touched.len();
        for &(x, y0, bw, bh) in &boxes {
            // Past the right edge too, as drawn: readers clamp to the width.
            self.touch(y0.min(h)..(y0 + bh).min(h), (x, x + bw));
        }
        self.hud = boxes;
    }
}

#[cfg(test)]
mod tests {
    use super::Shown;
    use crate::trace::{Changes, Image};

    /// A 4x3 picture whose pixel `i` is `[i, 100 + i, 200 + i, 255]` plus
    /// `add` in red.
    fn picture(add: u8) -> Image {
        let rgba = (0..12u8)
            .flat_map(|i| [i + add, 100 + i, 200 + i, 255])
            .collect();
        Image {
            width: 4,
            height: 3,
            rgba,
        }
    }

    #[test]
    fn a_picture_goes_whole_first_then_only_its_changes() {
        let mut shown = Shown::default();
        let mut frame = vec![0; 48];
        let first = picture(0);
        let full = Changes {
            id: 7,
            since: None,
            rows: &[],
        };
        shown.put(&mut frame, &first, Some(full), false);
        assert!(frame == first.rgba, "copied whole");
        // The next picture differs everywhere, but its changes name only row 1's
        // pixels 1..3: the rest stays as it was (so the copy did only them).
        let next = picture(50);
        let rows = [[0, 0], [1, 3], [0, 0]];
        let changes = Changes {
            id: 8,
            since: Some(7),
            rows: &rows,
        };
        shown.put(&mut frame, &next, Some(changes), false);
        for (i, px) in frame.chunks_exact(4).enumerate() {
            let named = (5..7).contains(&i);
            let want = if named { &next.rgba } else { &first.rgba };
            assert_eq!(px, &want[i * 4..i * 4 + 4], "pixel {i}");
        }
        // Changes since a picture the frame does not hold: copied whole.
        let changes = Changes {
            id: 9,
            since: Some(5),
            rows: &rows,
        };
        shown.put(&mut frame, &next, Some(changes), false);
        assert!(frame == next.rgba, "copied whole");
    }

    #[test]
    fn the_hud_box_is_put_back_and_bgra_swaps_red_and_blue() {
        let mut shown = Shown::default();
        let mut frame = vec![0; 48];
        let img = picture(0);
        let c = Changes {
            id: 1,
            since: None,
            rows: &[],
        };
        shown.put(&mut frame, &img, Some(c), true);
        assert_eq!(&frame[4..8], &[201, 101, 1, 255], "BGRA");
        // A HUD box of 2x2 drawn over it, then the same picture again: the box is
        // the picture's again.
        for y in 0..2 {
            frame[y * 16..y * 16 + 8].fill(9);
        }
        shown.hud(vec![(0, 0, 2, 2), (3, 2, 5, 5)]);
        shown.put(&mut frame, &img, Some(c), true);
        assert_eq!(&frame[16..20], &[204, 104, 4, 255], "pixel 4 put back");
        frame[44..48].fill(9);
        shown.hud(vec![(3, 2, 5, 5)]);
        shown.put(&mut frame, &img, Some(c), true);
        assert_eq!(
            &frame[44..48],
            &[211, 111, 11, 255],
            "a box clipped at the edge"
        );
        // After `forget`, copied whole.
        frame.fill(0);
        shown.forget();
        shown.put(&mut frame, &img, Some(c), true);
        assert_eq!(&frame[44..48], &[211, 111, 11, 255], "the last pixel");
    }

    #[test]
    fn it_knows_the_pixels_each_frame_wrote() {
        let mut shown = Shown::default();
        let mut frame = vec![0; 48];
        assert_eq!(shown.touched(), None, "nothing known yet");
        let c = Changes {
            id: 1,
            since: None,
            rows: &[],
        };
        shown.put(&mut frame, &picture(0), Some(c), false);
        assert_eq!(shown.touched(), Some(&[(0, 4); 3][..]), "copied whole");
        shown.hud(vec![(1, 2, 2, 1)]);
        let rows = [[0, 0], [2, 3], [0, 0]];
        let c = Changes {
            id: 2,
            since: Some(1),
            rows: &rows,
        };
        shown.put(&mut frame, &picture(9), Some(c), false);
        // Row 1's change, and row 2 where the HUD box was put back.
        assert_eq!(shown.touched(), Some(&[(0, 0), (2, 3), (1, 3)][..]));
        shown.hud(vec![(0, 0, 1, 1)]);
        assert_eq!(shown.touched(), Some(&[(0, 1), (2, 3), (1, 3)][..]));
        shown.forget();
        assert_eq!(shown.touched(), None);
    }
}
