//! `rotlang-lsp`: speaks the Language Server Protocol on stdin/stdout.

const USAGE: &str = "\
Usage: rotlang-lsp [--stdio]

The language server for rotlang infill rotation templates (.rot files and the
templates in OrcaSlicer JSON/INI profiles). It speaks the Language Server Protocol
on standard input and output; an editor starts it, a person does not need to.

Options:
      --stdio    Talk over stdin/stdout (the default and only transport; accepted
                 because many clients pass it)
  -h, --help     Print this help and exit
  -V, --version  Print the version and exit

Settings (the model hovers and inlay hints are computed for) come from the client:
see lsp/README.md.
";

fn main() {
    for arg in std::env::args_os().skip(1) {
        match arg.to_str() {
            Some("--stdio") => {}
            Some("-h" | "--help") => {
                print!("{USAGE}");
                return;
            }
            Some("-V" | "--version") => {
                println!("rotlang-lsp {}", env!("CARGO_PKG_VERSION"));
                return;
            }
            _ => {
                // An editor passing an option we do not know would otherwise get a server
                // that silently ignores what it asked for.
                eprintln!(
                    "rotlang-lsp: unexpected argument '{}'\n\n{USAGE}",
                    arg.to_string_lossy()
                );
                std::process::exit(2);
            }
        }
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
