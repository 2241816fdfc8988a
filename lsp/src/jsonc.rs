//! JSON with comments (`.jsonc`): comments and trailing commas are blanked out, byte for
//! byte, so the JSON scanner and validator see plain JSON at the very same offsets. Every
//! span found in the blanked text is therefore a span of the document as written.

/// The document with `//` and `/* */` comments and trailing commas replaced by spaces
/// (line breaks kept, so line numbers do not move). Strings are copied untouched. The
/// library's reader (`rotlang_profile::profile::json::strip_jsonc`), shared with the CLI.
pub fn blank(doc: &str) -> String {
    rotlang_profile::profile::json::strip_jsonc(doc).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_trailing_commas_become_spaces() {
        let doc = "{ // a comment, with \"quotes\"\n  \"a\": \"// not a comment\", /* é\n */ \"b\": [1, 2,],\n}";
        let clean = blank(doc);
        assert_eq!(clean.len(), doc.len());
        assert!(
            serde_json::from_str::<serde_json::Value>(&clean).is_ok(),
            "{clean}"
        );
        assert!(clean.contains("\"// not a comment\""));
        assert_eq!(clean.matches('\n').count(), doc.matches('\n').count());
        // A comma before a value stays; `[,]` stays invalid (only trailing commas go).
        assert_eq!(blank("[1, 2]"), "[1, 2]");
        assert!(serde_json::from_str::<serde_json::Value>(&blank("{,}")).is_err());
    }

    #[test]
    fn unterminated_comments_and_strings_do_not_panic() {
        for doc in [
            "/*",
            "/* é",
            "//",
            "\"abc",
            "\"\\",
            "{\"a\": 1, /* x */ }",
            "/",
            ",",
        ] {
            assert_eq!(blank(doc).len(), doc.len());
        }
    }
}
