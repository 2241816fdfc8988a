//! An open document: its text, kind, and the templates in it, parsed once per change.

use rotlang::{Instruction, Parse, Span, Target};

use crate::json::{self, OffsetMap};

/// What kind of file a document is: decides where its templates are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A `.rot` file: the whole text is one sparse template; newlines separate.
    Rot,
    /// A JSON slicer profile: templates are the values of the template keys.
    Json,
}

impl Kind {
    /// From the client's `languageId`, then the file extension. `None` for documents that
    /// are neither (a client that sends every plain-text file gets no diagnostics on them).
    pub fn detect(language_id: &str, uri: &str) -> Option<Kind> {
        match language_id {
            "json" | "jsonc" => return Some(Kind::Json),
            "rotlang" | "rot" => return Some(Kind::Rot),
            _ => {}
        }
        let path = uri
            .split(['?', '#'])
            .next()
            .unwrap_or(uri)
            .to_ascii_lowercase();
        if path.ends_with(".json") {
            Some(Kind::Json)
        } else if path.ends_with(".rot") {
            Some(Kind::Rot)
        } else {
            None
        }
    }
}

/// One template inside a document.
#[derive(Debug)]
pub struct Region {
    /// The JSON key (`None` in `.rot` files).
    pub key: Option<String>,
    /// The key's span in the document (JSON only).
    pub key_span: Option<Span>,
    pub target: Target,
    /// The template text (unescaped for JSON).
    pub text: String,
    /// Where the template's text lies in the document.
    pub contents: Span,
    pub map: OffsetMap,
    pub parse: Parse,
}

impl Region {
    /// A template span in document bytes.
    pub fn doc_span(&self, span: Span) -> Span {
        self.map.span_to_doc(span)
    }

    /// The template offset of a document offset, if it lies in this template (edges
    /// included, so a cursor right after the last character still counts).
    pub fn text_offset(&self, doc_offset: usize) -> Option<usize> {
        self.map.to_text(doc_offset)
    }

    /// The instruction under a template offset (its end included, where a cursor rests
    /// after typing it).
    pub fn instruction_at(&self, offset: usize) -> Option<(usize, &Instruction)> {
        self.parse
            .template
            .instructions
            .iter()
            .enumerate()
            .find(|(_, i)| i.span.start <= offset && offset <= i.span.end && !i.span.is_empty())
    }
}

#[derive(Debug)]
pub struct Document {
    pub text: String,
    pub kind: Kind,
    pub version: i32,
    pub regions: Vec<Region>,
    /// For JSON documents that are not valid JSON: where and why (reported once).
    pub json_error: Option<(usize, String)>,
    /// For documents over the size limit: their size and the limit. Their text is not
    /// kept and they have no templates.
    pub too_large: Option<(usize, usize)>,
}

impl Document {
    pub fn new(text: String, kind: Kind, version: i32) -> Document {
        let mut json_error = None;
        let regions = match kind {
            Kind::Rot => vec![Region {
                key: None,
                key_span: None,
                target: Target::Sparse,
                parse: rotlang::parse(&text, Target::Sparse),
                map: OffsetMap::identity(text.len()),
                contents: Span::new(0, text.len()),
                text: text.clone(),
            }],
            Kind::Json => {
                json_error = json::syntax_error(&text);
                json::find_templates(&text)
                    .into_iter()
                    .map(|t| Region {
                        parse: rotlang::parse(&t.text, t.target),
                        key: Some(t.key),
                        key_span: Some(t.key_span),
                        target: t.target,
                        text: t.text,
                        contents: t.contents,
                        map: t.map,
                    })
                    .collect()
            }
        };
        Document {
            text,
            kind,
            version,
            regions,
            json_error,
            too_large: None,
        }
    }

    /// A document of `len` bytes, over the `limit`: not parsed, its text dropped.
    pub fn too_large(len: usize, limit: usize, kind: Kind, version: i32) -> Document {
        Document {
            text: String::new(),
            kind,
            version,
            regions: Vec::new(),
            json_error: None,
            too_large: Some((len, limit)),
        }
    }

    /// The template containing a document offset, and the offset inside it.
    pub fn region_at(&self, offset: usize) -> Option<(&Region, usize)> {
        self.regions
            .iter()
            .find_map(|r| Some((r, r.text_offset(offset)?)))
    }

    /// Text to insert into the document at a template position (JSON needs escapes).
    pub fn encode(&self, text: &str) -> String {
        match self.kind {
            Kind::Rot => text.to_string(),
            Kind::Json => json::escape(text),
        }
    }
}
