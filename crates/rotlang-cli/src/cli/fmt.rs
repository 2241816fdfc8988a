//! `rotlang fmt`: the canonical form of templates.

use std::io::Write;
use std::path::PathBuf;

use super::{ColorArg, TargetArg, UsageError, gather, pieces_note, render_human};

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
The canonical form puts `, ` between instructions and keeps each instruction's
text as written, so formatting never changes what a template means. Templates
with errors are not formatted: their diagnostics are shown instead. Nor are,
without --force, templates that OrcaSlicer would read differently once formatted,
or where a space likely splits an instruction by mistake (`+30/ 50%`): formatting
would make the split permanent; `rotlang check --fix` applies the fix instead.

Examples:
  rotlang fmt '0 90  +30/50%'            prints `0, 90, +30/50%`
  rotlang fmt --file a.rot --write       rewrites a.rot in place
  rotlang fmt --check --file a.rot       exit 1 if a.rot is not canonical (for CI)
  rotlang fmt - < a.rot                  `-` is stdin (also `--file -`)

Exit status: 0 when done (or, with --check, already canonical), 1 on a template
with errors or, with --check, one that would change; 2 on a usage error.")]
pub struct FmtArgs {
    /// Templates to format; `-` is stdin. Put `--` before a template that begins with `-`.
    /// An existing file named here is formatted as with --file.
    #[arg(value_name = "TEMPLATE", allow_negative_numbers = true)]
    pub templates: Vec<String>,
    /// Format a template file (`-` is stdin). Repeatable.
    #[arg(long = "file", short = 'f', value_name = "PATH")]
    pub files: Vec<PathBuf>,
    /// Check only: print nothing on stdout, name each input that is not in canonical form
    /// on stderr, and exit 1 if there is any.
    #[arg(long, conflicts_with = "write")]
    pub check: bool,
    /// Rewrite files in place instead of printing (templates from arguments are printed).
    #[arg(long)]
    pub write: bool,
    /// Format even where OrcaSlicer would read the result differently (`0,,90` is
    /// 0, 0, 90 for OrcaSlicer, `0, 90` is 0, 90), or where a space likely splits an
    /// instruction by mistake (`+30/ 50%`, warned about by `check`); without it such a
    /// template is left as it is (printed unchanged) and the exit status is 1.
    #[arg(long)]
    pub force: bool,
    /// Which setting the templates are for.
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,
    /// Colour diagnostics.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

/// The warning on a space that splits what reads as one instruction (`+30/ 50%`).
const SPLIT_BY_SPACE: &str = "rotlang::space-splits-instruction";

pub fn run(args: &FmtArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    // `fmt a.rot`: a path (by the one rule of every command) is formatted as `--file a.rot`
    // would be (so `--write` rewrites it); a missing one is no such file. A profile holds
    // templates among other settings: not fmt's to rewrite.
    let mut templates = Vec::new();
    let mut files = Vec::new();
    for t in &args.templates {
        let path = std::path::Path::new(t);
        if !super::paths::looks_like_path(t) {
            templates.push(t.clone());
            continue;
        }
        if let Some(e) = super::paths::missing(t) {
            return Err(e);
        }
        if path.is_dir() {
            return Err(UsageError(format!(
                "{t} is a folder: fmt formats templates and template files (`rotlang check {}` \
                 checks every template in it)",
                super::shell_quote(t)
            )));
        }
        match crate::profile::Kind::from_extension(path) {
            Some(crate::profile::Kind::Template) | None => files.push(PathBuf::from(t)),
            Some(kind) => {
                return Err(UsageError(format!(
                    "`{t}` is a profile ({}): fmt formats templates and template files; \
                     `rotlang check {}` checks the templates in it",
                    kind.name(),
                    super::shell_quote(t)
                )));
            }
        }
    }
    files.extend(args.files.iter().cloned());
    let inputs = gather(&templates, &files)?;
    if let Some(note) = pieces_note("fmt", &args.templates) {
        err.write_all(note.as_bytes()).map_err(io)?;
    }
    let mut code = 0;
    for input in &inputs {
        // Diagnostics and the canonical form each in one streaming pass: no IR is kept.
        let parse = crate::check(&input.text, args.target.into());
        let formatted = crate::format::format(&input.text, args.target.into());
        let Some(formatted) = formatted.filter(|_| !parse.has_errors()) else {
            let report = render_human(&[(input, &parse.diagnostics)], args.color.enabled(false));
            err.write_all(report.as_bytes()).map_err(io)?;
            writeln!(err, "{}: not formatted: fix the errors first", input.name).map_err(io)?;
            code = 1;
            continue;
        };
        // A file keeps one trailing newline; the template itself is the rest.
        let current = input
            .text
            .strip_suffix('\n')
            .map_or(input.text.as_str(), |t| t.strip_suffix('\r').unwrap_or(t));
        // `+30/ 50%`: a space that likely splits one instruction by mistake. Formatting
        // would write the split as `+30/, 50%` and silence the warning: leave the text
        // as it is, with the warning and its fix (`check --fix` applies it).
        let splits: Vec<crate::Diagnostic> = parse
            .diagnostics
            .iter()
            .filter(|d| d.code == SPLIT_BY_SPACE)
            .cloned()
            .collect();
        if !args.force && !splits.is_empty() && current != formatted {
            let report = render_human(&[(input, &splits)], args.color.enabled(false));
            err.write_all(report.as_bytes()).map_err(io)?;
            writeln!(
                err,
                "{}: not formatted: a space likely splits an instruction by mistake (the \
                 warning above), and formatting would make it a separator (`{formatted}`); \
                 remove the space (`rotlang check --fix` does) or pass --force to format anyway",
                input.name
            )
            .map_err(io)?;
            if !args.check && (!args.write || input.path.is_none()) {
                writeln!(out, "{current}").map_err(io)?;
            }
            code = 1;
            continue;
        }
        // Canonical for rotlang, but OrcaSlicer may read the new text differently.
        if !args.check
            && !args.force
            && current != formatted
            && let Some(why) = crate::dialect::compat::orcaslicer_change(current, &formatted)
        {
            writeln!(
                err,
                "{}: not formatted: `{formatted}` would change what OrcaSlicer does ({why}); \
                 pass --force to format anyway",
                input.name
            )
            .map_err(io)?;
            if !args.write || input.path.is_none() {
                writeln!(out, "{current}").map_err(io)?;
            }
            code = 1;
            continue;
        }
        if args.check {
            if current != formatted {
                writeln!(
                    err,
                    "{}: not in canonical form (would be `{formatted}`)",
                    input.name
                )
                .map_err(io)?;
                code = 1;
            }
        } else if let (true, Some(path)) = (args.write, &input.path) {
            let new = format!("{formatted}\n");
            if current != formatted
                && let Err(why) =
                    super::write::write_file(path, input.text.as_bytes(), new.as_bytes())
            {
                writeln!(err, "{why}").map_err(io)?;
                code = 1;
            }
        } else {
            writeln!(out, "{formatted}").map_err(io)?;
        }
    }
    Ok(code)
}
