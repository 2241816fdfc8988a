#![warn(missing_docs)]
//! rotlang: the infill rotation template language of 3D-printing slicers.
//!
//! ```
//! let parse = rotlang::parse("+10L25%, -10l25%", rotlang::Target::Sparse);
//! assert!(parse.diagnostics.is_empty());
//! assert_eq!(parse.template.instructions.len(), 2);
//! ```

// pest_derive without its "std" feature generates code that names `alloc`.
extern crate alloc;

pub mod api;
pub mod diagnostic;
pub mod dialect;
pub mod eval;
pub mod explain;
pub mod fix;
pub mod format;
pub mod ir;
mod lint;
pub mod number;
mod syntax;

pub use syntax::{MAX_DIAGNOSTICS, Parse};

pub use diagnostic::{Diagnostic, Fix, Label, LineIndex, Severity, Span};
pub use ir::*;

/// Parse a template for the given target (sparse or solid infill).
pub fn parse(text: &str, target: Target) -> Parse {
    syntax::parse(text, target)
}

/// The diagnostics of a template, without its IR: `Parse::template` is empty, everything
/// else is as [`parse`] gives it. Memory stays within the text and the capped diagnostics
/// whatever the template's size (what `rotlang check` uses).
pub fn check(text: &str, target: Target) -> Parse {
    syntax::parse_each(text, target, drop).into_parse(Template::default())
}

/// [`check`], handing each instruction to `emit` in text order as it is read: the
/// instructions of [`parse`] without a `Template` holding them all (a consumer keeps what it
/// needs of each; the language server keeps their spans).
///
/// ```
/// let mut spans = Vec::new();
/// let parse = rotlang::parse_each("0, +30/5", rotlang::Target::Sparse, |i| spans.push(i.span));
/// assert_eq!(spans, [rotlang::Span::new(0, 1), rotlang::Span::new(3, 8)]);
/// assert!(parse.template.instructions.is_empty() && !parse.has_errors());
/// ```
pub fn parse_each(text: &str, target: Target, emit: impl FnMut(Instruction)) -> Parse {
    syntax::parse_each(text, target, emit).into_parse(Template::default())
}
