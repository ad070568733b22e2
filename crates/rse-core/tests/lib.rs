//! Integration tests of rse-core, one binary (see `STYLE.md`).

mod atlas;
mod difficulty;
mod golden;
mod mesh;
mod obstacles;
mod properties;
mod samples;
mod scheme_files;
mod util;
