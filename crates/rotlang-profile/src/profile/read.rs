//! Reading a file into a [`Profile`]: its kind, its bytes (bounded), the reader of its
//! format, and a preset's parents. The data and the helpers the format readers share live
//! in `mod.rs`; this module calls the readers, none of them calls it.

use std::io::Read;
use std::path::Path;

use super::settings::Settings;
#[cfg(feature = "3mf")]
use super::threemf;
use super::{
    Kind, MAX_FILE_BYTES, Profile, ProfileError, Source, error, ini, json_file, template_file, utf8,
};

/// How deep `inherits` chains are followed (OrcaSlicer's own are 2–4 deep).
const MAX_INHERITS: usize = 16;

impl Kind {
    /// By content first where it is unambiguous (a zip, a JSON object), then extension,
    /// then `key = value` lines; anything else is a template.
    pub fn detect(path: &Path, bytes: &[u8]) -> Kind {
        if bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06") {
            return Kind::ThreeMf;
        }
        let body = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        let first = body.iter().find(|b| !b.is_ascii_whitespace());
        if let Some(kind) = Kind::from_extension(path) {
            return kind;
        }
        if first == Some(&b'{') {
            return Kind::Json;
        }
        if ini::looks_like_ini(body) {
            return Kind::Ini;
        }
        Kind::Template
    }
}

impl Profile {
    /// For a JSON preset with `inherits`: the model keys it lacks, taken from its parent
    /// presets beside [`Profile::path`] (`<inherits>.json` in the same folder, recursively),
    /// as [`read`] does. For a text read some other way (an editor's buffer), set `path` to
    /// the file's place first, so that its parents are found as the CLI finds them.
    pub fn resolve_inherits(&mut self) {
        if self.kind == Some(Kind::Json) {
            resolve_inherits(&mut self.settings, &self.path);
        }
    }
}

/// Reads a file (at most [`MAX_FILE_BYTES`]) and what it holds; for a JSON preset with
/// `inherits`, missing model keys are looked up in the parent preset beside it
/// (`<inherits>.json` in the same folder), recursively.
pub fn read(path: &Path) -> Result<Profile, ProfileError> {
    read_with_bytes(path).map(|(profile, _)| profile)
}

/// [`read`], with the bytes read (what a rewrite of the file edits, and compares the file
/// with before writing).
pub fn read_with_bytes(path: &Path) -> Result<(Profile, Vec<u8>), ProfileError> {
    let bytes = read_bounded(path)?;
    let mut profile = parse(path, &bytes)?;
    profile.resolve_inherits();
    Ok((profile, bytes))
}

fn read_bounded(path: &Path) -> Result<Vec<u8>, ProfileError> {
    let file = std::fs::File::open(path).map_err(|e| error(path, format!("cannot read: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| error(path, format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(error(
            path,
            format!(
                "larger than {} MiB: not a profile or project",
                MAX_FILE_BYTES >> 20
            ),
        ));
    }
    Ok(bytes)
}

/// What `bytes` (the content of `path`) holds, without touching the file system.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<Profile, ProfileError> {
    let kind = Kind::detect(path, bytes);
    let name = path.display().to_string();
    let mut profile = Profile {
        path: path.to_owned(),
        kind: Some(kind),
        ..Profile::default()
    };
    match kind {
        Kind::ThreeMf => {
            #[cfg(feature = "3mf")]
            threemf::read(&name, bytes, &mut profile).map_err(|m| error(path, m))?;
            #[cfg(not(feature = "3mf"))]
            return Err(error(
                path,
                "a 3mf project: this build of rotlang reads them only with the `3mf` feature",
            ));
        }
        Kind::Template | Kind::Json | Kind::Ini => {
            let text = utf8(bytes).map_err(|m| error(path, m))?;
            profile.sources.push(Source { name, text });
            match kind {
                Kind::Template => template_file(&mut profile),
                Kind::Json => {
                    let jsonc = path
                        .extension()
                        .is_some_and(|e| e.eq_ignore_ascii_case("jsonc"));
                    json_file(&mut profile, 0, None, jsonc)
                }
                _ => ini::read(&mut profile),
            }
        }
    }
    Ok(profile)
}

/// Fills the keys `settings` lacks from its parent presets: `<inherits>.json` in the
/// folder of `path` (OrcaSlicer's own preset folders are laid out so), then its parent.
fn resolve_inherits(settings: &mut Settings, path: &Path) {
    let Some(dir) = path.parent() else { return };
    let mut seen = vec![path.to_owned()];
    let mut parent = settings.inherits().map(str::to_owned);
    while let Some(name) = parent.take() {
        if seen.len() > MAX_INHERITS || name.contains(['/', '\\']) {
            break;
        }
        let file = dir.join(format!("{name}.json"));
        if seen.contains(&file) || !file.is_file() {
            break;
        }
        seen.push(file.clone());
        let Ok(profile) = read_bounded(&file).and_then(|b| parse(&file, &b)) else {
            break;
        };
        parent = profile.settings.inherits().map(str::to_owned);
        for (key, mut setting) in profile.settings.values {
            if key == "inherits" {
                continue;
            }
            setting.inherited_from = Some(file.clone());
            settings.values.entry(key).or_insert(setting);
        }
    }
    // Resolved: the note about a missing parent no longer applies.
    if seen.len() > 1 {
        settings.values.remove("inherits");
    }
}
