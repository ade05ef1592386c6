//! The HUD: lines of text drawn into the CPU frame (so screenshots show it), with
//! an 8x8 bitmap font at 2x. A few hundred glyphs a frame: microseconds.

use font8x8::{BASIC_FONTS, UnicodeFonts};

/// Pixels per font pixel.
const SCALE: usize = 2;
/// Height of one text line in pixels.
pub const LINE: usize = 10 * SCALE;

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
            let gx = x + n * 8 * SCALE;
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits & (1 << col) == 0 {
                        continue;
                    }
                    for dy in 0..SCALE {
                        for dx in 0..SCALE {
                            let (px, py) = (gx + col * SCALE + dx, y + row * SCALE + dy);
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

    /// Draws lines of text in a shaded box at the top-left, wrapped at the frame's
    /// width (a long config error keeps its allowed range); returns the box's
    /// width and height.
    pub fn panel(&mut self, y: usize, lines: &[(String, [u8; 3])]) -> (usize, usize) {
        let lines = wrap(lines, (self.width.saturating_sub(16) / (8 * SCALE)).max(8));
        let longest = lines
            .iter()
            .map(|(l, _)| l.chars().count())
            .max()
            .unwrap_or(0);
        let (w, h) = (longest * 8 * SCALE + 16, lines.len() * LINE + 8);
        self.shade(0, y, w, h);
        for (i, (line, color)) in lines.iter().enumerate() {
            self.text(8, y + 4 + i * LINE, line, *color);
        }
        (w, h)
    }
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
    use super::{Canvas, wrap};

    #[test]
    fn the_shade_darkens_the_box_to_a_third_and_clips_at_the_frame() {
        let mut rgba = vec![90u8; 8 * 4 * 4];
        let mut canvas = Canvas {
            rgba: &mut rgba,
            width: 8,
            height: 4,
            bgra: false,
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
}
