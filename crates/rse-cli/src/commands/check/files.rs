//! A world folder's files: the manifest's hashes, well-formed XML, and every
//! file that a world file names (mesh URIs, includes, URLs, references).

use std::path::{Path, PathBuf};

use quick_xml::Reader;
use quick_xml::events::Event;
use rse_world::{MANIFEST, Manifest, sha256_hex};

/// Faults of the files against the manifest: missing, changed, unlisted.
pub fn check_hashes(
    world: &Path,
    manifest: &Manifest,
    present: &[String],
    faults: &mut Vec<String>,
) {
    for (path, digest) in &manifest.files {
        match std::fs::read(world.join(path)) {
            Ok(bytes) if sha256_hex(&bytes) == *digest => {}
            Ok(_) => faults.push(format!(
                "{path}: SHA-256 differs from rse.json (the file changed)"
            )),
            Err(e) => faults.push(format!(
                "{path}: listed in rse.json but cannot be read: {e}"
            )),
        }
    }
    for path in present {
        if path != MANIFEST && !manifest.files.contains_key(path) {
            faults.push(format!("{path}: not listed in rse.json"));
        }
    }
}

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
    match Path::new(path).extension()?.to_str()? {
        "world" | "sdf" | "config" | "xml" | "urdf" => Some(FileKind::Xml),
        "wbt" => Some(FileKind::Webots),
        "usda" => Some(FileKind::Usd),
        _ => None,
    }
}

/// Parses every XML file (well-formed?) and checks that every file named by
/// an XML, Webots or USD file exists.
pub fn check_files(world: &Path, present: &[String], faults: &mut Vec<String>) {
    for path in present {
        let Some(kind) = kind(path) else {
            continue;
        };
        let Ok(text) = std::fs::read_to_string(world.join(path)) else {
            faults.push(format!("{path}: not UTF-8 text"));
            continue;
        };
        let references = match kind {
            FileKind::Xml => match xml_references(&text) {
                Ok(found) => found,
                Err(message) => {
                    faults.push(format!("{path}: not well-formed XML: {message}"));
                    continue;
                }
            },
            FileKind::Webots => wbt_urls(&text),
            FileKind::Usd => usd_asset_paths(&text),
        };
        let folder = Path::new(path).parent().unwrap_or(Path::new(""));
        for reference in references {
            if let Some(fault) = check_reference(world, folder, &reference) {
                faults.push(format!("{path}: {fault}"));
            }
        }
    }
}

/// `None` if `reference` (named by a file in `folder`) exists in the world.
fn check_reference(world: &Path, folder: &Path, reference: &str) -> Option<String> {
    if reference.contains("://") && !reference.starts_with("model://") {
        return None; // a web address or a package the simulator resolves
    }
    if reference.starts_with('/') {
        return Some(format!(
            "names the absolute path {reference} (worlds must be movable)"
        ));
    }
    let target: PathBuf = match reference.strip_prefix("model://") {
        // Models are looked up on the Gazebo resource path: our `gazebo/`.
        Some(model) => Path::new("gazebo").join(model),
        None => folder.join(reference),
    };
    let full = world.join(&target);
    let exists = if reference.starts_with("model://")
        && !reference.trim_start_matches("model://").contains('/')
    {
        full.join("model.config").is_file()
    } else {
        full.is_file()
    };
    (!exists).then(|| format!("names {reference}, which does not exist"))
}

/// The files an XML world file names: `<uri>` and `<sdf>` texts (SDF,
/// model.config) and `file`/`filename` attributes (MJCF, URDF).
fn xml_references(text: &str) -> Result<Vec<String>, String> {
    let mut reader = Reader::from_str(text);
    let mut found = Vec::new();
    let mut in_reference = false;
    loop {
        let event = reader.read_event().map_err(|e| {
            let at = usize::try_from(reader.error_position())
                .unwrap_or(usize::MAX)
                .min(text.len());
            format!("line {}: {e}", text[..at].matches('\n').count() + 1)
        })?;
        match event {
            Event::Start(e) | Event::Empty(e) => {
                in_reference = matches!(e.local_name().into_inner(), "uri" | "sdf");
                for attribute in e.attributes() {
                    let attribute = attribute.map_err(|e| e.to_string())?;
                    if matches!(attribute.key.local_name().into_inner(), "file" | "filename") {
                        let value = attribute
                            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                            .map_err(|e| e.to_string())?;
                        found.push(value.into_owned());
                    }
                }
            }
            Event::Text(t) if in_reference => {
                let value = t.xml10_content();
                if !value.trim().is_empty() {
                    found.push(value.trim().to_owned());
                }
            }
            Event::End(_) => in_reference = false,
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
        rest = &list[end..];
    }
    found
}

/// The asset paths (`@path@`) of a USD layer.
fn usd_asset_paths(text: &str) -> Vec<String> {
    text.split('@')
        .skip(1)
        .step_by(2)
        .map(|p| p.trim_start_matches("./").to_owned())
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
            ["terrain.usda"]
        );
    }

    #[test]
    fn broken_xml_is_reported_with_its_line() {
        let err = xml_references("<a>\n<b>\n</a>\n").unwrap_err();
        assert!(err.starts_with("line 3"), "{err}");
    }
}
