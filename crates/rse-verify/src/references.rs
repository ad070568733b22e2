//! World files that name other files (SDF, `model.config`, MJCF, URDF,
//! Webots, USD): each must parse, and every file it names must be in the
//! world. XML is read as a stream with a depth cap and no DTD, so a
//! hostile file costs time in proportion to its (capped) size.

use quick_xml::Reader;
use quick_xml::events::Event;

use crate::fault::{Fault, FaultKind, excerpt, line_of};
use crate::folder::{Folder, resolve};
use crate::limits::{MAX_REFERENCES, MAX_XML_DEPTH};

/// The kinds of world file that name other files.
#[derive(Clone, Copy, PartialEq, Eq)]
enum FileKind {
    /// SDF worlds and models, `model.config`, MJCF, URDF.
    Xml,
    /// A Webots `.wbt` world.
    Webots,
    /// A USD ASCII layer.
    Usd,
}

/// The kind of a file, by suffix; `None` for files that name nothing.
fn kind(path: &str) -> Option<FileKind> {
    match std::path::Path::new(path).extension()?.to_str()? {
        "world" | "sdf" | "config" | "xml" | "urdf" => Some(FileKind::Xml),
        "wbt" => Some(FileKind::Webots),
        "usda" => Some(FileKind::Usd),
        _ => None,
    }
}

/// `true` for the files [`check`] looks into.
pub fn names_files(path: &str) -> bool {
    kind(path).is_some()
}

/// Faults of the world file `path` (its `bytes`): not text, not
/// well-formed, or naming a file that is not in `folder`.
pub fn check(path: &str, bytes: &[u8], folder: &Folder) -> Vec<Fault> {
    let Some(kind) = kind(path) else {
        return Vec::new();
    };
    let Ok(text) = std::str::from_utf8(bytes) else {
        return vec![Fault::of(path, FaultKind::NotText)];
    };
    let references = match kind {
        FileKind::Xml => match xml_references(text) {
            Ok(found) => found,
            Err((line, reason)) => {
                return vec![Fault::of(path, FaultKind::BadXml { line, reason })];
            }
        },
        FileKind::Webots => wbt_urls(text),
        FileKind::Usd => usd_asset_paths(text),
    };
    if references.len() > MAX_REFERENCES {
        return vec![Fault::of(
            path,
            FaultKind::TooManyReferences {
                cap: MAX_REFERENCES,
            },
        )];
    }
    let dir = path.rsplit_once('/').map_or("", |(dir, _)| dir);
    references
        .into_iter()
        .filter_map(|reference| check_reference(folder, path, dir, &reference))
        .map(|kind| Fault::of(path, kind))
        .collect()
}

/// `None` if `reference` (named by the file `path`, in `dir`) is in the
/// world.
fn check_reference(folder: &Folder, path: &str, dir: &str, reference: &str) -> Option<FaultKind> {
    if is_absolute(reference) {
        return Some(FaultKind::AbsoluteReference {
            reference: excerpt(reference),
        });
    }
    match uri_scheme(reference) {
        Some(scheme) if own_scheme(path) != Some(scheme) => {
            return Some(FaultKind::ForeignUri {
                scheme: excerpt(scheme),
                reference: excerpt(reference),
            });
        }
        None | Some("model") => {}
        // A ROS package the simulator resolves on its own path: nothing of
        // the world to look for, as long as it cannot climb out of its
        // package.
        Some(_) => {
            return reference
                .split(['/', '\\'])
                .any(|part| part == "..")
                .then(|| FaultKind::OutsideWorld {
                    path: excerpt(reference),
                });
        }
    }
    // Models are looked up on the Gazebo model path: the target folder of
    // the file naming them (`gazebo/`, `gazebo-classic/`).
    let models = dir.split('/').next().unwrap_or_default();
    let target = match reference.strip_prefix("model://") {
        Some(model) if !model.contains('/') => resolve(models, &format!("{model}/model.config")),
        Some(model) => resolve(models, model),
        None => resolve(dir, reference),
    };
    match target {
        None => Some(FaultKind::OutsideWorld {
            path: excerpt(reference),
        }),
        Some(target) if folder.has(&target) => None,
        Some(_) => Some(FaultKind::MissingReference {
            reference: excerpt(reference),
        }),
    }
}

/// `true` for a path that names a place whatever folder the world is in:
/// rooted (`/`, `\\`, `\\\\server`), a drive (`C:\\`, `C:/`, `C:x`), or a
/// home (`~`).
fn is_absolute(reference: &str) -> bool {
    let bytes = reference.as_bytes();
    let drive = bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':';
    reference.starts_with(['/', '\\', '~']) || drive
}

/// The scheme of a URI (`scheme:` at the start, RFC 3986: a letter, then
/// letters, digits, `+`, `-`, `.`), or `None` for a path.
fn uri_scheme(reference: &str) -> Option<&str> {
    let (scheme, _) = reference.split_once(':')?;
    let mut chars = scheme.chars();
    let first = chars.next()?;
    (first.is_ascii_alphabetic()
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.')))
    .then_some(scheme)
}

/// The URI scheme the simulator reading `path` resolves to files of the
/// world, if any: `model` for Gazebo's SDF files and `model.config`,
/// `package` for URDF.
fn own_scheme(path: &str) -> Option<&'static str> {
    match std::path::Path::new(path).extension()?.to_str()? {
        "world" | "sdf" | "config" => Some("model"),
        "urdf" => Some("package"),
        _ => None,
    }
}

/// The files an XML world file names: `<uri>` and `<sdf>` texts (SDF,
/// model.config) and `file`/`filename` attributes (MJCF, URDF). The error
/// is the 1-based line and what is wrong.
fn xml_references(text: &str) -> Result<Vec<String>, (usize, String)> {
    let mut reader = Reader::from_str(text);
    let line_at = |at: u64| line_of(text.as_bytes(), usize::try_from(at).unwrap_or(usize::MAX));
    let mut found = Vec::new();
    let mut in_reference = false;
    let mut depth = 0usize;
    loop {
        let start = reader.buffer_position();
        let event = reader
            .read_event()
            // quick-xml's words quote the text it stumbled on, which may be
            // anyone's: say where, not what.
            .map_err(|_| {
                (
                    line_at(reader.error_position()),
                    "is not well-formed XML".to_owned(),
                )
            })?;
        let fault = |reason: String| (line_at(start), reason);
        match event {
            Event::DocType(_) => {
                // Entities declared in a DTD can expand without bound in a
                // simulator's parser; `rse` writes none.
                return Err(fault("declares a DTD (world files have none)".to_owned()));
            }
            Event::Start(ref e) | Event::Empty(ref e) => {
                if matches!(event, Event::Start(_)) {
                    depth += 1;
                    if depth > MAX_XML_DEPTH {
                        return Err(fault(format!(
                            "elements nest deeper than {MAX_XML_DEPTH} levels"
                        )));
                    }
                }
                in_reference = matches!(e.local_name().into_inner(), "uri" | "sdf");
                for attribute in e.attributes() {
                    let attribute = attribute
                        .map_err(|_| fault("an attribute is not well-formed".to_owned()))?;
                    if matches!(attribute.key.local_name().into_inner(), "file" | "filename") {
                        let value = attribute
                            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                            .map_err(|_| {
                                fault("an attribute value is not well-formed".to_owned())
                            })?;
                        found.push(value.into_owned());
                        if found.len() > MAX_REFERENCES {
                            return Ok(found); // refused by the caller
                        }
                    }
                }
            }
            Event::Text(t) if in_reference => {
                let value = t.xml10_content();
                if !value.trim().is_empty() {
                    found.push(value.trim().to_owned());
                    if found.len() > MAX_REFERENCES {
                        return Ok(found); // refused by the caller
                    }
                }
            }
            Event::End(_) => {
                in_reference = false;
                depth = depth.saturating_sub(1);
            }
            // quick-xml stops at the end without asking for open elements.
            Event::Eof if depth > 0 => {
                return Err(fault(format!("ends with {depth} elements not closed")));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    Ok(found)
}

/// The strings of every `url [ … ]` field of a Webots world.
fn wbt_urls(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("url") {
        rest = &rest[at + 3..];
        let Some(list) = rest.trim_start().strip_prefix('[') else {
            continue;
        };
        let end = list.find(']').unwrap_or(list.len());
        found.extend(list[..end].split('"').skip(1).step_by(2).map(str::to_owned));
        if found.len() > MAX_REFERENCES {
            break; // refused by the caller
        }
        rest = &list[end..];
    }
    found
}

/// The asset paths (`@path@`) of a USD layer.
fn usd_asset_paths(text: &str) -> Vec<String> {
    text.split('@')
        .skip(1)
        .step_by(2)
        .take(MAX_REFERENCES + 1) // more: refused by the caller
        .map(str::to_owned)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_are_found_in_each_format() {
        let sdf =
            "<sdf><model><uri>model://m/meshes/a.obj</uri><x file=\"../b.obj\"/></model></sdf>";
        assert_eq!(
            xml_references(sdf).unwrap(),
            ["model://m/meshes/a.obj", "../b.obj"]
        );
        assert_eq!(
            wbt_urls("Mesh { url [\n \"../meshes/terrain.obj\" ] } url [ \"x\" \"y\" ]"),
            ["../meshes/terrain.obj", "x", "y"]
        );
        assert_eq!(
            usd_asset_paths("references = @./terrain.usda@\n"),
            ["./terrain.usda"]
        );
    }

    /// Hole 10 of the fifth round: `file:///etc/passwd` passed as a web
    /// address. Only a target's own scheme names a file; an absolute path
    /// in any form is a fault.
    #[test]
    fn only_a_targets_own_uri_scheme_and_relative_paths_pass() {
        let dir = tempfile::tempdir().unwrap();
        let (folder, _) = Folder::list(dir.path());
        let verdict = |path: &str, reference: &str| {
            let dir = path.rsplit_once('/').map_or("", |(d, _)| d);
            match check_reference(&folder, path, dir, reference) {
                None => "ok",
                Some(FaultKind::AbsoluteReference { .. }) => "absolute",
                Some(FaultKind::ForeignUri { .. }) => "foreign",
                Some(FaultKind::OutsideWorld { .. }) => "outside",
                Some(FaultKind::MissingReference { .. }) => "missing",
                Some(other) => panic!("{other:?}"),
            }
        };
        for (path, reference, want) in [
            ("gazebo/world.sdf", "file:///etc/passwd", "foreign"),
            ("gazebo/world.sdf", "file:/etc/passwd", "foreign"),
            ("gazebo/world.sdf", "FILE:terrain.obj", "foreign"),
            (
                "gazebo/world.sdf",
                "https://fuel.gazebosim.org/x",
                "foreign",
            ),
            ("gazebo/world.sdf", "package://p/terrain.obj", "foreign"),
            ("mujoco/world.xml", "model://rse_terrain", "foreign"),
            ("webots/world.wbt", "webots://projects/x.png", "foreign"),
            ("urdf/rse.urdf", "package://p/meshes/terrain.obj", "ok"),
            ("urdf/rse.urdf", "package://p/../../etc/passwd", "outside"),
            ("gazebo/world.sdf", "model://rse_terrain", "missing"),
            ("urdf/rse.urdf", "/etc/passwd", "absolute"),
            ("urdf/rse.urdf", "\\\\server\\share\\x.obj", "absolute"),
            ("urdf/rse.urdf", "C:\\x.obj", "absolute"),
            ("urdf/rse.urdf", "C:/x.obj", "absolute"),
            ("urdf/rse.urdf", "c:x.obj", "absolute"),
            ("urdf/rse.urdf", "~/x.obj", "absolute"),
            ("urdf/rse.urdf", "../meshes/terrain.obj", "missing"),
            ("urdf/rse.urdf", "../../x.obj", "outside"),
        ] {
            assert_eq!(verdict(path, reference), want, "{path}: {reference}");
        }
    }

    #[test]
    fn broken_xml_is_reported_with_its_line() {
        let (line, _) = xml_references("<a>\n<b>\n</a>\n").unwrap_err();
        assert_eq!(line, 3);
    }

    #[test]
    fn hostile_xml_is_refused_not_expanded_or_recursed() {
        let bomb = "<?xml version=\"1.0\"?>\n<!DOCTYPE a [<!ENTITY x \"xxxxxxxx\"><!ENTITY y \"&x;&x;&x;&x;\">]>\n<a b=\"&y;\"/>";
        let (line, reason) = xml_references(bomb).unwrap_err();
        assert_eq!(line, 2, "{reason}");
        assert!(reason.contains("DTD"), "{reason}");
        let deep = "<a>".repeat(MAX_XML_DEPTH + 1) + &"</a>".repeat(MAX_XML_DEPTH + 1);
        let (_, reason) = xml_references(&deep).unwrap_err();
        assert!(reason.contains("nest deeper"), "{reason}");
        let fine = "<a>".repeat(MAX_XML_DEPTH) + &"</a>".repeat(MAX_XML_DEPTH);
        assert!(xml_references(&fine).is_ok());
        // An entity no DTD declares is an error, not an expansion.
        assert!(xml_references("<a file=\"&z;\"/>").is_err());
        // Cut short.
        let (_, reason) = xml_references("<a><b></b>").unwrap_err();
        assert!(reason.contains("not closed"), "{reason}");
    }
}
