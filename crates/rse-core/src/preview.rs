//! The top-down preview of paper §3.1: blue (lowest) → green → red (highest).

use crate::error::Error;
use crate::terrain::Terrain;

/// Colour of pallet frame cells: wood, outside the blue–green–red palette so
/// frames stand out from 1-step blocks.
pub const FRAME_RGB: [u8; 3] = [150, 111, 71];

/// An RGB image, rows from the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Preview {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width·height` pixels of 3 bytes, row by row from the top.
    pub rgb: Vec<u8>,
}

/// The largest preview drawn, pixels (about 800 MB of RGB): a
/// 10000×10000 grid at 256 pixels per cell once tried to allocate 19.6 TB
/// and aborted.
pub const MAX_PIXELS: u64 = 1 << 28;

/// Refuses a preview of an `nx × ny` grid at `cell_pixels` larger than
/// [`MAX_PIXELS`], before anything is drawn.
pub fn validate_size(nx: u32, ny: u32, cell_pixels: u32) -> Result<(), Error> {
    let (width, height) = (
        u64::from(nx) * u64::from(cell_pixels),
        u64::from(ny) * u64::from(cell_pixels),
    );
    if width.saturating_mul(height) > MAX_PIXELS {
        return Err(Error::PreviewTooLarge {
            width,
            height,
            max: MAX_PIXELS,
        });
    }
    Ok(())
}

/// Pixels per cell that make a preview about 512 pixels wide (1 to 32).
pub fn auto_cell_pixels(nx: u32, ny: u32) -> u32 {
    (512 / nx.max(ny).max(1)).clamp(1, 32)
}

/// Colour of height `h` where the map spans `lo..=hi` (integer maths, so the
/// same on every machine).
pub fn palette(h: u16, lo: u16, hi: u16) -> [u8; 3] {
    let t = if hi > lo {
        u32::from(h.saturating_sub(lo)) * 510 / u32::from(hi - lo)
    } else {
        0
    };
    if t <= 255 {
        [0, t as u8, (255 - t) as u8]
    } else {
        [(t - 255) as u8, (510 - t) as u8, 0]
    }
}

/// Draws `terrain` seen from above, +x to the right and +y up (north up), with
/// `cell_pixels` pixels per cell. From 4 pixels per cell on, each cell's
/// right and bottom pixel lines are darker so every block reads on its own.
/// Colours span the lowest to the highest cell that is not frame.
pub fn render(terrain: &Terrain, cell_pixels: u32) -> Preview {
    let grid = terrain.grid();
    let map = terrain.heightmap();
    let cp = cell_pixels.max(1);
    let (mut lo, mut hi) = (u16::MAX, 0u16);
    for y in 0..grid.ny {
        for (x, &h) in map.row(y).iter().enumerate() {
            if !grid.is_frame(x as u32, y) {
                lo = lo.min(h);
                hi = hi.max(h);
            }
        }
    }
    let (width, height) = (grid.nx * cp, grid.ny * cp);
    let darker = |c: u8| c - c / 4;
    let mut rgb = Vec::with_capacity(width as usize * height as usize * 3);
    // Every pixel row of a cell row is the same line, but for the darker
    // edge row at the bottom: build the two lines once per cell row.
    let (mut line, mut edge_line) = (Vec::new(), Vec::new());
    for y in (0..grid.ny).rev() {
        line.clear();
        edge_line.clear();
        for x in 0..grid.nx {
            let colour = if grid.is_frame(x, y) {
                FRAME_RGB
            } else {
                palette(map.get(x, y), lo, hi)
            };
            for column in 0..cp {
                let edge = cp >= 4 && column == cp - 1;
                line.extend(if edge { colour.map(darker) } else { colour });
                edge_line.extend(colour.map(darker));
            }
        }
        for row in 0..cp {
            let edge_row = cp >= 4 && row == cp - 1;
            rgb.extend_from_slice(if edge_row { &edge_line } else { &line });
        }
    }
    Preview { width, height, rgb }
}

/// The PNG of `terrain` with `cell_pixels` pixels per cell (default:
/// [`auto_cell_pixels`]), refused past [`MAX_PIXELS`] before anything is
/// drawn: what a world's `preview.png`, `rse-gen preview`, the editor and
/// Python's `Terrain.preview()` hold.
pub fn png(terrain: &Terrain, cell_pixels: Option<u32>) -> Result<Vec<u8>, Error> {
    let grid = terrain.grid();
    let cell_pixels = cell_pixels.unwrap_or_else(|| auto_cell_pixels(grid.nx, grid.ny));
    validate_size(grid.nx, grid.ny, cell_pixels)?;
    encode_png(&render(terrain, cell_pixels))
}

/// Encodes a preview as PNG bytes.
pub fn encode_png(preview: &Preview) -> Result<Vec<u8>, Error> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, preview.width, preview.height);
    // Previews are flat colour blocks: the fast deflate packs them nearly as
    // well as the default, several times faster (a batch writes thousands).
    encoder.set_compression(png::Compression::Fast);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&preview.rgb)?;
    writer.finish()?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_runs_blue_green_red() {
        assert_eq!(palette(0, 0, 4), [0, 0, 255]);
        assert_eq!(palette(2, 0, 4), [0, 255, 0]);
        assert_eq!(palette(4, 0, 4), [255, 0, 0]);
        assert_eq!(palette(3, 3, 3), [0, 0, 255]);
    }
}
