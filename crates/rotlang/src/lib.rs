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

pub use syntax::MAX_DIAGNOSTICS;

pub use diagnostic::{Diagnostic, Fix, Label, LineIndex, Severity, Span};
pub use ir::*;

/// The result of parsing: the template (with every instruction that could be read) and
/// every diagnostic found. Parsing never fails as a whole.
#[derive(Clone, Debug, Default)]
pub struct Parse {
    /// The template: every instruction that could be read, in order.
    pub template: Template,
    /// At most `MAX_DIAGNOSTICS` (100), then one `rotlang::too-many-diagnostics` entry.
    /// Past the cap errors take precedence over warnings, so the first error is always
    /// in the list.
    pub diagnostics: Vec<Diagnostic>,
    /// How many diagnostics were found beyond the cap and not kept.
    pub omitted: usize,
    /// How many errors were found, kept or not (the "not shown" entry is not counted).
    pub errors: usize,
    /// How many warnings were found, kept or not.
    pub warnings: usize,
}

impl Parse {
    /// Whether any instruction failed to parse or validate: exact whatever the cap on
    /// `diagnostics`. Formatters and anything that rewrites text must check this.
    pub fn has_errors(&self) -> bool {
        self.errors > 0 || self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

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
