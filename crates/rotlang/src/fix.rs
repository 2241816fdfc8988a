//! Applying the fixes diagnostics carry (`rotlang check --fix`, a code action "fix all").
//!
//! A diagnostic's [`Fix`](crate::Fix) is a safe edit: meaning-preserving, or what was
//! obviously intended (remove a `°`, join `+30 /50%`). Fixes are applied in passes, the
//! non-overlapping ones of each pass at once, and the text is parsed again after each pass,
//! since one fix can reveal or remove another diagnostic.

use crate::{Parse, Target};

/// At most this many passes: each pass shortens or repairs the text, so a fixed point is
/// reached in a few; the bound guards against two fixes undoing each other.
const MAX_PASSES: usize = 8;

/// The result of [`apply_all`].
#[derive(Clone, Debug)]
pub struct Fixed {
    /// The text with every fix applied.
    pub text: String,
    /// The parse of `text`: what is left to fix by hand.
    pub parse: Parse,
    /// How many fixes were applied.
    pub applied: usize,
}

/// Applies every fix of every diagnostic, pass after pass, until none is left.
pub fn apply_all(text: &str, target: Target) -> Fixed {
    apply_all_with(text, target, |_| Vec::new())
}

/// [`apply_all`], with the fixes of more diagnostics of each pass's text: `more(text)`
/// (the OrcaSlicer compat lint, `check --compat orcaslicer --fix`).
pub fn apply_all_with(
    text: &str,
    target: Target,
    more: impl Fn(&str) -> Vec<crate::Diagnostic>,
) -> Fixed {
    let mut text = text.to_owned();
    let mut parse = crate::parse(&text, target);
    let mut applied = 0;
    for _ in 0..MAX_PASSES {
        let extra = more(&text);
        let mut fixes: Vec<&crate::Fix> = parse
            .diagnostics
            .iter()
            .chain(&extra)
            .filter_map(|d| d.fix.as_ref())
            .collect();
        if fixes.is_empty() {
            break;
        }
        fixes.sort_by_key(|f| (f.span.start, f.span.end));
        // Two diagnostics may carry the same fix (a rotlang and a compat warning on one
        // empty instruction): it is applied once.
        fixes.dedup_by(|a, b| a.span == b.span && a.replacement == b.replacement);
        let mut out = String::with_capacity(text.len());
        let mut at = 0;
        let mut count = 0;
        for f in fixes {
            // Overlapping fixes wait for the next pass; spans come from our own parse of
            // `text`, so they are in bounds and on char boundaries.
            if f.span.start < at || text.get(f.span.range()).is_none() {
                continue;
            }
            out.push_str(&text[at..f.span.start]);
            out.push_str(&f.replacement);
            at = f.span.end;
            count += 1;
        }
        out.push_str(&text[at..]);
        if count == 0 || out == text {
            break;
        }
        applied += count;
        text = out;
        parse = crate::parse(&text, target);
    }
    Fixed {
        text,
        parse,
        applied,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixes_are_applied_until_none_is_left() {
        let fixed = apply_all("\"+30°, 10,,20\"", Target::Sparse);
        assert_eq!(fixed.text, "+30, 10, 20");
        assert!(
            fixed.parse.diagnostics.is_empty(),
            "{:?}",
            fixed.parse.diagnostics
        );
        assert!(fixed.applied >= 3);
        let fixed = apply_all("+30 /50%, +30/ 50%", Target::Sparse);
        assert_eq!(fixed.text, "+30/50%, +30/50%");
        // What has no fix stays, and says so.
        let fixed = apply_all("+30X5, 45deg", Target::Sparse);
        assert_eq!(fixed.text, "+30X5, 45");
        assert!(fixed.parse.has_errors());
        let fixed = apply_all("0, 90", Target::Sparse);
        assert_eq!((fixed.text.as_str(), fixed.applied), ("0, 90", 0));
    }

    #[test]
    fn more_diagnostics_fix_too_and_one_fix_applies_once() {
        let insert = |text: &str| {
            let missing = !text.contains(',');
            text.find(" 90")
                .filter(|_| missing)
                .map_or(Vec::new(), |at| {
                    let span = crate::Span::new(at, at);
                    let d = crate::Diagnostic::warning("test::comma", "a comma")
                        .with_fix("add", span, ",");
                    vec![d.clone(), d]
                })
        };
        let fixed = apply_all_with("0 90", Target::Sparse, insert);
        assert_eq!(fixed.text, "0, 90");
    }
}
