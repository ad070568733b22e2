//! An RGB image drawn in memory, with text in the 8×8 font: the legend
//! under a preview and the contact sheet are drawn on it.

use font8x8::legacy::BASIC_LEGACY;

/// A glyph's side, pixels (the 8×8 font, unscaled).
pub(crate) const GLYPH: u32 = 8;
/// Pixels of one text line: a glyph and its leading.
pub(crate) const LINE: u32 = GLYPH + 3;

/// An RGB image being drawn.
pub(crate) struct Canvas {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
    ink: [u8; 3],
}

impl Canvas {
    /// A `width × height` canvas of `background`, its text in `ink`.
    pub(crate) fn new(width: u32, height: u32, background: [u8; 3], ink: [u8; 3]) -> Canvas {
        let pixels = width as usize * height as usize;
        Canvas {
            width,
            height,
            rgb: background.repeat(pixels),
            ink,
        }
    }

    pub(crate) fn put(&mut self, x: u32, y: u32, colour: [u8; 3]) {
        if x < self.width && y < self.height {
            let at = 3 * (y as usize * self.width as usize + x as usize);
            self.rgb[at..at + 3].copy_from_slice(&colour);
        }
    }

    /// A `w × h` rectangle of `colour` with its top-left corner at `(x0, y0)`.
    pub(crate) fn fill(&mut self, x0: u32, y0: u32, w: u32, h: u32, colour: [u8; 3]) {
        for y in y0..y0.saturating_add(h) {
            for x in x0..x0.saturating_add(w) {
                self.put(x, y, colour);
            }
        }
    }

    /// An image `width` pixels wide (`rgb`, rows from the top) with its
    /// top-left corner at `(x0, y0)`.
    pub(crate) fn blit(&mut self, x0: u32, y0: u32, width: u32, rgb: &[u8]) {
        let row_bytes = 3 * width as usize;
        for (y, row) in rgb.chunks(row_bytes.max(1)).enumerate() {
            for (x, px) in row.chunks_exact(3).enumerate() {
                self.put(x0 + x as u32, y0 + y as u32, [px[0], px[1], px[2]]);
            }
        }
    }

    /// `text` in the 8×8 font, ASCII only (anything else is a `?`); what
    /// falls outside the canvas is left out.
    pub(crate) fn text(&mut self, x0: u32, y0: u32, text: &str) {
        for (i, c) in text.chars().enumerate() {
            let glyph = BASIC_LEGACY[if c.is_ascii() {
                c as usize
            } else {
                '?' as usize
            }];
            for (dy, bits) in glyph.iter().enumerate() {
                for dx in 0..8 {
                    // font8x8: bit 0 is the leftmost pixel of a row.
                    if bits & (1 << dx) != 0 {
                        self.put(x0 + i as u32 * GLYPH + dx, y0 + 1 + dy as u32, self.ink);
                    }
                }
            }
        }
    }

    /// Its width, height and pixels (rows from the top).
    pub(crate) fn into_parts(self) -> (u32, u32, Vec<u8>) {
        (self.width, self.height, self.rgb)
    }
}
