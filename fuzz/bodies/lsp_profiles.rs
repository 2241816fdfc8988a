//! Fuzz target `lsp_profiles`: the language server's other readers on any text: `.jsonc`
//! blanking (same length, only comment and trailing-comma bytes become spaces, line breaks
//! kept), `.ini` templates (each exactly its slice of the document), LSP positions (lines
//! end at `\r`, `\n`, `\r\n`; offset → position → offset is the identity), and documents
//! of every kind (regions inside the text; formatting never panics).

use rotlang_lsp::document::{Document, Kind};
use rotlang_lsp::position::{Encoding, Positions};
use rotlang_lsp::{formatting, ini, jsonc};

/// Positions are checked at this many offsets at most (a long input stays fast).
const MAX_OFFSETS: usize = 4096;

pub fn run(data: &[u8]) {
    let doc = String::from_utf8_lossy(data).into_owned();

    let plain = jsonc::blank(&doc);
    assert_eq!(plain.len(), doc.len());
    for (i, (a, b)) in doc.bytes().zip(plain.bytes()).enumerate() {
        assert!(
            a == b || (b == b' ' && a != b'\n' && a != b'\r'),
            "byte {i}: {a:#x} became {b:#x}"
        );
    }

    for t in ini::find_templates(&doc) {
        assert_eq!(doc.get(t.contents.range()), Some(t.text.as_str()));
        assert_eq!(doc.get(t.key_span.range()), Some(t.key.as_str()));
        if let Some(i) = t.text.char_indices().last().map(|(i, _)| i) {
            assert_eq!(t.map.to_doc(i), t.contents.start + i);
        }
    }

    for encoding in [Encoding::Utf16, Encoding::Utf8] {
        let pos = Positions::new(&doc, encoding);
        let bytes = doc.as_bytes();
        for offset in (0..=doc.len())
            .filter(|&o| doc.is_char_boundary(o))
            .take(MAX_OFFSETS)
        {
            // Between the `\r` and `\n` of a pair there is no position of its own.
            if offset > 0 && bytes[offset - 1] == b'\r' && bytes.get(offset) == Some(&b'\n') {
                continue;
            }
            let p = pos.position(offset);
            assert_eq!(pos.offset(p), Some(offset), "offset {offset} → {p:?}");
        }
    }

    for kind in [Kind::Rot, Kind::Json, Kind::Jsonc, Kind::Ini] {
        let d = Document::new(doc.clone(), kind, 1, None);
        for r in &d.regions {
            let c = r.contents;
            assert!(
                c.start <= c.end && c.end <= doc.len(),
                "{kind:?} region {c:?}"
            );
            assert!(doc.is_char_boundary(c.start) && doc.is_char_boundary(c.end));
        }
        let _ = formatting::formatted_text(&d);
    }
}
