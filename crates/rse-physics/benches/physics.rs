//! Step time of the physics smoke test on an RSE beside a flat plane, for
//! the paper's sizes (10×10, 15×60, 50×50), with our single mesh, our merged
//! boxes, and a naive mesh of one closed box per cell. Prints a table; run
//! with `cargo bench -p rse-physics --bench physics`.
//!
//! Target: ratio under 1.3 for 50×50 with the
//! single mesh.

use rse_core::mesh::naive::box_per_cell;
use rse_core::{Scheme, Terrain, generate};
use rse_physics::{SmokeTest, TerrainModel, smoke_test};

/// One closed box per cell with solid, as the RL terrain generators build
/// their grids.
fn naive_mesh(terrain: &Terrain) -> TerrainModel {
    let (vertices, triangles) = box_per_cell(terrain);
    TerrainModel::Mesh {
        vertices,
        triangles,
    }
}

/// How a terrain becomes the model under test.
type ModelOf = fn(&Terrain) -> TerrainModel;

fn main() {
    let samples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../schemes/");
    let cases = [
        (
            "random H4 10x10",
            Scheme::from_csv("# size: 10x10\ntype,height\nrandom,4\n", None).unwrap(),
        ),
        (
            "random H4 15x60",
            Scheme::from_csv("# size: 15x60\ntype,height\nrandom,4\n", None).unwrap(),
        ),
        (
            "random H4 50x50",
            Scheme::from_csv("# size: 50x50\ntype,height\nrandom,4\n", None).unwrap(),
        ),
        (
            "six_obstacles 50x50",
            Scheme::load(format!("{samples}six_obstacles.csv")).unwrap(),
        ),
    ];
    println!(
        "{:<22} {:<12} {:>10} {:>12} {:>12} {:>7} {:>7}",
        "terrain", "model", "triangles", "RSE µs/step", "plane µs", "ratio", "errors"
    );
    let worlds = 3;
    for (name, scheme) in &cases {
        let terrains: Vec<Terrain> = (0..worlds).map(|i| generate(scheme, 0, i)).collect();
        let models: [(&str, ModelOf); 3] = [
            ("single mesh", TerrainModel::mesh_of),
            ("boxes", TerrainModel::boxes_of),
            ("naive mesh", naive_mesh),
        ];
        for (label, model_of) in models {
            let (mut rse, mut plane, mut errors, mut size) = (0.0, 0.0, 0, 0);
            for terrain in &terrains {
                let model = model_of(terrain);
                size = match &model {
                    TerrainModel::Mesh { triangles, .. } => triangles.len(),
                    TerrainModel::Boxes(boxes) => boxes.len(),
                };
                let report = smoke_test(&model, None, terrain, SmokeTest::default());
                rse += report.rse_step_us;
                plane += report.plane_step_us;
                errors += report.errors.len();
            }
            let n = worlds as f64;
            let shown = if label == "boxes" {
                format!("{size} boxes")
            } else {
                size.to_string()
            };
            println!(
                "{name:<22} {label:<12} {shown:>10} {:>12.1} {:>12.1} {:>7.2} {errors:>7}",
                rse / n,
                plane / n,
                rse / plane
            );
        }
    }
}
