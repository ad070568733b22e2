//! rse-world's modules form a line: no module uses another that uses it
//! back, directly or through others (ARCHITECTURE.md, "rse-world").

use std::collections::{BTreeMap, BTreeSet};

/// Each module of `src/` and the modules of this crate it names
/// (`crate::name`).
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut graph = BTreeMap::new();
    for entry in std::fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        let module = path.file_stem().unwrap().to_str().unwrap().to_owned();
        if module == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let used: BTreeSet<String> = text
            .match_indices("crate::")
            .map(|(at, _)| {
                text[at + "crate::".len()..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect::<String>()
            })
            .filter(|name| *name != module)
            .collect();
        graph.insert(module, used);
    }
    graph
}

/// Depth-first from `module`: a module on the current `path` seen again
/// is a cycle.
fn visit<'a>(
    module: &'a str,
    graph: &'a BTreeMap<String, BTreeSet<String>>,
    path: &mut Vec<&'a str>,
    done: &mut BTreeSet<&'a str>,
) {
    if let Some(at) = path.iter().position(|m| *m == module) {
        panic!(
            "modules import each other: {} -> {module}",
            path[at..].join(" -> ")
        );
    }
    if !done.insert(module) {
        return;
    }
    path.push(module);
    for next in &graph[module] {
        visit(next, graph, path, done);
    }
    path.pop();
}

#[test]
fn no_module_imports_one_that_imports_it() {
    let graph = imports();
    assert!(graph.len() > 10, "{graph:?}");
    for name in graph.values().flatten() {
        assert!(
            graph.contains_key(name),
            "crate::{name} is not a module of src/"
        );
    }
    let mut done = BTreeSet::new();
    for module in graph.keys() {
        visit(module, &graph, &mut Vec::new(), &mut done);
    }
}
