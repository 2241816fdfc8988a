//! Where diagnostics are collected while a template is read (`Sink`, capped at
//! `MAX_DIAGNOSTICS`) and what reading gives back (`Parse`).

use crate::diagnostic::{Diagnostic, Severity, Span};
use crate::ir::Template;

/// At most this many diagnostics are kept per template; a 1 MB file of garbage must not
/// produce a million reports.
pub const MAX_DIAGNOSTICS: usize = 100;

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

/// Collects diagnostics up to `MAX_DIAGNOSTICS` and counts the rest, so memory stays
/// bounded whatever the input. The counts are exact: whether a template has errors never
/// depends on the cap. Diagnostics arrive in source order, and once the list is full an
/// error replaces the last warning kept, so errors are never hidden behind warnings and
/// the first error is always shown.
#[derive(Default)]
pub(crate) struct Sink {
    list: Vec<Diagnostic>,
    errors: usize,
    warnings: usize,
    /// Warnings in `list`: the ones an error may replace.
    kept_warnings: usize,
}

/// What a `Sink` collected.
pub(crate) struct Collected {
    pub diagnostics: Vec<Diagnostic>,
    pub errors: usize,
    pub warnings: usize,
    pub omitted: usize,
}

impl Collected {
    pub fn into_parse(self, template: Template) -> Parse {
        Parse {
            template,
            diagnostics: self.diagnostics,
            omitted: self.omitted,
            errors: self.errors,
            warnings: self.warnings,
        }
    }
}

impl Sink {
    /// Whether a diagnostic of this severity, pushed now, would be kept. When it would
    /// not, callers may `count` it instead of building it.
    pub fn keeps(&self, severity: Severity) -> bool {
        self.list.len() < MAX_DIAGNOSTICS || (severity == Severity::Error && self.kept_warnings > 0)
    }

    pub fn errors(&self) -> usize {
        self.errors
    }

    /// Counts a diagnostic that is not kept.
    pub fn count(&mut self, severity: Severity) {
        match severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => self.warnings += 1,
        }
    }

    pub fn push(&mut self, d: Diagnostic) {
        self.count(d.severity);
        if !self.keeps(d.severity) {
            return;
        }
        if self.list.len() >= MAX_DIAGNOSTICS {
            // Bounded: each replacement removes one of at most `MAX_DIAGNOSTICS` warnings,
            // and no warning is added once the list is full.
            if let Some(i) = self.list.iter().rposition(|d| !d.is_error()) {
                self.list.remove(i);
                self.kept_warnings -= 1;
            }
        }
        if !d.is_error() {
            self.kept_warnings += 1;
        }
        self.list.push(d);
    }

    /// The diagnostics in source order, with a last one saying how many were dropped.
    pub fn finish(mut self) -> Collected {
        self.list
            .sort_by_key(|d| (d.primary_span().start, std::cmp::Reverse(d.severity)));
        let kept_errors = self.list.len() - self.kept_warnings;
        let (errors, warnings) = (
            self.errors - kept_errors,
            self.warnings - self.kept_warnings,
        );
        let omitted = errors + warnings;
        if omitted > 0 {
            let last = self
                .list
                .last()
                .map_or(Span::default(), Diagnostic::primary_span);
            let plural = |n: usize, w: &str| format!("{n} {w}{}", if n == 1 { "" } else { "s" });
            let message = match (errors, warnings) {
                (0, w) => format!("{} not shown", plural(w, "more warning")),
                (e, 0) => format!("{} not shown", plural(e, "more error")),
                (e, w) => format!(
                    "{} and {} not shown",
                    plural(e, "more error"),
                    plural(w, "more warning")
                ),
            };
            // An error when an error is among those not shown: a reader of the list alone
            // (an editor, a script) must still see that the template does not parse.
            let d = if errors > 0 {
                Diagnostic::error("rotlang::too-many-diagnostics", message)
            } else {
                Diagnostic::warning("rotlang::too-many-diagnostics", message)
            };
            self.list.push(
                d.with_primary(Span::new(last.end, last.end), "and more after this")
                    .with_help("fix the ones above first; the rest are often the same mistake"),
            );
        }
        Collected {
            diagnostics: self.list,
            errors: self.errors,
            warnings: self.warnings,
            omitted,
        }
    }
}
