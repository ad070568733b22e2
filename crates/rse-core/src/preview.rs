//! The top-down preview of paper §3.1: blue (lowest) → green → red (highest).

use crate::canvas::{Canvas, GLYPH, LINE};
use crate::error::Error;
use crate::png_rows;
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
///
/// # Panics
/// Never: drawing into memory cannot fail.
pub fn render(terrain: &Terrain, cell_pixels: u32) -> Preview {
    render_span(terrain, cell_pixels, height_span(terrain))
}

/// [`render`] with colours spanning heights `lo..=hi` (steps) instead of
/// the terrain's own: several terrains side by side on one scale.
///
/// # Panics
/// Never: drawing into memory cannot fail.
pub fn render_span(terrain: &Terrain, cell_pixels: u32, (lo, hi): (u16, u16)) -> Preview {
    let grid = terrain.grid();
    let cp = cell_pixels.max(1);
    let (width, height) = (grid.nx * cp, grid.ny * cp);
    let mut rgb = Vec::with_capacity(width as usize * height as usize * 3);
    for_each_row(terrain, cp, (lo, hi), &mut |row| {
        rgb.extend_from_slice(row);
        Ok(())
    })
    .expect("drawing into memory cannot fail");
    Preview { width, height, rgb }
}

/// The lowest and highest cell of `terrain` that is not frame, in steps
/// (`(u16::MAX, 0)` when every cell is frame).
pub fn height_span(terrain: &Terrain) -> (u16, u16) {
    heights_span(terrain.heightmap(), &terrain.grid())
}

/// [`height_span`] of heights `map` on `grid` (a world's `heightmap.csv`
/// read back, its record's grid).
pub fn heights_span(map: &crate::Heightmap, grid: &crate::Grid) -> (u16, u16) {
    let (mut lo, mut hi) = (u16::MAX, 0u16);
    for y in 0..grid.ny {
        for (x, &h) in map.row(y).iter().enumerate() {
            if !grid.is_frame(x as u32, y) {
                lo = lo.min(h);
                hi = hi.max(h);
            }
        }
    }
    (lo, hi)
}

/// Gives `emit` every pixel row of [`render_span`]'s image, from the top.
fn for_each_row(
    terrain: &Terrain,
    cell_pixels: u32,
    (lo, hi): (u16, u16),
    emit: &mut dyn FnMut(&[u8]) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let grid = terrain.grid();
    let map = terrain.heightmap();
    let cp = cell_pixels.max(1);
    let darker = |c: u8| c - c / 4;
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
            emit(if edge_row { &edge_line } else { &line })?;
        }
    }
    Ok(())
}

/// The PNG of `terrain` with `cell_pixels` pixels per cell (default:
/// [`auto_cell_pixels`]) and its legend under it ([`legend`]), refused
/// past [`MAX_PIXELS`] before anything is drawn: what a world's
/// `preview.png`, `rse-gen preview`, and Python's `Terrain.preview()` hold.
/// The map's rows are those of [`render`], written row by row without the
/// image in memory.
pub fn png(terrain: &Terrain, cell_pixels: Option<u32>) -> Result<Vec<u8>, Error> {
    let grid = terrain.grid();
    let cell_pixels = cell_pixels.unwrap_or_else(|| auto_cell_pixels(grid.nx, grid.ny));
    validate_size(grid.nx, grid.ny, cell_pixels)?;
    let cp = cell_pixels.max(1);
    let (width, height) = (grid.nx * cp, grid.ny * cp);
    let legend = legend(terrain, width);
    Ok(png_rows::encode(width, height + legend.height, |emit| {
        for_each_row(terrain, cp, height_span(terrain), emit)?;
        let row_bytes = 3 * width as usize;
        legend.rgb.chunks(row_bytes.max(1)).try_for_each(emit)
    })?)
}

/// The legend's background and text: the editor's page and ink.
const LEGEND_BACKGROUND: [u8; 3] = [246, 244, 240];
const LEGEND_INK: [u8; 3] = [34, 34, 34];
/// Pixels around the legend's lines.
const LEGEND_MARGIN: u32 = 4;
/// Heights a legend names at most (every one when there are fewer).
const LEGEND_HEIGHTS: u32 = 7;

/// The heights a legend of `lo..=hi` names: every height when there are at
/// most seven, else seven spread evenly from `lo` to `hi`
/// (the editor's page names the same).
pub fn legend_heights(lo: u16, hi: u16) -> Vec<u16> {
    if hi < lo {
        return Vec::new();
    }
    let span = u32::from(hi - lo);
    if span < LEGEND_HEIGHTS {
        return (lo..=hi).collect();
    }
    (0..LEGEND_HEIGHTS)
        .map(|i| {
            // Rounded to the nearest, halves up, in whole numbers.
            let at = (2 * span * i + (LEGEND_HEIGHTS - 1)) / (2 * (LEGEND_HEIGHTS - 1));
            lo + at as u16
        })
        .collect()
}

/// The legend drawn under a `width`-pixel preview of `terrain`: each
/// height of [`legend_heights`] as its colour and "N steps, X m", and the
/// pallet frames' wood where there are frames, in lines as wide as the
/// map (an item wider than the map is cut at its edge).
pub fn legend(terrain: &Terrain, width: u32) -> Preview {
    let (lo, hi) = height_span(terrain);
    let step = terrain.step_height();
    let mut items: Vec<([u8; 3], String)> = legend_heights(lo, hi)
        .into_iter()
        .map(|h| {
            let metres = (f64::from(h) * step * 1e4).round() / 1e4;
            let unit = if h == 1 { "step" } else { "steps" };
            (palette(h, lo, hi), format!("{h} {unit}, {metres} m"))
        })
        .collect();
    if terrain.grid().frame_period.is_some() {
        items.push((FRAME_RGB, "pallet frame".to_owned()));
    }
    // Each item's place: a swatch, a space, its words, then a space.
    let item_width = |text: &str| (text.chars().count() as u32 + 3) * GLYPH;
    let mut places = Vec::with_capacity(items.len());
    let (mut x, mut line) = (LEGEND_MARGIN, 0u32);
    for (_, text) in &items {
        let w = item_width(text);
        if x > LEGEND_MARGIN && x + w > width {
            x = LEGEND_MARGIN;
            line += 1;
        }
        places.push((x, line));
        x += w;
    }
    let lines = if items.is_empty() { 0 } else { line + 1 };
    let height = 2 * LEGEND_MARGIN + lines * LINE;
    let mut canvas = Canvas::new(width, height, LEGEND_BACKGROUND, LEGEND_INK);
    for ((colour, text), (x, line)) in items.iter().zip(places) {
        let y = LEGEND_MARGIN + line * LINE;
        canvas.fill(x, y + 1, GLYPH, GLYPH, LEGEND_INK);
        canvas.fill(x + 1, y + 2, GLYPH - 2, GLYPH - 2, *colour);
        canvas.text(x + 2 * GLYPH, y, text);
    }
    let (width, height, rgb) = canvas.into_parts();
    Preview { width, height, rgb }
}

/// Encodes a preview as PNG bytes: `png`'s encoder at `Compression::Fast`
/// (previews are flat colour blocks: the fast deflate packs them nearly as
/// well as the default, several times faster).
pub fn encode_png(preview: &Preview) -> Result<Vec<u8>, Error> {
    let row_bytes = preview.width as usize * 3;
    Ok(png_rows::encode(preview.width, preview.height, |emit| {
        preview
            .rgb
            .chunks(row_bytes.max(1))
            .try_for_each(&mut *emit)
    })?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `preview.png` is the map, then its legend: every height of a few
    /// named, seven of many, from the lowest to the highest, as the
    /// editor's page names them.
    #[test]
    fn the_png_is_the_map_then_its_legend() {
        assert_eq!(legend_heights(2, 4), vec![2, 3, 4]);
        assert_eq!(legend_heights(0, 40), vec![0, 7, 13, 20, 27, 33, 40]);
        assert_eq!(legend_heights(5, 4), Vec::<u16>::new());
        let scheme =
            crate::Scheme::from_csv("# size: 30x20\ntype,height\nrandom,40\n", None).unwrap();
        let terrain = crate::generate(&scheme, 1, 0);
        let png = png(&terrain, Some(4)).unwrap();
        let decoder = ::png::Decoder::new(std::io::Cursor::new(&png));
        let mut reader = decoder.read_info().unwrap();
        let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut rgb).unwrap();
        let map = render(&terrain, 4);
        let legend = legend(&terrain, 120);
        assert_eq!((info.width, info.height), (120, 80 + legend.height));
        assert_eq!(&rgb[..map.rgb.len()], &map.rgb[..], "the map on top");
        assert_eq!(
            &rgb[map.rgb.len()..info.buffer_size()],
            &legend.rgb[..],
            "the legend under it"
        );
        // Seven heights, wrapped to the map's width: more than one line.
        assert!(
            legend.height > 2 * LEGEND_MARGIN + LINE,
            "{}",
            legend.height
        );
    }

    #[test]
    fn previews_are_the_png_crates_bytes() {
        let samples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../schemes/");
        for name in ["nist_hill", "six_obstacles", "paper_pallets", "random"] {
            let scheme = crate::Scheme::load(format!("{samples}{name}.csv")).unwrap();
            let terrain = crate::generate(&scheme, 3, 1);
            for cell_pixels in [None, Some(1), Some(3), Some(4), Some(9)] {
                let map = render(
                    &terrain,
                    cell_pixels
                        .unwrap_or_else(|| auto_cell_pixels(terrain.grid().nx, terrain.grid().ny)),
                );
                // The map, then its legend.
                let under = legend(&terrain, map.width);
                let image = Preview {
                    width: map.width,
                    height: map.height + under.height,
                    rgb: [map.rgb, under.rgb].concat(),
                };
                let reference = crate::png_rows::png_crate(image.width, image.height, &image.rgb);
                assert_eq!(
                    png(&terrain, cell_pixels).unwrap(),
                    reference,
                    "{name} {cell_pixels:?}"
                );
                assert_eq!(
                    encode_png(&image).unwrap(),
                    reference,
                    "{name} {cell_pixels:?}"
                );
            }
        }
    }

    #[test]
    fn palette_runs_blue_green_red() {
        assert_eq!(palette(0, 0, 4), [0, 0, 255]);
        assert_eq!(palette(2, 0, 4), [0, 255, 0]);
        assert_eq!(palette(4, 0, 4), [255, 0, 0]);
        assert_eq!(palette(3, 3, 3), [0, 0, 255]);
    }
}
