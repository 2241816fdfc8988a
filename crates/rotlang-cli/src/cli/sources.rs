//! The texts under a report, for codespan-reporting: whole inputs, or excerpts of long
//! lines that keep the file's line and column numbers.

use std::ops::Range;

use codespan_reporting::files::{Error, Files};

struct Source {
    name: String,
    /// The text as shown: invisible characters made visible, byte for byte.
    text: String,
    /// The text itself, when it differs from `text`: columns count its characters.
    original: Option<String>,
    line_starts: Vec<usize>,
    /// Lines before the text starts, in the input it comes from.
    lines_before: usize,
    /// Characters before the text starts on its first line.
    columns_before: usize,
}

#[derive(Default)]
pub(super) struct Sources {
    list: Vec<Source>,
}

impl Sources {
    /// Adds a text starting `at` = (lines, characters) into its input; returns its id.
    pub fn add(&mut self, name: String, original: &str, at: (usize, usize)) -> usize {
        let mut text = visible(original);
        // A lone `\r` ends a line (as in editors): shown as `\n`, byte for byte, so the
        // report draws two lines instead of sending the terminal's cursor back.
        if text.contains('\r') {
            let bytes = text.as_bytes();
            let ends: Vec<usize> = (0..bytes.len())
                .filter(|&i| bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n'))
                .collect();
            let mut owned = text.into_bytes();
            for i in ends {
                owned[i] = b'\n';
            }
            text = String::from_utf8(owned).expect("one ASCII byte replaced by another");
        }
        let original = (text != original).then(|| original.to_owned());
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        self.list.push(Source {
            name,
            text,
            original,
            line_starts,
            lines_before: at.0,
            columns_before: at.1,
        });
        self.list.len() - 1
    }

    fn get(&self, id: usize) -> Result<&Source, Error> {
        self.list.get(id).ok_or(Error::FileMissing)
    }
}

impl<'a> Files<'a> for Sources {
    type FileId = usize;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: usize) -> Result<&'a str, Error> {
        Ok(&self.get(id)?.name)
    }

    fn source(&'a self, id: usize) -> Result<&'a str, Error> {
        Ok(&self.get(id)?.text)
    }

    fn line_index(&'a self, id: usize, byte_index: usize) -> Result<usize, Error> {
        Ok(self
            .get(id)?
            .line_starts
            .partition_point(|&s| s <= byte_index)
            - 1)
    }

    fn line_number(&'a self, id: usize, line_index: usize) -> Result<usize, Error> {
        Ok(self.get(id)?.lines_before + line_index + 1)
    }

    fn column_number(
        &'a self,
        id: usize,
        line_index: usize,
        byte_index: usize,
    ) -> Result<usize, Error> {
        let source = self.get(id)?;
        let range = self.line_range(id, line_index)?;
        let text = source.original.as_deref().unwrap_or(&source.text);
        let column = codespan_reporting::files::column_index(text, range, byte_index);
        let before = if line_index == 0 {
            source.columns_before
        } else {
            0
        };
        Ok(before + column + 1)
    }

    fn line_range(&'a self, id: usize, line_index: usize) -> Result<Range<usize>, Error> {
        let source = self.get(id)?;
        let start = *source
            .line_starts
            .get(line_index)
            .ok_or(Error::LineTooLarge {
                given: line_index,
                max: source.line_starts.len() - 1,
            })?;
        let end = source
            .line_starts
            .get(line_index + 1)
            .copied()
            .unwrap_or(source.text.len());
        Ok(start..end)
    }
}

/// The text as shown under a diagnostic: control characters (a NUL, an escape) would be
/// invisible or would drive the terminal, and zero-width ones invisible, so each becomes
/// `?`s of the same byte length.
fn visible(text: &str) -> String {
    // Zero-width characters (a byte-order mark, a zero-width space) would leave the caret
    // under nothing.
    let hidden = |c: char| {
        (c.is_control() && !matches!(c, '\n' | '\t' | '\r'))
            || matches!(c, '\u{feff}' | '\u{200b}'..='\u{200f}' | '\u{2060}')
    };
    if !text.contains(hidden) {
        return text.to_owned();
    }
    text.chars()
        .map(|c| {
            if hidden(c) {
                "?".repeat(c.len_utf8())
            } else {
                c.to_string()
            }
        })
        .collect()
}
