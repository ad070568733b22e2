//! A grid of cell heights in whole steps, and its CSV text (docs/schemes.md).

use std::fmt::Write as _;

/// Why a heightmap CSV does not parse; lines and columns count from 1.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum HeightmapCsvError {
    /// A value that is not a height in steps (a whole number 0–65535).
    #[error("line {line}, column {column}: `{value}` is not a height")]
    NotAHeight {
        /// 1-based line of the CSV text.
        line: usize,
        /// 1-based column (field) on that line.
        column: usize,
        /// The text found there.
        value: String,
    },
    /// A line with another number of values than the first line.
    #[error("line {line}: {found} values, but line 1 has {expected}")]
    Ragged {
        /// 1-based line of the CSV text.
        line: usize,
        /// Values on it.
        found: u32,
        /// Values on the first line.
        expected: u32,
    },
}

/// The walls of a heightmap ([`Heightmap::walls`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Walls {
    /// Pairs of neighbouring cells of different heights.
    pub count: u64,
    /// Their differences of height summed, in steps.
    pub steps: u64,
}

impl Walls {
    /// The mean height of a wall in steps (0 without walls).
    pub fn mean(self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.steps as f64 / self.count as f64
        }
    }
}

/// Cell heights in steps, `nx × ny`, stored row by row from `y = 0`
/// (`index = y·nx + x`), the layout of a numpy `(ny, nx)` array.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Heightmap {
    nx: u32,
    ny: u32,
    cells: Vec<u16>,
}

impl Heightmap {
    /// A flat map of height 0.
    pub fn zeros(nx: u32, ny: u32) -> Self {
        Heightmap {
            nx,
            ny,
            cells: vec![0; nx as usize * ny as usize],
        }
    }

    /// A map from row-major heights; `None` if `cells.len() != nx·ny`.
    pub fn from_cells(nx: u32, ny: u32, cells: Vec<u16>) -> Option<Self> {
        (cells.len() == nx as usize * ny as usize).then_some(Heightmap { nx, ny, cells })
    }

    /// Cells along x.
    pub fn nx(&self) -> u32 {
        self.nx
    }

    /// Cells along y.
    pub fn ny(&self) -> u32 {
        self.ny
    }

    /// Height of cell `(x, y)` in steps.
    ///
    /// # Panics
    /// If the cell is outside the map.
    pub fn get(&self, x: u32, y: u32) -> u16 {
        assert!(
            x < self.nx && y < self.ny,
            "cell ({x}, {y}) outside the map"
        );
        self.cells[self.index(x, y)]
    }

    /// All heights, row by row from `y = 0`.
    pub fn cells(&self) -> &[u16] {
        &self.cells
    }

    pub(crate) fn cells_mut(&mut self) -> &mut [u16] {
        &mut self.cells
    }

    /// Row `y`, from `x = 0`.
    pub fn row(&self, y: u32) -> &[u16] {
        let start = self.index(0, y);
        &self.cells[start..start + self.nx as usize]
    }

    pub(crate) fn row_mut(&mut self, y: u32) -> &mut [u16] {
        let start = self.index(0, y);
        &mut self.cells[start..start + self.nx as usize]
    }

    /// The walls between neighbouring cells: the pairs (along x or y) of
    /// different heights, and their heights summed. What the block model
    /// and the mesh cost follows: flat ground between them is cheap.
    pub fn walls(&self) -> Walls {
        let (mut count, mut steps) = (0u64, 0u64);
        let mut wall = |a: u16, b: u16| {
            if a != b {
                count += 1;
                steps += u64::from(a.abs_diff(b));
            }
        };
        for y in 0..self.ny {
            let row = self.row(y);
            for pair in row.windows(2) {
                wall(pair[0], pair[1]);
            }
            if y + 1 < self.ny {
                for (&a, &b) in row.iter().zip(self.row(y + 1)) {
                    wall(a, b);
                }
            }
        }
        Walls { count, steps }
    }

    /// The highest cell (0 for an empty map).
    pub fn max(&self) -> u16 {
        self.cells.iter().copied().max().unwrap_or(0)
    }

    /// The heightmap CSV text (docs/schemes.md): one line per `y` from 0, one column per `x`.
    pub fn to_csv(&self) -> String {
        let mut out = String::with_capacity(self.cells.len() * 3);
        for y in 0..self.ny {
            for (x, h) in self.row(y).iter().enumerate() {
                if x > 0 {
                    out.push(',');
                }
                write!(out, "{h}").expect("writing to a String cannot fail");
            }
            out.push('\n');
        }
        out
    }

    /// Parses the CSV text of [`Heightmap::to_csv`]. The error names the
    /// 1-based line and column of the first bad value.
    pub fn from_csv(text: &str) -> Result<Self, HeightmapCsvError> {
        let mut cells = Vec::new();
        let mut nx = None;
        let mut ny = 0u32;
        for (i, line) in text.lines().enumerate() {
            let line_no = i + 1;
            if line.trim().is_empty() {
                continue;
            }
            let before = cells.len();
            for (j, value) in line.split(',').enumerate() {
                let h = value
                    .trim()
                    .parse::<u16>()
                    .map_err(|_| HeightmapCsvError::NotAHeight {
                        line: line_no,
                        column: j + 1,
                        value: value.to_owned(),
                    })?;
                cells.push(h);
            }
            let width = (cells.len() - before) as u32;
            let expected = *nx.get_or_insert(width);
            if expected != width {
                return Err(HeightmapCsvError::Ragged {
                    line: line_no,
                    found: width,
                    expected,
                });
            }
            ny += 1;
        }
        Ok(Heightmap {
            nx: nx.unwrap_or(0),
            ny,
            cells,
        })
    }

    fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.nx as usize + x as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_has_one_line_per_y_from_zero() {
        let mut map = Heightmap::zeros(3, 2);
        map.cells_mut()[1] = 4; // (1, 0)
        map.cells_mut()[5] = 2; // (2, 1)
        assert_eq!(map.to_csv(), "0,4,0\n0,0,2\n");
        assert_eq!(map.get(1, 0), 4);
        assert_eq!(Heightmap::from_csv(&map.to_csv()), Ok(map));
    }

    #[test]
    fn from_csv_names_the_bad_value() {
        let error = Heightmap::from_csv("1,2\n3,x\n").unwrap_err();
        assert_eq!(
            error,
            HeightmapCsvError::NotAHeight {
                line: 2,
                column: 2,
                value: "x".to_owned()
            }
        );
        assert!(error.to_string().contains("line 2, column 2"), "{error}");
        assert_eq!(
            Heightmap::from_csv("1,2\n3\n").unwrap_err(),
            HeightmapCsvError::Ragged {
                line: 2,
                found: 1,
                expected: 2
            }
        );
    }
}
