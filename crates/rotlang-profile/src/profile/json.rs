//! A small, forgiving scanner for JSON slicer profiles (and jsonc: `//` and `/* */`
//! comments, trailing commas). It finds the values of given keys and maps offsets between
//! an unescaped string and the document. Shared by the CLI and the language server.
//!
//! Why not serde_json: it forgets where values were and what escapes they used, and
//! diagnostics must land on the exact characters inside a string such as
//! `"+30\u00b0X"`. The scanner never fails: on malformed input it returns what it found.

use std::borrow::Cow;

use crate::{Span, Target};

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

    /// An empty map for a value whose contents start at `doc_start` in the document.
    pub(crate) fn starting_at(doc_start: usize) -> OffsetMap {
        OffsetMap {
            segments: Vec::new(),
            doc_start,
        }
    }

    /// `len` bytes copied verbatim: template offset `text` is document offset `doc`.
    pub(crate) fn push_verbatim(&mut self, text: usize, doc: usize, len: usize) {
        if len > 0 {
            self.push(Segment {
                text,
                text_len: len,
                doc,
                doc_len: len,
                verbatim: true,
            });
        }
    }

    /// An escape: `doc_len` document bytes at `doc` stand for `text_len` template bytes.
    #[cfg(feature = "3mf")]
    pub(crate) fn push_escape(&mut self, text: usize, text_len: usize, doc: usize, doc_len: usize) {
        self.push(Segment {
            text,
            text_len,
            doc,
            doc_len,
            verbatim: false,
        });
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

/// One value found for a key: a string (unescaped, with its offset map), or the span of
/// anything else (a number, `true`, an object...), for messages about its type.
#[derive(Clone, Debug, PartialEq)]
pub enum JsonValue {
    String {
        text: String,
        /// The contents of the literal (quotes excluded).
        contents: Span,
        map: OffsetMap,
    },
    Number(Span),
    Other(Span),
}

/// A key found in a document with its value, or each string/number of an array value
/// (some exporters write every option as an array).
#[derive(Clone, Debug, PartialEq)]
pub struct KeyValues {
    pub key: String,
    /// The span of the key, quotes included.
    pub key_span: Span,
    pub values: Vec<JsonValue>,
    /// Whether the value was an array.
    pub array: bool,
}

/// Find every template in a JSON document: keys of the top-level object only (presets are
/// flat objects; a key inside a nested object is some other thing's). A value may be a
/// string or an array of strings. Values of another type are skipped.
pub fn find_templates(doc: &str) -> Vec<JsonTemplate> {
    let keys: Vec<&str> = TEMPLATE_KEYS.iter().map(|(k, _)| *k).collect();
    let mut found = Vec::new();
    for kv in find_values(doc, &keys) {
        let Some(&(_, target)) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == kv.key) else {
            continue;
        };
        for value in kv.values {
            if let JsonValue::String {
                text,
                contents,
                map,
            } = value
            {
                found.push(JsonTemplate {
                    key: kv.key.clone(),
                    key_span: kv.key_span,
                    target,
                    text,
                    contents,
                    map,
                });
            }
        }
    }
    found
}

/// Find the values of the given keys of the top-level object, in document order (keys of
/// nested objects and arrays are not the preset's). Comments are skipped (jsonc); malformed
/// input ends the scan where it cannot be read reliably.
pub fn find_values(doc: &str, keys: &[&str]) -> Vec<KeyValues> {
    let bytes = doc.as_bytes();
    let mut found = Vec::new();
    let mut i = 0;
    // Nesting outside strings: 1 inside the top-level object.
    let mut depth = 0usize;
    let mut top_is_object = false;
    while i < bytes.len() {
        if let Some(end) = comment_end(bytes, i) {
            i = end;
            continue;
        }
        if bytes[i] != b'"' {
            match bytes[i] {
                b'{' | b'[' => {
                    if depth == 0 {
                        top_is_object = bytes[i] == b'{';
                    }
                    depth += 1;
                }
                b'}' | b']' => depth = depth.saturating_sub(1),
                _ => {}
            }
            i += 1;
            continue;
        }
        let Some(key) = scan_string(doc, i) else {
            break; // unterminated string: nothing more can be read reliably
        };
        i = key.end;
        let mut j = skip_ws(bytes, i);
        if bytes.get(j) != Some(&b':')
            || !(depth == 1 && top_is_object)
            || !keys.contains(&key.text.as_str())
        {
            continue; // a value, a nested key, or a key we do not look for
        }
        j = skip_ws(bytes, j + 1);
        let mut kv = KeyValues {
            key: key.text.clone(),
            key_span: Span::new(key.start, key.end),
            values: Vec::new(),
            array: false,
        };
        if bytes.get(j) == Some(&b'[') {
            kv.array = true;
            // The main loop counts the `]` that ends it.
            depth += 1;
            j += 1;
            loop {
                j = skip_ws(bytes, j);
                match bytes.get(j) {
                    Some(b',') => j += 1,
                    Some(b']') | None => break,
                    // A nested object or array: noted, then scanned (and counted) as usual.
                    Some(b'{' | b'[') => {
                        kv.values.push(JsonValue::Other(Span::new(j, j + 1)));
                        break;
                    }
                    Some(_) => match value_at(doc, j) {
                        Some((value, end)) => {
                            kv.values.push(value);
                            j = end;
                        }
                        None => {
                            found.push(kv);
                            return found;
                        }
                    },
                }
            }
            i = j;
        } else if j < bytes.len() {
            match value_at(doc, j) {
                Some((value, end)) => {
                    kv.values.push(value);
                    // An object value is scanned on (its keys are nested): its `{` counted.
                    i = if bytes[j] == b'{' { j } else { end };
                }
                None => {
                    found.push(kv);
                    break;
                }
            }
        }
        found.push(kv);
    }
    found
}

/// The value starting at `j` and the offset after it; `None` for an unterminated string.
/// Objects and arrays nested in a value are not entered here (`Other` spans one byte).
fn value_at(doc: &str, j: usize) -> Option<(JsonValue, usize)> {
    let bytes = doc.as_bytes();
    match bytes[j] {
        b'"' => {
            let s = scan_string(doc, j)?;
            let end = s.end;
            Some((
                JsonValue::String {
                    text: s.text,
                    contents: Span::new(s.start + 1, s.end - 1),
                    map: s.map,
                },
                end,
            ))
        }
        b'-' | b'0'..=b'9' => {
            let len = bytes[j..]
                .iter()
                .take_while(|b| matches!(b, b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E'))
                .count();
            Some((JsonValue::Number(Span::new(j, j + len)), j + len))
        }
        b'{' | b'[' => Some((JsonValue::Other(Span::new(j, j + 1)), j + 1)),
        _ => {
            let len = bytes[j..]
                .iter()
                .take_while(|b| b.is_ascii_alphanumeric())
                .count()
                .max(1);
            let end = crate::diagnostic::ceil_char_boundary(doc, j + len);
            Some((JsonValue::Other(Span::new(j, end)), end))
        }
    }
}

/// If a comment starts at `i` (`//` to the end of the line, `/* */`), the offset after it.
fn comment_end(bytes: &[u8], i: usize) -> Option<usize> {
    if bytes.get(i) != Some(&b'/') {
        return None;
    }
    match bytes.get(i + 1) {
        Some(b'/') => Some(
            bytes[i..]
                .iter()
                .position(|&b| b == b'\n' || b == b'\r')
                .map_or(bytes.len(), |p| i + p),
        ),
        Some(b'*') => Some(
            bytes[i + 2..]
                .windows(2)
                .position(|w| w == b"*/")
                .map_or(bytes.len(), |p| i + 2 + p + 2),
        ),
        _ => None,
    }
}

/// The document with jsonc's extras (comments, trailing commas, a byte-order mark) turned
/// into spaces, so that plain JSON parsers read it and every offset stays where it was.
pub fn strip_jsonc(doc: &str) -> Cow<'_, str> {
    let bytes = doc.as_bytes();
    let mut out: Option<Vec<u8>> = None;
    let blank = |out: &mut Option<Vec<u8>>, from: usize, to: usize| {
        let buf = out.get_or_insert_with(|| bytes.to_vec());
        for b in &mut buf[from..to] {
            // Line breaks stay, so line numbers do too; multi-byte characters become spaces.
            if *b != b'\n' && *b != b'\r' {
                *b = b' ';
            }
        }
    };
    if doc.starts_with('\u{feff}') {
        blank(&mut out, 0, 3);
    }
    let mut i = 0;
    // The last byte that is not whitespace or comment: a trailing comma follows a value.
    let mut prev = b'{';
    while i < bytes.len() {
        let b = bytes[i];
        if !b.is_ascii_whitespace() && b != b'/' {
            prev = if b == b',' && matches!(prev, b'{' | b'[' | b',' | b':') {
                b'!'
            } else {
                b
            };
        }
        match b {
            b'"' => {
                // Skip the string; an unterminated one ends the line.
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
            }
            b'/' => match comment_end(bytes, i) {
                Some(end) => {
                    blank(&mut out, i, end.min(bytes.len()));
                    i = end;
                }
                None => i += 1,
            },
            b',' => {
                let mut j = i + 1;
                loop {
                    j = skip_ws(bytes, j);
                    match comment_end(bytes, j) {
                        Some(end) => j = end,
                        None => break,
                    }
                }
                // `prev` is `!` for a comma that follows no value (`{,}`): left to fail.
                if prev == b',' && matches!(bytes.get(j), Some(b'}' | b']')) {
                    blank(&mut out, i, i + 1);
                }
                i += 1;
            }
            _ => i += 1,
        }
    }
    match out {
        // Only ASCII bytes and whole comments (which end on ASCII) were blanked.
        Some(buf) => Cow::Owned(
            String::from_utf8(buf)
                .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()),
        ),
        None => Cow::Borrowed(doc),
    }
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
/// for valid JSON. A byte-order mark is allowed (OrcaSlicer skips it); comments and
/// trailing commas are not: for `.jsonc`, pass the text through [`strip_jsonc`] first. The server reports it once instead of guessing at the templates.
pub fn syntax_error(doc: &str) -> Option<(usize, String)> {
    let plain = match doc.strip_prefix('\u{feff}') {
        Some(rest) => Cow::Owned(format!("   {rest}")),
        None => Cow::Borrowed(doc),
    };
    let err = serde_json::from_str::<serde::de::IgnoredAny>(&plain).err()?;
    // serde_json counts lines from 1 and columns in bytes from 1.
    let line_start = if err.line() <= 1 {
        0
    } else {
        doc.match_indices('\n')
            .nth(err.line() - 2)
            .map_or(doc.len(), |(i, _)| i + 1)
    };
    let offset =
        crate::diagnostic::floor_char_boundary(doc, line_start + err.column().saturating_sub(1));
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
