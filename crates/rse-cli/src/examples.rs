//! The examples each subcommand's `--help` ends with, as cargo's and
//! ripgrep's do. Every `rse-gen …` line here is parsed by a test, so an
//! example cannot name a flag that does not exist.

pub const HEIGHTMAP: &str = "\
Examples:
  # World 0 of the scheme's seed, one CSV line per y
  rse-gen heightmap schemes/wall.csv

  # World 3 of seed 7, at half difficulty, into a file
  rse-gen heightmap schemes/wall.csv --seed 7 --index 3 --difficulty 0.5 > world.csv";

pub const PREVIEW: &str = "\
Examples:
  rse-gen preview schemes/nist_hill.csv -o hill.png

  # World 4, 16 pixels per cell
  rse-gen preview schemes/nist_hill.csv -o hill.png --index 4 --cell-pixels 16";

pub const MESH: &str = "\
Examples:
  # OBJ, with terrain.mtl beside it
  rse-gen mesh schemes/six_obstacles.csv -o terrain.obj

  # World 2 as GLB, with steps of 5 cm instead of the scheme's
  rse-gen mesh schemes/six_obstacles.csv -o terrain.glb --index 2 --step-height 0.05";

pub const HFIELD: &str = "\
Examples:
  # Writes terrain.bin; prints what <hfield> and its geom need
  rse-gen hfield schemes/six_obstacles.csv -o terrain.bin --oversample 4";

pub const BATCH: &str = "\
Examples:
  # 100 worlds for Gazebo and MuJoCo; run it again and it skips the worlds already there
  rse-gen batch schemes/nist_hill.csv -o worlds --amount 100 --target gazebo,mujoco

  # Share 1000 worlds among 4 machines: each runs its own shard, 0/4 to 3/4
  rse-gen batch schemes/curriculum.csv -o worlds --amount 1000 --shard 0/4 --jobs 8

  # MuJoCo colliding with a height field instead of boxes; custom templates
  rse-gen batch schemes/six_obstacles.csv -o worlds --target mujoco --mujoco-collider hfield
  rse-gen batch schemes/wall.csv -o worlds --template my_templates";

pub const ATLAS: &str = "\
Examples:
  # 10 difficulty levels along x, 4 columns alternating two schemes along y
  rse-gen atlas schemes/six_obstacles.csv schemes/nist_hill.csv -o atlas --rows 10 --cols 4 --target mujoco

  # Easy tiles only, a 2-cell gap between them, 5 flat spawn points per tile
  rse-gen atlas schemes/curriculum.csv -o easy --rows 3 --cols 3 --difficulty 0..0.4 --border 2 --flat-patches 5";

pub const CHECK: &str = "\
Examples:
  # Every world of a batch: exit 1 if any fails
  rse-gen check worlds

  # One world, with bodies dropped on it in rapier
  rse-gen check worlds/world_0003 --physics

  # A JSON report for scripts
  rse-gen check worlds --json > report.json";

pub const CHECK_CURRICULUM: &str = "\
Examples:
  # Ten levels (mjlab's), 50 worlds each: exit 1 if a level is dead or no higher than the one below
  rse-gen check-curriculum schemes/curriculum.csv

  # More draws, another seed, as JSON
  rse-gen check-curriculum schemes/random.csv --draws 200 --seed 7 --json

  # Every scheme of a mix
  rse-gen check-curriculum schemes/mix_stairs.csv schemes/mix_walls.csv schemes/mix_rough.csv";

pub const CONTACT_SHEET: &str = "\
Examples:
  # 16 envs' first terrains, as a training run starts them at difficulty 1
  rse-gen contact-sheet schemes/six_obstacles.csv -o sheet.png

  # 40 envs over mjlab's 10 levels, two schemes mixed 3:1, each tile naming its scheme
  rse-gen contact-sheet schemes/mix_stairs.csv schemes/mix_walls.csv --proportions 3,1 --envs 40 --levels 10 -o mix.png";

pub const EDIT: &str = "\
Examples:
  # Edit a scheme in the browser (Ctrl-C stops the editor)
  rse-gen edit schemes/wall.csv --open

  # A new scheme, on a fixed port (e.g. forwarded over ssh)
  rse-gen edit --port 8080";

pub const TEMPLATES_EXPORT: &str = "\
Examples:
  # Copy ours, edit one, and generate with it (the rest stay ours)
  rse-gen templates export my_templates
  rse-gen batch schemes/wall.csv -o worlds --template my_templates";

/// Every example text, for the test that parses them.
#[cfg(test)]
pub const ALL: [&str; 9] = [
    HEIGHTMAP,
    PREVIEW,
    MESH,
    HFIELD,
    BATCH,
    ATLAS,
    CHECK,
    EDIT,
    TEMPLATES_EXPORT,
];
