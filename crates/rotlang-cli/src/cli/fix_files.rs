//! `rotlang check --fix [--write] PATH…` on profiles: the templates of presets (`.json`,
//! `.jsonc`), `.ini` exports and `.rot` files (and folders of them) fixed where they
//! stand. Only each template's value changes; every other byte of the file is kept. A
//! value written into JSON is JSON-escaped; into `.ini` it goes as the `.ini` reader reads
//! it (verbatim, one line). `.3mf` projects are not rewritten (see [`THREE_MF`]).

use std::io::Write;
use std::path::{Path, PathBuf};

use super::check::CheckArgs;
use super::{Input, UsageError, render_human};
use crate::Span;
use crate::profile::{self, DEFAULT_OBJECT_HEIGHT, Found, Kind, Profile};

/// Why a project is not fixed.
const THREE_MF: &str = "--fix does not rewrite .3mf projects: a project is a zip archive, and \
    rewriting one entry means writing the whole archive anew (every entry recompressed), \
    which is not a change of the template alone; fix the template in OrcaSlicer, or run \
    `rotlang check --fix 'TEMPLATE'` and paste the result";

#[derive(Default)]
struct Totals {
    applied: usize,
    written: usize,
    code: i32,
}

pub(crate) fn run(
    args: &CheckArgs,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<i32, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    let mut totals = Totals::default();
    let mut paths: Vec<PathBuf> = Vec::new();
    let mut templates: Vec<String> = Vec::new();
    for arg in &args.templates {
        let path = Path::new(arg);
        if path.is_dir() {
            let (files, errors) = profile::files_under(path);
            for e in errors {
                writeln!(err, "error: {e}").map_err(io)?;
                totals.code = 1;
            }
            paths.extend(files);
        } else if path.exists() {
            paths.push(path.to_owned());
        } else {
            templates.push(arg.clone());
        }
    }
    paths.extend(args.files.iter().cloned());
    // `-` is stdin, as everywhere a template goes.
    let inputs = if templates.is_empty() {
        Vec::new()
    } else {
        super::gather(&templates, &[])?
    };
    for input in &inputs {
        let text = &input.text;
        let (text, why) = fix_text(args, text, crate::Target::from(args.target), None);
        match why {
            Ok(n) => totals.applied += n,
            Err(why) => {
                writeln!(err, "{}: not fixed: {why}", input.name).map_err(io)?;
                totals.code = 1;
            }
        }
        writeln!(out, "{}", text.strip_suffix('\n').unwrap_or(&text)).map_err(io)?;
    }
    for path in &paths {
        file(args, path, &mut totals, out, err).map_err(io)?;
    }
    let fixes = if totals.applied == 1 {
        "1 fix".to_owned()
    } else {
        format!("{} fixes", totals.applied)
    };
    let mut line = format!("fixed: {fixes} applied");
    if args.write {
        let files = if totals.written == 1 { "file" } else { "files" };
        line.push_str(&format!(", {} {files} rewritten", totals.written));
    }
    writeln!(err, "{line}").map_err(io)?;
    Ok(totals.code)
}

/// The fixed text of one template and how many fixes were applied, or why it is left as
/// it is (the text unchanged): the rules of `check --fix` on a template.
fn fix_text(
    args: &CheckArgs,
    text: &str,
    target: crate::Target,
    model: Option<&profile::ProfileModel>,
) -> (String, Result<usize, String>) {
    let compat = |t: &str| {
        if !super::files::compat_on(args.compat) {
            return Vec::new();
        }
        match model {
            Some(pm) => pm.compat(t, target),
            None => crate::dialect::compat::compat(
                t,
                target,
                &crate::eval::Model::cube20(),
                crate::eval::Options::default(),
            ),
        }
    };
    let fixed = crate::fix::apply_all_with(text, target, compat);
    if let Some(why) = super::check::refusal(args, text, &fixed, target, &compat) {
        return (text.to_owned(), Err(why));
    }
    (fixed.text, Ok(fixed.applied))
}

fn file(
    args: &CheckArgs,
    path: &Path,
    totals: &mut Totals,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> std::io::Result<()> {
    let shown = path.display().to_string();
    let (profile, bytes) = match profile::read_with_bytes(path) {
        Ok(read) => read,
        Err(e) => {
            writeln!(err, "error: {e}")?;
            totals.code = 1;
            return Ok(());
        }
    };
    let doc = match profile.kind {
        Some(Kind::ThreeMf) => {
            writeln!(err, "{shown}: not fixed: {THREE_MF}")?;
            totals.code = 1;
            return Ok(());
        }
        _ => profile.sources[0].text.clone(),
    };
    if let Some(note) = profile
        .notes
        .iter()
        .find(|n| n.error && n.message.starts_with("invalid JSON"))
    {
        writeln!(err, "{shown}: not fixed: {}", note.message)?;
        totals.code = 1;
        return Ok(());
    }
    let mut edits: Vec<(Span, String)> = Vec::new();
    for found in &profile.templates {
        if let Some(edit) = template(args, &profile, found, &shown, totals, err)? {
            edits.push(edit);
        }
    }
    // Back to front, so each span is still where it was found.
    edits.sort_by_key(|(span, _)| std::cmp::Reverse(span.start));
    let mut new = doc.clone();
    for (span, text) in &edits {
        new.replace_range(span.range(), text);
    }
    if !args.write {
        out.write_all(new.as_bytes())?;
        if !new.ends_with('\n') {
            writeln!(out)?;
        }
    } else if new != doc {
        match super::write::write_file(path, &bytes, new.as_bytes()) {
            Ok(()) => totals.written += 1,
            Err(why) => {
                writeln!(err, "{why}")?;
                totals.code = 1;
            }
        }
    }
    Ok(())
}

/// One template of a file fixed: the span of its value in the file and the value to write
/// there (escaped for the file's kind), or `None` when it stays as it is.
fn template(
    args: &CheckArgs,
    profile: &Profile,
    found: &Found,
    shown: &str,
    totals: &mut Totals,
    err: &mut dyn Write,
) -> std::io::Result<Option<(Span, String)>> {
    let pm = profile.model(found.target, found.object.as_deref(), DEFAULT_OBJECT_HEIGHT);
    let (fixed, result) = fix_text(args, &found.text, found.target, Some(&pm));
    let label = match profile.kind {
        Some(Kind::Template) => shown.to_owned(),
        _ => format!("{shown}: {}", found.label()),
    };
    let applied = match result {
        Ok(n) => n,
        Err(why) => {
            // The diagnostics as `check` shows them: in the file, on the value as it is.
            let diagnostics: Vec<crate::Diagnostic> = crate::check(&found.text, found.target)
                .diagnostics
                .into_iter()
                .map(|d| super::files::into_file(d, found))
                .collect();
            let input = Input {
                name: shown.to_owned(),
                text: profile.sources[found.source].text.clone(),
                path: Some(profile.path.clone()),
            };
            let report = render_human(&[(&input, &diagnostics)], args.color.enabled(false));
            err.write_all(report.as_bytes())?;
            writeln!(err, "{label}: not fixed: {why}")?;
            totals.code = 1;
            return Ok(None);
        }
    };
    if fixed == found.text {
        return Ok(None);
    }
    let value = match profile.kind {
        Some(Kind::Json) => crate::profile::json::escape(&fixed),
        Some(Kind::Ini) => {
            // The `.ini` reader takes the rest of the line, trimmed: a line break or an
            // edge space cannot be written back as it reads.
            if fixed.contains(['\n', '\r']) || fixed.trim_matches([' ', '\t']) != fixed {
                writeln!(
                    err,
                    "{label}: not fixed: `{}` cannot be written on one .ini line as it reads",
                    fixed.escape_debug()
                )?;
                totals.code = 1;
                return Ok(None);
            }
            fixed
        }
        // A template file: the whole text after a byte-order mark.
        _ => fixed,
    };
    totals.applied += applied;
    let span = found.span_in_source(Span::new(0, found.text.len()));
    Ok(Some((span, value)))
}

/// Why `check --fix` leaves `text` as it is, if it does: errors remain (an OrcaSlicer hang
/// included), or, without --force, the fixes would make two agreeing readings part. One
/// rule for templates, `--file` and the values in profiles.
pub(crate) fn refusal(
    args: &CheckArgs,
    text: &str,
    fixed: &crate::fix::Fixed,
    target: crate::Target,
    compat: &dyn Fn(&str) -> Vec<crate::Diagnostic>,
) -> Option<String> {
    let trim = |t: &str| t.strip_suffix('\n').unwrap_or(t).to_owned();
    let (before, after) = (trim(text), trim(&fixed.text));
    if fixed.parse.has_errors() || compat(&fixed.text).iter().any(|d| d.is_error()) {
        Some("errors remain that have no automatic fix".to_owned())
    } else if !args.force
        && fixed.text != text
        && !rotlang_change(text, &fixed.text, target)
        && crate::dialect::compat::readings_agree(&before, target)
        && !crate::dialect::compat::readings_agree(&after, target)
    {
        // A fix is what the user asked for when, afterwards, OrcaSlicer reads the
        // template as rotlang does, or as it read it before: only a fix that makes
        // two agreeing readings part needs --force. (Fixes that repair what rotlang
        // reads, `+30/ 50%` into `+30/50%`, or what OrcaSlicer misreads, `10,,20`
        // into `10, 20`, are what the warnings asked for.)
        Some(format!(
            "`{after}` would make OrcaSlicer read it differently from rotlang ({}); \
             pass --force to fix anyway",
            crate::dialect::compat::orcaslicer_change(&before, &after)
                .unwrap_or_else(|| "on some layer".to_owned())
        ))
    } else {
        None
    }
}

/// Whether rotlang reads `fixed` differently from `text`, which has no errors (on the 20 mm
/// cube and a model of other shell counts and heights). A text with errors has no reading
/// to keep: `false`, so that the OrcaSlicer guard applies to its fixes.
pub(crate) fn rotlang_change(text: &str, fixed: &str, target: crate::Target) -> bool {
    let options = crate::eval::Options::default();
    let mut models = vec![crate::eval::Model::cube20()];
    models.extend(crate::eval::Model::uniform(75, 0.2, Some(0.3)).map(|m| m.with_shells(4, 5)));
    models.iter().any(|model| {
        let (parse, a) = crate::eval::parse_layers(text, target, model, options);
        if parse.has_errors() {
            return false;
        }
        let (_, b) = crate::eval::parse_layers(fixed, target, model, options);
        a.zip(b)
            .any(|(x, y)| x.fill != y.fill || crate::number::round_angle(x.angle - y.angle) != 0.0)
    })
}
