//! Command-line arguments: every clap type of `rse-gen` lives here.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use crate::examples;
use rse_core::{Difficulty, GlobalKey, GlobalsPatch, SchemeErrorKind};
use rse_world::{OptionValue, Shard, Templates, WorldConfig, WorldOptions};

/// Mass-generate Random Step Environments (NIST stepfields) as simulator worlds.
///
/// A scheme CSV (see docs/schemes.md) lists global parameters and an ordered
/// table of obstacles; every world drawn from it is reproducible from the
/// scheme and the seed pair (seed, index).
#[derive(Debug, Parser)]
#[command(
    name = "rse-gen",
    version,
    propagate_version = true,
    max_term_width = 100,
    after_help = "Scheme overrides go after the subcommand (or before it) and apply to the subcommands \
                  that read a scheme: heightmap, preview, mesh, hfield, batch, atlas, edit.\n\
                  Every subcommand's --help ends with examples: rse-gen batch --help"
)]
pub struct Cli {
    // Plain comments: clap would show doc comments in the help.
    #[command(subcommand)]
    #[allow(missing_docs)]
    pub command: Command,

    // Before the subcommand: for any subcommand that reads a scheme.
    #[command(flatten)]
    #[allow(missing_docs)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Print the heightmap of one world as CSV: one line per y from 0, one column per x, heights in steps.
    #[command(after_help = examples::HEIGHTMAP)]
    Heightmap(HeightmapArgs),
    /// Draw one world seen from above as a PNG (blue lowest, green, red highest; pallet frames brown).
    #[command(after_help = examples::PREVIEW)]
    Preview(PreviewArgs),
    /// Write one world's closed terrain mesh as OBJ (with its .mtl), binary STL or GLB, by suffix.
    #[command(after_help = examples::MESH)]
    Mesh(MeshArgs),
    /// Write one world as a MuJoCo height field file (int32 nrow, int32 ncol, float32 samples); print
    /// its nrow, ncol, size and geom pos as JSON on stdout.
    #[command(after_help = examples::HFIELD)]
    Hfield(HfieldArgs),
    /// Write a batch of simulator worlds, one folder each (`OUT/world_0000`, …); a rerun resumes.
    #[command(after_help = examples::BATCH)]
    Batch(BatchArgs),
    /// Write ONE world whose terrain is a grid of tiles for RL curricula: rows along x are difficulty
    /// levels, columns along y cycle through the schemes; atlas.json gives every tile's spawn origin.
    #[command(after_help = examples::ATLAS)]
    Atlas(AtlasArgs),
    /// Check world folders (or batch folders of them): files, hashes, reproducibility, meshes, physics.
    #[command(after_help = examples::CHECK)]
    Check(CheckArgs),
    /// Check a scheme as a curriculum: per difficulty level, the share of flat worlds, mean height, mean and
    /// largest step, steepest slope and distinct worlds over many draws; exit 1 on a dead or non-rising level.
    #[command(name = "check-curriculum", after_help = examples::CHECK_CURRICULUM)]
    CheckCurriculum(CheckCurriculumArgs),
    /// Draw the terrains of N parallel envs in one PNG, as `rse.EnvTerrains.contact_sheet` does: one
    /// tile per env, labelled with its env id (and scheme), episode and difficulty, on a colour
    /// scale (one per scheme of a mix).
    #[command(name = "contact-sheet", after_help = examples::CONTACT_SHEET)]
    ContactSheet(ContactSheetArgs),
    /// Open the scheme editor, a local web page (prints its URL): table, live preview, save, generate.
    #[command(after_help = examples::EDIT)]
    Edit(EditArgs),
    /// Our world templates, to start your own from (`--template DIR` overlays them file by file).
    Templates(TemplatesArgs),
}

#[derive(Debug, Args)]
pub struct TemplatesArgs {
    #[command(subcommand)]
    pub action: TemplatesAction,
}

#[derive(Debug, Subcommand)]
pub enum TemplatesAction {
    /// Write the built-in templates into DIR/<target>/… (refuses to overwrite a file).
    #[command(after_help = examples::TEMPLATES_EXPORT)]
    Export {
        /// The folder to write them into (created if missing).
        #[arg(value_name = "DIR")]
        dir: PathBuf,
    },
}

#[derive(Debug, Args)]
pub struct EditArgs {
    /// The scheme CSV file to start from (the editor saves where you say).
    pub scheme: Option<PathBuf>,

    /// Port on 127.0.0.1 [default: the one this file was last edited on, when free; else a free one].
    #[arg(long, value_name = "P")]
    pub port: Option<u16>,

    /// Open the page in the desktop's browser.
    #[arg(long)]
    pub open: bool,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// World folders, or batch folders whose sub-folders are worlds.
    #[arg(required = true, value_name = "PATH")]
    pub paths: Vec<PathBuf>,

    /// Print a JSON report (one object per world) on stdout instead of one line per failed world.
    #[arg(long)]
    pub json: bool,

    /// Also drop 20 bodies on each terrain in rapier for 5 simulated seconds at 1 kHz: report
    /// bodies that sink, keep moving or leave, and the step time against a flat plane.
    #[arg(long)]
    pub physics: bool,

    /// The folder of templates custom worlds were made with (as given to `batch --template`):
    /// their files are rebuilt and compared byte for byte instead of by hash.
    #[arg(long, value_name = "DIR")]
    pub template: Option<PathBuf>,

    /// Fail every world some of whose files could be compared only with their hashes in rse.json.
    #[arg(long)]
    pub strict: bool,

    /// Allow each world's rebuild F times the default budget (2·10¹⁰ cell visits, some 100 s, and the memory
    /// available per world checked at once) [default: 1].
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    pub budget: Option<rse_verify::Budget>,
}

#[derive(Debug, Args)]
pub struct CheckCurriculumArgs {
    /// Scheme CSV files (the schemes of a mix: each is checked in turn; JSON: a list of reports).
    #[arg(required = true, value_name = "SCHEME")]
    pub schemes: Vec<PathBuf>,

    /// Difficulty levels from 0 to 1, evenly spaced (mjlab's terrain levels: 10).
    #[arg(long, value_name = "N", default_value_t = rse_core::DEFAULT_LEVELS)]
    pub levels: u32,

    /// Worlds drawn per level (the same draws at every level).
    #[arg(long, value_name = "N", default_value_t = rse_core::DEFAULT_DRAWS)]
    pub draws: u32,

    /// Base seed of the draws [default: the scheme's `seed`, else 0].
    #[arg(long, value_name = "B")]
    pub seed: Option<u64>,

    /// Allow F times the default budget (2·10¹⁰ cell visits, some 100 s on one core): a check priced over it
    /// is refused before a world is generated [default: 1].
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    pub budget: Option<rse_verify::Budget>,

    /// Print the report as JSON instead of a table.
    #[arg(long)]
    pub json: bool,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct ContactSheetArgs {
    /// Scheme CSV files: with several, each env draws its scheme by `--proportions` from its env id and
    /// the seed (as a mix of schemes in the RL adapters), and its tile names the scheme.
    #[arg(required = true, value_name = "SCHEME")]
    pub schemes: Vec<PathBuf>,

    /// The PNG file to write.
    #[arg(short, long, value_name = "PNG")]
    pub output: PathBuf,

    /// Environments drawn (env ids 0 to N-1).
    #[arg(long, value_name = "N", default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..=65_536))]
    pub envs: u32,

    /// Every env at difficulty D, 0 ≤ D ≤ 1 [default: 1, the schemes as written].
    #[arg(
        long,
        value_name = "D",
        conflicts_with = "levels",
        allow_negative_numbers = true
    )]
    pub difficulty: Option<Difficulty>,

    /// Spread the envs over L difficulty levels, the easiest first: env e at level ⌊e·L/N⌋, difficulty
    /// level / (L − 1) (mjlab's terrain levels: 10).
    #[arg(long, value_name = "L", value_parser = clap::value_parser!(u32).range(2..=1000))]
    pub levels: Option<u32>,

    /// Each scheme's share of the envs, comma-separated, in the order of the schemes [default: equal].
    #[arg(
        long,
        value_name = "P,P,…",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub proportions: Option<Vec<f64>>,

    /// Base seed of every env's terrains and of the mix's draw [default: the first scheme's `seed`, else
    /// 0].
    #[arg(long, value_name = "B")]
    pub seed: Option<u64>,

    /// The envs' episode: their terrains after so many resets.
    #[arg(long, value_name = "K", default_value_t = 0)]
    pub episode: u32,

    /// Tiles per row [default: about square].
    #[arg(long, value_name = "C", value_parser = clap::value_parser!(u32).range(1..))]
    pub cols: Option<u32>,

    /// Pixels per cell [default: tiles about 120 pixels wide].
    #[arg(long, value_name = "P", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub cell_pixels: Option<u32>,

    /// Draw a mix's schemes on one colour scale, to compare their heights
    /// [default: each scheme on its own scale, with a legend bar each].
    #[arg(long)]
    pub one_scale: bool,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct BatchArgs {
    /// The scheme CSV file.
    pub scheme: PathBuf,

    /// The output folder; worlds go in `OUT/world_NNNN/`.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,

    /// Worlds in the batch [default: the scheme's `amount`, else 1].
    #[arg(long, value_name = "N")]
    pub amount: Option<u64>,

    /// Base seed [default: the scheme's `seed`, else 0].
    #[arg(long, value_name = "B")]
    pub seed: Option<u64>,

    #[command(flatten)]
    pub difficulty: DifficultyArg,

    #[command(flatten)]
    pub files: WorldFilesArgs,

    /// Worker threads [default: one per core].
    #[arg(short, long, value_name = "J", value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,

    /// Write only the worlds with index ≡ K (mod N), for N machines or processes (K from 0);
    /// `auto`: this task's shard of a Slurm array job (`SLURM_ARRAY_TASK_ID`, `_MIN`, `_COUNT`, `_STEP`).
    #[arg(long, value_name = "K/N|auto", value_parser = parse_shard)]
    pub shard: Option<Shard>,

    /// Replace world folders that hold a different world.
    #[arg(long)]
    pub force: bool,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct AtlasArgs {
    /// The scheme CSV files; column c uses scheme c mod (number of schemes).
    #[arg(required = true, value_name = "SCHEME")]
    pub schemes: Vec<PathBuf>,

    /// The world folder to write (its name is the world's).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,

    /// Tiles along x: difficulty levels, from the range's low end to its high end.
    #[arg(long, value_name = "R", value_parser = clap::value_parser!(u32).range(1..))]
    pub rows: u32,

    /// Tiles along y.
    #[arg(long, value_name = "C", value_parser = clap::value_parser!(u32).range(1..))]
    pub cols: u32,

    /// Base seed of every tile; tile (r, c) is world r·C + c [default: the first scheme's `seed`, else 0].
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,

    /// Cells of height 0 between tiles and around the outside.
    #[arg(long, value_name = "N", default_value_t = rse_core::AtlasOptions::default().border)]
    pub border: u32,

    /// Difficulty of the first row and of the last (`LO..HI`, or one value for every row).
    #[arg(long, value_name = "LO..HI", default_value = "0..1", allow_hyphen_values = true, value_parser = parse_difficulty_range)]
    pub difficulty: (Difficulty, Difficulty),

    /// A tile's origin z is the highest top within this many metres of its centre.
    #[arg(long, value_name = "M", default_value_t = rse_core::spawn::DEFAULT_SPAWN_RADIUS, value_parser = radius)]
    pub spawn_radius: f64,

    /// Flat patches per tile to list in atlas.json (spawn or goal points).
    #[arg(long, value_name = "N", default_value_t = rse_core::AtlasOptions::default().patches.count)]
    pub flat_patches: u32,

    /// Radius in metres of the disc a flat patch must cover.
    #[arg(long, value_name = "M", default_value_t = rse_core::spawn::DEFAULT_PATCH_RADIUS, value_parser = radius)]
    pub patch_radius: f64,

    /// Largest height difference under a flat patch, in steps.
    #[arg(long, value_name = "K", default_value_t = rse_core::AtlasOptions::default().patches.max_step)]
    pub max_step: u16,

    #[command(flatten)]
    pub files: WorldFilesArgs,

    /// Worker threads [default: one per core]; the atlas is the same on any number.
    #[arg(short, long, value_name = "J", value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,

    /// Replace the folder if it holds a different world.
    #[arg(long)]
    pub force: bool,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct HfieldArgs {
    /// The scheme CSV file.
    pub scheme: PathBuf,

    /// Where to write MuJoCo's binary height field (`<hfield file="…">`).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,

    /// Samples per cell along each axis: the surface is exact but within half a sample of a step edge.
    #[arg(long, value_name = "K", default_value_t = rse_core::DEFAULT_OVERSAMPLE, value_parser = clap::value_parser!(u32).range(1..))]
    pub oversample: u32,

    #[command(flatten)]
    pub world: WorldArgs,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct MeshArgs {
    /// The scheme CSV file.
    pub scheme: PathBuf,

    /// Where to write the mesh: `.obj` (and its `.mtl` beside it), `.stl` or `.glb`.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,

    #[command(flatten)]
    pub world: WorldArgs,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct HeightmapArgs {
    /// The scheme CSV file.
    pub scheme: PathBuf,

    #[command(flatten)]
    pub world: WorldArgs,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

#[derive(Debug, Args)]
pub struct PreviewArgs {
    /// The scheme CSV file.
    pub scheme: PathBuf,

    /// Where to write the PNG.
    #[arg(short, long, value_name = "FILE.png")]
    pub output: PathBuf,

    /// Pixels per cell, 1 to 256 [default: as many as make about 512 pixels across, at most 32].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=256))]
    pub cell_pixels: Option<u32>,

    #[command(flatten)]
    pub world: WorldArgs,

    #[command(flatten)]
    pub overrides: SchemeOverrides,
}

/// Which world of the batch: world `index` of base seed `seed`.
#[derive(Debug, Args)]
pub struct WorldArgs {
    /// Base seed of the batch [default: the scheme's `seed`, else 0].
    #[arg(long, value_name = "B")]
    pub seed: Option<u64>,

    /// Index of the world in the batch.
    #[arg(long, value_name = "I", default_value_t = 0)]
    pub index: u64,

    #[command(flatten)]
    pub difficulty: DifficultyArg,
}

/// `WorldFilesArgs` from rse-world's table of world options
/// (`for_each_world_option!`): a flag for each, its value read by the
/// option's own parser and range, and `config`.
macro_rules! world_files_args {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: $record:tt,
            range: $range:expr,
            flag: $flag:literal,
            value_name: $value_name:literal,
            help: $help:literal,
            py_type: $py_type:literal,
            default: $default:literal,
            $($rest:tt)*
        }
    )*) => {
        /// What goes in a world folder: targets, terrain model, colliders,
        /// templates (`batch` and `atlas` alike).
        #[derive(Debug, Args)]
        pub struct WorldFilesArgs {
            $(
                #[arg(
                    long = $flag,
                    value_name = $value_name,
                    help = concat!($help, " [default: ", $default, "]"),
                    value_parser = |text: &str| world_flag::<$ty>(text, &$range),
                )]
                pub $field: Option<$ty>,
            )*

            /// A folder of templates overlaying ours file by file (DIR/gazebo/rse.world.j2, …).
            #[arg(long, value_name = "DIR")]
            pub template: Option<PathBuf>,
        }

        impl WorldFilesArgs {
            /// What these flags give a world folder, at `difficulty`: what
            /// the user gave, `None` for the rest (rse-world's
            /// `WorldConfig` resolves them).
            pub fn config(&self, difficulty: Difficulty) -> WorldConfig {
                WorldConfig {
                    difficulty: Some(difficulty),
                    $($field: self.$field.clone(),)*
                }
            }
        }
    };
}

rse_world::for_each_world_option!(world_files_args);

/// A world option's flag value: read by the option's parser, then its
/// range (rse-world's, which `WorldConfig::resolve` checks again for every
/// front end).
fn world_flag<T: OptionValue>(
    text: &str,
    range: &impl rse_core::global_range::GlobalRange<T>,
) -> Result<T, String> {
    let value = T::parse_option(text)?;
    range.check(&value)?;
    Ok(value)
}

impl WorldFilesArgs {
    /// The world options these flags give, at `difficulty`.
    pub fn options(&self, difficulty: Difficulty) -> anyhow::Result<WorldOptions> {
        self.config(difficulty).resolve().map_err(in_flags)
    }

    /// The templates: ours, or ours overlaid by `--template DIR`.
    pub fn templates(&self) -> anyhow::Result<Templates> {
        Ok(match &self.template {
            Some(dir) => Templates::with_overrides(dir)?,
            None => Templates::builtin(),
        })
    }
}

/// A world option's error in the command line's words: the only option
/// clap cannot refuse alone is an oversample without a height field.
pub fn in_flags(error: rse_world::Error) -> anyhow::Error {
    match error {
        rse_world::Error::BadOption {
            option: "mujoco_collider",
            ..
        } => anyhow::anyhow!("--oversample: {error}; add --mujoco-collider hfield"),
        error => error.into(),
    }
}

/// A difficulty for curricula (docs/schemes.md, "Difficulty").
#[derive(Debug, Args)]
pub struct DifficultyArg {
    /// Scale every obstacle height h to floor(D·h + 0.5) steps, 0 ≤ D ≤ 1; the layout stays, frames stay 1 step.
    #[arg(
        long = "difficulty",
        value_name = "D",
        default_value = "1",
        allow_negative_numbers = true
    )]
    pub value: Difficulty,
}

/// `SchemeOverrides` from rse-core's table of global keys
/// (`for_each_global_key!`): one flag for each key that has one, its type,
/// help line and clap settings as the table gives them, its value read by
/// the scheme file's parser and range ([`flag_value`]). Munches the table
/// entry by entry, keeping the keys with a flag (`amount` and `seed` are
/// the batch's own flags).
macro_rules! scheme_overrides {
    (@munch [$($variant:ident $field:ident: $flag:ty => $help:literal ($($arg:tt)*);)*]) => {
        /// Global parameters that override the scheme's, on the subcommands
        /// that read a scheme (after the subcommand, or before it for all of
        /// them).
        #[derive(Debug, Clone, Copy, Default, Args)]
        #[command(next_help_heading = "Scheme overrides")]
        pub struct SchemeOverrides {
            $(
                #[doc = $help]
                #[arg(
                    long,
                    value_parser = |text: &str| flag_value::<_, $flag>(GlobalKey::$variant, text, |patch| patch.$field),
                    $($arg)*
                )]
                pub $field: Option<$flag>,
            )*
        }

        impl SchemeOverrides {
            /// The flags as core's patch of the scheme's globals (the keys
            /// without a flag unset).
            pub fn patch(&self) -> GlobalsPatch {
                GlobalsPatch {
                    $($field: self.$field.map(FlagValue::into_patch),)*
                    ..GlobalsPatch::default()
                }
            }
        }

        impl From<GlobalsPatch> for SchemeOverrides {
            /// The flags of a patch (it holds no more than they set: it is
            /// made from them).
            fn from(patch: GlobalsPatch) -> Self {
                SchemeOverrides {
                    $($field: patch.$field.map(FlagValue::from_patch),)*
                }
            }
        }
    };
    (@munch [$($done:tt)*]
        $(#[doc = $what:literal])*
        $variant:ident { $field:ident: $ty:ty, range: $range:expr, stored: $stored:tt, flag: {} }
        $($rest:tt)*
    ) => {
        scheme_overrides!(@munch [$($done)*] $($rest)*);
    };
    (@munch [$($done:tt)*]
        $(#[doc = $what:literal])*
        $variant:ident {
            $field:ident: $ty:ty,
            range: $range:expr,
            stored: $stored:tt,
            flag: { ty: $flag:ty, help: $help:literal, arg: ($($arg:tt)*) }
        }
        $($rest:tt)*
    ) => {
        scheme_overrides!(@munch [$($done)* $variant $field: $flag => $help ($($arg)*);] $($rest)*);
    };
    ($($table:tt)*) => {
        scheme_overrides!(@munch [] $($table)*);
    };
}

/// A global flag's value, read as a scheme file reads `key` (core's
/// parser, then its range: one rule for both), `take` picking it from the
/// patch; the error is the scheme file's reason, which clap prefixes with
/// the flag and the text.
fn flag_value<Patch, Flag: FlagValue<Patch>>(
    key: GlobalKey,
    text: &str,
    take: impl FnOnce(GlobalsPatch) -> Option<Patch>,
) -> Result<Flag, String> {
    let mut patch = GlobalsPatch::default();
    match patch.set_key(key, text) {
        Ok(()) => take(patch)
            .map(Flag::from_patch)
            .ok_or_else(|| format!("expected {}", key.expects())),
        Err(error) => Err(match error.kind {
            SchemeErrorKind::BadGlobal { reason, .. } => reason,
            _ => error.to_string(),
        }),
    }
}

rse_core::for_each_global_key!(scheme_overrides);

/// A flag's value as core's patch holds it, and back: the same value, but
/// `--pallets`, whose `off` clap cannot hold as an `Option<Option<_>>`.
trait FlagValue<Patch>: Sized {
    fn into_patch(self) -> Patch;
    fn from_patch(patch: Patch) -> Self;
}

impl<T> FlagValue<T> for T {
    fn into_patch(self) -> T {
        self
    }

    fn from_patch(patch: T) -> T {
        patch
    }
}

impl FlagValue<Option<[u32; 2]>> for PalletsFlag {
    fn into_patch(self) -> Option<[u32; 2]> {
        self.0
    }

    fn from_patch(patch: Option<[u32; 2]>) -> Self {
        PalletsFlag(patch)
    }
}

impl SchemeOverrides {
    /// These flags, each unset one taken from `outer` (the same flags given
    /// before the subcommand): core's `GlobalsPatch::combine`.
    pub fn or(self, outer: SchemeOverrides) -> SchemeOverrides {
        SchemeOverrides::from(self.patch().combine(outer.patch()))
    }

    /// The first global flag given, as typed (`--size`), if any.
    pub fn first_set(&self) -> Option<String> {
        let key = *self.patch().given().first()?;
        Some(format!("--{}", key.name().replace('_', "-")))
    }
}

/// `--pallets`: a layout, or `None` for off (read as a scheme file's
/// `pallets` is).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PalletsFlag(pub Option<[u32; 2]>);

fn parse_shard(text: &str) -> Result<Shard, String> {
    let shard = if text == "auto" {
        Shard::from_slurm_array(|name| std::env::var(name).ok())
    } else {
        text.parse()
    };
    shard.map_err(|e: rse_world::Error| e.to_string())
}

/// `LO..HI`, or one difficulty `D` meaning `D..D`.
fn parse_difficulty_range(text: &str) -> Result<(Difficulty, Difficulty), String> {
    let (lo, hi) = text.split_once("..").unwrap_or((text, text));
    let parse = |s: &str| s.parse::<Difficulty>().map_err(|e| e.to_string());
    let (lo, hi) = (parse(lo)?, parse(hi)?);
    if lo > hi {
        return Err(format!("the range {lo}..{hi} runs backwards"));
    }
    Ok((lo, hi))
}

/// A radius in metres, by core's one rule for radii.
fn radius(text: &str) -> Result<f64, String> {
    let value = text
        .parse::<f64>()
        .map_err(|_| "expected a length in metres".to_owned())?;
    rse_core::spawn::check_radius(value)
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory as _;

    #[test]
    fn the_command_line_is_well_formed() {
        super::Cli::command().debug_assert();
    }

    #[test]
    fn every_example_in_the_help_parses() {
        let mut parsed = 0;
        for text in crate::examples::ALL {
            for line in text.lines().map(str::trim) {
                let Some(rest) = line.strip_prefix("rse-gen ") else {
                    continue;
                };
                // A redirection is the shell's, not ours.
                let words = rest.split(" > ").next().unwrap_or(rest).split_whitespace();
                let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
                for scheme in words.clone().filter(|w| w.starts_with("schemes/")) {
                    assert!(repo.join(scheme).exists(), "{line}: no {scheme}");
                }
                let args = std::iter::once("rse-gen").chain(words);
                if let Err(e) = <super::Cli as clap::Parser>::try_parse_from(args) {
                    panic!("{line}: {e}");
                }
                parsed += 1;
            }
        }
        assert!(parsed >= 18, "{parsed} examples");
    }
}
