//! The rules of ARCHITECTURE.md that the sources can break: no crate's
//! modules use each other in a circle, and the command-line binary is a
//! leaf that no crate (the Python extension included) links.

use rse_layout::{crate_dirs, find_cycle, module_graph, workspace_dependencies};

#[test]
fn every_crates_modules_form_a_dag() {
    let dirs = crate_dirs();
    assert!(dirs.len() >= 8, "found only {} crates", dirs.len());
    let circles: Vec<String> = dirs
        .iter()
        .filter_map(|dir| {
            let cycle = find_cycle(&module_graph(dir))?;
            let name = dir.file_name().unwrap().to_string_lossy();
            Some(format!("{name}: {}", cycle.join(" -> ")))
        })
        .collect();
    assert!(
        circles.is_empty(),
        "modules use each other in a circle:\n{}",
        circles.join("\n")
    );
}

/// The module graph of the crate `name`.
fn graph_of(name: &str) -> rse_layout::ModuleGraph {
    let dir = crate_dirs()
        .into_iter()
        .find(|dir| dir.ends_with(name))
        .unwrap_or_else(|| panic!("no crate {name}"));
    module_graph(&dir)
}

#[test]
fn the_graph_sees_uses_and_cycles() {
    // The reader itself, on a crate known to have edges: rse-world's
    // `files/place` uses `files/nofollow`, and a made-up back edge is a
    // circle.
    let (place, nofollow) = ("files/place", "files/nofollow");
    let mut graph = graph_of("rse-world");
    assert!(graph[place].contains(nofollow), "{:?}", graph[place]);
    assert!(find_cycle(&graph).is_none());
    graph.get_mut(nofollow).unwrap().insert(place.to_owned());
    let cycle = find_cycle(&graph).expect("a back edge is a cycle");
    assert!(cycle.contains(&place.to_owned()) && cycle.contains(&nofollow.to_owned()));
    // A grouped import counts each of its items: rse-verify's `world`
    // names `crate::{references, terrain}`.
    let verify = crate_dirs()
        .into_iter()
        .find(|dir| dir.ends_with("rse-verify"))
        .unwrap();
    let verify = module_graph(&verify);
    assert!(
        verify["world"].contains("references") && verify["world"].contains("terrain"),
        "{:?}",
        verify["world"]
    );
    // Nested modules: rse-core's mesh folder is read module by module.
    let core = crate_dirs()
        .into_iter()
        .find(|dir| dir.ends_with("rse-core"))
        .unwrap();
    let core = module_graph(&core);
    assert!(
        core.contains_key("mesh/stitch") && core.contains_key("mesh"),
        "{core:?}"
    );
}
#[test]
fn the_command_line_is_a_leaf() {
    for dir in crate_dirs() {
        let deps = workspace_dependencies(&dir);
        assert!(
            !deps.contains("rse-cli"),
            "{} depends on rse-cli: the binary is a leaf (ARCHITECTURE.md)",
            dir.display()
        );
    }
}
