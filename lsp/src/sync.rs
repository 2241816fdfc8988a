//! Document synchronisation: the latest text of every open document, the edits applied to
//! it, and what happens when an edit cannot be applied.
//!
//! The server announces full sync, so clients send the whole text on every change; ranged
//! changes are applied too, for clients that send them anyway. An edit that cannot be
//! applied (a reversed range, a range outside the document, or one the server cannot even
//! read, such as a negative position) is never guessed at: the document is marked out of
//! sync, the error is logged (`window/logMessage`) and shown as one diagnostic at its start,
//! requests on it answer null, and later ranged edits are ignored, until the client sends
//! the whole text again (any full-sync edit, or closing and reopening the file). The last
//! good text is kept meanwhile; nothing is applied to it that the client did not mean.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicI32;

use rotlang::Span;
use tower_lsp_server::ls_types::{Range, TextDocumentContentChangeEvent};

use crate::document::{Document, Kind};
use crate::position::{Encoding, Positions};

/// The code of the diagnostic shown while a document is out of sync.
pub const OUT_OF_SYNC: &str = "rotlang-lsp::out-of-sync";

/// An open document.
#[derive(Debug)]
pub struct Open {
    pub kind: Kind,
    /// The version of `text`: the client's latest.
    pub version: i32,
    /// The client's latest text; `None` when it was over the size limit (not kept).
    pub text: Option<Arc<String>>,
    /// The file's place, where a preset's `inherits` parents are found.
    pub path: Option<PathBuf>,
    /// The latest analysis; its version may trail `version` while the next is computed.
    pub analysed: Option<Arc<Document>>,
    /// An analysis task runs for this document (it picks up the latest text when done).
    pub busy: bool,
    /// A publishing task runs for this document (it picks up the latest analysis).
    pub publishing: bool,
    /// The version and settings whose diagnostics were last published (or found stale).
    pub published: Option<(i32, crate::settings::ModelSettings)>,
    /// Why the text is no longer the client's, if an edit could not be applied.
    pub out_of_sync: Option<String>,
    /// `version`, readable by an analysis in progress without the server's lock: work for
    /// the latest text only (previews) is skipped once a newer text has come.
    pub latest: Arc<AtomicI32>,
}

impl Open {
    pub fn new(kind: Kind, version: i32, text: String, path: Option<PathBuf>) -> Open {
        Open {
            kind,
            version,
            text: Some(Arc::new(text)),
            path,
            analysed: None,
            busy: false,
            publishing: false,
            published: None,
            out_of_sync: None,
            latest: Arc::new(AtomicI32::new(version)),
        }
    }

    /// The analysis of the latest version, if it is done and the document is in sync.
    pub fn current(&self) -> Option<&Arc<Document>> {
        self.analysed
            .as_ref()
            .filter(|d| d.version == self.version && self.out_of_sync.is_none())
    }
}

/// What applying one `didChange` gave.
#[derive(Debug, PartialEq)]
pub enum Applied {
    /// The new text.
    Text(String),
    /// An edit could not be applied: why (the text is unchanged).
    Rejected(String),
    /// Nothing to apply (no changes, or only ranged ones while out of sync).
    Nothing,
}

/// Apply the changes of one `didChange` to `text` (`None`: not kept, or out of sync, so
/// only a full text can be applied).
pub fn apply(
    text: Option<&str>,
    changes: Vec<TextDocumentContentChangeEvent>,
    encoding: Encoding,
) -> Applied {
    let mut current: Option<String> = None;
    for (i, change) in changes.into_iter().enumerate() {
        match change.range {
            None => current = Some(change.text),
            Some(range) => {
                let Some(base) = current.as_deref().or(text) else {
                    // Out of sync: only the whole text helps.
                    continue;
                };
                let span = match edit_span(base, range, encoding) {
                    Ok(span) => span,
                    Err(why) => return Applied::Rejected(format!("change {}: {why}", i + 1)),
                };
                let mut next = match current.take() {
                    Some(next) => next,
                    None => text.unwrap_or_default().to_owned(),
                };
                next.replace_range(span.range(), &change.text);
                current = Some(next);
            }
        }
    }
    current.map_or(Applied::Nothing, Applied::Text)
}

/// The bytes a ranged edit replaces, or why it cannot be applied: a range that ends before
/// it starts, or starts or ends on a line the document does not have. (A column past the
/// end of its line is the line's end, as the protocol says.)
pub fn edit_span(text: &str, range: Range, encoding: Encoding) -> Result<Span, String> {
    let (start, end) = (range.start, range.end);
    if (end.line, end.character) < (start.line, start.character) {
        return Err(format!(
            "the range ends ({}:{}) before it starts ({}:{})",
            end.line, end.character, start.line, start.character
        ));
    }
    let pos = Positions::new(text, encoding);
    let offset = |p| {
        pos.offset(p).ok_or_else(|| {
            format!(
                "line {} is past the end of the document, which has {} lines",
                p.line,
                pos.line_count()
            )
        })
    };
    // The position just after the last line (some clients end a whole-document range
    // there) is the end of the text.
    let after_last = |p: tower_lsp_server::ls_types::Position| {
        p.line as usize == pos.line_count() && p.character == 0
    };
    let a = if after_last(start) {
        text.len()
    } else {
        offset(start)?
    };
    let b = if after_last(end) {
        text.len()
    } else {
        offset(end)?
    };
    // Columns past their lines' ends can still meet in reverse order on one line.
    Ok(Span::new(a, b.max(a)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tower_lsp_server::ls_types::Position;

    fn ranged(l0: u32, c0: u32, l1: u32, c1: u32, text: &str) -> TextDocumentContentChangeEvent {
        TextDocumentContentChangeEvent {
            range: Some(Range::new(Position::new(l0, c0), Position::new(l1, c1))),
            range_length: None,
            text: text.into(),
        }
    }

    #[test]
    fn ranged_edits_apply_in_order_and_bad_ones_are_rejected() {
        let e = Encoding::Utf16;
        assert_eq!(
            apply(
                Some("0, 90"),
                vec![ranged(0, 3, 0, 5, "45"), ranged(0, 0, 0, 1, "10")],
                e
            ),
            Applied::Text("10, 45".into())
        );
        let reversed = apply(Some("0, 90"), vec![ranged(0, 4, 0, 1, "x")], e);
        assert!(
            matches!(reversed, Applied::Rejected(ref why) if why.contains("before it starts")),
            "{reversed:?}"
        );
        let past = apply(Some("0, 90"), vec![ranged(3, 0, 3, 0, "x")], e);
        assert!(
            matches!(past, Applied::Rejected(ref why) if why.contains("line 3")),
            "{past:?}"
        );
        // Out of sync: ranged edits wait for the whole text.
        assert_eq!(
            apply(None, vec![ranged(0, 0, 0, 0, "x")], e),
            Applied::Nothing
        );
        let full = TextDocumentContentChangeEvent {
            range: None,
            range_length: None,
            text: "30".into(),
        };
        assert_eq!(
            apply(None, vec![full, ranged(0, 2, 0, 2, "!")], e),
            Applied::Text("30!".into())
        );
    }
}
