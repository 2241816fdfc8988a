//! Prints the file graph of a crate, then each cycle with its edges and the paths that make
//! them: `cargo run -p rotlang-cycles --example graph -- lsp/src`.
fn main() {
    let dir = std::env::args().nth(1).expect("a src folder");
    let src = std::path::Path::new(&dir);
    let graph = rotlang_cycles::crate_graph(src).unwrap_or_else(|e| panic!("{e}"));
    for (from, to) in &graph {
        println!(
            "{from} -> {}",
            to.iter().cloned().collect::<Vec<_>>().join(" ")
        );
    }
    let reasons = rotlang_cycles::crate_reasons(src).unwrap_or_else(|e| panic!("{e}"));
    for cycle in rotlang_cycles::cycles(&graph) {
        println!("cycle: {}", cycle.join(" ↔ "));
        for ((from, to), paths) in &reasons {
            if cycle.contains(from) && cycle.contains(to) {
                let paths: Vec<&str> = paths.iter().map(String::as_str).collect();
                println!("  {from} -> {to}: {}", paths.join(", "));
            }
        }
    }
}
