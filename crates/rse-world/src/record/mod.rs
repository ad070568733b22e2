//! `rse.json`, the record a world is rebuilt from: the world options it
//! holds (`options`), the manifest itself (`manifest`, `atlas_record`), and
//! reading it back: what a rebuild costs (`cost`) and the rebuild
//! (`rebuild`).

pub(crate) mod atlas_record;
pub(crate) mod cost;
pub(crate) mod manifest;
pub(crate) mod options;
pub(crate) mod rebuild;
