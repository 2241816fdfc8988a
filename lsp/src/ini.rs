//! `.ini` slicer configs (OrcaSlicer's "export config"): `key = value` lines. The value of a
//! template key is the template, verbatim to the end of its line.

use rotlang::Span;

use crate::json::{JsonTemplate, OffsetMap, TEMPLATE_KEYS};

/// Every template line of an `.ini` document. Lines end at `\n`, `\r\n` or `\r`; comments
/// (`#`, `;`) and section headers are lines without a template key, so they are skipped.
pub fn find_templates(doc: &str) -> Vec<JsonTemplate> {
    let mut found = Vec::new();
    let mut start = 0;
    for line in doc.split_inclusive(['\n', '\r']) {
        let line_start = start;
        start += line.len();
        let line = line.trim_end_matches(['\n', '\r']);
        let Some(eq) = line.find('=') else { continue };
        let key = line[..eq].trim();
        let Some(&(_, target)) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == key) else {
            continue;
        };
        let key_start = line_start + line.find(key).unwrap_or(0);
        let value = &line[eq + 1..];
        let lead = value.len() - value.trim_start_matches([' ', '\t']).len();
        let text = value[lead..].trim_end_matches([' ', '\t']);
        let contents_start = line_start + eq + 1 + lead;
        found.push(JsonTemplate {
            key: key.to_string(),
            key_span: Span::new(key_start, key_start + key.len()),
            target,
            text: text.to_string(),
            contents: Span::new(contents_start, contents_start + text.len()),
            map: OffsetMap::verbatim(contents_start, text.len()),
        });
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotlang::Target;

    #[test]
    fn finds_template_lines_with_their_offsets() {
        let doc = "; generated\r\n[print]\rsparse_infill_rotate_template = 0, +30X \nsolid_infill_rotate_template=90\nname = sparse_infill_rotate_template";
        let found = find_templates(doc);
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].text, "0, +30X");
        assert_eq!(&doc[found[0].contents.range()], "0, +30X");
        assert_eq!(
            &doc[found[0].key_span.range()],
            "sparse_infill_rotate_template"
        );
        let x = found[0].text.find('X').unwrap();
        assert_eq!(&doc[found[0].map.to_doc(x)..][..1], "X");
        assert_eq!(found[1].target, Target::Solid);
        assert_eq!(found[1].text, "90");
        assert!(find_templates("sparse_infill_rotate_template").is_empty());
        assert_eq!(
            find_templates("sparse_infill_rotate_template =")[0].text,
            ""
        );
    }
}
