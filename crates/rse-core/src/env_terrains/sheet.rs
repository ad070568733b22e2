//! A contact sheet of a pool's current terrains: one top-down preview per
//! env in a grid, each labelled with its env id, episode and difficulty, on
//! one colour scale, or in a mix one scale per scheme (a 5 cm wall beside
//! 70 cm stairs would be one colour on theirs), and a legend of each scale
//! below.

use super::EnvTerrains;
use crate::Terrain;
use crate::canvas::{Canvas, GLYPH, LINE};
use crate::error::Error;
use crate::preview::{MAX_PIXELS, Preview, height_span, palette, render_span};

/// Pixels between tiles and around the sheet.
const GAP: u32 = 6;
/// The sheet's background and its text.
const BACKGROUND: [u8; 3] = [32, 32, 32];
const TEXT: [u8; 3] = [235, 235, 235];
/// A tile is at least this wide, so its label fits ("ep 123 D 0.444").
const MIN_TILE: u32 = 15 * GLYPH;

/// How to lay out a contact sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SheetOptions {
    /// Tiles per row; default `ceil(sqrt(n))`.
    pub cols: Option<u32>,
    /// Pixels per cell; default the fewest that make a tile at least
    /// 120 pixels wide (and at most 16).
    pub cell_pixels: Option<u32>,
    /// Every tile on one colour scale, whatever [`SheetTile::scale`] says:
    /// to compare heights across the schemes of a mix.
    pub one_scale: bool,
}

/// One tile of a contact sheet: a terrain and the two lines above it.
#[derive(Debug, Clone, Copy)]
pub struct SheetTile<'a> {
    /// The terrain drawn.
    pub terrain: &'a Terrain,
    /// The label's first line (e.g. `env 3`).
    pub title: &'a str,
    /// Its second line (e.g. `ep 2 D 0.500`).
    pub caption: &'a str,
    /// The colour scale it is drawn on, by name (a mix's scheme): tiles of
    /// one name share a scale from 0 to their highest cell, and the legend
    /// has a bar for each name. `None`: the sheet's common scale.
    pub scale: Option<&'a str>,
}

/// The contact sheet of envs `envs` of `pool` (every env when empty), in
/// the order given. Refused past [`MAX_PIXELS`] before anything is drawn.
pub fn contact_sheet(
    pool: &EnvTerrains,
    envs: &[usize],
    options: SheetOptions,
) -> Result<Preview, Error> {
    contact_sheet_named(pool, envs, options, &[])
}

/// [`contact_sheet`], each tile of a mix of schemes titled with its
/// scheme's name from `names` (in the mix's order; `scheme N`, from 1,
/// where a name is missing). A pool of one scheme shows no scheme.
pub fn contact_sheet_named(
    pool: &EnvTerrains,
    envs: &[usize],
    options: SheetOptions,
    names: &[String],
) -> Result<Preview, Error> {
    let all: Vec<usize>;
    let envs = if envs.is_empty() {
        all = (0..pool.num_envs()).collect();
        &all[..]
    } else {
        envs
    };
    let mixed = pool.schemes().len() > 1;
    let scheme_names: Vec<String> = (0..pool.schemes().len())
        .map(|j| {
            names
                .get(j)
                .cloned()
                .unwrap_or_else(|| format!("scheme {}", j + 1))
        })
        .collect();
    let labels: Vec<(String, String)> = envs
        .iter()
        .map(|&e| {
            let difficulty = pool.terrain(e).difficulty().get();
            let title = if mixed {
                format!("env {e} {}", scheme_names[pool.scheme_index(e)])
            } else {
                format!("env {e}")
            };
            (title, format!("ep {} D {difficulty:.3}", pool.episode(e)))
        })
        .collect();
    let tiles: Vec<SheetTile<'_>> = envs
        .iter()
        .zip(&labels)
        .map(|(&e, (title, caption))| SheetTile {
            terrain: pool.terrain(e),
            title,
            caption,
            scale: mixed.then(|| scheme_names[pool.scheme_index(e)].as_str()),
        })
        .collect();
    tiles_sheet(&tiles, options)
}

/// A contact sheet of any terrains, each with its label, in the order
/// given, each on its colour scale ([`SheetTile::scale`]; one for all with
/// [`SheetOptions::one_scale`]): from 0 to the highest cell of the tiles on
/// it, in metres (each terrain's steps mapped onto it), with a legend bar
/// per scale. Terrains of other grids are drawn at the same pixels per
/// cell, in tiles as large as the largest. Refused past [`MAX_PIXELS`]
/// before anything is drawn.
pub fn tiles_sheet(tiles: &[SheetTile<'_>], options: SheetOptions) -> Result<Preview, Error> {
    let scales = Scales::of(tiles, options.one_scale);
    let n = tiles.len() as u64;
    let widest = tiles.iter().map(|t| t.terrain.grid().nx).max().unwrap_or(1);
    let cols = u64::from(options.cols.unwrap_or(0));
    let cols = if cols == 0 {
        n.isqrt() + u64::from(n.isqrt().pow(2) < n)
    } else {
        cols
    }
    .max(1);
    let rows = n.div_ceil(cols).max(1);
    let cp = options
        .cell_pixels
        .unwrap_or_else(|| MIN_TILE.div_ceil(widest.max(1)).clamp(1, 16))
        .max(1);
    let (tile_w, tile_h) = tiles.iter().fold((0u64, 0u64), |(w, h), t| {
        let grid = t.terrain.grid();
        (
            w.max(u64::from(grid.nx) * u64::from(cp)),
            h.max(u64::from(grid.ny) * u64::from(cp)),
        )
    });
    let label_h = u64::from(2 * LINE);
    let (cell_w, cell_h) = (tile_w.max(u64::from(MIN_TILE)), tile_h + label_h);
    let gap = u64::from(GAP);
    let width = gap + cols * (cell_w + gap);
    // The legend: a line per scale and one of leading.
    let legend_h = (scales.names.len() as u64 + 1) * u64::from(LINE);
    let height = gap + rows * (cell_h + gap) + legend_h + gap;
    if width.saturating_mul(height) > MAX_PIXELS {
        return Err(Error::SheetTooLarge {
            width,
            height,
            cols,
            cell_pixels: u64::from(cp),
            max: MAX_PIXELS,
        });
    }
    // Within MAX_PIXELS (2²⁸), so every coordinate fits a u32.
    let mut sheet = Canvas::new(width as u32, height as u32, BACKGROUND, TEXT);
    let glyphs = (cell_w / u64::from(GLYPH)) as usize;
    for (i, tile) in tiles.iter().enumerate() {
        let (col, row) = (i as u64 % cols, i as u64 / cols);
        let x0 = (gap + col * (cell_w + gap)) as u32;
        let y0 = (gap + row * (cell_h + gap)) as u32;
        sheet.text(x0, y0, &clip(tile.title, glyphs));
        sheet.text(x0, y0 + LINE, &clip(tile.caption, glyphs));
        // This terrain's steps that reach its scale's top (rounded).
        let hi = steps_to(scales.top[scales.of_tile[i]], tile.terrain.step_height());
        let tile_image = render_span(tile.terrain, cp, (0, hi));
        sheet.blit(x0, y0 + 2 * LINE, tile_image.width, &tile_image.rgb);
    }
    let legend_y = (gap + rows * (cell_h + gap)) as u32;
    let named = scales.names.len() > 1;
    // Names padded to the longest, so that the bars line up.
    let longest = scales
        .names
        .iter()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(0);
    for (k, name) in scales.names.iter().enumerate() {
        let label = if named {
            format!("{:<width$}", format!("{name}:"), width = longest + 2)
        } else {
            String::new()
        };
        legend(
            &mut sheet,
            GAP,
            legend_y + k as u32 * LINE,
            &label,
            scales.top[k],
            scales.step[k],
        );
    }
    let (width, height, rgb) = sheet.into_parts();
    Ok(Preview { width, height, rgb })
}

/// The colour scales of a sheet's tiles: each scale's name (in the order
/// of its first tile), top (metres: its tiles' highest cell) and step
/// height where all its tiles share one, and each tile's scale.
struct Scales<'a> {
    names: Vec<&'a str>,
    top: Vec<f64>,
    step: Vec<Option<f64>>,
    of_tile: Vec<usize>,
}

impl<'a> Scales<'a> {
    fn of(tiles: &[SheetTile<'a>], one_scale: bool) -> Scales<'a> {
        let mut scales = Scales {
            names: Vec::new(),
            top: Vec::new(),
            step: Vec::new(),
            of_tile: Vec::with_capacity(tiles.len()),
        };
        for tile in tiles {
            let name = if one_scale {
                ""
            } else {
                tile.scale.unwrap_or("")
            };
            let k = scales
                .names
                .iter()
                .position(|&n| n == name)
                .unwrap_or_else(|| {
                    scales.names.push(name);
                    scales.top.push(0.0);
                    scales.step.push(Some(tile.terrain.step_height()));
                    scales.names.len() - 1
                });
            let step = tile.terrain.step_height();
            let top = f64::from(height_span(tile.terrain).1) * step;
            scales.top[k] = scales.top[k].max(top);
            if scales.step[k].is_some_and(|s| s.to_bits() != step.to_bits()) {
                scales.step[k] = None;
            }
            scales.of_tile.push(k);
        }
        if scales.names.is_empty() {
            // No tile: the legend still shows an empty scale.
            scales.names.push("");
            scales.top.push(0.0);
            scales.step.push(None);
        }
        scales
    }
}

/// `metres` in steps of `step` metres, rounded, within `u16`.
fn steps_to(metres: f64, step: f64) -> u16 {
    if step > 0.0 {
        (metres / step).round().clamp(0.0, f64::from(u16::MAX)) as u16
    } else {
        0
    }
}

/// `text` cut to `glyphs` characters, its end marked with `~` when cut.
fn clip(text: &str, glyphs: usize) -> String {
    if text.chars().count() <= glyphs {
        return text.to_owned();
    }
    let mut cut: String = text.chars().take(glyphs.saturating_sub(1)).collect();
    cut.push('~');
    cut
}

/// The colour scale from 0 to `hi_m` metres, as a bar and its ends (in
/// steps too where every terrain on it has the same step height, `step`),
/// after `label`.
fn legend(sheet: &mut Canvas, x0: u32, y0: u32, label: &str, hi_m: f64, step: Option<f64>) {
    {
        sheet.text(x0, y0, label);
        let x0 = x0 + label.chars().count() as u32 * GLYPH;
        let bar = 120;
        // The bar's colours in steps of the scale: the common step, else
        // millimetres.
        let unit = step.unwrap_or(0.001);
        let hi = steps_to(hi_m, unit);
        for x in 0..bar {
            // Equal lengths of bar for the heights 0 … hi.
            let h = ((u32::from(hi) + 1) * x / bar).min(u32::from(hi)) as u16;
            for y in 0..GLYPH {
                sheet.put(x0 + x, y0 + 1 + y, palette(h, 0, hi));
            }
        }
        let mm = hi_m * 1000.0;
        let text = match step {
            Some(_) => format!("0 .. {hi} steps (0 .. {mm:.0} mm)"),
            None => format!("0 .. {mm:.0} mm"),
        };
        sheet.text(x0 + bar + GLYPH, y0, &text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{EnvRequest, Scheme};

    fn pool(n: usize) -> EnvTerrains {
        let scheme = Scheme::from_csv("# size: 20x10\ntype,height\nrandom,3\n", None).unwrap();
        let options = EnvRequest {
            num_envs: n,
            difficulty: Some(crate::Difficulty::new(0.5).unwrap()),
            ..EnvRequest::default()
        }
        .resolve(&scheme)
        .unwrap();
        EnvTerrains::new(scheme, options).unwrap()
    }

    #[test]
    fn tiles_are_the_terrains_on_one_scale_in_a_grid() {
        let pool = pool(5);
        let sheet = contact_sheet(&pool, &[], SheetOptions::default()).unwrap();
        // 5 envs: 3 columns, 2 rows; 20 cells × 6 px = 120 px tiles.
        let cell_w = 120;
        assert_eq!(sheet.width, GAP + 3 * (cell_w + GAP));
        let hi = (0..5)
            .map(|e| height_span(pool.terrain(e)).1)
            .max()
            .unwrap();
        let tile = render_span(pool.terrain(4), 6, (0, hi));
        // Env 4: column 1, row 1.
        let (x0, y0) = (
            GAP + cell_w + GAP,
            GAP + (10 * 6 + 2 * LINE) + GAP + 2 * LINE,
        );
        for y in 0..tile.height {
            let at = |img: &[u8], w: u32, x: u32, y: u32| {
                let i = 3 * (y * w + x) as usize;
                [img[i], img[i + 1], img[i + 2]]
            };
            for x in 0..tile.width {
                assert_eq!(
                    at(&sheet.rgb, sheet.width, x0 + x, y0 + y),
                    at(&tile.rgb, tile.width, x, y)
                );
            }
        }
    }

    fn terrain_of(csv: &str) -> Terrain {
        let scheme = Scheme::from_csv(csv, None).unwrap();
        crate::generate_at(&scheme, 1, 0, crate::Difficulty::FULL)
    }

    /// The pixel at `(x, y)` of an RGB image `width` wide.
    fn pixel(rgb: &[u8], width: u32, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y * width + x) as usize;
        [rgb[i], rgb[i + 1], rgb[i + 2]]
    }

    #[test]
    fn each_scheme_of_a_mix_is_drawn_on_its_own_scale_unless_one_is_asked() {
        let low = terrain_of("# size: 20x10\n# step_height: 0.05\ntype,height\nrandom,2\n");
        let high = terrain_of("# size: 20x10\n# step_height: 0.05\ntype,height\nrandom,14\n");
        let tiles = [
            SheetTile {
                terrain: &low,
                title: "env 0 walls",
                caption: "",
                scale: Some("walls"),
            },
            SheetTile {
                terrain: &high,
                title: "env 1 stairs",
                caption: "",
                scale: Some("stairs"),
            },
        ];
        let top = |t: &Terrain| height_span(t).1;
        let (x0, y0) = (GAP, GAP + 2 * LINE);
        for one_scale in [false, true] {
            let options = SheetOptions {
                cols: Some(2),
                one_scale,
                ..SheetOptions::default()
            };
            let sheet = tiles_sheet(&tiles, options).unwrap();
            let hi = if one_scale { top(&high) } else { top(&low) };
            let drawn = render_span(&low, 6, (0, hi));
            for y in 0..drawn.height {
                for x in 0..drawn.width {
                    assert_eq!(
                        pixel(&sheet.rgb, sheet.width, x0 + x, y0 + y),
                        pixel(&drawn.rgb, drawn.width, x, y),
                        "one_scale {one_scale}"
                    );
                }
            }
            // A legend line per scale.
            let lines = if one_scale { 1 } else { 2 };
            assert_eq!(
                sheet.height,
                GAP + (10 * 6 + 2 * LINE) + GAP + (lines + 1) * LINE + GAP
            );
        }
        assert!(top(&low) < top(&high));
    }

    #[test]
    fn a_sheet_too_large_is_refused() {
        let pool = pool(2);
        let options = SheetOptions {
            cell_pixels: Some(100_000),
            ..SheetOptions::default()
        };
        assert!(matches!(
            contact_sheet(&pool, &[], options),
            Err(Error::SheetTooLarge { .. })
        ));
    }
}
