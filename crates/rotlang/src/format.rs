//! The canonical formatter: `, ` between instructions, each instruction as written.
//!
//! Instructions cannot contain separators, so the canonical form only rewrites the
//! separators; it never touches an instruction's text, which is why it cannot change the
//! meaning. Empty instructions (which rotlang ignores) disappear.

use crate::Target;

/// The canonical form of a template, or `None` when it has any error, whether or not it
/// is among the diagnostics listed (a template that does not parse is left for the user
/// to fix; guessing could change its meaning, and an instruction that failed would be
/// missing from the output). Streams: no IR is kept, whatever the template's size.
pub fn format(text: &str, target: Target) -> Option<String> {
    let mut out = String::with_capacity(text.len());
    let collected = crate::syntax::parse_each(text, target, |ins| {
        if !out.is_empty() {
            out.push_str(", ");
        }
        out.push_str(&text[ins.span.range()]);
    });
    (collected.errors == 0).then_some(out)
}

/// Joins the instructions' texts with `, `.
pub fn canonical(text: &str, template: &crate::Template) -> String {
    let mut out = String::with_capacity(text.len());
    for (i, ins) in template.instructions.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&text[ins.span.range()]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_separators() {
        assert_eq!(format("0 90", Target::Sparse).as_deref(), Some("0, 90"));
        assert_eq!(
            format("  +10L25%,-10l25%\n\n#5 ,", Target::Sparse).as_deref(),
            Some("+10L25%, -10l25%, #5")
        );
        assert_eq!(format("10,,20", Target::Sparse).as_deref(), Some("10, 20"));
        assert_eq!(format("", Target::Sparse).as_deref(), Some(""));
        assert_eq!(format("+30X5", Target::Sparse), None);
    }
}
