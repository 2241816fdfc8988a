//! `rotlang-lsp`: the language server for rotlang templates, as a library so that the
//! binary stays a thin `main` and benchmarks can call the features directly.
//!
//! Protocol glue only: every bit of language knowledge comes from the `rotlang` crate.
//! Spans are bytes throughout; `position` converts at the edge.

pub mod code_actions;
pub mod compat;
pub mod completion;
pub mod diagnostics;
pub mod document;
pub mod formatting;
pub mod hover;
pub mod incremental;
pub mod ini;
pub mod inlay_hints;
pub mod instructions;
pub mod json;
pub mod jsonc;
mod kind;
pub mod markup;
pub mod memory;
pub mod position;
pub mod preview;
pub mod reading;
pub mod semantic_tokens;
pub mod server;
pub mod settings;
pub mod symbols;
pub mod sync;
pub mod transport;
