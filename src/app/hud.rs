//! The HUD: lines of text drawn into the CPU frame (so screenshots show it), with
//! an 8x8 bitmap font at 2x. A few hundred glyphs a frame: microseconds.

use font8x8::{BASIC_FONTS, UnicodeFonts};

/// Pixels per font pixel.
const SCALE: usize = 2;
/// Height of one text line in pixels.
pub const LINE: usize = 10 * SCALE;

/// An RGBA8 frame to draw into.
pub struct Canvas<'a> {
    /// Pixels, rows top to bottom.
    pub rgba: &'a mut [u8],
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
}

impl Canvas<'_> {
    /// Darkens a box behind the text so it reads on any background.
    pub fn shade(&mut self, x0: usize, y0: usize, w: usize, h: usize) {
        for y in y0..(y0 + h).min(self.height) {
            for x in x0..(x0 + w).min(self.width) {
                let i = (y * self.width + x) * 4;
                for c in &mut self.rgba[i..i + 3] {
                    *c /= 3;
                }
            }
        }
    }

    /// Draws `text` with its top-left corner at `(x, y)` in `color`; characters
    /// without a glyph are skipped, and whatever leaves the frame is clipped.
    pub fn text(&mut self, x: usize, y: usize, text: &str, color: [u8; 3]) {
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

    /// Draws lines of text in a shaded box at the top-left; returns the box height.
    pub fn panel(&mut self, y: usize, lines: &[(String, [u8; 3])]) -> usize {
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
        h
    }
}
