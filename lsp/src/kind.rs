//! What kind of file a document is (a leaf: the document reads its templates by it, the
//! settings decide by it whether OrcaSlicer's reading applies). Public as
//! `crate::document::Kind`.

/// What kind of file a document is: decides where its templates are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A `.rot` file: the whole text is one sparse template; newlines separate.
    Rot,
    /// A JSON slicer profile: templates are the values of the template keys.
    Json,
    /// JSON with comments and trailing commas (`.jsonc`): read as JSON once they are
    /// blanked out (OrcaSlicer itself reads plain JSON only, so `.json` keeps reporting them).
    Jsonc,
    /// An `.ini` config export: `key = value` lines.
    Ini,
}

impl Kind {
    /// From the file extension, else from the client's `languageId`. The extension comes
    /// first: clients such as eglot send one `languageId` for every file a server handles,
    /// so it cannot tell a profile from a template. `None` for documents that are neither
    /// (a client that sends every plain-text file gets no diagnostics on them), and for
    /// `.3mf` projects, which are zip archives, not text.
    pub fn detect(language_id: &str, uri: &str) -> Option<Kind> {
        let path = uri.split(['?', '#']).next().unwrap_or(uri);
        let name = path.rsplit('/').next().unwrap_or(path);
        let extension = name
            .rsplit_once('.')
            .map(|(_, e)| e.to_ascii_lowercase())
            .unwrap_or_default();
        match extension.as_str() {
            "rot" => return Some(Kind::Rot),
            "json" => return Some(Kind::Json),
            "jsonc" => return Some(Kind::Jsonc),
            "ini" => return Some(Kind::Ini),
            "3mf" => return None,
            _ => {}
        }
        match language_id {
            "rotlang" | "rot" => Some(Kind::Rot),
            "json" => Some(Kind::Json),
            "jsonc" => Some(Kind::Jsonc),
            "ini" => Some(Kind::Ini),
            _ => None,
        }
    }
}
