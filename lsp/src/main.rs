//! `rotlang-lsp`: speaks the Language Server Protocol on stdin/stdout.

fn main() {
    if std::env::args().any(|a| a == "--version" || a == "-V") {
        println!("rotlang-lsp {}", env!("CARGO_PKG_VERSION"));
        return;
    }
    // A current-thread runtime built by hand: `#[tokio::main]` would pull in tokio-macros
    // (and with it a second major version of syn) for one line.
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("rotlang-lsp: cannot start the async runtime: {e}");
            std::process::exit(1);
        }
    };
    runtime.block_on(rotlang_lsp::server::run_stdio());
    // Tokio's stdin reader may still be blocked in a read that will never finish;
    // everything has been written, so leave without waiting for it.
    std::process::exit(0);
}
