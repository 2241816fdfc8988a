//! Completion: the language's signs, each with its meaning from the library.
//!
//! Every item inserts at the cursor through an empty-range text edit. The signs are not
//! word characters, so a client filtering by "the word before the cursor" (`30` in `+30`)
//! would otherwise hide them all.

use rotlang::{Joint, Solid, Target, Unit};
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, MarkupContent,
    MarkupKind, Range, TextEdit,
};

use crate::document::Document;

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

/// All items for a template of this target. `None` outside any template (in a JSON
/// profile, anywhere but the template strings).
pub fn completion(doc: &Document, offset: usize, range: Range) -> Option<Vec<CompletionItem>> {
    let (region, at) = doc.region_at(offset)?;
    let (joint_fits, layers_unit_fits) = hash_roles(&region.text, at);
    let mut items = Vec::new();
    let mut push = |label: String, kind, detail: &str, doc_text: String, sort: usize| {
        items.push(CompletionItem {
            text_edit: Some(CompletionTextEdit::Edit(TextEdit::new(
                range,
                doc.encode(&label),
            ))),
            filter_text: Some(label.clone()),
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

/// `#` is both a joint (a step) and a unit (standard layers): offer each once, where it
/// fits. The joint fits while the instruction typed so far has no joint; the unit fits
/// right after a count's number (digits after a joint or a flip).
fn hash_roles(text: &str, at: usize) -> (bool, bool) {
    let before = text.get(..at).unwrap_or("");
    let start = before
        .rfind(|c: char| matches!(c, ',' | ' ' | '\t' | '\r' | '\n'))
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
    fn hash_is_offered_once_per_role() {
        assert_eq!(hash_roles("+30", 3), (true, false));
        assert_eq!(hash_roles("+30/5", 5), (false, true));
        assert_eq!(hash_roles("0, +30/-5", 9), (false, true));
        assert_eq!(hash_roles("+30/", 4), (false, false));
        assert_eq!(hash_roles("", 0), (true, false));
    }
}
