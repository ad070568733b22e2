//! A terrain as a MuJoCo height field: `k` samples per cell along each
//! axis, placed inside the cells so that every sample has its cell's exact
//! top (docs/schemes.md, "Height fields").
//!
//! MuJoCo's layout: samples row by row, row 0 at the lowest y, column 0 at
//! the lowest x; the field spans `[-radius_x, radius_x] × [-radius_y,
//! radius_y]` around its geom, a sample `v ∈ [0, 1]` standing at
//! `v · elevation` above the geom, and a box reaches `base` below it.
//! MuJoCo rescales the samples it reads from a file or an MJCF attribute to
//! span exactly `[0, 1]`, so [`HField`] always spans `[0, 1]` (or is all 0
//! on a flat terrain) and puts its geom at the lowest top.

use crate::globals::Grid;
use crate::terrain::Terrain;

/// At most this many samples (`nx·ny·k²`): 2^27 float32 are 512 MiB.
pub const MAX_HFIELD_SAMPLES: u64 = 1 << 27;

/// Samples per cell along each axis when none is asked for: every front
/// end's default (`rse-gen hfield`, `--mujoco-collider hfield`, Python's
/// `Terrain.hfield`). Four keeps a step edge within an eighth of a cell.
pub const DEFAULT_OVERSAMPLE: u32 = 4;

/// A terrain's height field, ready for MuJoCo.
#[derive(Debug, Clone, PartialEq)]
pub struct HField {
    /// Samples along y (MuJoCo's `nrow`): `ny·k`.
    pub nrow: u32,
    /// Samples along x (MuJoCo's `ncol`): `nx·k`.
    pub ncol: u32,
    /// `nrow·ncol` samples in `[0, 1]`, row by row from the lowest y.
    pub data: Vec<f32>,
    /// MuJoCo's `size`: `[radius_x, radius_y, elevation, base]`, metres.
    pub size: [f64; 4],
    /// Where the hfield geom goes, metres: the grid's centre in x and y, the
    /// lowest top in z.
    pub pos: [f64; 3],
}

/// Why a height field cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum HFieldError {
    /// `oversample` is 0, or gives more samples than [`MAX_HFIELD_SAMPLES`].
    #[error("oversample {oversample}: {reason}")]
    Oversample {
        /// What was asked.
        oversample: u32,
        /// Why it cannot be.
        reason: String,
    },
    /// A buffer of the wrong length.
    #[error(
        "the buffer holds {found} samples, but the height field has {nrow}x{ncol} = {expected}"
    )]
    Buffer {
        /// Rows of the field.
        nrow: u32,
        /// Columns of the field.
        ncol: u32,
        /// `nrow·ncol`.
        expected: usize,
        /// The buffer's length.
        found: usize,
    },
    /// Tops that do not fit the range a live height field was built for.
    #[error(
        "the terrain's tops run from {lowest} m to {highest} m, but the height field covers {from} m to {to} m; build it with a larger elevation (or place its geom lower)"
    )]
    OutOfRange {
        /// Lowest top, metres.
        lowest: f64,
        /// Highest top, metres.
        highest: f64,
        /// The field's lowest surface, metres.
        from: f64,
        /// The field's highest surface, metres.
        to: f64,
    },
}

impl Terrain {
    /// `(nrow, ncol)` of the height field with `oversample` samples per
    /// cell along each axis; refused for 0, for more than
    /// [`MAX_HFIELD_SAMPLES`], and for fewer than 2 samples along an axis
    /// (MuJoCo needs 2).
    pub fn hfield_shape(&self, oversample: u32) -> Result<(u32, u32), HFieldError> {
        hfield_shape_of(self.grid(), oversample)
    }

    /// The height field with `oversample` (k) samples per cell along each
    /// axis. Sample `j` of a cell sits `(j + ½)/k` of the way across it, so
    /// every sample has its cell's top and MuJoCo's surface is exact except
    /// within half a sample spacing (`S/2k`) of a step edge or of the grid's
    /// border.
    pub fn hfield(&self, oversample: u32) -> Result<HField, HFieldError> {
        let mut hfield = self.hfield_layout(oversample)?;
        let (lowest, elevation) = (hfield.pos[2], hfield.size[2]);
        hfield.data = vec![0.0f32; hfield.nrow as usize * hfield.ncol as usize];
        self.fill_hfield(oversample, lowest, elevation, &mut hfield.data);
        Ok(hfield)
    }

    /// [`Terrain::hfield`] without its samples (`data` empty): the shape,
    /// `size` and `pos`. With [`Terrain::hfield_into`]`(k, pos[2], size[2],
    /// buffer)` it fills a caller's buffer with the same samples.
    pub fn hfield_layout(&self, oversample: u32) -> Result<HField, HFieldError> {
        let (nrow, ncol) = self.hfield_shape(oversample)?;
        let (lowest, highest) = self.top_range(oversample);
        // A flat terrain: all samples 0, any positive elevation.
        let elevation = if highest <= lowest {
            self.step_height()
        } else {
            highest - lowest
        };
        let grid = self.grid();
        let s = self.block_size();
        let spacing = s / f64::from(oversample);
        let (width, depth) = (f64::from(grid.nx) * s, f64::from(grid.ny) * s);
        // Below the lowest top down to the ground, or a step's depth when
        // the lowest top is the ground.
        let base = if lowest > 0.0 {
            lowest
        } else {
            self.step_height()
        };
        let (size, pos) = field_geometry(width, depth, spacing, elevation, base, lowest);
        Ok(HField {
            nrow,
            ncol,
            data: Vec::new(),
            size,
            pos,
        })
    }

    /// Writes the samples into `out` (`nrow·ncol` long) for a live height
    /// field whose geom surface is `z0` at 0 and `z0 + elevation` at 1:
    /// `(top − z0) / elevation` per sample. Refused when a top falls
    /// outside that range or `out` has another length; nothing is written
    /// then.
    pub fn hfield_into(
        &self,
        oversample: u32,
        z0: f64,
        elevation: f64,
        out: &mut [f32],
    ) -> Result<(), HFieldError> {
        let (nrow, ncol) = self.hfield_shape(oversample)?;
        let expected = nrow as usize * ncol as usize;
        if out.len() != expected {
            return Err(HFieldError::Buffer {
                nrow,
                ncol,
                expected,
                found: out.len(),
            });
        }
        let (lowest, highest) = self.top_range(oversample);
        // A micrometre of slack: z0 and elevation come back from f32 and
        // from sums of f64.
        let slack = 1e-6;
        let fits = elevation > 0.0 && lowest >= z0 - slack && highest <= z0 + elevation + slack;
        if !fits {
            return Err(HFieldError::OutOfRange {
                lowest,
                highest,
                from: z0,
                to: z0 + elevation,
            });
        }
        self.fill_hfield(oversample, z0, elevation, out);
        Ok(())
    }

    /// Lowest and highest sample of the field with `k` samples a cell,
    /// metres: the cells' tops, and a ramp's plane at its highest sample
    /// (half a sample below its top edge).
    fn top_range(&self, k: u32) -> (f64, f64) {
        let map = self.heightmap();
        let (lo, hi) = map
            .cells()
            .iter()
            .fold((u16::MAX, 0u16), |(lo, hi), &h| (lo.min(h), hi.max(h)));
        let top = |h: u16| self.base() + f64::from(h) * self.step_height();
        let ramps = self.ramps().iter().map(|r| {
            let samples = f64::from(r.run()) * f64::from(k);
            self.base() + f64::from(r.rise) * self.step_height() * (samples - 0.5) / samples
        });
        (top(lo.min(hi)), ramps.fold(top(hi), f64::max))
    }

    /// `out[r·ncol + c] = (top of the cell under sample (r, c) − z0) / elevation`,
    /// clamped to `[0, 1]`.
    fn fill_hfield(&self, k: u32, z0: f64, elevation: f64, out: &mut [f32]) {
        let ncol = self.heightmap().nx() as usize * k as usize;
        self.fill_hfield_rows(k, z0, elevation, out, ncol);
    }

    /// [`fill_hfield`](Self::fill_hfield) into rows `stride` samples apart:
    /// sample `(r, c)` at `out[r·stride + c]`, the rest of each row
    /// untouched (a tile of a larger field).
    pub(crate) fn fill_hfield_rows(
        &self,
        k: u32,
        z0: f64,
        elevation: f64,
        out: &mut [f32],
        stride: usize,
    ) {
        let map = self.heightmap();
        let (k, nx) = (k as usize, map.nx() as usize);
        let ncol = nx * k;
        // Heights in steps are few and repeat a lot: each sample value is
        // computed once per height (the same formula, so the same bits) and
        // looked up per cell — the division per cell was most of the write.
        let highest = map.cells().iter().copied().max().unwrap_or(0);
        let value: Vec<f32> = (0..=highest)
            .map(|h| {
                let top = self.base() + f64::from(h) * self.step_height();
                (((top - z0) / elevation).clamp(0.0, 1.0)) as f32
            })
            .collect();
        for (y, row) in (0..map.ny()).map(|y| (y as usize, map.row(y))) {
            let start = y * k * stride;
            let first = &mut out[start..start + ncol];
            // Fixed widths for the usual oversamples let the compiler emit
            // straight stores instead of a fill loop per cell.
            match k {
                1 => spread::<1>(row, &value, first),
                2 => spread::<2>(row, &value, first),
                4 => spread::<4>(row, &value, first),
                _ => first
                    .chunks_exact_mut(k)
                    .zip(row)
                    .for_each(|(samples, &h)| samples.fill(value[usize::from(h)])),
            }
            // The other k − 1 sample rows of this cell row are copies.
            for j in 1..k {
                out.copy_within(start..start + ncol, start + j * stride);
            }
        }
        for ramp in self.ramps() {
            self.fill_ramp(ramp, k, (z0, elevation), out, stride);
        }
    }

    /// Raises the samples over `ramp` to its plane where it is above them
    /// (the maximum rule of the heightmap, on the plane): sample `j` of a
    /// cell `(j + ½)/k` of the way across it, as everywhere.
    fn fill_ramp(
        &self,
        ramp: &crate::Ramp,
        k: usize,
        (z0, elevation): (f64, f64),
        out: &mut [f32],
        stride: usize,
    ) {
        let [x0, y0, x1, y1] = ramp.cells.map(|c| c as usize);
        let (base, step) = (self.base(), self.step_height());
        let across = |i: usize| (i as f64 + 0.5) / k as f64;
        for r in y0 * k..(y1 + 1) * k {
            let row = &mut out[r * stride..];
            for (c, sample) in row.iter_mut().enumerate().take((x1 + 1) * k).skip(x0 * k) {
                let top = ramp.height_at(across(c), across(r), base, step);
                let value = (((top - z0) / elevation).clamp(0.0, 1.0)) as f32;
                *sample = sample.max(value);
            }
        }
    }
}

/// Each cell's value `K` times along a sample row.
#[inline]
fn spread<const K: usize>(row: &[u16], value: &[f32], out: &mut [f32]) {
    let (samples, _) = out.as_chunks_mut::<K>();
    for (samples, &h) in samples.iter_mut().zip(row) {
        *samples = [value[usize::from(h)]; K];
    }
}

/// [`Terrain::hfield_shape`] of any terrain of `grid`: the shape depends on
/// the grid and `oversample` alone.
/// MuJoCo's `size` (`[radius_x, radius_y, elevation, base]`) and the geom's
/// `pos` of a field `width × depth` metres across with samples `spacing`
/// apart, its surface at sample 0 at height `z`: the one formula of every
/// height field rse makes (a terrain's, a slot's, a tile map's). MuJoCo
/// puts the first and last samples on the field's edges, so the radii are
/// half of `width − spacing`, and the centre goes half a sample inside the
/// first cell's centre line.
pub(crate) fn field_geometry(
    width: f64,
    depth: f64,
    spacing: f64,
    elevation: f64,
    base: f64,
    z: f64,
) -> ([f64; 4], [f64; 3]) {
    (
        [
            (width - spacing) / 2.0,
            (depth - spacing) / 2.0,
            elevation,
            base,
        ],
        [width / 2.0, depth / 2.0, z],
    )
}

pub(crate) fn hfield_shape_of(grid: Grid, oversample: u32) -> Result<(u32, u32), HFieldError> {
    let bad = |reason: String| HFieldError::Oversample { oversample, reason };
    if oversample == 0 {
        return Err(bad("expected 1 or more samples per cell".to_owned()));
    }
    let (nrow, ncol) = (
        u64::from(grid.ny) * u64::from(oversample),
        u64::from(grid.nx) * u64::from(oversample),
    );
    if nrow.saturating_mul(ncol) > MAX_HFIELD_SAMPLES {
        return Err(bad(format!(
            "{nrow}x{ncol} samples; at most {MAX_HFIELD_SAMPLES} are made"
        )));
    }
    if nrow < 2 || ncol < 2 {
        return Err(bad(format!(
            "{nrow}x{ncol} samples; MuJoCo needs 2 or more along each axis"
        )));
    }
    Ok((nrow as u32, ncol as u32))
}

impl HField {
    /// MuJoCo's binary height field file: `int32 nrow`, `int32 ncol`, then
    /// `nrow·ncol` `float32`, little-endian. MuJoCo reads it exactly: the
    /// samples already span `[0, 1]` (tested against MuJoCo).
    pub fn to_mujoco_bin(&self) -> Vec<u8> {
        let mut bytes = Vec::with_capacity(8 + 4 * self.data.len());
        bytes.extend_from_slice(&(self.nrow as i32).to_le_bytes());
        bytes.extend_from_slice(&(self.ncol as i32).to_le_bytes());
        for v in &self.data {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // samples are exact fractions of exact tops
mod tests {
    use crate::{Scheme, generate};

    fn terrain(text: &str) -> crate::Terrain {
        generate(&Scheme::from_csv(text, None).unwrap(), 0, 0)
    }

    /// An oversample read from a file may be anything: a sample count past
    /// 2⁶⁴ is refused, never wrapped into a small one.
    #[test]
    fn a_huge_oversample_is_refused_not_wrapped() {
        let t = terrain("# size: 5x5\ntype,height\nrandom,3\n");
        assert!(matches!(
            t.hfield_shape(u32::MAX),
            Err(crate::HFieldError::Oversample { .. })
        ));
    }

    #[test]
    fn every_sample_of_a_cell_has_its_top() {
        let t = terrain("# size: 3x2\ntype,height\nrandom,3\n");
        let map = t.heightmap();
        let (lo, hi) = (
            f64::from(*map.cells().iter().min().unwrap()),
            f64::from(map.max()),
        );
        assert!(hi > lo, "the test needs two heights");
        let hf = t.hfield(2).unwrap();
        assert_eq!((hf.nrow, hf.ncol), (4, 6));
        for r in 0..4 {
            for c in 0..6 {
                let h = f64::from(map.get(c / 2, r / 2));
                let want = ((h - lo) / (hi - lo)) as f32;
                assert_eq!(hf.data[(r * 6 + c) as usize], want, "sample ({r}, {c})");
            }
        }
        let spacing = 0.1 / 2.0;
        assert!((hf.size[0] - (0.3 - spacing) / 2.0).abs() < 1e-12);
        assert!((hf.size[1] - (0.2 - spacing) / 2.0).abs() < 1e-12);
        assert!((hf.size[2] - (hi - lo) * 0.1).abs() < 1e-12);
        assert!((hf.pos[0] - 0.15).abs() < 1e-12 && (hf.pos[1] - 0.1).abs() < 1e-12);
        assert!((hf.pos[2] - lo * 0.1).abs() < 1e-12);
    }

    #[test]
    fn samples_over_a_ramp_lie_on_its_plane_and_the_highest_is_one() {
        // 8 cells climbing 4 steps of 5 cm along x, on a 1 cm slab.
        let t = terrain(
            "# size: 8x2\n# step_height: 0.05\n# base: 0.01\ntype,height,angle,x1,y1,x2,y2\nramp,4,,0,0,7,1\n",
        );
        let hf = t.hfield(2).unwrap();
        let (z0, elevation) = (hf.pos[2], hf.size[2]);
        assert_eq!(z0, 0.01, "the foot's cell is the lowest top");
        for r in 0..4 {
            for c in 0..16 {
                // Sample c sits (c + ½)/2 cells along: the plane's height there.
                let plane = 0.01 + 0.2 * (f64::from(c) + 0.5) / 16.0;
                let z = z0 + f64::from(hf.data[(r * 16 + c) as usize]) * elevation;
                assert!(
                    (z - plane).abs() < 1e-6,
                    "sample ({r}, {c}): {z} vs {plane}"
                );
            }
        }
        assert_eq!(hf.data.iter().copied().fold(0.0, f32::max), 1.0);
    }

    #[test]
    fn a_raised_or_flat_terrain_keeps_its_lowest_top_in_pos() {
        let t = terrain("# size: 4x4\n# base: 0.05\ntype,height\nrandom,0\n");
        let hf = t.hfield(1).unwrap();
        assert!(hf.data.iter().all(|v| *v == 0.0));
        assert_eq!(hf.pos[2], 0.05);
        assert_eq!((hf.size[2], hf.size[3]), (0.1, 0.05));
    }

    #[test]
    fn bad_oversamples_and_buffers_are_refused() {
        let t = terrain("# size: 1x5\ntype,height\nrandom,2\n");
        assert!(t.hfield(0).is_err());
        assert!(
            t.hfield(1).is_err(),
            "1 column is not a MuJoCo height field"
        );
        assert!(t.hfield(2).is_ok());
        assert!(t.hfield(1 << 20).is_err());
        let mut short = vec![0.0; 3];
        assert!(matches!(
            t.hfield_into(2, 0.0, 1.0, &mut short),
            Err(crate::HFieldError::Buffer { .. })
        ));
        let mut right = vec![0.0; 20];
        assert!(matches!(
            t.hfield_into(2, 0.0, 0.05, &mut right),
            Err(crate::HFieldError::OutOfRange { .. })
        ));
    }
}
