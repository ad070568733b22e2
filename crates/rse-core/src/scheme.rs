//! A scheme: global parameters plus the ordered obstacle table, validated.

use std::path::Path;

use crate::error::{Error, SchemeError, SchemeErrorKind};
use crate::globals::{Globals, Grid};
use crate::obstacle::{Field, Obstacle};

/// Where a scheme came from, kept so that errors found later (e.g. a point
/// that leaves the grid after `--size` shrinks it) still name file and line.
#[derive(Debug, Clone, Default)]
pub(crate) struct Origin {
    pub file: Option<String>,
    /// Per obstacle: its line, and the 1-based column of each field present.
    pub rows: Vec<RowOrigin>,
    /// Per global key: the line it was set on.
    pub global_lines: Vec<(&'static str, u64)>,
}

#[derive(Debug, Clone, Default)]
pub(crate) struct RowOrigin {
    pub line: u64,
    pub columns: Vec<(Field, u64)>,
}

impl RowOrigin {
    /// Puts this row's line, and the column of the error's field, on `error`.
    pub(crate) fn place(&self, error: &mut SchemeError) {
        error.line = Some(self.line);
        let field = error.field.as_deref().and_then(Field::from_header);
        error.column = self
            .columns
            .iter()
            .find(|(f, _)| Some(*f) == field)
            .map(|(_, column)| *column);
    }
}

impl Origin {
    /// Puts the file, line and column of `obstacle`'s `field` on `error`.
    pub(crate) fn locate_obstacle(&self, mut error: SchemeError, obstacle: usize) -> SchemeError {
        error.file.clone_from(&self.file);
        error.obstacle = Some(obstacle);
        if let Some(row) = self.rows.get(obstacle) {
            row.place(&mut error);
        }
        error
    }

    /// Puts the file and line of the global key in `error.field` on `error`.
    pub(crate) fn locate_global(&self, mut error: SchemeError) -> SchemeError {
        error.file.clone_from(&self.file);
        let key = error.field.as_deref();
        error.line = self
            .global_lines
            .iter()
            .find(|(k, _)| Some(*k) == key)
            .map(|(_, line)| *line);
        error
    }
}

/// Global parameters and an ordered obstacle table, checked to work together.
///
/// Every `Scheme` is valid: [`Scheme::new`], [`Scheme::from_csv`] and
/// [`Scheme::with_globals`] refuse one that is not, so generating from it
/// cannot fail.
#[derive(Debug, Clone)]
pub struct Scheme {
    globals: Globals,
    obstacles: Vec<Obstacle>,
    pub(crate) notes: Vec<String>,
    origin: Origin,
}

impl PartialEq for Scheme {
    /// Two schemes are equal when their parameters, tables and notes are;
    /// where they were read from does not matter.
    fn eq(&self, other: &Self) -> bool {
        self.globals == other.globals
            && self.obstacles == other.obstacles
            && self.notes == other.notes
    }
}

/// One cell visit, nanoseconds on one core of the development machine:
/// the unit of [`Scheme::generation_visits`], and of every cost `check`
/// and `check-curriculum` price in cell visits.
pub const VISIT_NANOS: f64 = 5.0;

/// The work one priced job (a world's rebuild in `check`, a whole
/// `check-curriculum`) may cost under the default budget, in cell visits:
/// some 100 s on one core. A budget factor allows that many times as much.
pub const BUDGET_VISITS: u64 = 20_000_000_000;

impl Scheme {
    /// Checks `globals` and that every obstacle's points lie inside the grid.
    pub fn new(globals: Globals, obstacles: Vec<Obstacle>) -> Result<Self, SchemeError> {
        Self::with_origin(globals, obstacles, Vec::new(), Origin::default())
    }

    pub(crate) fn with_origin(
        globals: Globals,
        obstacles: Vec<Obstacle>,
        notes: Vec<String>,
        origin: Origin,
    ) -> Result<Self, SchemeError> {
        let mut globals = globals;
        // `-0` is 0: one terrain, one canonical scheme (`base: -0` was
        // accepted and written back as `-0`).
        globals.base += 0.0;
        globals.validate().map_err(|e| origin.locate_global(e))?;
        let grid = globals.grid();
        for (i, obstacle) in obstacles.iter().enumerate() {
            check_inside(obstacle, grid).map_err(|e| origin.locate_obstacle(e, i))?;
            check_height(obstacle, &globals).map_err(|e| origin.locate_obstacle(e, i))?;
        }
        Ok(Scheme {
            globals,
            obstacles,
            notes,
            origin,
        })
    }

    /// Reads a scheme CSV file (docs/schemes.md): a regular file of at most
    /// [`MAX_SCHEME_BYTES`](crate::MAX_SCHEME_BYTES) ([`read_scheme_file`](crate::read_scheme_file)).
    /// Errors name the path as given.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let bytes = crate::read_scheme_file(path).map_err(|source| Error::Io {
            path: name.clone(),
            source,
        })?;
        Ok(Self::from_csv_bytes(&bytes, Some(&name))?)
    }

    /// The same table with other global parameters (e.g. command-line
    /// overrides), checked again. Errors still name the original file and line.
    pub fn with_globals(&self, globals: Globals) -> Result<Self, SchemeError> {
        Self::with_origin(
            globals,
            self.obstacles.clone(),
            self.notes.clone(),
            self.origin.clone(),
        )
    }

    /// The global parameters.
    pub fn globals(&self) -> &Globals {
        &self.globals
    }

    /// The base seed a run of this scheme uses: the one its user gave,
    /// else the scheme's `# seed:` (the one fallback every front end and
    /// request shares).
    pub fn seed_or(&self, given: Option<u64>) -> u64 {
        given.unwrap_or(self.globals.seed)
    }

    /// The obstacle table, in the order it is applied.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// Free-text comment lines of the file (without the leading `#`).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The highest top any world of this scheme can have, metres:
    /// `base + H·step_height`, `H` the largest obstacle height the table
    /// allows (its ranges' upper ends; at least one step, for frames). A
    /// height field sized to it holds every world (`rse.mujoco`).
    pub fn max_top(&self) -> f64 {
        let highest = self
            .obstacles
            .iter()
            .filter_map(|o| o.fields().height)
            .map(|h| h.hi())
            .fold(1, u32::max);
        self.globals.top(highest)
    }

    /// At most how many cells its ramps cover in any world, counted once a
    /// ramp (overlaps counted each time): the samples a height field
    /// writes again over a ramp's plane are these cells' samples.
    pub fn ramp_cells(&self) -> u64 {
        let grid = self.grid();
        let units = crate::stamp::Units {
            block_size: self.globals.block_size,
            step_height: self.globals.step_height,
        };
        self.obstacles
            .iter()
            .filter(|o| o.kind().is_ramp())
            .map(|o| crate::stamp::visits(o, grid, units))
            .fold(0, u64::saturating_add)
    }

    /// At most how many cells generating one world of this scheme visits
    /// ([`VISIT_NANOS`] each),
    /// whatever its ranges draw: each obstacle's reach on the grid (every
    /// cell for a random or gaussian field; a peak or wall only the cells
    /// within its slope's reach of its points), plus the grid once for the
    /// heights and frames. The measure of generation work that `check`
    /// holds to a budget before it rebuilds a world from a file it was
    /// handed.
    pub fn generation_visits(&self) -> u64 {
        let grid = self.grid();
        let units = crate::stamp::Units {
            block_size: self.globals.block_size,
            step_height: self.globals.step_height,
        };
        // Gaussian rows alike share their table: priced as generation
        // builds them (`rng::GaussianTables`).
        let gaussians = self
            .obstacles
            .iter()
            .filter(|o| o.kind() == crate::obstacle::ObstacleKind::Gaussian)
            .map(|o| {
                let f = o.fields();
                let height = f.height.unwrap_or(crate::param::Param::Fixed(0));
                let sigma = f
                    .sigma
                    .unwrap_or(crate::param::Param::Fixed(crate::limits::DEFAULT_SIGMA));
                let key = match (height, sigma) {
                    (crate::param::Param::Fixed(h), crate::param::Param::Fixed(s)) => {
                        Some((h, s.to_bits()))
                    }
                    _ => None,
                };
                (key, height.hi(), sigma.hi())
            });
        self.obstacles
            .iter()
            .map(|o| crate::stamp::visits(o, grid, units))
            .fold(grid.cells() as u64, u64::saturating_add)
            .saturating_add(crate::rng::tables_visits(gaussians))
    }

    /// The grid (frame included).
    pub fn grid(&self) -> Grid {
        self.globals.grid()
    }

    /// The file this scheme was read from, as given.
    pub fn file(&self) -> Option<&str> {
        self.origin.file.as_deref()
    }
}

/// An obstacle's height (its range's top) must not make a wall too slender
/// for an exact `f32` mesh.
fn check_height(obstacle: &Obstacle, globals: &Globals) -> Result<(), SchemeError> {
    let Some(height) = obstacle.fields().height else {
        return Ok(());
    };
    let (top, limit) = (
        globals.top(height.hi()),
        crate::limits::MAX_TOP_IN_BLOCKS * globals.block_size,
    );
    if top > limit {
        return Err(SchemeError::new(SchemeErrorKind::TooTall {
            height: height.hi(),
            top,
            limit,
        })
        .with_field("height"));
    }
    let steps = top / globals.step_height;
    if steps > crate::limits::MAX_LATTICE_UNITS as f64 {
        return Err(SchemeError::new(SchemeErrorKind::TooManySteps {
            height: height.hi(),
            steps,
        })
        .with_field("height"));
    }
    Ok(())
}

fn check_inside(obstacle: &Obstacle, grid: Grid) -> Result<(), SchemeError> {
    for (field, axis, coordinate) in obstacle.fields().coordinates() {
        let Some(param) = coordinate else { continue };
        let limit = if axis == 'x' { grid.nx } else { grid.ny };
        if param.hi() >= limit {
            return Err(SchemeError::new(SchemeErrorKind::PointOutsideGrid {
                value: param.hi().into(),
                axis,
                max: limit - 1,
                nx: grid.nx,
                ny: grid.ny,
            })
            .with_field(field.name()));
        }
    }
    Ok(())
}
