//! The terrain's look in the files rse-core writes itself, read from the
//! scheme's globals: the `.mtl` material of the OBJ and the display
//! colour of the USD mesh. A look key these files draw is read here
//! alone (the world files' looks are the templates' `look.j2`), so the
//! writers and their callers take the whole `Globals` and need no edit
//! when a key is added (docs/development.md, "Adding a global key").

use super::obj::MATERIAL;
use crate::Globals;

/// The MTL text defining [`MATERIAL`]: matte, of the scheme's `color`
/// (light wood by default).
pub fn mtl(globals: &Globals) -> String {
    format!(
        "# rse {}\nnewmtl {MATERIAL}\nKa 0.2 0.2 0.2\nKd {}\nKs 0.05 0.05 0.05\nNs 10\nd 1\nillum 2\n",
        crate::VERSION,
        globals.color
    )
}

/// The USD mesh's look: its `primvars:displayColor` line (the scheme's
/// `color`), indented as a property of the prim.
pub(super) fn usd_display(globals: &Globals) -> String {
    let [r, g, b] = globals.color.rgb();
    format!("    color3f[] primvars:displayColor = [({r}, {g}, {b})]\n")
}
