//! OrcaSlicer `.3mf` projects: a zip whose `Metadata/project_settings.config` is the
//! project's JSON settings and whose `Metadata/model_settings.config` is XML with
//! per-object (and per-part) `<metadata key=… value=…/>` overrides.
//!
//! Archives are untrusted: an entry is inflated only up to [`MAX_ENTRY_BYTES`] (a zip
//! bomb stops there with an error), whatever size its header claims; a corrupt or
//! truncated archive, a bad checksum, or XML that does not parse is an error for the file.

use std::io::{Cursor, Read};

use super::json::OffsetMap;
use super::{Found, Profile, Settings, Source, TEMPLATE_KEYS, json_file, utf8};
use crate::Span;

/// Settings files are kilobytes; a project's whole model settings a few megabytes.
pub const MAX_ENTRY_BYTES: u64 = 16 * 1024 * 1024;

/// A project holds a few dozen entries (the model, settings, plate pictures); reading the
/// central directory costs memory per entry (600k empty entries took 410 MB), so an archive
/// claiming more is refused before it is read.
pub const MAX_ENTRIES: u64 = 10_000;

const PROJECT: &str = "Metadata/project_settings.config";
const MODEL: &str = "Metadata/model_settings.config";

pub(super) fn read(name: &str, bytes: &[u8], profile: &mut Profile) -> Result<(), String> {
    if let Some(n) = entry_count(bytes).filter(|&n| n > MAX_ENTRIES) {
        return Err(format!(
            "a zip archive of {n} entries, more than the {MAX_ENTRIES} a project can hold"
        ));
    }
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| format!("not a readable 3mf (zip) archive: {e}"))?;
    let mut any = false;
    if let Some(text) = entry(&mut archive, PROJECT)? {
        any = true;
        let source = profile.sources.len();
        profile.sources.push(Source {
            name: format!("{name}!{PROJECT}"),
            text,
        });
        json_file(profile, source, None, false);
    }
    if let Some(text) = entry(&mut archive, MODEL)? {
        any = true;
        let source = profile.sources.len();
        profile.sources.push(Source {
            name: format!("{name}!{MODEL}"),
            text,
        });
        model_settings(profile, source)?;
    }
    // Parts are collected before their object ends: back to document order.
    profile
        .templates
        .sort_by_key(|f| (f.source, f.span_in_source(crate::Span::new(0, 0)).start));
    if !any {
        return Err(format!(
            "a zip archive without {PROJECT} or {MODEL}: not an OrcaSlicer project"
        ));
    }
    Ok(())
}

/// The number of entries the archive's end-of-central-directory record (or its zip64
/// record) declares, which is what the zip reader will read; `None` when there is no such
/// record (the zip reader then reports the archive).
fn entry_count(bytes: &[u8]) -> Option<u64> {
    const EOCD: &[u8] = b"PK\x05\x06";
    const LOCATOR: &[u8] = b"PK\x06\x07";
    const EOCD64: &[u8] = b"PK\x06\x06";
    let u16_at = |at: usize| Some(u16::from_le_bytes(bytes.get(at..at + 2)?.try_into().ok()?));
    let u32_at = |at: usize| Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    let u64_at = |at: usize| Some(u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?));
    // The record is 22 bytes plus a comment of at most 65535, at the end of the file.
    let last = bytes.len().checked_sub(22)?;
    let eocd = (last.saturating_sub(65535)..=last)
        .rev()
        .find(|&at| bytes[at..].starts_with(EOCD))?;
    let count = u16_at(eocd + 10)?;
    let (size, offset) = (u32_at(eocd + 12)?, u32_at(eocd + 16)?);
    if count != u16::MAX && size != u32::MAX && offset != u32::MAX {
        return Some(u64::from(count));
    }
    // Zip64: the locator sits right before the record and points at the zip64 record.
    let locator = eocd.checked_sub(20)?;
    if !bytes[locator..].starts_with(LOCATOR) {
        return Some(u64::from(count));
    }
    let at = usize::try_from(u64_at(locator + 8)?).ok()?;
    if !bytes.get(at..)?.starts_with(EOCD64) {
        return None;
    }
    u64_at(at + 32)
}

/// The text of entry `path`, `None` if the archive has none; inflation is capped.
fn entry(
    archive: &mut zip::ZipArchive<Cursor<&[u8]>>,
    path: &str,
) -> Result<Option<String>, String> {
    let file = match archive.by_name(path) {
        Ok(f) => f,
        Err(zip::result::ZipError::FileNotFound) => return Ok(None),
        Err(e) => return Err(format!("{path}: cannot read the entry: {e}")),
    };
    if file.size() > MAX_ENTRY_BYTES {
        return Err(format!(
            "{path}: claims {} bytes once inflated, more than the {} MiB a settings file can be",
            file.size(),
            MAX_ENTRY_BYTES >> 20
        ));
    }
    let mut bytes = Vec::new();
    // The header may lie: the cap holds whatever it says.
    file.take(MAX_ENTRY_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("{path}: corrupt or truncated entry: {e}"))?;
    if bytes.len() as u64 > MAX_ENTRY_BYTES {
        return Err(format!(
            "{path}: inflates beyond {} MiB (a zip bomb?)",
            MAX_ENTRY_BYTES >> 20
        ));
    }
    utf8(&bytes).map(Some).map_err(|e| format!("{path}: {e}"))
}

/// Where an element sits: inside an object, or a part of one.
#[derive(Default)]
struct Scope {
    /// Metadata of the current object (or part): key, value, value's contents span, map.
    entries: Vec<(String, String, Span, OffsetMap)>,
    id: Option<String>,
    /// An object's parts, read: their labels and own settings, completed from the
    /// object's once the object ends (its metadata may follow its parts).
    parts: Vec<(String, Settings)>,
}

/// `<config><object id=…><metadata key=… value=…/><part id=…><metadata …/></part></object>`.
fn model_settings(profile: &mut Profile, source: usize) -> Result<(), String> {
    use quick_xml::events::Event;
    let text = profile.sources[source].text.clone();
    let mut reader = quick_xml::Reader::from_str(&text);
    reader.config_mut().check_end_names = true;
    // object, then (inside it) a part.
    let mut object: Option<Scope> = None;
    let mut part: Option<Scope> = None;
    let mut object_name = String::new();
    // Elements opened and not yet closed, with where they start: at the end of the text
    // there must be none, or the file was cut short and what followed is lost.
    let mut open: Vec<(String, usize)> = Vec::new();
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader.read_event().map_err(|e| {
            let at = reader.error_position() as usize;
            let (line, col) = crate::diagnostic::LineIndex::new(&text).line_col(at.min(text.len()));
            format!("{MODEL}: invalid XML at {line}:{col}: {e}")
        })?;
        let end = (reader.buffer_position() as usize).min(text.len());
        if let Event::Start(e) = &event {
            let name = e.name();
            let name: &str = name.as_ref();
            open.push((name.to_owned(), start));
        } else if let Event::End(_) = &event {
            open.pop();
        }
        match event {
            Event::Eof => break,
            Event::Start(e) | Event::Empty(e) => {
                let empty = text.as_bytes().get(end.saturating_sub(2)) == Some(&b'/');
                let name = e.local_name();
                let attrs = || attributes(&e, &text, start);
                match name.as_ref() {
                    "object" if object.is_none() => {
                        object = Some(Scope {
                            id: find(&attrs()?, "id").map(|(v, ..)| v),
                            ..Scope::default()
                        });
                        object_name.clear();
                        if empty {
                            finish_object(profile, source, object.take(), &object_name);
                        }
                    }
                    "part" if object.is_some() && part.is_none() => {
                        part = Some(Scope {
                            id: find(&attrs()?, "id").map(|(v, ..)| v),
                            ..Scope::default()
                        });
                        if empty {
                            part = None;
                        }
                    }
                    "metadata" if object.is_some() => {
                        let attrs = attrs()?;
                        if let (Some((key, ..)), Some((value, span, map))) =
                            (find(&attrs, "key"), find(&attrs, "value"))
                        {
                            if let Some(p) = part.as_mut() {
                                p.entries.push((key, value, span, map));
                            } else if let Some(o) = object.as_mut() {
                                if key == "name" {
                                    object_name = value.clone();
                                }
                                o.entries.push((key, value, span, map));
                            }
                        }
                    }
                    _ => {}
                }
            }
            Event::End(e) => match e.local_name().as_ref() {
                "part" if part.is_some() => {
                    let p = part.take().unwrap_or_default();
                    let part_name = p
                        .entries
                        .iter()
                        .find(|(k, ..)| k == "name")
                        .map(|(_, v, ..)| v.clone())
                        .or(p.id.clone())
                        .unwrap_or_default();
                    let owner = object_label(object.as_ref(), &object_name);
                    let label = format!("{owner} / part {part_name}");
                    let settings = collect(profile, source, p, &label);
                    if let Some(o) = object.as_mut() {
                        o.parts.push((label, settings));
                    }
                }
                "object" if object.is_some() => {
                    finish_object(profile, source, object.take(), &object_name);
                }
                _ => {}
            },
            _ => {}
        }
    }
    if let Some((name, at)) = open.last() {
        return Err(truncated(
            &text,
            &open,
            name,
            *at,
            object.as_ref(),
            &object_name,
        ));
    }
    Ok(())
}

/// The error for a model settings text that ends inside elements: which element is cut
/// off, where it began, and what its loss means (an object's overrides are not read).
fn truncated(
    text: &str,
    open: &[(String, usize)],
    name: &str,
    at: usize,
    object: Option<&Scope>,
    object_name: &str,
) -> String {
    let index = crate::diagnostic::LineIndex::new(text);
    let (line, column) = index.line_col(at.min(text.len()));
    let unclosed: Vec<String> = open.iter().rev().map(|(n, _)| format!("</{n}>")).collect();
    let lost = match object {
        Some(o) => format!(
            "the settings of object {} (and of every object after it) are lost",
            object_label(Some(o), object_name)
        ),
        None => "what followed it is lost".to_owned(),
    };
    format!(
        "{MODEL}: truncated: the text ends before {} (`<{name}>` opened at {line}:{column} is \
         never closed); {lost}: the project cannot be read as it was saved",
        unclosed.join(", ")
    )
}

fn object_label(object: Option<&Scope>, name: &str) -> String {
    match (name, object.and_then(|o| o.id.as_deref())) {
        ("", Some(id)) => format!("#{id}"),
        ("", None) => "(unnamed)".to_owned(),
        (n, _) => n.to_owned(),
    }
}

/// A part inherits every model key it does not set from its object, which inherits from
/// the project (`Profile::model`): part → object → project, as OrcaSlicer resolves them.
fn finish_object(profile: &mut Profile, source: usize, object: Option<Scope>, name: &str) {
    if let Some(mut o) = object {
        let label = object_label(Some(&o), name);
        let parts = std::mem::take(&mut o.parts);
        let settings = collect(profile, source, o, &label);
        for (part, mut own) in parts {
            own.merge_missing(settings.clone());
            if !own.values.is_empty() {
                profile.objects.push((part, own));
            }
        }
        if !settings.values.is_empty() {
            profile.objects.push((label, settings));
        }
    }
}

/// The templates and model settings of one object (or part); the settings are returned.
fn collect(profile: &mut Profile, source: usize, scope: Scope, label: &str) -> Settings {
    let mut settings = Settings::default();
    let later = super::superseded(
        scope
            .entries
            .iter()
            .map(|(k, _, span, _)| (k.as_str(), *span)),
    );
    // The text is needed (for line numbers) only when a key repeats: not copied per object.
    let text = if later.iter().any(Option::is_some) {
        profile.sources[source].text.clone()
    } else {
        String::new()
    };
    let mut duplicates = super::Duplicates::new(&text);
    for ((key, value, span, map), later) in scope.entries.into_iter().zip(later) {
        if let Some(used) = later {
            let note = duplicates.note(source, &key, span, used);
            profile.notes.push(note);
            continue;
        }
        if let Some(&(_, target)) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == key) {
            profile.templates.push(Found {
                key: Some(key),
                object: Some(label.to_owned()),
                target,
                text: value,
                source,
                map,
            });
        } else if super::MODEL_KEYS.contains(&key.as_str())
            || super::INFILL_KEYS.contains(&key.as_str())
        {
            settings.set(&key, value, source, span);
        }
    }
    settings
}

/// One attribute of a tag: its name, its value unescaped, the span of the raw value in
/// the document and the map from the value to the document.
type Attr = (String, String, Span, OffsetMap);

/// The attributes of a tag, read by quick-xml (quoting, `=`, duplicates checked), each value
/// unescaped (`&quot;`, `&amp;`, `&#x2B;`, …) with its place in `text`. `at` is the tag's
/// offset, for the error's line and column.
fn attributes(
    tag: &quick_xml::events::BytesStart<'_>,
    text: &str,
    at: usize,
) -> Result<Vec<Attr>, String> {
    let mut out = Vec::new();
    for attr in tag.attributes().with_checks(true) {
        let attr = attr.map_err(|e| {
            let (line, col) = crate::diagnostic::LineIndex::new(text).line_col(at.min(text.len()));
            format!("{MODEL}: invalid XML attribute in the tag at {line}:{col}: {e}")
        })?;
        let key: &str = attr.key.as_ref();
        // The raw value is borrowed from `text` (the reader reads from the string): its
        // place is where it points.
        let raw: &str = &attr.value;
        let offset = (raw.as_ptr() as usize).wrapping_sub(text.as_ptr() as usize);
        if text.get(offset..offset + raw.len()) != Some(raw) {
            return Err(format!("{MODEL}: cannot place the attribute `{key}`"));
        }
        let (value, map) = unescape_xml(raw, offset);
        out.push((
            key.to_owned(),
            value,
            Span::new(offset, offset + raw.len()),
            map,
        ));
    }
    Ok(out)
}

/// The value of attribute `name`: unescaped, its raw span, its map.
fn find(attrs: &[Attr], name: &str) -> Option<(String, Span, OffsetMap)> {
    attrs
        .iter()
        .find(|(k, ..)| k == name)
        .map(|(_, v, span, map)| (v.clone(), *span, map.clone()))
}

/// XML entities (`&amp;` `&lt;` `&gt;` `&quot;` `&apos;` `&#N;` `&#xH;`) decoded, with the
/// map from the text to the raw value (which starts at `doc` in the tag). An unknown or
/// malformed entity stays as written.
pub(super) fn unescape_xml(raw: &str, doc: usize) -> (String, OffsetMap) {
    let mut text = String::with_capacity(raw.len());
    let mut map = OffsetMap::starting_at(doc);
    let mut run = 0;
    let mut i = 0;
    while let Some(at) = raw[i..].find('&') {
        let amp = i + at;
        let Some(semi) = raw[amp..].find(';').map(|s| amp + s) else {
            break;
        };
        let entity = &raw[amp + 1..semi];
        let decoded = match entity {
            "amp" => Some('&'),
            "lt" => Some('<'),
            "gt" => Some('>'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            _ => entity
                .strip_prefix("#x")
                .or_else(|| entity.strip_prefix("#X"))
                .map(|h| u32::from_str_radix(h, 16))
                .or_else(|| entity.strip_prefix('#').map(str::parse::<u32>))
                .and_then(Result::ok)
                .and_then(char::from_u32),
        };
        match decoded {
            Some(c) => {
                map.push_verbatim(text.len(), doc + run, amp - run);
                text.push_str(&raw[run..amp]);
                map.push_escape(text.len(), c.len_utf8(), doc + amp, semi + 1 - amp);
                text.push(c);
                run = semi + 1;
                i = semi + 1;
            }
            None => i = amp + 1,
        }
    }
    map.push_verbatim(text.len(), doc + run, raw.len() - run);
    text.push_str(&raw[run..]);
    (text, map)
}

/// Whether a 3MF holds OrcaSlicer's settings (`Metadata/*.config`): a project, whose
/// settings `rotlang preview project.3mf` takes, not only a mesh.
pub fn is_project(bytes: &[u8]) -> bool {
    let Ok(archive) = zip::ZipArchive::new(std::io::Cursor::new(bytes)) else {
        return false;
    };
    archive
        .file_names()
        .any(|n| n == "Metadata/project_settings.config" || n == "Metadata/model_settings.config")
}
