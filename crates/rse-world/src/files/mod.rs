//! The world folders on disk: reading them without following links
//! (`nofollow`), listing and naming their files (`tree`, `names`), writing
//! a file whole (`write`), placing a world folder atomically (`place`,
//! `folder`), and the digest every file is recorded by (`digest`).

pub(crate) mod digest;
pub(crate) mod folder;
pub(crate) mod names;
pub(crate) mod nofollow;
pub(crate) mod place;
pub(crate) mod tree;
pub(crate) mod write;
