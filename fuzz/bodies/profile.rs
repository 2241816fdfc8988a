//! Fuzz target `profile`: any bytes as a profile (`rotlang_profile::profile::parse`) under one of
//! the names the first byte chooses (`.json`, `.jsonc`, `.ini`, `.3mf`, `.rot`, none): an
//! error or a profile whose templates map inside their source texts, and whose model can
//! always be built; a repeated key keeps one value (the others are warnings, not errors),
//! and the template a command takes is one of the templates found.

use std::path::Path;

use rotlang::Span;
use rotlang::Target;

pub fn run(data: &[u8]) {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let name = ["p.json", "p.jsonc", "p.ini", "p.3mf", "p.rot", "p"][usize::from(first % 6)];
    let Ok(profile) = rotlang_profile::profile::parse(Path::new(name), rest) else {
        return;
    };
    for found in &profile.templates {
        let text = &profile.sources[found.source].text;
        for (a, b) in [
            (0, found.text.len()),
            (0, 0),
            (found.text.len(), found.text.len()),
        ] {
            let span = found.span_in_source(Span::new(a, b));
            assert!(
                text.get(span.range()).is_some(),
                "{span:?} in {}",
                text.len()
            );
        }
        let m = profile.model(found.target, found.object.as_deref(), 20.0);
        assert!(!m.model.is_empty() && m.options(&found.text).base.is_finite());
    }
    for note in &profile.notes {
        let text = &profile.sources[note.source].text;
        assert!(text.get(note.span.range()).is_some(), "{note:?}");
    }
    let _ = profile.model(Target::Solid, None, 20.0);
    for note in profile
        .notes
        .iter()
        .filter(|n| n.message.contains("is set again"))
    {
        assert!(!note.error, "{note:?}");
    }
    // Outside a per-extruder array, one value per key: the last (as OrcaSlicer keeps).
    if profile.kind == Some(rotlang_profile::profile::Kind::Ini) {
        let mut keys: Vec<&str> = profile
            .templates
            .iter()
            .filter_map(|f| f.key.as_deref())
            .collect();
        let all = keys.len();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), all, "a repeated .ini key kept twice");
    }
    for target in [Target::Sparse, Target::Solid] {
        if let Ok(found) = profile.template(target) {
            assert!(profile.templates.iter().any(|f| std::ptr::eq(f, found)));
        }
    }
}
