//! `key = value` configs, as OrcaSlicer and PrusaSlicer export them: one setting per line,
//! `#` or `;` comment lines, values taken as written (no escapes), CRLF tolerated.

use super::{Found, MODEL_KEYS, OffsetMap, Profile, Settings, TEMPLATE_KEYS};
use crate::Span;

/// Whether most non-comment lines look like `key = value` (for files without extension).
pub(super) fn looks_like_ini(bytes: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return false;
    };
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with(['#', ';']));
    let Some(first) = lines.next() else {
        return false;
    };
    std::iter::once(first)
        .chain(lines)
        .take(20)
        .all(|l| setting(l).is_some())
}

/// `key = value`: the key and the value's byte range within the line.
fn setting(line: &str) -> Option<(&str, usize, usize)> {
    let eq = line.find('=')?;
    let key = line[..eq].trim();
    if key.is_empty() || !key.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
        return None;
    }
    let rest = &line[eq + 1..];
    let lead = rest.len() - rest.trim_start().len();
    let value = rest.trim();
    let start = eq + 1 + lead;
    Some((key, start, start + value.len()))
}

pub(super) fn read(profile: &mut Profile) {
    let text = profile.sources[0].text.clone();
    let mut settings = Settings::default();
    let mut offset = 0;
    for raw in text.split_inclusive('\n') {
        let line_start = offset;
        offset += raw.len();
        let mut line = raw.strip_suffix('\n').unwrap_or(raw);
        line = line.strip_suffix('\r').unwrap_or(line);
        // A byte-order mark before the first key.
        let skip = if line_start == 0 && line.starts_with('\u{feff}') {
            3
        } else {
            0
        };
        let line = &line[skip..];
        let base = line_start + skip;
        let Some((key, start, end)) = setting(line) else {
            continue;
        };
        let value = &line[start..end];
        if let Some(&(_, target)) = TEMPLATE_KEYS.iter().find(|(k, _)| *k == key) {
            let mut map = OffsetMap::starting_at(base + start);
            map.push_verbatim(0, base + start, value.len());
            profile.templates.push(Found {
                key: Some(key.to_owned()),
                object: None,
                target,
                text: value.to_owned(),
                source: 0,
                map,
            });
        } else if MODEL_KEYS.contains(&key) || key == "inherits" {
            settings.set(
                key,
                value.to_owned(),
                0,
                Span::new(base + start, base + end),
            );
        }
    }
    profile.settings.merge_missing(settings);
}
