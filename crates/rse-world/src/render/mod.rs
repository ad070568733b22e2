//! A world's files made in memory: the templates (`templates`) rendered
//! with a world's values (`context`, `box_value`, `join_filter`) beside the
//! heightmap, preview and meshes (`world`).

pub(crate) mod box_value;
pub(crate) mod context;
pub(crate) mod join_filter;
pub(crate) mod templates;
pub(crate) mod world;
