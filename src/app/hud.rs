//! The HUD: lines of text drawn into the CPU frame (so screenshots show it), with
//! an 8x8 bitmap font. A few hundred glyphs a frame: microseconds.
//!
//! The layout keeps the cradle clear: the status sits in the top band and the
//! key help and notices in the bottom band, the bands the fitted camera keeps
//! the swing out of (`scene::view::FIT_TOP`, `FIT_BOTTOM`).

use super::keys::HELP;
use super::session::Overlay;
use font8x8::{BASIC_FONTS, UnicodeFonts};

/// Height of one text line in font pixels (8 of glyph, 2 of space).
const LINE_UNITS: usize = 10;

/// A box drawn over the picture: left, top, width and height in pixels.
pub type Rect = (usize, usize, usize, usize);

/// The font's scale for a `width x height` picture: 2x where the status
/// lines fit across it and within the top band the fitted camera keeps clear
/// (12% of 570 pixels holds three lines of 20), else 1x.
#[must_use]
pub fn scale_for(width: usize, height: usize) -> usize {
    if width >= 800 && height >= 570 { 2 } else { 1 }
}

/// An RGBA8 (or BGRA8) frame to draw into.
pub struct Canvas<'a> {
    /// Pixels, rows top to bottom.
    pub rgba: &'a mut [u8],
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The bytes are in BGRA order (colours are given as RGB all the same).
    pub bgra: bool,
    /// Pixels per font pixel.
    pub scale: usize,
}

impl Canvas<'_> {
    /// Darkens a box behind the text so it reads on any background.
    pub fn shade(&mut self, x0: usize, y0: usize, w: usize, h: usize) {
        let x1 = (x0 + w).min(self.width);
        if x0 >= x1 {
            return;
        }
        for y in y0..(y0 + h).min(self.height) {
            let row = y * self.width * 4;
            // A row's span at a time, so the compiler divides many bytes at once.
            for px in self.rgba[row + x0 * 4..row + x1 * 4].chunks_exact_mut(4) {
                px[0] /= 3;
                px[1] /= 3;
                px[2] /= 3;
            }
        }
    }

    /// Draws `text` with its top-left corner at `(x, y)` in `color`; characters
    /// without a glyph are skipped, and whatever leaves the frame is clipped.
    pub fn text(&mut self, x: usize, y: usize, text: &str, color: [u8; 3]) {
        let color = if self.bgra {
            [color[2], color[1], color[0]]
        } else {
            color
        };
        for (n, ch) in text.chars().enumerate() {
            let Some(glyph) = BASIC_FONTS.get(ch) else {
                continue;
            };
            let scale = self.scale;
            let gx = x + n * 8 * scale;
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits & (1 << col) == 0 {
                        continue;
                    }
                    for dy in 0..scale {
                        for dx in 0..scale {
                            let (px, py) = (gx + col * scale + dx, y + row * scale + dy);
                            if px < self.width && py < self.height {
                                let i = (py * self.width + px) * 4;
                                self.rgba[i..i + 3].copy_from_slice(&color);
                            }
                        }
                    }
                }
            }
        }
    }

    /// Height of a text line in pixels.
    #[must_use]
    pub fn line(&self) -> usize {
        LINE_UNITS * self.scale
    }

    /// Draws lines of text in a shaded box with its top-left corner at
    /// `(x, y)`, wrapped at the frame's width (a long config error keeps its
    /// allowed range); returns the box.
    pub fn boxed(&mut self, x: usize, y: usize, lines: &[(String, [u8; 3])]) -> Rect {
        let glyph = 8 * self.scale;
        let lines = wrap(lines, (self.width.saturating_sub(16 + x) / glyph).max(8));
        let longest = lines
            .iter()
            .map(|(l, _)| l.chars().count())
            .max()
            .unwrap_or(0);
        let (w, h) = (longest * glyph + 16, lines.len() * self.line() + 8);
        self.shade(x, y, w, h);
        for (i, (line, color)) in lines.iter().enumerate() {
            self.text(x + 8, y + 4 + i * self.line(), line, *color);
        }
        (x, y, w.min(self.width.saturating_sub(x)), h)
    }

    /// The height of the box [`Self::boxed`] draws for `lines`.
    fn boxed_height(&self, lines: usize) -> usize {
        lines * self.line() + 8
    }

    /// Draws `overlay`: the status at the top left, the key help in columns
    /// at the bottom (in the font's smaller size), the notices at the bottom
    /// left above it. Returns the boxes drawn.
    pub fn overlay(&mut self, overlay: &Overlay) -> Vec<Rect> {
        let mut drawn = Vec::new();
        if !overlay.status.is_empty() {
            drawn.push(self.boxed(0, 0, &overlay.status));
        }
        let mut bottom = self.height;
        if overlay.help {
            let scale = std::mem::replace(&mut self.scale, 1);
            let lines = help_columns(self.width.saturating_sub(16) / 8);
            let h = self.boxed_height(lines.len());
            let w = lines.first().map_or(0, |(l, _)| l.chars().count() * 8 + 16);
            let x = self.width.saturating_sub(w) / 2;
            bottom = self.height.saturating_sub(h);
            drawn.push(self.boxed(x, bottom, &lines));
            self.scale = scale;
        }
        if !overlay.notices.is_empty() {
            let h = self.boxed_height(overlay.notices.len());
            drawn.push(self.boxed(0, bottom.saturating_sub(h), &overlay.notices));
        }
        drawn
    }
}

/// The key help laid out in as many columns as fit in `chars` characters,
/// row by row.
#[must_use]
pub fn help_columns(chars: usize) -> Vec<(String, [u8; 3])> {
    let keys = HELP.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    let what = HELP.iter().map(|(_, w)| w.len()).max().unwrap_or(0);
    let cell = keys + 1 + what;
    let columns = ((chars + 3) / (cell + 3)).clamp(1, HELP.len());
    let rows = HELP.len().div_ceil(columns);
    (0..rows)
        .map(|r| {
            let cells: Vec<String> = (0..columns)
                .filter_map(|c| HELP.get(c * rows + r))
                .map(|(k, w)| format!("{k:<keys$} {w:<what$}"))
                .collect();
            (cells.join("   ").trim_end().to_string(), [200, 210, 220])
        })
        .map(|(line, color)| {
            (
                format!("{line:<width$}", width = columns * (cell + 3) - 3),
                color,
            )
        })
        .collect()
}

/// `lines` broken at spaces (or mid-word when a word is longer) into lines of at
/// most `chars` characters, each keeping its colour.
#[must_use]
pub fn wrap(lines: &[(String, [u8; 3])], chars: usize) -> Vec<(String, [u8; 3])> {
    let mut out = Vec::new();
    for (line, color) in lines {
        let mut current = String::new();
        for word in line.split(' ') {
            let fits =
                current.chars().count() + usize::from(!current.is_empty()) + word.chars().count()
                    <= chars;
            if !fits && !current.is_empty() {
                out.push((std::mem::take(&mut current), *color));
            }
            if !current.is_empty() {
                current.push(' ');
            }
            current.push_str(word);
            while current.chars().count() > chars {
                let head: String = current.chars().take(chars).collect();
                current = current.chars().skip(chars).collect();
                out.push((head, *color));
            }
        }
        out.push((current, *color));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{Canvas, help_columns, wrap};
    use crate::app::keys::HELP;
    use crate::app::session::Overlay;

    #[test]
    fn the_shade_darkens_the_box_to_a_third_and_clips_at_the_frame() {
        let mut rgba = vec![90u8; 8 * 4 * 4];
        let mut canvas = Canvas {
            rgba: &mut rgba,
            width: 8,
            height: 4,
            bgra: false,
            scale: 2,
        };
        // From (5, 2), 6 wide and 6 high: clipped to pixels 5..8 of rows 2..4.
        canvas.shade(5, 2, 6, 6);
        canvas.shade(9, 0, 2, 2);
        for (i, px) in rgba.chunks_exact(4).enumerate() {
            let inside = i % 8 >= 5 && i / 8 >= 2;
            let c = if inside { 30 } else { 90 };
            assert_eq!(px, [c, c, c, 90], "pixel {i}: alpha untouched");
        }
    }

    #[test]
    fn text_takes_its_colour_in_the_frames_byte_order() {
        // The glyph's pixels all get the colour, in the frame's order.
        for (bgra, want) in [(false, [200, 100, 50]), (true, [50, 100, 200])] {
            let mut rgba = vec![0u8; 32 * 32 * 4];
            let mut canvas = Canvas {
                rgba: &mut rgba,
                width: 32,
                height: 32,
                bgra,
                scale: 2,
            };
            canvas.text(0, 0, "#", [200, 100, 50]);
            let lit: Vec<&[u8]> = rgba.chunks_exact(4).filter(|p| p[..3] != [0; 3]).collect();
            assert!(!lit.is_empty(), "the glyph shows");
            assert!(
                lit.iter().all(|p| p[..3] == want),
                "bgra {bgra}: {:?}",
                lit[0]
            );
        }
    }

    #[test]
    fn long_lines_wrap_at_spaces_and_keep_every_character() {
        let red = [255, 0, 0];
        let line = "config error: cradle.balls is 0; allowed: 1..=200".to_owned();
        let out = wrap(&[(line.clone(), red)], 20);
        assert!(
            out.iter()
                .all(|(l, c)| l.chars().count() <= 20 && *c == red),
            "{out:?}"
        );
        let joined: Vec<&str> = out.iter().map(|(l, _)| l.as_str()).collect();
        assert_eq!(joined.join(" "), line, "nothing lost");
        let long = wrap(&[("x".repeat(45), red)], 20);
        assert_eq!(
            long.iter().map(|(l, _)| l.len()).collect::<Vec<_>>(),
            [20, 20, 5]
        );
    }

    #[test]
    fn the_help_lists_every_entry_once_in_columns_that_fit() {
        for chars in [40, 100, 148, 300] {
            let lines = help_columns(chars);
            let text: String = lines
                .iter()
                .map(|(l, _)| l.as_str())
                .collect::<Vec<_>>()
                .join("\n");
            // Keys are padded to the longest, then one space, then what they do.
            let keys = HELP.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
            for (k, w) in HELP {
                let entry = format!("{k:<keys$} {w}");
                assert_eq!(text.matches(&entry).count(), 1, "{entry} once at {chars}");
            }
            let widest = lines
                .iter()
                .map(|(l, _)| l.chars().count())
                .max()
                .unwrap_or(0);
            assert!(widest <= chars.max(40), "{widest} > {chars}");
        }
        assert!(
            help_columns(148).len() < help_columns(40).len(),
            "wider: fewer rows"
        );
    }

    #[test]
    fn status_goes_top_left_help_and_notices_at_the_bottom() {
        let (w, h) = (1200, 600);
        let mut rgba = vec![0u8; w * h * 4];
        let mut canvas = Canvas {
            rgba: &mut rgba,
            width: w,
            height: h,
            bgra: false,
            scale: 2,
        };
        let overlay = Overlay {
            status: vec![("RUNNING".into(), [255; 3]), ("balls 5".into(), [255; 3])],
            help: true,
            notices: vec![("saved x.png".into(), [255; 3])],
        };
        let boxes = canvas.overlay(&overlay);
        assert_eq!(boxes.len(), 3);
        let (status, help, notice) = (boxes[0], boxes[1], boxes[2]);
        assert_eq!((status.0, status.1), (0, 0));
        assert_eq!(help.1 + help.3, h, "the help ends at the bottom edge");
        assert_eq!(notice.1 + notice.3, help.1, "the notice sits on the help");
        // The cradle is fitted between 12% and 88% of the height: the boxes
        // stay in those bands at this size.
        assert!(status.3 as f32 <= crate::scene::view::FIT_TOP * h as f32);
        assert!(help.1 as f32 >= crate::scene::view::FIT_BOTTOM * h as f32);
    }
}
