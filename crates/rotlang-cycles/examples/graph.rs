//! Prints the file graph of a crate: `cargo run -p rotlang-cycles --example graph -- lsp/src`.
fn main() {
    let dir = std::env::args().nth(1).expect("a src folder");
    let graph = rotlang_cycles::crate_graph(std::path::Path::new(&dir)).unwrap();
    for (from, to) in &graph {
        println!(
            "{from} -> {}",
            to.iter().cloned().collect::<Vec<_>>().join(" ")
        );
    }
    for cycle in rotlang_cycles::cycles(&graph) {
        println!("cycle: {}", cycle.join(" ↔ "));
    }
}
