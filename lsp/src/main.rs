//! `rotlang-lsp`: speaks the Language Server Protocol on stdin/stdout.

#[tokio::main(flavor = "current_thread")]
async fn main() {
    if std::env::args().any(|a| a == "--version" || a == "-V") {
        println!("rotlang-lsp {}", env!("CARGO_PKG_VERSION"));
        return;
    }
    rotlang_lsp::server::run_stdio().await;
    // Tokio's stdin reader may still be blocked in a read that will never finish;
    // everything has been written, so leave without waiting for it.
    std::process::exit(0);
}
