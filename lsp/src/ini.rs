//! `.ini` slicer configs (OrcaSlicer's "export config"): `key = value` lines. The value of a
//! template key is the template, verbatim to the end of its line.

/// The library's reader (`rotlang_profile::profile::ini`), shared with the CLI.
pub use rotlang_profile::profile::ini::find_templates;

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
