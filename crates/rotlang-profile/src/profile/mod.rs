//! Finding templates in files: `.rot` templates, OrcaSlicer JSON presets (and jsonc),
//! exported `.ini` configs, `.3mf` projects (feature `3mf`), and folders of them. Every
//! template keeps a map from its text back to the file (through JSON and XML escapes), so
//! diagnostics land on the file's own characters; and a profile's `layer_height`,
//! `initial_layer_print_height`, shell counts and infill direction become the model its
//! templates are evaluated on ([`Profile::model`]); the direction is the angle of an empty
//! template only, as in OrcaSlicer ([`ProfileModel::options`]).
//!
//! Bad input (not UTF-8, corrupt or truncated archives, zip bombs, huge files, values of
//! the wrong type) is an error for that file or a note on that value, never a panic.
//!
//! ```
//! use std::path::Path;
//! use rotlang_profile::profile;
//!
//! let preset = br#"{ "layer_height": "0.12", "sparse_infill_rotate_template": "0 90" }"#;
//! let p = profile::parse(Path::new("fine.json"), preset).unwrap();
//! assert_eq!(p.templates[0].text, "0 90");
//! assert_eq!(p.templates[0].key.as_deref(), Some("sparse_infill_rotate_template"));
//! let m = p.model(rotlang::Target::Sparse, None, 20.0);
//! assert_eq!(m.model.layer_height(), 0.12);
//! // OrcaSlicer's default direction (45°) turns an empty template only.
//! assert_eq!(m.options("0 90").base, 0.0);
//! assert_eq!(m.options("").base, 45.0);
//! ```

pub mod ini;
pub mod json;
mod part;
mod read;
mod settings;
#[cfg(feature = "3mf")]
mod threemf;

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};

pub use json::OffsetMap;
pub use part::{PartInfill, orcaslicer_pattern};
pub use read::{parse, read, read_with_bytes};
pub use settings::{
    DEFAULT_OBJECT_HEIGHT, Direction, INFILL_KEYS, MODEL_KEYS, ProfileModel, Setting, Settings,
};
#[cfg(feature = "3mf")]
pub use threemf::{MAX_ENTRIES, MAX_ENTRY_BYTES, is_project};

use crate::{Span, Target};

/// The largest file read. Profiles are kilobytes; projects a few megabytes.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// The profile keys whose values are templates, and the target each is checked for.
pub const TEMPLATE_KEYS: [(&str, Target); 2] = json::TEMPLATE_KEYS;

/// The kinds of file read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// A template on its own (`.rot`; newlines separate instructions).
    Template,
    /// An OrcaSlicer preset (process, filament, machine), JSON or jsonc.
    Json,
    /// `key = value` lines, as OrcaSlicer and PrusaSlicer export configs.
    Ini,
    /// An OrcaSlicer project (a zip of 3MF parts and settings).
    ThreeMf,
}

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Template => "template",
            Kind::Json => "json",
            Kind::Ini => "ini",
            Kind::ThreeMf => "3mf",
        }
    }

    /// The kind a file name's extension announces (`.rot`, `.json`, `.jsonc`, `.ini`,
    /// `.3mf`); directories are searched for these only.
    pub fn from_extension(path: &Path) -> Option<Kind> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "rot" => Kind::Template,
            "json" | "jsonc" => Kind::Json,
            "ini" => Kind::Ini,
            "3mf" => Kind::ThreeMf,
            _ => return None,
        })
    }
}

/// A text that positions refer to: the file itself, or an entry of a `.3mf` archive.
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    /// `profile.json`, or `project.3mf!Metadata/model_settings.config`.
    pub name: String,
    pub text: String,
}

/// One template found in a file.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// The key (`sparse_infill_rotate_template`); `None` for a `.rot` file.
    pub key: Option<String>,
    /// For a per-object override in a `.3mf` project: the object (and part) it applies to.
    pub object: Option<String>,
    pub target: Target,
    /// The template, unescaped.
    pub text: String,
    /// Index into [`Profile::sources`].
    pub source: usize,
    /// Template offsets → source offsets.
    pub map: OffsetMap,
}

impl Found {
    /// A span of the template as a span of its source text.
    pub fn span_in_source(&self, span: Span) -> Span {
        self.map.span_to_doc(span)
    }

    /// `key` or `key (object Cube)`, for reports.
    pub fn label(&self) -> String {
        match (&self.key, &self.object) {
            (Some(k), Some(o)) => format!("{k} (object {o})"),
            (Some(k), None) => k.clone(),
            (None, _) => "template".to_owned(),
        }
    }
}

/// A problem with one value or part of a file that does not stop the rest from being read
/// (a template key holding a number, invalid JSON after the templates...).
#[derive(Clone, Debug, PartialEq)]
pub struct Note {
    pub source: usize,
    pub span: Span,
    pub message: String,
    /// An error fails the file; otherwise it is information.
    pub error: bool,
    /// The key the note is about (a value of the wrong type), if any.
    pub key: Option<String>,
}

/// A file read: its texts, the templates in it, and the settings the model comes from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    pub path: PathBuf,
    pub kind: Option<Kind>,
    pub sources: Vec<Source>,
    pub templates: Vec<Found>,
    /// The file's (or the project's) settings.
    pub settings: Settings,
    /// Per-object settings of a `.3mf` project, by object name.
    pub objects: Vec<(String, Settings)>,
    pub notes: Vec<Note>,
}

impl Profile {
    /// The model and direction for a template of `target` (of `object`, for a 3mf override),
    /// for an object `height` mm tall: see [`Settings::model`].
    pub fn model(&self, target: Target, object: Option<&str>, height: f64) -> ProfileModel {
        let own = object.and_then(|o| self.objects.iter().find(|(n, _)| n == o).map(|(_, s)| s));
        self.settings.model(own, target, height)
    }

    /// The template of `target` a command takes from this file (`expand --profile`): the
    /// file's (or the project's) own, else the first object's. When there is none, why:
    /// the key holds a value of another type (what `check` reports), or no such key.
    pub fn template(&self, target: Target) -> Result<&Found, String> {
        let key = TEMPLATE_KEYS
            .iter()
            .find(|(_, t)| *t == target)
            .map_or("", |(k, _)| *k);
        if let Some(found) = self
            .templates
            .iter()
            .find(|f| f.target == target && f.object.is_none())
            .or_else(|| self.templates.iter().find(|f| f.target == target))
        {
            return Ok(found);
        }
        match self
            .notes
            .iter()
            .find(|n| n.error && n.key.as_deref() == Some(key))
        {
            Some(note) => {
                let text = self
                    .sources
                    .get(note.source)
                    .map_or("", |s| s.text.as_str());
                let (line, column) = crate::diagnostic::LineIndex::new(text)
                    .line_col(note.span.start.min(text.len()));
                Err(format!("{} (line {line}, column {column})", note.message))
            }
            None => Err(format!("no `{key}` in this file")),
        }
    }

    /// Whether any note is an error.
    pub fn has_errors(&self) -> bool {
        self.notes.iter().any(|n| n.error)
    }
}

/// A file that could not be read at all.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProfileError {
    pub path: PathBuf,
    pub message: String,
}

impl fmt::Display for ProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for ProfileError {}

pub(super) fn error(path: &Path, message: impl Into<String>) -> ProfileError {
    ProfileError {
        path: path.to_owned(),
        message: message.into(),
    }
}

/// The text of a file, or where it stops being UTF-8.
pub(crate) fn utf8(bytes: &[u8]) -> Result<String, String> {
    String::from_utf8(bytes.to_vec()).map_err(|e| {
        format!(
            "not UTF-8 text (invalid byte at offset {}): a profile must be saved as UTF-8",
            e.utf8_error().valid_up_to()
        )
    })
}

/// A `.rot` file: one template, the whole text after a byte-order mark.
pub(super) fn template_file(profile: &mut Profile) {
    let text = &profile.sources[0].text;
    let start = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let mut map = OffsetMap::starting_at(start);
    map.push_verbatim(0, start, text.len() - start);
    let found = Found {
        key: None,
        object: None,
        target: Target::Sparse,
        text: text[start..].to_owned(),
        source: 0,
        map,
    };
    profile.templates.push(found);
}

/// The template and model keys of the JSON text `profile.sources[source]`; `object` names
/// the object a 3mf entry's settings belong to (none: the file's own). `jsonc` allows
/// comments and trailing commas (OrcaSlicer itself reads plain JSON only).
pub(crate) fn json_file(profile: &mut Profile, source: usize, object: Option<&str>, jsonc: bool) {
    let doc = profile.sources[source].text.clone();
    let plain = json::strip_jsonc(&doc);
    let error = if jsonc {
        json::syntax_error(&plain)
    } else {
        json::syntax_error(&doc).map(|(offset, message)| {
            if json::syntax_error(&plain).is_none() {
                let why = "comments or trailing commas, which OrcaSlicer cannot read (name the file .jsonc if it is not a preset)";
                (offset, format!("{message}: {why}"))
            } else {
                (offset, message)
            }
        })
    };
    if let Some((offset, message)) = error {
        // The offset may come from the jsonc-stripped text, where a byte-order mark is
        // blanked: it must be a boundary of the file's own text.
        let offset = crate::diagnostic::floor_char_boundary(&doc, offset);
        profile.notes.push(Note {
            source,
            span: Span::new(offset, offset),
            message: format!("invalid JSON: {message}"),
            error: true,
            key: None,
        });
    }
    let mut keys: Vec<&str> = TEMPLATE_KEYS.iter().map(|(k, _)| *k).collect();
    keys.extend(MODEL_KEYS);
    keys.extend(INFILL_KEYS);
    keys.push("inherits");
    let mut settings = Settings::default();
    let found = json::find_values(&doc, &keys);
    let later = superseded(found.iter().map(|kv| (kv.key.as_str(), kv.key_span)));
    let mut duplicates = Duplicates::new(&doc);
    for (kv, later) in found.iter().zip(later) {
        if let Some(used) = later {
            profile
                .notes
                .push(duplicates.note(source, &kv.key, kv.key_span, used));
            continue;
        }
        let template = TEMPLATE_KEYS.iter().find(|(k, _)| *k == kv.key);
        for value in &kv.values {
            match (value, template) {
                (json::JsonValue::String { text, map, .. }, Some(&(_, target))) => {
                    profile.templates.push(Found {
                        key: Some(kv.key.clone()),
                        object: object.map(str::to_owned),
                        target,
                        text: text.clone(),
                        source,
                        map: map.clone(),
                    });
                }
                (json::JsonValue::String { text, contents, .. }, None) => {
                    settings.set(&kv.key, text.clone(), source, *contents);
                }
                (json::JsonValue::Number(span), None) => {
                    settings.set(&kv.key, doc[span.range()].to_owned(), source, *span);
                }
                (json::JsonValue::Number(span) | json::JsonValue::Other(span), _) => {
                    let what = if template.is_some() {
                        "a template (a string)"
                    } else {
                        "a string or a number"
                    };
                    profile.notes.push(Note {
                        source,
                        span: *span,
                        message: format!(
                            "`{}` should be {what}, not `{}`",
                            kv.key,
                            &doc[span.range()]
                        ),
                        error: template.is_some(),
                        key: Some(kv.key.clone()),
                    });
                }
            }
            // Per-extruder arrays: the first value is the one that matters here.
            if template.is_none() {
                break;
            }
        }
    }
    match object {
        None => profile.settings.merge_missing(settings),
        Some(o) => profile.objects.push((o.to_owned(), settings)),
    }
}

/// For each key in document order, the span of the later occurrence of the same key that
/// replaces it, if any: OrcaSlicer keeps the last value of a key (nlohmann::json, which
/// OrcaSlicer reads presets with, assigns each repeated key over the one before; a 3mf's
/// `<metadata>` are set one after the other), so rotlang does too, everywhere. Linear.
pub(crate) fn superseded<'a>(keys: impl Iterator<Item = (&'a str, Span)>) -> Vec<Option<Span>> {
    let keys: Vec<(&str, Span)> = keys.collect();
    let mut last: std::collections::HashMap<&str, Span> = std::collections::HashMap::new();
    for &(k, span) in &keys {
        last.insert(k, span);
    }
    keys.iter()
        .map(|&(k, span)| last.get(k).copied().filter(|&l| l != span))
        .collect()
}

/// The warnings on values that a later one of the same key replaces; the line index is
/// built on the first (most files have none).
pub(crate) struct Duplicates<'a> {
    doc: &'a str,
    index: Option<crate::diagnostic::LineIndex<'a>>,
}

impl<'a> Duplicates<'a> {
    pub(crate) fn new(doc: &'a str) -> Self {
        Duplicates { doc, index: None }
    }

    /// The note on the value of `key` at `span`, replaced by the one at `used`.
    pub(crate) fn note(&mut self, source: usize, key: &str, span: Span, used: Span) -> Note {
        let doc = self.doc;
        let index = self
            .index
            .get_or_insert_with(|| crate::diagnostic::LineIndex::new(doc));
        // The line only: a column costs the length of its line, and one-line files of
        // 100,000 repeated keys must stay linear.
        let line = index.line(used.start.min(doc.len())) + 1;
        Note {
            source,
            span,
            message: format!(
                "`{key}` is set again later (line {line}): OrcaSlicer keeps the \
                 last value, so this one is ignored (remove one of them)"
            ),
            error: false,
            key: Some(key.to_owned()),
        }
    }
}

/// The files under `dir` that [`Kind::from_extension`] knows, recursively, sorted; symbolic
/// links to directories are not followed (no loops). Unreadable folders are errors.
pub fn files_under(dir: &Path) -> (Vec<PathBuf>, Vec<ProfileError>) {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    let mut stack = vec![dir.to_owned()];
    let mut seen = BTreeSet::new();
    while let Some(d) = stack.pop() {
        if !seen.insert(d.clone()) {
            continue;
        }
        let entries = match std::fs::read_dir(&d) {
            Ok(e) => e,
            Err(e) => {
                errors.push(error(&d, format!("cannot read folder: {e}")));
                continue;
            }
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                stack.push(path);
            } else if (kind.is_file() || kind.is_symlink() && path.is_file())
                && Kind::from_extension(&path).is_some()
            {
                files.push(path);
            }
        }
    }
    files.sort();
    (files, errors)
}

#[cfg(test)]
mod tests;
