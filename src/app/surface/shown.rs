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
}

impl Shown {
    /// The framebuffer no longer holds a known picture.
    pub(super) fn forget(&mut self) {
        self.id = None;
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
        match changes {
            // The same picture again: only the HUD box below.
            Some(c) if self.id == Some(c.id) => {}
            Some(c) if c.since.is_some() && c.since == self.id && c.rows.len() == h => {
                for (y, &[a, b]) in c.rows.iter().enumerate() {
                    let span = y * stride + a as usize * 4..y * stride + b as usize * 4;
                    put(&mut frame[span.clone()], &img.rgba[span]);
                }
            }
            _ => put(frame, &img.rgba),
        }
        for &(x, y0, bw, bh) in &self.hud {
            let (x0, x1) = (x.min(w), (x + bw).min(w));
            for y in y0.min(h)..(y0 + bh).min(h) {
                let span = y * stride + x0 * 4..y * stride + x1 * 4;
                put(&mut frame[span.clone()], &img.rgba[span]);
            }
        }
        self.id = id;
        self.hud.clear();
    }

    /// The HUD boxes just drawn over the picture.
    pub(super) fn hud(&mut self, boxes: Vec<Rect>) {
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
}
