//! The workspace's shape as data: each crate's module graph, read from its
//! sources, and the arrows between crates, read from their manifests.
//! `tests/` holds the rules (ARCHITECTURE.md); nothing here is shipped.

// A test helper: an unreadable workspace is a failed test, so reading it
// panics with what failed rather than returning errors.
#![allow(clippy::missing_panics_doc)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A crate's modules (paths under `src/` without extension, `mod.rs` as its
/// folder: `mesh/faces`, `mesh`) and, for each, the modules of the same
/// crate its code names.
pub type ModuleGraph = BTreeMap<String, BTreeSet<String>>;

/// The workspace's root folder.
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .nth(2)
        .expect("crates/rse-layout sits two levels below the root")
        .to_path_buf()
}

/// The folders of every crate under `crates/`, sorted.
pub fn crate_dirs() -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(workspace_root().join("crates"))
        .expect("crates/ lists")
        .map(|entry| entry.expect("crates/ lists").path())
        .filter(|dir| dir.join("Cargo.toml").is_file())
        .collect();
    dirs.sort();
    dirs
}

/// Every `.rs` file under `dir`, as module paths relative to `src`.
fn module_files(src: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) {
    for entry in std::fs::read_dir(dir).expect("src/ lists") {
        let path = entry.expect("src/ lists").path();
        if path.is_dir() {
            module_files(src, &path, out);
            continue;
        }
        if path.extension().is_none_or(|ext| ext != "rs") {
            continue;
        }
        let relative = path
            .strip_prefix(src)
            .expect("under src/")
            .with_extension("");
        let mut name = relative.to_string_lossy().replace('\\', "/");
        if name.ends_with("/mod") {
            name.truncate(name.len() - "/mod".len());
        }
        out.push((name, path));
    }
}

/// The code of a file without its comments (a doc link names a module
/// without using it) and without its unit tests (a `#[cfg(test)]` module,
/// last in the file by the house style: tests sit above every module and
/// may use any).
fn code_of(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod ") {
        Some(at) => &text[..at],
        None => text,
    };
    text.lines()
        .map(|line| match line.find("//") {
            Some(at) => &line[..at],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The path segments that follow each occurrence of `prefix` (`crate::`,
/// `super::`) in `code`: `crate::mesh::faces::Face` gives
/// `["mesh", "faces", "Face"]`, and a group gives one path per item:
/// `crate::{a, b::{c, d}}` gives `["a"]`, `["b", "c"]`, `["b", "d"]`.
fn paths_after<'a>(code: &'a str, prefix: &str) -> Vec<Vec<&'a str>> {
    let mut paths = Vec::new();
    for (at, _) in code.match_indices(prefix) {
        // `foo_crate::` or `rse_core::crate` are not this crate's paths.
        let joined = code[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
        if !joined {
            tree_paths(&code[at + prefix.len()..], Vec::new(), &mut paths);
        }
    }
    paths
}

/// The paths of the use tree at the start of `rest`, each after `base`.
/// Returns how many bytes of `rest` the tree spans.
fn tree_paths<'a>(rest: &'a str, mut base: Vec<&'a str>, out: &mut Vec<Vec<&'a str>>) -> usize {
    let mut at = 0;
    loop {
        let name_len = rest[at..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(rest.len() - at);
        if name_len > 0 {
            base.push(&rest[at..at + name_len]);
            at += name_len;
        }
        if rest[at..].starts_with("::") {
            at += 2;
            continue;
        }
        if rest[at..].starts_with('{') {
            at += 1;
            loop {
                at += rest[at..].len() - rest[at..].trim_start().len();
                if rest[at..].starts_with('}') || at >= rest.len() {
                    return (at + 1).min(rest.len());
                }
                at += tree_paths(&rest[at..], base.clone(), out);
                at += rest[at..].len() - rest[at..].trim_start().len();
                if rest[at..].starts_with(',') {
                    at += 1;
                }
            }
        }
        if !base.is_empty() {
            out.push(base);
        }
        return at;
    }
}

/// The deepest module of `modules` that `base` + `segments` names.
fn resolve(modules: &BTreeSet<String>, base: &[&str], segments: &[&str]) -> Option<String> {
    let mut path: Vec<&str> = base.to_vec();
    let mut found = None;
    for segment in segments {
        path.push(segment);
        let name = path.join("/");
        if modules.contains(&name) {
            found = Some(name);
        } else {
            break;
        }
    }
    found
}

/// The module graph of the crate in `crate_dir`. `lib.rs` and `main.rs`
/// (the roots, which declare every module) are left out, and so are uses
/// of a module's own ancestors (a folder's `mod.rs` declares its children,
/// which may use what it holds).
pub fn module_graph(crate_dir: &Path) -> ModuleGraph {
    let src = crate_dir.join("src");
    let mut files = Vec::new();
    module_files(&src, &src, &mut files);
    files.retain(|(name, _)| name != "lib" && name != "main");
    let modules: BTreeSet<String> = files.iter().map(|(name, _)| name.clone()).collect();
    let mut graph = ModuleGraph::new();
    for (name, path) in &files {
        let code = code_of(&std::fs::read_to_string(path).expect("a module reads"));
        let own: Vec<&str> = name.split('/').collect();
        let parent = &own[..own.len() - 1];
        let mut used = BTreeSet::new();
        for segments in paths_after(&code, "crate::") {
            used.extend(resolve(&modules, &[], &segments));
        }
        for segments in paths_after(&code, "super::") {
            used.extend(resolve(&modules, parent, &segments));
        }
        used.retain(|other| {
            other != name && !own.starts_with(&other.split('/').collect::<Vec<_>>()[..])
        });
        graph.insert(name.clone(), used);
    }
    graph
}

/// A cycle of `graph` as the modules along it, if it has one.
pub fn find_cycle(graph: &ModuleGraph) -> Option<Vec<String>> {
    fn visit<'a>(
        module: &'a str,
        graph: &'a ModuleGraph,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(at) = path.iter().position(|m| *m == module) {
            let mut cycle: Vec<String> = path[at..].iter().map(|m| (*m).to_owned()).collect();
            cycle.push(module.to_owned());
            return Some(cycle);
        }
        if !done.insert(module) {
            return None;
        }
        path.push(module);
        for next in graph.get(module).into_iter().flatten() {
            if let Some(cycle) = visit(next, graph, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|module| visit(module, graph, &mut Vec::new(), &mut done))
}

/// The workspace crates a crate's manifest names under `[dependencies]`
/// (normal, optional or per target; not dev or build ones).
pub fn workspace_dependencies(crate_dir: &Path) -> BTreeSet<String> {
    let manifest = std::fs::read_to_string(crate_dir.join("Cargo.toml")).expect("Cargo.toml reads");
    let mut section = String::new();
    let mut deps = BTreeSet::new();
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            line.clone_into(&mut section);
            continue;
        }
        let normal = section == "[dependencies]"
            || (section.starts_with("[target.") && section.ends_with(".dependencies]"));
        if !normal {
            continue;
        }
        let name = line.split(['=', ' ', '.']).next().unwrap_or("");
        if name.starts_with("rse-") {
            deps.insert(name.to_owned());
        }
    }
    deps
}

#[cfg(test)]
mod tests {
    use super::paths_after;

    #[test]
    fn paths_are_read_plain_grouped_and_nested() {
        let code = "use crate::a::B;\nuse crate::{c, d::{e, f::G}, h};\nlet x = my_crate::z;";
        assert_eq!(
            paths_after(code, "crate::"),
            [
                vec!["a", "B"],
                vec!["c"],
                vec!["d", "e"],
                vec!["d", "f", "G"],
                vec!["h"],
            ]
        );
    }
}
