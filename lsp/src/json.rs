//! A small, forgiving scanner for JSON slicer profiles. It finds the string values of the
//! template keys and maps offsets between the unescaped template and the document.
//!
//! Why not serde_json: it forgets where values were and what escapes they used, and the
//! server must put diagnostics on the exact characters inside a string such as
//! `"+30\u00b0X"`. The scanner never fails: on malformed input it returns what it found.

use rotlang::{Span, Target};

/// The profile keys whose string values are templates, and the target each is checked for.
pub const TEMPLATE_KEYS: [(&str, Target); 2] = [
    ("sparse_infill_rotate_template", Target::Sparse),
    ("solid_infill_rotate_template", Target::Solid),
];

/// One template found in a JSON document.
#[derive(Clone, Debug, PartialEq)]
pub struct JsonTemplate {
    pub key: String,
    /// The span of the key, quotes included (for document symbols).
    pub key_span: Span,
    pub target: Target,
    /// The template after unescaping.
    pub text: String,
    /// The contents of the string literal in the document (quotes excluded).
    pub contents: Span,
    pub map: OffsetMap,
}

/// Maps byte offsets between a string's unescaped text and its place in the document.
///
/// The string is a sequence of segments: runs copied verbatim (offsets map one to one)
/// and escapes (`\u00b0` is six document bytes for two template bytes), which map only
/// at their edges.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OffsetMap {
    segments: Vec<Segment>,
    /// Document offset of the contents' start, for empty strings.
    doc_start: usize,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    text: usize,
    text_len: usize,
    doc: usize,
    doc_len: usize,
    verbatim: bool,
}

impl OffsetMap {
    /// The identity map of a `.rot` document (the whole text is the template).
    pub fn identity(len: usize) -> OffsetMap {
        OffsetMap::verbatim(0, len)
    }

    /// A template copied verbatim from the document at `doc_start` (an `.ini` value).
    pub fn verbatim(doc_start: usize, len: usize) -> OffsetMap {
        OffsetMap {
            segments: vec![Segment {
                text: 0,
                text_len: len,
                doc: doc_start,
                doc_len: len,
                verbatim: true,
            }],
            doc_start,
        }
    }

    /// Template offset → document offset. Offsets inside an escape's output go to the
    /// escape's end, which is where a span ending there must end.
    pub fn to_doc(&self, offset: usize) -> usize {
        let i = self
            .segments
            .partition_point(|s| s.text + s.text_len < offset);
        let Some(s) = self.segments.get(i) else {
            return self
                .segments
                .last()
                .map_or(self.doc_start, |s| s.doc + s.doc_len);
        };
        let into = offset.saturating_sub(s.text);
        if s.verbatim {
            s.doc + into.min(s.doc_len)
        } else if into == 0 {
            s.doc
        } else {
            s.doc + s.doc_len
        }
    }

    /// A template span → document span.
    pub fn span_to_doc(&self, span: Span) -> Span {
        let start = self.to_doc(span.start);
        Span::new(start, self.to_doc(span.end).max(start))
    }

    /// Document offset → template offset, if the offset lies within the string contents
    /// (both edges included). Inside an escape it maps to the escape's start.
    pub fn to_text(&self, offset: usize) -> Option<usize> {
        let first = self.segments.first().map_or(self.doc_start, |s| s.doc);
        let last = self
            .segments
            .last()
            .map_or(self.doc_start, |s| s.doc + s.doc_len);
        if offset < first || offset > last {
            return None;
        }
        let i = self
            .segments
            .partition_point(|s| s.doc + s.doc_len <= offset);
        match self.segments.get(i) {
            Some(s) if s.verbatim => Some(s.text + (offset - s.doc)),
            Some(s) => Some(s.text),
            None => Some(self.segments.last().map_or(0, |s| s.text + s.text_len)),
        }
    }

    fn push(&mut self, seg: Segment) {
        // Adjacent verbatim runs merge, so a plain string is a single segment.
        if let Some(last) = self.segments.last_mut()
            && seg.verbatim
            && last.verbatim
            && last.text + last.text_len == seg.text
            && last.doc + last.doc_len == seg.doc
        {
            last.text_len += seg.text_len;
            last.doc_len += seg.doc_len;
            return;
        }
        self.segments.push(seg);
    }
}

/// Find every template in a JSON document. Keys match at any depth; a value may be a
/// string or an array of strings (some exporters write every option as an array).
pub fn find_templates(doc: &str) -> Vec<JsonTemplate> {
    let bytes = doc.as_bytes();
    let mut found = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'"' {
            i += 1;
            continue;
        }
        let Some(key) = scan_string(doc, i) else {
            break; // unterminated string: nothing more can be read reliably
        };
        i = key.end;
        let mut j = skip_ws(bytes, i);
        if bytes.get(j) != Some(&b':') {
            continue; // a value, not a key
        }
        let target = TEMPLATE_KEYS
            .iter()
            .find(|(k, _)| *k == key.text)
            .map(|&(_, t)| t);
        let Some(target) = target else {
            i = j + 1;
            continue;
        };
        j = skip_ws(bytes, j + 1);
        let key_span = Span::new(key.start, key.end);
        let mut push = |s: Scanned| {
            found.push(JsonTemplate {
                key: key.text.clone(),
                key_span,
                target,
                text: s.text,
                contents: Span::new(s.start + 1, s.end - 1),
                map: s.map,
            })
        };
        match bytes.get(j) {
            Some(b'"') => {
                if let Some(value) = scan_string(doc, j) {
                    i = value.end;
                    push(value);
                } else {
                    break;
                }
            }
            Some(b'[') => {
                j += 1;
                loop {
                    j = skip_ws(bytes, j);
                    match bytes.get(j) {
                        Some(b'"') => match scan_string(doc, j) {
                            Some(value) => {
                                j = value.end;
                                push(value);
                            }
                            None => return found,
                        },
                        Some(b',') => j += 1,
                        _ => break,
                    }
                }
                i = j;
            }
            _ => i = j,
        }
    }
    found
}

fn skip_ws(bytes: &[u8], mut i: usize) -> usize {
    while matches!(bytes.get(i), Some(b' ' | b'\t' | b'\n' | b'\r')) {
        i += 1;
    }
    i
}

struct Scanned {
    /// Offset of the opening quote.
    start: usize,
    /// Offset just past the closing quote.
    end: usize,
    text: String,
    map: OffsetMap,
}

/// Read the string literal whose opening quote is at `start`. `None` if it never ends
/// (a raw newline also ends it: JSON strings cannot span lines, and stopping there keeps
/// one bad string from swallowing the rest of the document).
fn scan_string(doc: &str, start: usize) -> Option<Scanned> {
    let bytes = doc.as_bytes();
    let mut text = String::new();
    let mut map = OffsetMap {
        segments: Vec::new(),
        doc_start: start + 1,
    };
    let mut i = start + 1;
    let mut run = i; // start of the current verbatim run
    let flush = |text: &mut String, map: &mut OffsetMap, run: usize, i: usize| {
        if i > run {
            map.push(Segment {
                text: text.len(),
                text_len: i - run,
                doc: run,
                doc_len: i - run,
                verbatim: true,
            });
            text.push_str(&doc[run..i]);
        }
    };
    loop {
        match bytes.get(i)? {
            b'"' => {
                flush(&mut text, &mut map, run, i);
                return Some(Scanned {
                    start,
                    end: i + 1,
                    text,
                    map,
                });
            }
            b'\n' => return None,
            b'\\' => {
                flush(&mut text, &mut map, run, i);
                let (c, len) = unescape(bytes, i);
                map.push(Segment {
                    text: text.len(),
                    text_len: c.len_utf8(),
                    doc: i,
                    doc_len: len,
                    verbatim: false,
                });
                text.push(c);
                i += len;
                run = i;
            }
            // Multi-byte UTF-8 continues the run; `"` and `\` are ASCII, so they can never
            // appear inside a multi-byte character.
            _ => i += 1,
        }
    }
}

/// Decode the escape at `bytes[i] == b'\\'`: the character and the escape's byte length.
/// Invalid escapes decode to U+FFFD and consume only what was read, so the offsets still
/// land on the document's characters.
fn unescape(bytes: &[u8], i: usize) -> (char, usize) {
    let Some(&e) = bytes.get(i + 1) else {
        return ('\u{fffd}', 1);
    };
    let simple = match e {
        b'"' => Some('"'),
        b'\\' => Some('\\'),
        b'/' => Some('/'),
        b'b' => Some('\u{8}'),
        b'f' => Some('\u{c}'),
        b'n' => Some('\n'),
        b'r' => Some('\r'),
        b't' => Some('\t'),
        _ => None,
    };
    if let Some(c) = simple {
        return (c, 2);
    }
    if e != b'u' {
        // `\` before a non-ASCII byte would split a character: consume only the `\`.
        return ('\u{fffd}', if e.is_ascii() { 2 } else { 1 });
    }
    let Some(hi) = hex4(bytes, i + 2) else {
        return ('\u{fffd}', 2);
    };
    if (0xD800..0xDC00).contains(&hi)
        && bytes.get(i + 6) == Some(&b'\\')
        && bytes.get(i + 7) == Some(&b'u')
        && let Some(lo) = hex4(bytes, i + 8)
        && (0xDC00..0xE000).contains(&lo)
    {
        let c = 0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00);
        return (char::from_u32(c).unwrap_or('\u{fffd}'), 12);
    }
    (char::from_u32(hi).unwrap_or('\u{fffd}'), 6)
}

fn hex4(bytes: &[u8], i: usize) -> Option<u32> {
    let digits = bytes.get(i..i + 4)?;
    let s = std::str::from_utf8(digits).ok()?;
    u32::from_str_radix(s, 16).ok()
}

/// Escape text for the inside of a JSON string literal (for edits into JSON documents).
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out
}

/// Where a JSON document stops being valid JSON, as a byte offset and a message. `None`
/// for valid JSON. The server reports it once instead of guessing at the templates.
pub fn syntax_error(doc: &str) -> Option<(usize, String)> {
    let err = serde_json::from_str::<serde::de::IgnoredAny>(doc).err()?;
    // serde_json counts lines from 1 and columns in bytes from 1.
    let line_start = if err.line() <= 1 {
        0
    } else {
        doc.match_indices('\n')
            .nth(err.line() - 2)
            .map_or(doc.len(), |(i, _)| i + 1)
    };
    let offset =
        rotlang::diagnostic::floor_char_boundary(doc, line_start + err.column().saturating_sub(1));
    let mut message = err.to_string();
    // serde_json appends " at line L column C": the range already says where.
    if let Some(cut) = message.find(" at line ") {
        message.truncate(cut);
    }
    Some((offset, message))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_both_keys_with_escapes() {
        let doc = r#"{"name": "x", "sparse_infill_rotate_template": "+30\u00b0, \"a\"", "solid_infill_rotate_template" : ["0", "90"]}"#;
        let found = find_templates(doc);
        assert_eq!(found.len(), 3);
        assert_eq!(found[0].text, "+30°, \"a\"");
        assert_eq!(found[0].target, Target::Sparse);
        assert_eq!(found[1].text, "0");
        assert_eq!(found[2].target, Target::Solid);
        let t = &found[0];
        // The `,` after the escaped degree sign.
        let comma = t.text.find(',').unwrap();
        assert_eq!(&doc[t.map.to_doc(comma)..t.map.to_doc(comma) + 1], ",");
        // The degree sign: starts at the backslash, ends after the escape.
        let deg = t.text.find('°').unwrap();
        let span = t.map.span_to_doc(Span::new(deg, deg + 2));
        assert_eq!(&doc[span.range()], "\\u00b0");
        assert_eq!(t.map.to_text(span.start), Some(deg));
        assert_eq!(t.map.to_text(span.start + 3), Some(deg));
        assert_eq!(t.map.to_text(t.contents.end), Some(t.text.len()));
        assert_eq!(t.map.to_text(t.contents.end + 1), None);
    }

    #[test]
    fn surrogate_pairs_and_bad_escapes() {
        let doc = r#"{"sparse_infill_rotate_template": "\ud835\udd4f+1\q\u12"}"#;
        let t = &find_templates(doc)[0];
        assert!(t.text.starts_with("𝕏+1"));
        let plus = t.text.find('+').unwrap();
        assert_eq!(&doc[t.map.to_doc(plus)..t.map.to_doc(plus) + 1], "+");
    }

    #[test]
    fn malformed_documents_do_not_panic() {
        for doc in [
            "",
            "{",
            r#"{"sparse_infill_rotate_template": "#,
            r#"{"sparse_infill_rotate_template": "abc"#,
            r#"{"sparse_infill_rotate_template": ["a", "#,
            "\"\\",
            "\"\\u",
            "\"\\ud800\\u",
            "\"é\\é\"",
        ] {
            let _ = find_templates(doc);
            let _ = syntax_error(doc);
        }
        assert!(syntax_error("{}").is_none());
        assert!(syntax_error("{,}").is_some());
    }

    #[test]
    fn empty_string_maps_its_position() {
        let doc = r#"{"sparse_infill_rotate_template": ""}"#;
        let t = &find_templates(doc)[0];
        assert_eq!(t.text, "");
        assert_eq!(t.map.to_doc(0), t.contents.start);
        assert_eq!(t.map.to_text(t.contents.start), Some(0));
    }

    #[test]
    fn escape_round_trips() {
        assert_eq!(escape("1\"\\\n°"), "1\\\"\\\\\\n°");
    }
}
