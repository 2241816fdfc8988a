//! The command-line front end: reading inputs and rendering diagnostics.
//!
//! Lives in the library (behind the `cli` feature) so integration tests and the binary
//! share one implementation; `src/main.rs` only dispatches.

pub mod args;
pub mod check;
mod check_args;
pub mod completions;
mod dialect;
pub mod expand;
pub mod explain;
pub mod export;
pub mod files;
mod fix_files;
pub mod fmt;
mod from_profile;
pub mod gcode;
pub mod model;
pub mod part;
pub mod paths;
pub mod plot;
pub mod preview;
mod sources;
mod stream;
mod write;

use std::io::{IsTerminal, Read};
use std::path::{Path, PathBuf};

use codespan_reporting::diagnostic as cs;
use codespan_reporting::term::{self, termcolor};

use crate::Target;
use crate::diagnostic::{
    BYTE_ORDER_MARK, Diagnostic, LineIndex, Severity, ceil_char_boundary, floor_char_boundary,
};

/// The largest input read (a template file or stdin). Templates are a few bytes; this
/// bounds memory on a mistaken `--file /dev/zero`.
pub const MAX_INPUT_BYTES: u64 = 16 * 1024 * 1024;

/// One template to work on, with the name reports give it.
#[derive(Clone, Debug)]
pub struct Input {
    pub name: String,
    pub text: String,
    pub path: Option<PathBuf>,
}

/// A usage error: exit code 2.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum TargetArg {
    /// `sparse_infill_rotate_template`: solid signs allowed
    #[default]
    Sparse,
    /// `solid_infill_rotate_template`: solid signs are errors
    Solid,
}

impl From<TargetArg> for Target {
    fn from(t: TargetArg) -> Target {
        match t {
            TargetArg::Sparse => Target::Sparse,
            TargetArg::Solid => Target::Solid,
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ColorArg {
    /// Colour when writing to a terminal and NO_COLOR is unset
    #[default]
    Auto,
    Always,
    Never,
}

impl ColorArg {
    /// Whether to colour output written to stdout (`stdout == true`) or stderr.
    pub fn enabled(self, stdout: bool) -> bool {
        match self {
            ColorArg::Always => true,
            ColorArg::Never => false,
            ColorArg::Auto => {
                let tty = if stdout {
                    std::io::stdout().is_terminal()
                } else {
                    std::io::stderr().is_terminal()
                };
                tty && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
            }
        }
    }
}

/// Reads a file (bounded), turning bytes that are not UTF-8 into U+FFFD so they get a
/// diagnostic instead of a crash.
pub fn read_file(path: &Path) -> Result<String, UsageError> {
    let file = std::fs::File::open(path)
        .map_err(|e| UsageError(format!("cannot read {}: {e}", path.display())))?;
    read_bounded(file, &path.display().to_string())
}

fn read_bounded(reader: impl Read, name: &str) -> Result<String, UsageError> {
    let mut bytes = Vec::new();
    reader
        .take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| UsageError(format!("cannot read {name}: {e}")))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(UsageError(format!(
            "{name} is larger than {} MiB; a template is a line of text",
            MAX_INPUT_BYTES / 1024 / 1024
        )));
    }
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// Templates from arguments, then files; stdin when there are neither. A template or a
/// file `-` is stdin (read once).
pub fn gather(templates: &[String], files: &[PathBuf]) -> Result<Vec<Input>, UsageError> {
    let mut stdin_read = false;
    let mut stdin = || -> Result<Input, UsageError> {
        if std::mem::replace(&mut stdin_read, true) {
            return Err(UsageError("`-` (stdin) can be given only once".into()));
        }
        Ok(Input {
            name: "<stdin>".into(),
            text: read_bounded(std::io::stdin().lock(), "stdin")?,
            path: None,
        })
    };
    let mut inputs = Vec::new();
    for (i, t) in templates.iter().enumerate() {
        if t == "-" {
            inputs.push(stdin()?);
            continue;
        }
        inputs.push(Input {
            name: if templates.len() == 1 {
                "<template>".into()
            } else {
                format!("<template {}>", i + 1)
            },
            text: t.clone(),
            path: None,
        });
    }
    for path in files {
        if path.as_os_str() == "-" {
            inputs.push(stdin()?);
            continue;
        }
        inputs.push(Input {
            name: path.display().to_string(),
            text: read_file(path)?,
            path: Some(path.clone()),
        });
    }
    if inputs.is_empty() {
        let stdin = std::io::stdin();
        if stdin.is_terminal() {
            return Err(UsageError(
                "no template given: pass one as an argument, with --file PATH, or on stdin".into(),
            ));
        }
        inputs.push(Input {
            name: "<stdin>".into(),
            text: read_bounded(stdin.lock(), "stdin")?,
            path: None,
        });
    }
    Ok(inputs)
}

/// Renders diagnostics of many inputs as one terminal report (codespan-reporting).
pub fn render_human(reports: &[(&Input, &[Diagnostic])], color: bool) -> String {
    let mut files = sources::Sources::default();
    let mut buffer = if color {
        termcolor::Buffer::ansi()
    } else {
        termcolor::Buffer::no_color()
    };
    let config = term::Config::default();
    for (input, diagnostics) in reports {
        // A byte-order mark is hidden by editors: shown, it would be `???` before the
        // first line. The report is of the text after it, with the spans moved.
        let unmarked;
        let moved: Vec<Diagnostic>;
        let (input, diagnostics) = match input.text.strip_prefix(BYTE_ORDER_MARK) {
            Some(rest) => {
                unmarked = Input {
                    text: rest.to_owned(),
                    ..(*input).clone()
                };
                moved = diagnostics
                    .iter()
                    .map(|d| unshifted(d, BYTE_ORDER_MARK.len()))
                    .collect();
                (&unmarked, moved.as_slice())
            }
            None => (*input, *diagnostics),
        };
        let long = input.text.lines().any(|l| l.len() > LONG_LINE);
        let index = LineIndex::new(&input.text);
        let id = if long {
            files.add(input.name.clone(), "", (0, 0))
        } else {
            files.add(input.name.clone(), &input.text, (0, 0))
        };
        for d in diagnostics.iter() {
            let (file, d) = if long {
                // A 1 MB one-line template would be printed whole under every diagnostic:
                // show a window around the diagnostic instead.
                // Line and column numbers stay the file's (`1:123`, not the excerpt's).
                let (excerpt, at, d) = excerpt(input, &index, d);
                (files.add(input.name.clone(), &excerpt, at), d)
            } else {
                (id, d.clone())
            };
            // A rendering failure (it cannot happen with spans from our parser) must not
            // lose the rest of the report; fall back to the message alone.
            if term::emit_to_write_style(&mut buffer, &config, &files, &to_codespan(file, &d))
                .is_err()
            {
                use std::io::Write;
                let _ = writeln!(buffer, "{}[{}]: {}", d.severity.as_str(), d.code, d.message);
            }
        }
    }
    String::from_utf8_lossy(buffer.as_slice()).into_owned()
}

/// Every span of `d` moved left by `by` bytes (spans inside the first `by` bytes become
/// empty spans at 0).
fn unshifted(d: &Diagnostic, by: usize) -> Diagnostic {
    let back =
        |s: crate::Span| crate::Span::new(s.start.saturating_sub(by), s.end.saturating_sub(by));
    let mut d = d.clone();
    for l in &mut d.labels {
        l.span = back(l.span);
    }
    if let Some(f) = &mut d.fix {
        f.span = back(f.span);
    }
    d
}

/// Lines longer than this are shown as a window around each diagnostic.
const LONG_LINE: usize = 400;

/// A window of the input around a diagnostic's primary label (itself cut to a few dozen
/// bytes), where it starts (lines and characters before it on its first line), and the
/// diagnostic moved into it.
fn excerpt(
    input: &Input,
    index: &LineIndex<'_>,
    d: &Diagnostic,
) -> (String, (usize, usize), Diagnostic) {
    let text = &input.text;
    let primary = d.primary_span();
    let start = floor_char_boundary(text, primary.start.saturating_sub(60));
    let end = ceil_char_boundary(text, primary.end.min(primary.start + 120) + 60);
    let clip = |s: crate::Span| {
        let (a, b) = (s.start.clamp(start, end), s.end.clamp(start, end));
        crate::Span::new(
            ceil_char_boundary(text, a) - start,
            floor_char_boundary(text, b).max(ceil_char_boundary(text, a)) - start,
        )
    };
    let mut moved = d.clone();
    // Labels outside the window are dropped; the primary one is always inside.
    moved
        .labels
        .retain(|l| l.primary || (l.span.end > start && l.span.start < end));
    for l in &mut moved.labels {
        l.span = clip(l.span);
    }
    if moved
        .fix
        .as_ref()
        .is_some_and(|f| f.span.start < start || f.span.end > end)
    {
        moved.fix = None;
    } else if let Some(f) = &mut moved.fix {
        f.span = clip(f.span);
    }
    let (line, col) = index.line_col(start);
    (text[start..end].to_owned(), (line - 1, col - 1), moved)
}

fn to_codespan(id: usize, d: &Diagnostic) -> cs::Diagnostic<usize> {
    let base = match d.severity {
        Severity::Error => cs::Diagnostic::error(),
        Severity::Warning => cs::Diagnostic::warning(),
    };
    let labels = d
        .labels
        .iter()
        .map(|l| {
            let label = if l.primary {
                cs::Label::primary(id, l.span.range())
            } else {
                cs::Label::secondary(id, l.span.range())
            };
            label.with_message(&l.message)
        })
        .collect();
    let mut notes: Vec<String> = d.help.iter().map(|h| format!("help: {h}")).collect();
    if let Some(fix) = &d.fix {
        notes.push(format!("fix: {}", fix.title));
    }
    base.with_code(d.code)
        .with_message(&d.message)
        .with_labels(labels)
        .with_notes(notes)
}

/// One diagnostic as the JSON object of `--format json`.
pub fn diagnostic_json(index: &LineIndex<'_>, d: &Diagnostic) -> serde_json::Value {
    let span = d.primary_span();
    let (line, column) = index.line_col(span.start);
    serde_json::json!({
        "code": d.code,
        "severity": d.severity.as_str(),
        "message": d.message,
        "start": span.start,
        "end": span.end,
        "line": line,
        "column": column,
        "help": d.help,
        "labels": d.labels.iter().map(|l| serde_json::json!({
            "start": l.span.start, "end": l.span.end, "message": l.message, "primary": l.primary,
        })).collect::<Vec<_>>(),
        "fix": d.fix.as_ref().map(|f| serde_json::json!({
            "title": f.title, "start": f.span.start, "end": f.span.end, "replacement": f.replacement,
        })),
    })
}

/// The JSON object of one input's diagnostics, one line of `check --format json` (and what
/// `expand --format json` prints for a template with errors).
pub fn report_json(input: &Input, parse: &crate::Parse) -> serde_json::Value {
    let index = LineIndex::new(&input.text);
    let diagnostics: Vec<_> = parse
        .diagnostics
        .iter()
        .map(|d| diagnostic_json(&index, d))
        .collect();
    serde_json::json!({
        "input": input.text, "name": input.name, "diagnostics": diagnostics,
        "errors": parse.errors, "warnings": parse.warnings, "omitted": parse.omitted,
    })
}

/// A note when template arguments look like the pieces of one template the shell split at
/// its spaces (`check 0, 90`, `check +30/50 %`): an argument ending in `,`, a lone unit, or
/// one that begins with a joint.
pub fn pieces_note(command: &str, templates: &[String]) -> Option<String> {
    pieces_note_saying(command, templates, "each is read as a template of its own")
}

/// [`pieces_note`] with what the command did with the pieces.
pub(crate) fn pieces_note_saying(
    command: &str,
    templates: &[String],
    consequence: &str,
) -> Option<String> {
    // An argument with a space or a newline in it was quoted: the user splits on purpose.
    if templates.len() < 2 || templates.iter().any(|t| t.contains(char::is_whitespace)) {
        return None;
    }
    let piece = |(i, t): (usize, &String)| {
        (i + 1 < templates.len() && t.ends_with(','))
            || ["%", "mm", "cm", "m", "'", "\"", "#"].contains(&t.as_str())
            || (i > 0
                && t.starts_with(|c: char| crate::Joint::from_symbol(c).is_some() && c != '#'))
    };
    if !templates.iter().enumerate().any(piece) {
        return None;
    }
    let quoted = shell_quote(&templates.join(" "));
    Some(format!(
        "note: the {} arguments look like the pieces of one template, split by the shell at \
         its spaces; {consequence}.\n      \
         To pass one template, quote it: rotlang {command} {quoted}\n",
        templates.len()
    ))
}

/// `arg` as a POSIX shell reads it back: as it is when it holds only characters no shell
/// treats specially, else in single quotes (a `'` inside becomes `'\''`).
pub fn shell_quote(arg: &str) -> String {
    let plain = |b: u8| b.is_ascii_alphanumeric() || b"-_./=:@%+,".contains(&b);
    if !arg.is_empty() && arg.bytes().all(plain) {
        arg.to_owned()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    }
}

/// Plain one-line-per-diagnostic rendering, for places where a full report would be noise.
pub fn render_diagnostics(input: &Input, diagnostics: &[Diagnostic], color: bool) -> String {
    render_human(&[(input, diagnostics)], color)
}
