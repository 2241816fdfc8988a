//! Completion: the language's signs, each with its meaning from the library.
//!
//! Every item's text edit replaces the instruction under the cursor (`+30` at `0, +30⎀`)
//! with that instruction and the sign inserted at the cursor (`+30/`), and its
//! `filterText` and `insertText` are that same text. Clients filter by the text between
//! the edit's start and the cursor, which is then a prefix of every item. eglot (1.9)
//! filters by the symbol at point, replaces the symbol with `insertText`, then applies the
//! edit over the same characters: right when its mode makes an instruction one symbol (the
//! documented `rot-mode` does), and nothing after the cursor is lost. A label typed in part
//! (`*` of `*2`) is completed, not repeated; a unit typed so far (`m`, `c`, `mm` after a
//! count's number) is replaced by the item's unit (`+30/5m`: `cm` gives `+30/5cm`, `m`
//! gives `+30/5m`). Where the new text does not begin with the text typed (`cm` after
//! `m`), `filterText` is the typed text and the label, so prefix-filtering clients keep it.

use rotlang::{Joint, Solid, Target, Unit};
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, MarkupContent,
    MarkupKind, Range, TextEdit,
};

use crate::document::Document;
use crate::position::Positions;

/// Runtime marks and shell counts: (text, label detail, meaning).
const MARKS: [(&str, &str, &str); 6] = [
    (
        "*",
        "dummy",
        "a dummy instruction: sets an initial angle and takes no layer",
    ),
    (
        "*2",
        "repeat",
        "repeat the instruction ℤ times in a row (`*ℤ`, here 2)",
    ),
    (
        "!",
        "one-time",
        "the instruction runs only once for the whole model",
    ),
    ("*!", "one-time dummy", "a dummy that runs only once"),
    (
        "B",
        "bottom shells",
        "count: the number of bottom shell layers",
    ),
    ("T", "top shells", "count: the number of top shell layers"),
];

/// The runtime marks among `MARKS`.
const RUNTIME_MARKS: [&str; 4] = ["*", "*2", "!", "*!"];

/// The signs an angle may begin with, offered at the start of an instruction.
const ANGLE_SIGNS: [(&str, &str, &str); 2] = [
    (
        "+",
        "angle sign: a turn",
        "the angle is a turn added to the previous angle",
    ),
    (
        "-",
        "angle sign: a turn",
        "the angle is a turn subtracted from the previous angle",
    ),
];

/// Whether `text`, an instruction that an item would make, is one the library accepts, or
/// would accept once finished (its only diagnostic says it ends too early).
fn begins_instruction(text: &str, target: Target) -> bool {
    rotlang::parse(text, target)
        .diagnostics
        .iter()
        .all(|d| d.code == "rotlang::incomplete")
}

/// Longer "instructions" (a paste without separators) are not copied into the items.
const MAX_INSTRUCTION: usize = 256;

/// All items for a template of this target. `None` outside any template (in a JSON
/// profile, anywhere but the template strings).
pub fn completion(doc: &Document, offset: usize, pos: &Positions) -> Option<Vec<CompletionItem>> {
    let (region, at) = doc.region_at(offset)?;
    // The instruction under the cursor: between the separators around it (instructions
    // never contain one).
    const SEPARATORS: [char; 5] = [',', ' ', '\t', '\r', '\n'];
    let mut start = region.text[..at].rfind(SEPARATORS).map_or(0, |i| i + 1);
    let mut end = region.text[at..]
        .find(SEPARATORS)
        .map_or(region.text.len(), |i| at + i);
    if end - start > MAX_INSTRUCTION {
        // No instruction is this long; a pasted blob must not be copied into every item
        // (34 copies of a megabyte). Insert at the cursor instead.
        (start, end) = (at, at);
    }
    let (typed, after) = (&region.text[start..at], &region.text[at..end]);
    let range = Range::new(
        pos.position(region.map.to_doc(start)),
        pos.position(region.map.to_doc(end)),
    );
    let (joint_fits, layers_unit_fits) = hash_roles(&region.text, at);
    // At the start of an instruction (`0, ⎀+30`, `0, ⎀`) only what can begin one is
    // offered: what leaves the instruction valid, or valid once finished, as the library
    // reads it (`/+30` and `*+30` do not).
    let at_start = typed.is_empty();
    let begins =
        |label: &str| !at_start || begins_instruction(&format!("{label}{after}"), region.target);
    let mut items = Vec::new();
    let typed_unit = unit_typed(typed);
    let mut push = |label: String, kind, detail: &str, doc_text: String, sort: usize| {
        if !begins(&label) {
            return;
        }
        let partial = if kind == CompletionItemKind::UNIT {
            // The unit typed so far, whichever it begins: the item's unit replaces it.
            typed_unit
        } else {
            // The longest end of `typed` that begins the label but is not all of it.
            (1..label.len())
                .rev()
                .find(|&n| label.is_char_boundary(n) && typed.ends_with(&label[..n]))
                .unwrap_or(0)
        };
        let kept = &typed[..typed.len() - partial];
        let new_text = doc.encode(&format!("{kept}{label}{after}"));
        // Clients show an item when the text typed begins its filter text.
        let filter_text = if format!("{kept}{label}").starts_with(typed) {
            new_text.clone()
        } else {
            doc.encode(&format!("{typed}{label}{after}"))
        };
        items.push(CompletionItem {
            text_edit: Some(CompletionTextEdit::Edit(TextEdit::new(
                range,
                new_text.clone(),
            ))),
            filter_text: Some(filter_text),
            insert_text: Some(new_text),
            label,
            kind: Some(kind),
            detail: Some(detail.to_string()),
            documentation: Some(Documentation::MarkupContent(MarkupContent {
                kind: MarkupKind::Markdown,
                value: doc_text,
            })),
            sort_text: Some(format!("{sort:03}")),
            ..CompletionItem::default()
        });
    };
    let mut n = 0;
    if at_start {
        for (sign, detail, meaning) in ANGLE_SIGNS {
            n += 1;
            push(
                sign.to_string(),
                CompletionItemKind::OPERATOR,
                detail,
                format!("`{sign}` before the angle: {meaning} (e.g. `{sign}30`)."),
                n,
            );
        }
    }
    for joint in Joint::ALL {
        if joint == Joint::Step && !joint_fits {
            continue;
        }
        n += 1;
        push(
            joint.symbol().to_string(),
            CompletionItemKind::OPERATOR,
            if joint == Joint::Step {
                "joint sign: a step"
            } else {
                "joint sign"
            },
            format!(
                "Joint sign: turns {} across the range (e.g. `+22.5{}50%`).",
                joint.meaning(),
                joint.symbol()
            ),
            n,
        );
    }
    for unit in Unit::ALL {
        if unit == Unit::StandardLayers && !layers_unit_fits {
            continue;
        }
        n += 1;
        push(
            unit.symbol().to_string(),
            CompletionItemKind::UNIT,
            if unit == Unit::StandardLayers {
                "length unit: standard layers"
            } else {
                "length unit"
            },
            format!(
                "Length unit after a count: {} (e.g. `+30/5{}`).",
                unit.meaning(),
                unit.symbol()
            ),
            n,
        );
    }
    if region.target == Target::Sparse {
        for solid in Solid::ALL {
            n += 1;
            push(
                solid.symbol().to_string(),
                CompletionItemKind::ENUM_MEMBER,
                "solid sign",
                format!("Solid sign: {} (sparse templates only).", solid.meaning()),
                n,
            );
        }
    }
    for (text, detail, meaning) in MARKS {
        if at_start && RUNTIME_MARKS.contains(&text) {
            // A runtime mark follows an angle (`+30*2`): it never begins an instruction,
            // although the library reads a lone `!` as one on the angle 0.
            continue;
        }
        n += 1;
        push(
            text.to_string(),
            CompletionItemKind::KEYWORD,
            detail,
            format!("`{text}`: {meaning}."),
            n,
        );
    }
    Some(items)
}

/// The length in bytes of the unit typed at the end of `typed`: the longest end that begins
/// some unit (`m` of `m` or `mm`, `c` of `cm`, `mm`) right after a count's number; 0 if none.
fn unit_typed(typed: &str) -> usize {
    (1..=typed.len().min(2))
        .rev()
        .filter(|&n| typed.is_char_boundary(typed.len() - n))
        .find(|&n| {
            let (before, end) = typed.split_at(typed.len() - n);
            before.ends_with(|c: char| c.is_ascii_digit() || c == '.')
                && Unit::ALL.iter().any(|u| u.symbol().starts_with(end))
        })
        .unwrap_or(0)
}

/// `#` is both a joint (a step) and a unit (standard layers): offer each once, where it
/// fits. The joint fits while the instruction typed so far has no joint; the unit fits
/// right after a count's number (digits after a joint or a flip).
fn hash_roles(text: &str, at: usize) -> (bool, bool) {
    let before = text.get(..at).unwrap_or("");
    let start = before
        .rfind([',', ' ', '\t', '\r', '\n'])
        .map_or(0, |i| i + 1);
    let typed = &before[start..];
    // The angle's own sign is not a flip, and `%` after the angle is not a joint.
    let body = typed.trim_start_matches(['+', '-']);
    let joint_at = body.find(|c: char| Joint::from_symbol(c).is_some() || c == '-');
    let count_digits = typed.ends_with(|c: char| c.is_ascii_digit())
        && joint_at.is_some_and(|j| {
            body[j + 1..]
                .chars()
                .all(|c| c.is_ascii_digit() || c == '.' || c == '-')
        });
    (joint_at.is_none(), count_digits)
}

#[cfg(test)]
mod tests {
    use super::hash_roles;

    #[test]
    fn what_begins_an_instruction() {
        use super::begins_instruction;
        use rotlang::Target;
        for ok in ["+", "-", "+30", "-30", "#14", "/50%", "B!"] {
            assert!(begins_instruction(ok, Target::Sparse), "{ok}");
        }
        for bad in ["/+30", "*+30", "++30", "S+30", "*", "mm"] {
            assert!(!begins_instruction(bad, Target::Sparse), "{bad}");
        }
    }

    #[test]
    fn the_unit_typed_so_far() {
        use super::unit_typed;
        assert_eq!(unit_typed("+30/5m"), 1);
        assert_eq!(unit_typed("+30/5c"), 1);
        assert_eq!(unit_typed("+30/5mm"), 2);
        assert_eq!(unit_typed("+30/5.5%"), 1);
        assert_eq!(unit_typed("+30/5"), 0);
        assert_eq!(unit_typed("+30/"), 0);
        assert_eq!(unit_typed("+30/5x"), 0);
        assert_eq!(unit_typed("é"), 0);
    }

    #[test]
    fn hash_is_offered_once_per_role() {
        assert_eq!(hash_roles("+30", 3), (true, false));
        assert_eq!(hash_roles("+30/5", 5), (false, true));
        assert_eq!(hash_roles("0, +30/-5", 9), (false, true));
        assert_eq!(hash_roles("+30/", 4), (false, false));
        assert_eq!(hash_roles("", 0), (true, false));
    }
}
