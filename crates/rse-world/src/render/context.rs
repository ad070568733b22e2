//! The values a template can use (documented in `templates/README.md`).

use rse_core::mesh::Block;
use rse_core::{HField, Terrain};
use serde::Serialize;

use crate::record::options::{MeshMode, WorldOptions};
use crate::render::box_value::BoxValue;

/// The name of the terrain model in every target.
pub(crate) const MODEL: &str = "rse_terrain";

/// Everything a world's templates see.
#[derive(Debug, Serialize)]
pub(crate) struct WorldContext {
    /// Generator version.
    pub version: &'static str,
    /// The world's folder name, e.g. `world_0007`.
    pub world: String,
    /// The terrain model's name.
    pub model: &'static str,
    /// Base seed of the batch the world belongs to.
    pub seed: u64,
    pub index: u64,
    /// `single` or `blocks`: the mode of the target being rendered
    /// (`auto` resolved per target).
    pub mesh: &'static str,
    /// `false` when the terrain is empty (no mesh, no boxes).
    pub solid: bool,
    /// `[nx, ny]`.
    pub cells: [u32; 2],
    pub block_size: f64,
    pub step_height: f64,
    pub base: f64,
    /// Size of the terrain in metres: `[nx·S, ny·S, highest top]`.
    pub extent: [f64; 3],
    /// Centre of its footprint at the ground, metres.
    pub center: [f64; 3],
    /// The box set (`MuJoCo` collides with it in both modes unless
    /// `collider` is `hfield`): a list of [`BoxValue`]s, made once per world,
    /// as every target's render shares it (serializing the boxes again for
    /// each target was a tenth of a batch's time).
    pub boxes: minijinja::Value,
    /// Each ramp's wedge as its corners, `[x, y, z]` in metres (the ground's
    /// four, then those on its plane where they are above the ground): a
    /// convex solid, so `MuJoCo` collides with it exactly as a mesh geom
    /// (the box set holds only the staircase under it).
    pub ramps: Vec<Vec<[f64; 3]>>,
    /// What `MuJoCo` collides with: `boxes` or `hfield`.
    pub collider: &'static str,
    /// The height field, when `collider` is `hfield`.
    pub hfield: Option<HFieldContext>,
    /// The scheme's globals by their keys' names (`scheme.block_size`,
    /// `scheme.amount`; pallets as `scheme.pallets.count`, `.size`,
    /// `.boundary`, or none): the terrain carries them as one value, so a
    /// key added to the scheme reaches the templates here with no other
    /// edit. An atlas's are its first tile's scheme's.
    pub scheme: rse_core::Globals,
    /// The world options by name (`options.targets`, `options.mesh`, …),
    /// every one even at its default: an option added to rse-world's
    /// table reaches the templates here with no other edit.
    pub options: minijinja::Value,
}

/// A `MuJoCo` height field: its file and where it goes.
#[derive(Debug, Serialize)]
pub(crate) struct HFieldContext {
    /// Relative to the MJCF file.
    pub file: &'static str,
    pub nrow: u32,
    pub ncol: u32,
    /// `[radius_x, radius_y, elevation, base]`.
    pub size: [f64; 4],
    /// The geom's position.
    pub pos: [f64; 3],
}

impl WorldContext {
    pub(crate) fn new(world: String, terrain: &Terrain, mesh: MeshMode, boxes: &[Block]) -> Self {
        let s = terrain.block_size();
        let grid = terrain.grid();
        let ramps = wedge_corners(terrain);
        let top = boxes
            .iter()
            .map(|b| 2.0 * b.half_size[2])
            .chain(ramps.iter().flatten().map(|p| p[2]))
            .fold(0.0, f64::max);
        let extent = [f64::from(grid.nx) * s, f64::from(grid.ny) * s, top].map(tidy);
        WorldContext {
            version: rse_core::VERSION,
            world,
            model: MODEL,
            seed: terrain.seed(),
            index: terrain.index(),
            mesh: mesh.name(),
            solid: !boxes.is_empty(),
            cells: [grid.nx, grid.ny],
            block_size: terrain.block_size(),
            step_height: terrain.step_height(),
            base: terrain.base(),
            center: [extent[0] / 2.0, extent[1] / 2.0, 0.0].map(tidy),
            extent,
            boxes: minijinja::Value::from(
                boxes
                    .iter()
                    .map(|b| BoxValue::value(b, tidy))
                    .collect::<Vec<_>>(),
            ),
            ramps,
            collider: "boxes",
            hfield: None,
            scheme: *terrain.globals(),
            options: WorldOptions::default().template_value(),
        }
    }

    /// The same context for a world of `options`.
    pub(crate) fn with_options(self, options: &WorldOptions) -> Self {
        WorldContext {
            options: options.template_value(),
            ..self
        }
    }

    /// The same context for a world whose `MuJoCo` file collides `hfield`.
    pub(crate) fn with_hfield(self, hfield: &HField) -> Self {
        WorldContext {
            collider: "hfield",
            hfield: Some(HFieldContext {
                file: "terrain.bin",
                nrow: hfield.nrow,
                ncol: hfield.ncol,
                size: hfield.size.map(tidy),
                pos: hfield.pos.map(tidy),
            }),
            ..self
        }
    }
}

/// The corners of each of `terrain`'s ramps that rises ([`WorldContext::ramps`]).
fn wedge_corners(terrain: &Terrain) -> Vec<Vec<[f64; 3]>> {
    let (s, step, base) = (terrain.block_size(), terrain.step_height(), terrain.base());
    terrain
        .ramps()
        .iter()
        .filter(|r| r.rise > 0)
        .map(|r| {
            r.wedge_corners(s, base, step)
                .into_iter()
                .map(|p| p.map(tidy))
                .collect()
        })
        .collect()
}

/// `v` rounded to the nanometre, so files read `0.15`, not
/// `0.15000000000000002`. Exact IEEE arithmetic: the same on every machine.
pub(crate) fn tidy(v: f64) -> f64 {
    (v * 1e9).round() / 1e9
}
