//! The six obstacle types of the paper (§3.2), the stairs researchers train
//! on beside them (a straight flight, a pyramid and its inverse), the
//! inclined planes of the NIST test methods (a ramp, crossing ramps), and
//! the fields each one uses.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::{SchemeError, SchemeErrorKind};
use crate::limits::MAX_HEIGHT;
use crate::param::Param;

/// An obstacle type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObstacleKind {
    /// Every cell uniform in `0..=H`.
    Random,
    /// Every cell `round(N(H/2, σ))` clamped to `0..=H` (the paper's "normal").
    Gaussian,
    /// A block at one point with slopes around it.
    Peak,
    /// A peak that is subtracted.
    Pit,
    /// A ridge along a segment with slopes on both sides.
    Wall,
    /// A wall that is subtracted.
    LongPit,
    /// A straight flight of stairs over a rectangle of cells, climbing one
    /// step a tread from one side to the other.
    Stairs,
    /// Pyramid stairs over a rectangle of cells: rings of `tread` cells,
    /// each a step above the one around it, up to `H` (mjlab's and Isaac
    /// Lab's pyramid stairs).
    Pyramid,
    /// A pyramid that is subtracted: stairs down into a pit (the inverted
    /// pyramid stairs).
    PyramidPit,
    /// An inclined plane over a rectangle of cells, rising `H` steps from
    /// one side to the other: a wedge lying on the terrain (docs/schemes.md,
    /// "Ramps").
    Ramp,
    /// Two ramps side by side over a rectangle, climbing opposite ways
    /// (NIST's crossing ramps).
    CrossingRamps,
}

impl ObstacleKind {
    /// All kinds: the paper's, in its order, then the stairs, then the ramps.
    pub const ALL: [ObstacleKind; 11] = [
        ObstacleKind::Random,
        ObstacleKind::Gaussian,
        ObstacleKind::Peak,
        ObstacleKind::Pit,
        ObstacleKind::Wall,
        ObstacleKind::LongPit,
        ObstacleKind::Stairs,
        ObstacleKind::Pyramid,
        ObstacleKind::PyramidPit,
        ObstacleKind::Ramp,
        ObstacleKind::CrossingRamps,
    ];

    /// The canonical name, as written in scheme files.
    pub fn name(self) -> &'static str {
        match self {
            ObstacleKind::Random => "random",
            ObstacleKind::Gaussian => "gaussian",
            ObstacleKind::Peak => "peak",
            ObstacleKind::Pit => "pit",
            ObstacleKind::Wall => "wall",
            ObstacleKind::LongPit => "long_pit",
            ObstacleKind::Stairs => "stairs",
            ObstacleKind::Pyramid => "pyramid",
            ObstacleKind::PyramidPit => "pyramid_pit",
            ObstacleKind::Ramp => "ramp",
            ObstacleKind::CrossingRamps => "crossing_ramps",
        }
    }

    /// `true` for pit, long pit and pyramid pit, which subtract instead of
    /// taking the maximum.
    pub fn lowers(self) -> bool {
        matches!(
            self,
            ObstacleKind::Pit | ObstacleKind::LongPit | ObstacleKind::PyramidPit
        )
    }

    /// `true` for the ramps: wedges laid on the terrain after every other
    /// obstacle, not cells combined in table order.
    pub fn is_ramp(self) -> bool {
        matches!(self, ObstacleKind::Ramp | ObstacleKind::CrossingRamps)
    }

    /// `true` for the kinds over the rectangle of two corners: stairs,
    /// pyramids and ramps.
    pub fn is_rectangle(self) -> bool {
        matches!(
            self,
            ObstacleKind::Stairs
                | ObstacleKind::Pyramid
                | ObstacleKind::PyramidPit
                | ObstacleKind::Ramp
                | ObstacleKind::CrossingRamps
        )
    }

    /// Whether this kind needs, may have, or must not have `field`.
    pub fn usage(self, field: Field) -> Usage {
        use ObstacleKind::{
            CrossingRamps, Gaussian, LongPit, Peak, Pit, Pyramid, PyramidPit, Ramp, Random, Stairs,
            Wall,
        };
        match (field, self) {
            (Field::Type | Field::Height, _)
            | (Field::Angle, Peak | Pit | Wall | LongPit)
            | (
                Field::X1 | Field::Y1,
                Peak | Pit | Wall | LongPit | Stairs | Pyramid | PyramidPit | Ramp | CrossingRamps,
            )
            | (
                Field::X2 | Field::Y2,
                Wall | LongPit | Stairs | Pyramid | PyramidPit | Ramp | CrossingRamps,
            )
            | (Field::Tread, Pyramid | PyramidPit) => Usage::Required,
            (Field::Sigma, Gaussian) => Usage::Optional,
            (
                Field::Angle,
                Random | Gaussian | Stairs | Pyramid | PyramidPit | Ramp | CrossingRamps,
            )
            | (Field::X1 | Field::Y1, Random | Gaussian)
            | (Field::X2 | Field::Y2, Random | Gaussian | Peak | Pit)
            | (
                Field::Sigma,
                Random | Peak | Pit | Wall | LongPit | Stairs | Pyramid | PyramidPit | Ramp
                | CrossingRamps,
            )
            | (
                Field::Tread,
                Random | Gaussian | Peak | Pit | Wall | LongPit | Stairs | Ramp | CrossingRamps,
            ) => Usage::Unused,
        }
    }
}

impl fmt::Display for ObstacleKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ObstacleKind {
    type Err = SchemeErrorKind;

    /// Case-insensitive; `long pit`, `long-pit`, `longpit`, `normal`,
    /// `pyramid stairs`, `inverted pyramid`, `slope`, `inclined plane` and
    /// `crossing ramp` are accepted too.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let key: String = text
            .trim()
            .to_ascii_lowercase()
            .chars()
            .filter(|c| !matches!(c, ' ' | '_' | '-'))
            .collect();
        Ok(match key.as_str() {
            "random" => ObstacleKind::Random,
            "gaussian" | "normal" => ObstacleKind::Gaussian,
            "peak" => ObstacleKind::Peak,
            "pit" => ObstacleKind::Pit,
            "wall" => ObstacleKind::Wall,
            "longpit" => ObstacleKind::LongPit,
            "stairs" => ObstacleKind::Stairs,
            "pyramid" | "pyramidstairs" => ObstacleKind::Pyramid,
            "pyramidpit" | "invertedpyramid" => ObstacleKind::PyramidPit,
            "ramp" | "slope" | "inclinedplane" => ObstacleKind::Ramp,
            "crossingramps" | "crossingramp" => ObstacleKind::CrossingRamps,
            _ => return Err(SchemeErrorKind::UnknownType(text.trim().to_owned())),
        })
    }
}

/// A column of the obstacle table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// `type`
    Type,
    /// `height`, in steps
    Height,
    /// `angle`, slope angle in degrees
    Angle,
    /// `x1`, first point
    X1,
    /// `y1`
    Y1,
    /// `x2`, second point (walls)
    X2,
    /// `y2`
    Y2,
    /// `sigma`, standard deviation in steps (gaussian)
    Sigma,
    /// `tread`, cells per step of a pyramid's rings
    Tread,
}

impl Field {
    /// All columns in the order the writer emits them.
    pub const ALL: [Field; 9] = [
        Field::Type,
        Field::Height,
        Field::Angle,
        Field::X1,
        Field::Y1,
        Field::X2,
        Field::Y2,
        Field::Sigma,
        Field::Tread,
    ];

    /// The header name.
    pub fn name(self) -> &'static str {
        match self {
            Field::Type => "type",
            Field::Height => "height",
            Field::Angle => "angle",
            Field::X1 => "x1",
            Field::Y1 => "y1",
            Field::X2 => "x2",
            Field::Y2 => "y2",
            Field::Sigma => "sigma",
            Field::Tread => "tread",
        }
    }

    /// The unit of its numbers, as the editor shows it beside them.
    pub const fn unit(self) -> Option<&'static str> {
        match self {
            Field::Type => None,
            Field::Height | Field::Sigma => Some("steps"),
            Field::Angle => Some("degrees"),
            Field::X1 | Field::Y1 | Field::X2 | Field::Y2 | Field::Tread => Some("cells"),
        }
    }

    /// One line of documentation: the "meaning" column of docs/schemes.md's
    /// table of columns, without its backticks (the editor's tooltip; a
    /// test in rse-edit holds the two together).
    pub const fn doc(self) -> &'static str {
        match self {
            Field::Type => {
                "the obstacle: random, gaussian, peak, pit, wall, long_pit, stairs, pyramid, pyramid_pit, ramp or crossing_ramps"
            }
            Field::Height => {
                "height H in whole steps (the depth of a pit or long pit, a ramp's rise)"
            }
            Field::Angle => "slope of its sides from the ground, 0 to 90 (90: straight sides)",
            Field::X1 => {
                "column of the point (the first end of a wall or long pit, the first corner of stairs, a pyramid or a ramp), from 0"
            }
            Field::Y1 => {
                "row of the point (the first end of a wall or long pit, the first corner of stairs, a pyramid or a ramp), from 0"
            }
            Field::X2 => {
                "column of the second end of a wall or long pit (the opposite corner of stairs, a pyramid or a ramp)"
            }
            Field::Y2 => {
                "row of the second end of a wall or long pit (the opposite corner of stairs, a pyramid or a ramp)"
            }
            Field::Sigma => "spread of a gaussian's heights, in steps (default 1)",
            Field::Tread => {
                "cells from one step to the next of a pyramid or pyramid pit, 1 or more"
            }
        }
    }

    /// The column for a header name (trimmed, case-insensitive).
    pub fn from_header(name: &str) -> Option<Field> {
        let name = name.trim().to_ascii_lowercase();
        Field::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// How an obstacle type uses a field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Usage {
    /// Must be given.
    Required,
    /// May be given; has a default.
    Optional,
    /// Must be left empty.
    Unused,
}

/// The values of one table row, before validation. `None` is an empty field.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObstacleFields {
    /// Height in steps.
    pub height: Option<Param<u32>>,
    /// Slope angle in degrees, `0..=90`.
    pub angle: Option<Param<f64>>,
    /// First point, x cell.
    pub x1: Option<Param<u32>>,
    /// First point, y cell.
    pub y1: Option<Param<u32>>,
    /// Second point, x cell.
    pub x2: Option<Param<u32>>,
    /// Second point, y cell.
    pub y2: Option<Param<u32>>,
    /// Standard deviation in steps (gaussian; default [`DEFAULT_SIGMA`](crate::DEFAULT_SIGMA)).
    pub sigma: Option<Param<f64>>,
    /// Cells per step of a pyramid's rings, `1..`.
    pub tread: Option<Param<u32>>,
}

impl ObstacleFields {
    fn is_set(&self, field: Field) -> bool {
        match field {
            Field::Type => true,
            Field::Height => self.height.is_some(),
            Field::Angle => self.angle.is_some(),
            Field::X1 => self.x1.is_some(),
            Field::Y1 => self.y1.is_some(),
            Field::X2 => self.x2.is_some(),
            Field::Y2 => self.y2.is_some(),
            Field::Sigma => self.sigma.is_some(),
            Field::Tread => self.tread.is_some(),
        }
    }

    /// The coordinate fields with the axis each one is on.
    pub(crate) fn coordinates(&self) -> [(Field, char, Option<Param<u32>>); 4] {
        [
            (Field::X1, 'x', self.x1),
            (Field::Y1, 'y', self.y1),
            (Field::X2, 'x', self.x2),
            (Field::Y2, 'y', self.y2),
        ]
    }
}

/// One validated row of the obstacle table.
///
/// Built with [`Obstacle::new`], which checks that the type has every field it
/// needs and none it does not use, and that every value is in its domain.
/// Whether points lie inside the grid is checked by [`crate::Scheme::new`],
/// which knows the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    kind: ObstacleKind,
    fields: ObstacleFields,
}

impl Obstacle {
    /// Validates a row. The error's `field` names the faulty column.
    pub fn new(kind: ObstacleKind, fields: ObstacleFields) -> Result<Self, SchemeError> {
        for field in Field::ALL {
            let error = match (kind.usage(field), fields.is_set(field)) {
                (Usage::Required, false) => SchemeErrorKind::MissingField(kind.name()),
                (Usage::Unused, true) => SchemeErrorKind::UnusedField(kind.name()),
                _ => continue,
            };
            return Err(SchemeError::new(error).with_field(field.name()));
        }
        let fail = |field: Field, kind| Err(SchemeError::new(kind).with_field(field.name()));
        if let Some(height) = fields.height {
            check_order(height, Field::Height)?;
            if height.hi() > MAX_HEIGHT {
                return fail(
                    Field::Height,
                    SchemeErrorKind::HeightTooLarge(height.hi().into()),
                );
            }
        }
        if let Some(angle) = fields.angle {
            for a in [angle.lo(), angle.hi()] {
                if !(0.0..=90.0).contains(&a) {
                    return fail(Field::Angle, SchemeErrorKind::AngleOutOfRange(a));
                }
            }
            check_order(angle, Field::Angle)?;
        }
        if let Some(sigma) = fields.sigma {
            for s in [sigma.lo(), sigma.hi()] {
                if !(s.is_finite() && s >= 0.0) {
                    return fail(Field::Sigma, SchemeErrorKind::BadSigma(s));
                }
            }
            check_order(sigma, Field::Sigma)?;
        }
        if let Some(tread) = fields.tread {
            if tread.lo() == 0 {
                return fail(
                    Field::Tread,
                    SchemeErrorKind::NotANumber {
                        value: "0".into(),
                        expected: "a whole number ≥ 1 (cells from one step to the next)",
                    },
                );
            }
            check_order(tread, Field::Tread)?;
        }
        for (field, _, coordinate) in fields.coordinates() {
            if let Some(c) = coordinate {
                check_order(c, field)?;
            }
        }
        Ok(Obstacle { kind, fields })
    }

    /// Which obstacle type the row is.
    pub fn kind(&self) -> ObstacleKind {
        self.kind
    }

    /// The row's values as given (empty fields are `None`).
    pub fn fields(&self) -> &ObstacleFields {
        &self.fields
    }
}

fn check_order<T: Copy + PartialOrd + fmt::Display>(
    param: Param<T>,
    field: Field,
) -> Result<(), SchemeError> {
    if param.is_reversed() {
        return Err(SchemeError::new(SchemeErrorKind::ReversedRange {
            lo: param.lo().to_string(),
            hi: param.hi().to_string(),
        })
        .with_field(field.name()));
    }
    Ok(())
}

/// An obstacle as drawn for one world: every range resolved to a value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DrawnObstacle {
    /// Which obstacle type it was.
    pub kind: ObstacleKind,
    /// Height in steps.
    pub height: u32,
    /// Slope angle in degrees (peak, pit, wall, long pit).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub angle: Option<f64>,
    /// First point `[x, y]` in cells.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub p1: Option<[u32; 2]>,
    /// Second point `[x, y]` in cells (wall, long pit).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub p2: Option<[u32; 2]>,
    /// Standard deviation in steps (gaussian).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub sigma: Option<f64>,
    /// Cells per step (pyramid, pyramid pit).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub tread: Option<u32>,
}
