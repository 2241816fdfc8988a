//! Fuzz target `lsp_json`: the language server's JSON profile scanner on any text. It
//! never fails; every template it finds lies inside the document, its offset map sends
//! every template offset into the string's contents (on char boundaries, in order), and
//! escaping a template and scanning it again gives the same text back.

use rotlang::Span;
use rotlang_lsp::json;

pub fn run(data: &[u8]) {
    let doc = String::from_utf8_lossy(data);
    let _ = json::syntax_error(&doc);
    for t in json::find_templates(&doc) {
        let c = t.contents;
        assert!(c.start <= c.end && c.end <= doc.len(), "contents {c:?}");
        assert!(doc.is_char_boundary(c.start) && doc.is_char_boundary(c.end));
        assert!(doc.is_char_boundary(t.key_span.start) && doc.is_char_boundary(t.key_span.end));
        let mut previous = c.start;
        for (i, _) in t.text.char_indices().chain([(t.text.len(), ' ')]) {
            let at = t.map.to_doc(i);
            assert!(
                at >= previous && at <= c.end,
                "to_doc({i}) = {at} outside {c:?}"
            );
            assert!(
                doc.is_char_boundary(at),
                "to_doc({i}) = {at} inside a character"
            );
            previous = at;
        }
        let whole = t.map.span_to_doc(Span::new(0, t.text.len()));
        assert!(whole.start >= c.start && whole.end <= c.end);
        for offset in [c.start, c.end, (c.start + c.end) / 2] {
            if let Some(back) = t.map.to_text(offset) {
                assert!(back <= t.text.len(), "to_text({offset}) = {back}");
            }
        }
        // Escaping round trip.
        let again = format!("{{\"{}\": \"{}\"}}", t.key, json::escape(&t.text));
        let found = json::find_templates(&again);
        assert_eq!(found.len(), 1, "{again:?}");
        assert_eq!(found[0].text, t.text);
        assert_eq!(json::syntax_error(&again), None, "{again:?}");
    }
}
