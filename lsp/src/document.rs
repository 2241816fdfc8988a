//! An open document: its text, kind, and the templates in it, parsed once per change.

use std::path::Path;
use std::sync::{Arc, Mutex};

use rotlang::{Instruction, Parse, Span, Target, Template};
use rotlang_profile::profile::ProfileModel;

use crate::instructions::Spans;
use crate::json::{self, OffsetMap};
use crate::preview::Preview;
use crate::reading::Reading;
use crate::settings::ModelSettings;
use crate::{ini, jsonc};

pub use crate::kind::Kind;

/// One template inside a document.
#[derive(Clone, Debug)]
pub struct Region {
    /// The JSON key (`None` in `.rot` files).
    pub key: Option<String>,
    /// The key's span in the document (JSON only).
    pub key_span: Option<Span>,
    pub target: Target,
    /// The template text (unescaped for JSON). In a `.rot` file, the document's own text,
    /// shared.
    pub text: Arc<String>,
    /// Where the template's text lies in the document.
    pub contents: Span,
    pub map: OffsetMap,
    /// The library's diagnostics and counts. Its `template` is empty: the instructions are
    /// kept as `spans` and read again where a feature needs them (`Region::instructions`).
    pub parse: Parse,
    /// The instructions' spans (8 bytes each, where the library's IR takes hundreds).
    pub spans: Spans,
    /// In a profile the library can read: the model it gives this template's target (its
    /// layer heights, shells and direction). `None` in `.rot` files.
    pub profile: Option<ProfileModel>,
}

impl Region {
    /// The one reading of this template (model and base) that hover, inlay hints, symbols
    /// and the compat diagnostics share: the profile's where there is one, else the
    /// settings' model.
    pub fn reading(&self, settings: &ModelSettings) -> Reading {
        match &self.profile {
            Some(profile) => Reading::of_profile(profile, &self.text),
            None => Reading::of_settings(settings),
        }
    }

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
    /// after typing it), read again from the text.
    pub fn instruction_at(&self, offset: usize) -> Option<(usize, Instruction)> {
        let i = self.spans.index_at(offset)?;
        Some((i, self.instructions(i..i + 1).pop()?))
    }

    /// Instructions `range`, as the library's parse gives them (read again from the text).
    pub fn instructions(&self, range: std::ops::Range<usize>) -> Vec<Instruction> {
        self.spans.get(&self.text, self.target, range)
    }

    /// The template of instructions `range` (`0..self.spans.len()`: the whole template).
    pub fn template(&self, range: std::ops::Range<usize>) -> Template {
        self.spans.template(&self.text, self.target, range)
    }

    /// Each of instructions `range` with its index, in order, while `f` returns `true`: read
    /// again a batch at a time, so a walk that stops early reads little.
    pub fn each_instruction(
        &self,
        range: std::ops::Range<usize>,
        mut f: impl FnMut(usize, Instruction) -> bool,
    ) {
        const BATCH: usize = 4096;
        let end = range.end.min(self.spans.len());
        let mut at = range.start;
        while at < end {
            let next = (at + BATCH).min(end);
            for (i, ins) in (at..next).zip(self.instructions(at..next)) {
                if !f(i, ins) {
                    return;
                }
            }
            at = next;
        }
    }

    /// The first index in `0..len` where `pred` turns false (`pred` holds on a prefix).
    pub fn partition(len: usize, pred: impl Fn(usize) -> bool) -> usize {
        let (mut lo, mut hi) = (0, len);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if pred(mid) {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// What previews and first runs read of this template.
    pub fn source(&self) -> crate::preview::Source<'_> {
        crate::preview::Source {
            text: &self.text,
            target: self.target,
            spans: &self.spans,
        }
    }
}

/// A template value that a later one of the same key replaces (OrcaSlicer's reader keeps
/// the last; so does the library, `rotlang_profile::profile`): it is not read, and gets the warning
/// `rotlang check` gives it.
#[derive(Debug)]
pub struct Duplicate {
    pub key: String,
    pub key_span: Span,
    /// Where its (unused) value lies in the document.
    pub contents: Span,
    /// The key of the value that is used.
    pub used: Span,
    /// The library's words (`rotlang check` prints the same).
    pub message: String,
}

/// A value computed for some settings.
type Cached<T> = (ModelSettings, Arc<T>);

/// Compat findings, each with the index of its region.
pub type Findings = Arc<Vec<(usize, rotlang::Diagnostic)>>;

#[derive(Debug)]
pub struct Document {
    /// The text, shared with the server's store of open documents (not a copy of it).
    pub text: Arc<String>,
    pub kind: Kind,
    pub version: i32,
    pub regions: Vec<Region>,
    /// Template values that later ones of the same key replace (not in `regions`).
    pub duplicates: Vec<Duplicate>,
    /// For JSON documents that are not valid JSON: where and why (reported once).
    pub json_error: Option<(usize, String)>,
    /// For documents over the size limit: their size and the limit. Their text is not
    /// kept and they have no templates.
    pub too_large: Option<(usize, usize)>,
    /// The compat findings, computed once per settings for diagnostics and code actions
    /// alike (`crate::compat::cached`).
    pub compat: Mutex<Option<(ModelSettings, Findings)>>,
    /// Each region's preview (its layers summarised), computed once per settings: the
    /// evaluator prepares the whole template first, which on a 3 MB template costs more
    /// than a hover may take (`Document::preview`).
    previews: Mutex<Vec<Option<Cached<Preview>>>>,
}

impl Document {
    /// Parse a document. `path`: the file's place, where a JSON preset's `inherits`
    /// parents are found (as the CLI finds them).
    pub fn new(
        text: impl Into<Arc<String>>,
        kind: Kind,
        version: i32,
        path: Option<&Path>,
    ) -> Document {
        Document::build(text.into(), kind, version, path, None)
    }

    /// The document's next version, from the analysis of its previous one: each template
    /// that is still there (same place in the list, same key) is re-read only where the
    /// edit touched it (`crate::incremental`), with the same result as `new`.
    pub fn update(
        previous: Document,
        text: impl Into<Arc<String>>,
        kind: Kind,
        version: i32,
        path: Option<&Path>,
    ) -> Document {
        Document::build(text.into(), kind, version, path, Some(previous))
    }

    fn build(
        text: Arc<String>,
        kind: Kind,
        version: i32,
        path: Option<&Path>,
        previous: Option<Document>,
    ) -> Document {
        // The previous templates, by index, where the kind is the same.
        let mut before: Vec<Option<Region>> = match previous {
            Some(p) if p.kind == kind && p.too_large.is_none() => {
                p.regions.into_iter().map(Some).collect()
            }
            _ => Vec::new(),
        };
        let mut parse = |index: usize, key: Option<&str>, target: Target, new: &str| match before
            .get_mut(index)
            .and_then(Option::take)
        {
            Some(old) if old.key.as_deref() == key && old.target == target => {
                crate::incremental::reparse(&old.text, (old.parse, old.spans), new, target)
            }
            _ => Spans::read(new, target),
        };
        let mut json_error = None;
        let mut duplicates = Vec::new();
        let mut regions = match kind {
            Kind::Rot => {
                let (parse, spans) = parse(0, None, Target::Sparse, &text);
                vec![Region {
                    key: None,
                    key_span: None,
                    target: Target::Sparse,
                    parse,
                    spans,
                    map: OffsetMap::identity(text.len()),
                    contents: Span::new(0, text.len()),
                    text: text.clone(),
                    profile: None,
                }]
            }
            Kind::Json | Kind::Jsonc | Kind::Ini => {
                let found = match kind {
                    Kind::Ini => ini::find_templates(&text),
                    Kind::Jsonc => {
                        // Same offsets as the text, so every span found is the document's.
                        let plain = jsonc::blank(&text);
                        json_error = json::syntax_error(&plain);
                        json::find_templates(&plain)
                    }
                    _ => {
                        json_error = json::syntax_error(&text);
                        json::find_templates(&text)
                    }
                };
                let (found, replaced) = last_of_each_key(&text, found);
                duplicates = replaced;
                found
                    .into_iter()
                    .enumerate()
                    .map(|(i, t)| {
                        let (parse, spans) = parse(i, Some(&t.key), t.target, &t.text);
                        Region {
                            parse,
                            spans,
                            key: Some(t.key),
                            key_span: Some(t.key_span),
                            target: t.target,
                            text: Arc::new(t.text),
                            contents: t.contents,
                            map: t.map,
                            profile: None,
                        }
                    })
                    .collect()
            }
        };
        if kind != Kind::Rot && !regions.is_empty() {
            let profile = profile_of(&text, kind, path);
            for region in &mut regions {
                region.profile = profile.as_ref().map(|p| {
                    p.model(
                        region.target,
                        None,
                        rotlang_profile::profile::DEFAULT_OBJECT_HEIGHT,
                    )
                });
            }
        }
        // A JSON file that never names a template key is not a profile (an editor may hand
        // the server every JSON file: settings.json, package.json, tsconfig.json with its
        // comments): its syntax is the JSON server's business, not ours.
        if regions.is_empty() && !json::TEMPLATE_KEYS.iter().any(|(k, _)| text.contains(k)) {
            json_error = None;
        }
        Document {
            text,
            kind,
            version,
            regions,
            duplicates,
            json_error,
            too_large: None,
            compat: Mutex::default(),
            previews: Mutex::default(),
        }
    }

    /// What `update` needs of this document, copied: for when the analysis is still in use
    /// elsewhere (a request being answered on it), so it cannot be taken. Copying the parsed
    /// instructions costs far less than parsing them again.
    pub fn copy_for_update(&self) -> Document {
        Document {
            text: Arc::default(),
            kind: self.kind,
            version: self.version,
            regions: self.regions.clone(),
            duplicates: Vec::new(),
            json_error: None,
            too_large: self.too_large,
            compat: Mutex::default(),
            previews: Mutex::default(),
        }
    }

    /// A document of `len` bytes, over the `limit`: not parsed, its text dropped.
    pub fn too_large(len: usize, limit: usize, kind: Kind, version: i32) -> Document {
        Document {
            text: Arc::default(),
            kind,
            version,
            regions: Vec::new(),
            duplicates: Vec::new(),
            json_error: None,
            too_large: Some((len, limit)),
            compat: Mutex::default(),
            previews: Mutex::default(),
        }
    }

    /// The preview of region `index` in its reading, computed on first use for these
    /// settings and kept (the analysis computes them in the background, so that a hover
    /// finds them ready).
    pub fn preview(&self, index: usize, settings: &ModelSettings) -> Option<Arc<Preview>> {
        let region = self.regions.get(index)?;
        let lock = || self.previews.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(Some((for_settings, preview))) = lock().get(index)
            && for_settings == settings
        {
            return Some(preview.clone());
        }
        let preview = Arc::new(Preview::compute(region.source(), &region.reading(settings)));
        let mut previews = lock();
        if previews.len() < self.regions.len() {
            previews.resize(self.regions.len(), None);
        }
        previews[index] = Some((*settings, preview.clone()));
        Some(preview)
    }

    /// The index of a region of this document (found by address).
    pub fn index_of(&self, region: &Region) -> Option<usize> {
        self.regions.iter().position(|r| std::ptr::eq(r, region))
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
            Kind::Rot | Kind::Ini => text.to_string(),
            Kind::Json | Kind::Jsonc => json::escape(text),
        }
    }
}

/// The templates whose value is used (the last of each key, as the library reads a
/// profile), and the others as duplicates, with the library's warning.
fn last_of_each_key(
    doc: &str,
    found: Vec<json::JsonTemplate>,
) -> (Vec<json::JsonTemplate>, Vec<Duplicate>) {
    let mut last: std::collections::HashMap<&str, Span> = std::collections::HashMap::new();
    for t in &found {
        last.insert(&t.key, t.key_span);
    }
    let last: Vec<Option<Span>> = found
        .iter()
        .map(|t| {
            last.get(t.key.as_str())
                .copied()
                .filter(|&l| l != t.key_span)
        })
        .collect();
    if last.iter().all(Option::is_none) {
        return (found, Vec::new());
    }
    // Built only when there is a duplicate (a line number is in the message).
    let index = rotlang::LineIndex::new(doc);
    let (mut used, mut replaced) = (Vec::new(), Vec::new());
    for (t, later) in found.into_iter().zip(last) {
        match later {
            None => used.push(t),
            Some(at) => {
                // `rotlang_profile::profile`'s words for the note `rotlang check` prints.
                let line = index.line(at.start.min(doc.len())) + 1;
                replaced.push(Duplicate {
                    message: format!(
                        "`{}` is set again later (line {line}): OrcaSlicer keeps the last \
                         value, so this one is ignored (remove one of them)",
                        t.key
                    ),
                    key: t.key,
                    key_span: t.key_span,
                    contents: t.contents,
                    used: at,
                });
            }
        }
    }
    (used, replaced)
}

/// The library's reading of a profile's text: its settings, with the `inherits` parents
/// beside `path` when the document is a file. `None` when the library cannot read it.
fn profile_of(
    text: &str,
    kind: Kind,
    path: Option<&Path>,
) -> Option<rotlang_profile::profile::Profile> {
    // A name that says its kind: the library decides the format from it.
    let name = match kind {
        Kind::Rot => return None,
        Kind::Json => "profile.json",
        Kind::Jsonc => "profile.jsonc",
        Kind::Ini => "profile.ini",
    };
    let mut profile = rotlang_profile::profile::parse(Path::new(name), text.as_bytes()).ok()?;
    if let Some(path) = path {
        profile.path = path.to_owned();
        profile.resolve_inherits();
    }
    Some(profile)
}
