//! The scheme editor (`rse-gen edit`) as a library: the page (HTML, script,
//! style), the page's model of a scheme (typed fields in, a core
//! [`Scheme`](rse_core::Scheme) out, faults mapped back to the field) and the
//! JSON API the page calls. Every answer comes from rse-core and rse-world,
//! so what the page shows is what `batch` writes. The command line serves
//! it over a loopback socket; the fuzz targets call the API directly.

pub mod api;
pub mod desktop;
mod drafts;
mod model;
pub mod page;
mod samples;
pub mod words;

pub use api::{Answer, Editor, Job};
pub use drafts::Drafts;
pub use model::{FieldError, PageScheme};
pub use samples::{NEW_SCHEME, SAMPLES};
