//! Other readings of a template than rotlang's own: OrcaSlicer's (SEMANTICS.md section 10),
//! and the compat lint that compares the two.
//!
//! rotlang's meaning (sections 1–9) is the sane one; OrcaSlicer, which ships the language,
//! reads some templates differently. [`orcaslicer::layers`] reproduces its angles exactly
//! on any text, so that a slicer can replace OrcaSlicer's code without changing existing
//! profiles, and so that a user can see where the two part.

pub mod compat;
pub mod orcaslicer;

pub use compat::compat;

use crate::diagnostic::Span;
use std::fmt;
use std::str::FromStr;

/// OrcaSlicer never finishes slicing (its walk through the template loops).
pub const HANGS: &str = "orcaslicer::hangs";
/// OrcaSlicer's behaviour is undefined (a count outside the 32-bit range): it crashes.
pub const UNDEFINED: &str = "orcaslicer::undefined";
/// OrcaSlicer computes NaN or infinite angles on some layers.
pub const NAN: &str = "orcaslicer::nan";

/// Something the OrcaSlicer reading found while computing layers: where OrcaSlicer hangs,
/// crashes or yields NaN, and the dialect gives finite angles instead.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Finding {
    /// [`HANGS`], [`UNDEFINED`] or [`NAN`].
    pub code: &'static str,
    /// One sentence: what OrcaSlicer does there.
    pub message: String,
    /// The first layer concerned.
    pub first_layer: usize,
    /// How many layers are concerned: for a hang or undefined behaviour, every layer from
    /// `first_layer` up; for NaN, the NaN layers seen so far (not necessarily contiguous).
    pub layers: usize,
    /// The token at fault (byte range in the text): the one read when OrcaSlicer crashes,
    /// the one governing the first NaN layer; `None` for a hang (a loop over many tokens).
    pub span: Option<Span>,
}

/// Which reading of a template: rotlang's (SEMANTICS sections 1–9) or OrcaSlicer's exact
/// one (section 10). Also `rotlang::eval::Dialect`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// rotlang's reading (SEMANTICS sections 1–9), the grammar's.
    #[default]
    Rotlang,
    /// OrcaSlicer's own reading (section 10), with its hangs and NaN layers made finite.
    OrcaSlicer,
}

impl Dialect {
    /// Both dialects, rotlang's first.
    pub const ALL: [Dialect; 2] = [Dialect::Rotlang, Dialect::OrcaSlicer];

    /// Its name as options spell it: `rotlang` or `orcaslicer`.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Rotlang => "rotlang",
            Dialect::OrcaSlicer => "orcaslicer",
        }
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The error of [`Dialect::from_str`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownDialect(pub String);

impl fmt::Display for UnknownDialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown dialect `{}`; expected `rotlang` or `orcaslicer`",
            self.0
        )
    }
}

impl std::error::Error for UnknownDialect {}

impl FromStr for Dialect {
    type Err = UnknownDialect;

    /// `rotlang` or `orcaslicer` (any case).
    fn from_str(s: &str) -> Result<Dialect, UnknownDialect> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| UnknownDialect(s.to_owned()))
    }
}
