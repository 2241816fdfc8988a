//! `rotlang check`: diagnostics for templates.

use std::io::Write;
use std::path::PathBuf;

use super::{ColorArg, Input, TargetArg, UsageError, gather, pieces_note, render_human};

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang check '+10L25%, -10l25%'        one template
  rotlang check -- -30                    a template that begins with '-'
  rotlang check --file profile.rot        a file (newlines separate instructions)
  echo '+30/50 %' | rotlang check         from stdin
  rotlang check --target solid 'S/, +10'  as a solid_infill_rotate_template
  rotlang check --format json '+30X5'     one JSON object per input, one per line
  rotlang check profiles/ project.3mf     every template in presets, exports, projects
  rotlang check --compat none '0 90'      rotlang's reading alone, no OrcaSlicer lint
  rotlang check --fix '+30°, 10,,20'      print the template with every fix applied
  rotlang check --fix --write -f a.rot    apply the fixes to a.rot in place
  rotlang check --fix --write process.json   fix the templates of a preset in place
  rotlang check -f - < a.rot              `-` is stdin, as a template or a file

`--fix` applies the fix of every diagnostic that has one (the `fix:` lines of the
report, the OrcaSlicer lint's included), again and again until none is left, and
prints one line (or file text) per input, in order. A fix is applied when afterwards
OrcaSlicer reads the template as rotlang does, or as it read it before (`0; 90`,
`b!, +30`, `+30/50 %`, `10,,20`). An input is left as it is (printed unchanged, not
written, exit 1, its name and the reason on stderr) when errors remain that have no
fix (an OrcaSlicer hang included), or, without --force, when the fixes would make two
agreeing readings part.
On presets (.json, .jsonc), .ini exports and folders it fixes each template's value
in place and keeps every other byte of the file (.3mf projects are not rewritten).

OrcaSlicer's reading is compared by default (`--compat none` turns it off): `0 90`
is a warning (OrcaSlicer reads `0`), `10!, 5*` an error (OrcaSlicer never finishes
slicing). An input over 64 KiB gets the OrcaSlicer lint only with --compat orcaslicer.

Exit status: 0 when every input is clean or has only warnings, 1 when any has an
error or a file cannot be read (the other files are still checked), 2 on a usage error.")]
pub struct CheckArgs {
    /// Templates to check, each one input, or files and folders: an argument naming an
    /// existing path is read as a profile (.json, .jsonc, .ini, .3mf) or template (.rot).
    /// `-` is stdin. Put `--` before a template that begins with `-`.
    #[arg(value_name = "TEMPLATE", allow_negative_numbers = true)]
    pub templates: Vec<String>,
    /// Read a template from a file (one template per file; newlines are separators; `-` is
    /// stdin). Repeatable.
    #[arg(long = "file", short = 'f', value_name = "PATH")]
    pub files: Vec<PathBuf>,
    /// Which setting the template is for.
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,
    /// `human`: a report with the source underlined; `json`: one object per input per line.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Colour the human report.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
    /// Treat warnings as errors (exit 1).
    #[arg(long)]
    pub deny_warnings: bool,
    /// Apply every fix and print the fixed templates, one per input in order (diagnostics
    /// go to stderr). The OrcaSlicer lint's fixes too, unless --compat none.
    #[arg(long, conflicts_with = "format")]
    pub fix: bool,
    /// With --fix: rewrite files in place instead of printing them.
    #[arg(long, requires = "fix")]
    pub write: bool,
    /// With --fix: fix even where the fixes would make OrcaSlicer's reading part from
    /// rotlang's where the two agreed; without it such a template is left as it is
    /// (printed unchanged) and the exit status is 1.
    #[arg(long, requires = "fix")]
    pub force: bool,
    /// Compare with a slicer's own reading, by default OrcaSlicer's: where its angles
    /// part from rotlang's on the model (the profile's own, or the 20 mm cube) is a
    /// warning, where it hangs, crashes or computes NaN angles an error, and constructs it
    /// reads differently are warnings. `none` checks rotlang's reading alone.
    #[arg(long, value_enum, value_name = "SLICER")]
    pub compat: Option<super::files::CompatArg>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    #[default]
    Human,
    Json,
}

/// Runs the check; returns the exit code.
pub fn run(args: &CheckArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    // Files, folders (an argument naming an existing path is one) and the compat lint.
    if args.fix && super::files::has_paths(args) {
        return super::fix_files::run(args, out, err);
    }
    if !args.fix && super::files::has_paths(args) {
        return super::files::check(args, out);
    }
    let inputs = gather(&args.templates, &args.files)?;
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    if let Some(note) = pieces_note("check", &args.templates) {
        err.write_all(note.as_bytes()).map_err(io)?;
    }
    if args.fix {
        return fix(args, &inputs, out, err);
    }
    let target = args.target.into();
    let mut parses: Vec<_> = inputs
        .iter()
        .map(|i| crate::check(&i.text, target))
        .collect();
    // The OrcaSlicer lint (by default): its findings join each input's diagnostics. A
    // template with errors gets those alone (as in the language server): OrcaSlicer's view
    // of text rotlang rejects would only add noise until it is fixed.
    for (input, parse) in inputs.iter().zip(&mut parses) {
        if parse.has_errors() {
            continue;
        }
        if let Some(note) = super::files::compat_skipped(args.compat, &input.name, input.text.len())
        {
            writeln!(err, "note: {note}").map_err(io)?;
        }
        if super::files::compat_on(args.compat, input.text.len()) {
            let found = crate::dialect::compat::compat(
                &input.text,
                target,
                &crate::eval::Model::cube20(),
                crate::eval::Options::default(),
            );
            for d in found {
                match d.severity {
                    crate::Severity::Error => parse.errors += 1,
                    crate::Severity::Warning => parse.warnings += 1,
                }
                parse.diagnostics.push(d);
            }
            // The "N more not shown" entry stays last.
            parse
                .diagnostics
                .sort_by_key(|d| (d.code == "rotlang::too-many-diagnostics", d.primary_span()));
        }
    }
    let failed =
        |p: &crate::Parse| p.has_errors() || (args.deny_warnings && !p.diagnostics.is_empty());
    let code = i32::from(parses.iter().any(failed));
    match args.format {
        Format::Json => {
            for (input, parse) in inputs.iter().zip(&parses) {
                writeln!(out, "{}", super::report_json(input, parse)).map_err(io)?;
            }
        }
        Format::Human => {
            let reports: Vec<(&Input, &[crate::Diagnostic])> = inputs
                .iter()
                .zip(&parses)
                .map(|(i, p)| (i, p.diagnostics.as_slice()))
                .collect();
            let color = args.color.enabled(true);
            out.write_all(render_human(&reports, color).as_bytes())
                .map_err(io)?;
            // Exact counts, whatever the cap on the diagnostics listed above.
            let errors = parses.iter().map(|p| p.errors).sum();
            let warnings = parses.iter().map(|p| p.warnings).sum();
            let omitted: usize = parses.iter().map(|p| p.omitted).sum();
            let mut summary = summary(inputs.len(), errors, warnings, args.deny_warnings);
            if omitted > 0 {
                summary.push_str(&format!(" ({omitted} not shown)"));
            }
            writeln!(out, "{summary}").map_err(io)?;
        }
    }
    Ok(code)
}

/// `check --fix`: every fix applied; the fixed text printed or written, one per input in
/// order. An input left as it is (errors remain, or OrcaSlicer would read the fix
/// differently) is printed unchanged, and named on stderr with the reason (exit 1).
fn fix(
    args: &CheckArgs,
    inputs: &[Input],
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<i32, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    let target = args.target.into();
    // The compat lint on the model `check --compat` uses for templates.
    let compat = |text: &str| {
        if super::files::compat_on(args.compat, text.len()) {
            crate::dialect::compat::compat(
                text,
                target,
                &crate::eval::Model::cube20(),
                crate::eval::Options::default(),
            )
        } else {
            Vec::new()
        }
    };
    let mut code = 0;
    let (mut applied, mut written) = (0, 0);
    for input in inputs {
        let fixed = crate::fix::apply_all_with(&input.text, target, compat);
        let left = Input {
            text: fixed.text.clone(),
            ..input.clone()
        };
        let refused = refusal(args, &input.text, &fixed, target, &compat);
        // The report is of the text printed: the input when it is left as it is, else
        // what is left of the fixed text.
        let (shown, mut diagnostics) = match refused {
            Some(_) => (input, crate::parse(&input.text, target).diagnostics),
            None => (&left, fixed.parse.diagnostics.clone()),
        };
        diagnostics.extend(compat(&shown.text));
        if !diagnostics.is_empty() {
            let report = render_human(&[(shown, &diagnostics)], args.color.enabled(false));
            err.write_all(report.as_bytes()).map_err(io)?;
        }
        let counted = |d: &&crate::Diagnostic| d.code != "rotlang::too-many-diagnostics";
        let warnings = diagnostics.iter().filter(counted).count();
        if let Some(why) = refused {
            writeln!(err, "{}: not fixed: {why}", input.name).map_err(io)?;
            code = 1;
            if !(args.write && input.path.is_some()) {
                let text = input.text.strip_suffix('\n').unwrap_or(&input.text);
                writeln!(out, "{text}").map_err(io)?;
            }
            continue;
        }
        applied += fixed.applied;
        if args.deny_warnings && warnings > 0 {
            code = 1;
        }
        match (&input.path, args.write) {
            (Some(path), true) => {
                if fixed.text != input.text {
                    let (read, new) = (input.text.as_bytes(), fixed.text.as_bytes());
                    match super::write::write_file(path, read, new) {
                        Ok(()) => written += 1,
                        Err(why) => {
                            writeln!(err, "{why}").map_err(io)?;
                            code = 1;
                        }
                    }
                }
            }
            _ => {
                let text = fixed.text.strip_suffix('\n').unwrap_or(&fixed.text);
                writeln!(out, "{text}").map_err(io)?;
            }
        }
    }
    let plural = |n: usize, w: &str| {
        if n == 1 {
            format!("1 {w}")
        } else {
            format!("{n} {w}s")
        }
    };
    let fixes = if applied == 1 {
        "1 fix".to_owned()
    } else {
        format!("{applied} fixes")
    };
    let mut line = format!("fixed: {fixes} applied");
    if args.write {
        line.push_str(&format!(", {} rewritten", plural(written, "file")));
    }
    writeln!(err, "{line}").map_err(io)?;
    Ok(code)
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

fn summary(inputs: usize, errors: usize, warnings: usize, deny_warnings: bool) -> String {
    let what = if inputs == 1 {
        "1 template".to_owned()
    } else {
        format!("{inputs} templates")
    };
    let plural = |n: usize, w: &str| {
        if n == 1 {
            format!("1 {w}")
        } else {
            format!("{n} {w}s")
        }
    };
    match (errors, warnings) {
        (0, 0) => format!("ok: {what}, no problems"),
        (0, w) if deny_warnings => format!(
            "failed: {what}, {} (denied by --deny-warnings)",
            plural(w, "warning")
        ),
        (0, w) => format!("ok: {what}, {}", plural(w, "warning")),
        (e, 0) => format!("failed: {what}, {}", plural(e, "error")),
        (e, w) => format!(
            "failed: {what}, {}, {}",
            plural(e, "error"),
            plural(w, "warning")
        ),
    }
}
