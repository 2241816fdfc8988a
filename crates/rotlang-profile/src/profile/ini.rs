//! `key = value` configs, as OrcaSlicer and PrusaSlicer export them: one setting per line
//! (lines end at `\n`, `\r\n` or `\r`), `#`/`;` comments and `[section]` headers skipped
//! (they hold no key we look for), values taken as written to the end of the line (no
//! escapes). Shared by the CLI and the language server.

use super::json::{JsonTemplate, OffsetMap};
use super::{Found, Profile, Settings, TEMPLATE_KEYS};
use crate::Span;

/// Whether most non-comment lines look like `key = value` (for files without extension).
pub(super) fn looks_like_ini(bytes: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return false;
    };
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with(['#', ';', '[']));
    let Some(first) = lines.next() else {
        return false;
    };
    std::iter::once(first).chain(lines).take(20).all(|l| {
        l.split_once('=').is_some_and(|(k, _)| {
            let k = k.trim();
            !k.is_empty() && k.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        })
    })
}

/// One `key = value` line: the key and the value (trimmed of spaces and tabs), with spans.
struct Line<'a> {
    key: &'a str,
    key_span: Span,
    value: &'a str,
    value_span: Span,
}

fn settings(doc: &str) -> impl Iterator<Item = Line<'_>> {
    let mut start = 0;
    doc.split_inclusive(['\n', '\r']).filter_map(move |raw| {
        let mut line_start = start;
        start += raw.len();
        let mut line = raw.trim_end_matches(['\n', '\r']);
        if line_start == 0
            && let Some(rest) = line.strip_prefix('\u{feff}')
        {
            line = rest;
            line_start += 3;
        }
        let eq = line.find('=')?;
        let key = line[..eq].trim();
        let key_start = line_start + line.find(key).unwrap_or(0);
        let value = &line[eq + 1..];
        let lead = value.len() - value.trim_start_matches([' ', '\t']).len();
        let text = value[lead..].trim_end_matches([' ', '\t']);
        let value_start = line_start + eq + 1 + lead;
        Some(Line {
            key,
            key_span: Span::new(key_start, key_start + key.len()),
            value: text,
            value_span: Span::new(value_start, value_start + text.len()),
        })
    })
}

/// Every template line of an `.ini` document, with the key's span and the value's map.
pub fn find_templates(doc: &str) -> Vec<JsonTemplate> {
    settings(doc)
        .filter_map(|l| {
            let &(_, target) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == l.key)?;
            Some(JsonTemplate {
                key: l.key.to_owned(),
                key_span: l.key_span,
                target,
                text: l.value.to_owned(),
                contents: l.value_span,
                map: OffsetMap::verbatim(l.value_span.start, l.value.len()),
            })
        })
        .collect()
}

pub(super) fn read(profile: &mut Profile) {
    let text = profile.sources[0].text.clone();
    let mut settings_found = Settings::default();
    // Only the keys looked for: a long export's other lines need no duplicate check.
    let lines: Vec<Line<'_>> = settings(&text)
        .filter(|l| {
            TEMPLATE_KEYS.iter().any(|(k, _)| *k == l.key) || super::settings::is_setting(l.key)
        })
        .collect();
    let later = super::superseded(lines.iter().map(|l| (l.key, l.key_span)));
    let mut duplicates = super::Duplicates::new(&text);
    for (l, later) in lines.into_iter().zip(later) {
        if let Some(used) = later {
            let note = duplicates.note(0, l.key, l.key_span, used);
            profile.notes.push(note);
            continue;
        }
        if let Some(&(_, target)) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == l.key) {
            profile.templates.push(Found {
                key: Some(l.key.to_owned()),
                object: None,
                target,
                text: l.value.to_owned(),
                source: 0,
                map: OffsetMap::verbatim(l.value_span.start, l.value.len()),
            });
        } else if super::settings::is_setting(l.key) {
            settings_found.set(l.key, l.value.to_owned(), 0, l.value_span);
        }
    }
    profile.settings.merge_missing(settings_found);
}
