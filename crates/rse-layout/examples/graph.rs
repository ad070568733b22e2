//! Prints every crate's module graph, one module a line with the modules
//! it uses: `cargo run -p rse-layout --example graph`.

fn main() {
    for dir in rse_layout::crate_dirs() {
        let name = dir.file_name().map(|n| n.to_string_lossy().into_owned());
        println!("{}", name.unwrap_or_default());
        for (module, uses) in rse_layout::module_graph(&dir) {
            let uses: Vec<&str> = uses.iter().map(String::as_str).collect();
            println!("  {module} -> {}", uses.join(", "));
        }
    }
}
