//! Fuzz target `parse`: any bytes (lossily UTF-8) parsed for the sparse and the solid
//! target. Checks what every consumer relies on: spans inside the text and on char
//! boundaries, instructions in order, at most 101 diagnostics, and exact error counts
//! (an error is never lost behind the cap).

use rotlang::{Parse, Span, Target};

pub fn run(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    for target in [Target::Sparse, Target::Solid] {
        check(&text, &rotlang::parse(&text, target));
    }
}

fn span_ok(text: &str, s: Span) -> bool {
    s.start <= s.end
        && s.end <= text.len()
        && text.is_char_boundary(s.start)
        && text.is_char_boundary(s.end)
}

pub fn check(text: &str, parse: &Parse) {
    assert!(
        parse.diagnostics.len() <= 101,
        "{} diagnostics",
        parse.diagnostics.len()
    );
    let mut listed = 0;
    let mut listed_errors = 0;
    for d in &parse.diagnostics {
        for s in d
            .labels
            .iter()
            .map(|l| l.span)
            .chain(d.fix.iter().map(|f| f.span))
        {
            assert!(
                span_ok(text, s),
                "{}: span {s:?} in {} bytes",
                d.code,
                text.len()
            );
        }
        assert!(!d.message.is_empty(), "{}: no message", d.code);
        if d.code != "rotlang::too-many-diagnostics" {
            listed += 1;
            listed_errors += usize::from(d.is_error());
        }
        if let Some(fix) = &d.fix {
            // Applying a fix yields text (no panic, no broken UTF-8).
            let mut fixed = text.to_owned();
            fixed.replace_range(fix.span.range(), &fix.replacement);
        }
    }
    assert_eq!(parse.has_errors(), parse.errors > 0);
    assert_eq!(parse.errors + parse.warnings, listed + parse.omitted);
    if parse.errors > 0 {
        assert!(listed_errors > 0, "errors counted but none listed");
    }
    let mut end = 0;
    for ins in &parse.template.instructions {
        assert!(span_ok(text, ins.span), "instruction span {:?}", ins.span);
        assert!(!ins.span.is_empty());
        assert!(ins.span.start >= end, "instructions overlap or go back");
        end = ins.span.end;
        assert!(ins.degrees().is_finite());
    }
}
