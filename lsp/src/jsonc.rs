//! JSON with comments (`.jsonc`): comments and trailing commas are blanked out, byte for
//! byte, so the JSON scanner and validator see plain JSON at the very same offsets. Every
//! span found in the blanked text is therefore a span of the document as written.

/// The document with `//` and `/* */` comments and trailing commas replaced by spaces
/// (line breaks inside block comments kept, so line numbers do not move). Strings are
/// copied untouched. An unterminated block comment runs to the end, as editors show it.
pub fn blank(doc: &str) -> String {
    let mut out = doc.as_bytes().to_vec();
    let bytes = doc.as_bytes();
    let mut i = 0;
    // The last comma seen outside strings and not yet followed by a value: blanked if the
    // next significant byte closes an object or array.
    let mut pending_comma: Option<usize> = None;
    // The last significant byte: a comma right after `{`, `[`, `,` or `:` follows no value,
    // so it is an error to report, not a trailing comma.
    let mut last = b'{';
    while i < bytes.len() {
        let byte = bytes[i];
        if byte == b',' && !matches!(last, b'{' | b'[' | b',' | b':') {
            pending_comma = Some(i);
        }
        if !matches!(byte, b' ' | b'\t' | b'\n' | b'\r' | b'/') {
            last = byte;
        }
        match byte {
            b'"' => {
                pending_comma = None;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
            }
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' && bytes[i] != b'\r' {
                    out[i] = b' ';
                    i += 1;
                }
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                let end = doc[i + 2..]
                    .find("*/")
                    .map_or(bytes.len(), |e| i + 2 + e + 2);
                for b in &mut out[i..end] {
                    if *b != b'\n' && *b != b'\r' {
                        *b = b' ';
                    }
                }
                i = end;
            }
            b',' => i += 1,
            b'}' | b']' => {
                if let Some(comma) = pending_comma.take() {
                    out[comma] = b' ';
                }
                i += 1;
            }
            b' ' | b'\t' | b'\n' | b'\r' => i += 1,
            _ => {
                pending_comma = None;
                i += 1;
            }
        }
    }
    // Only ASCII bytes were replaced, each whole character of a comment byte by byte, so
    // the result is UTF-8 again; the fallback is never taken.
    String::from_utf8(out).unwrap_or_else(|_| doc.to_string())
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
