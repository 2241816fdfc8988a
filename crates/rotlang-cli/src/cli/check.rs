//! `rotlang check`: diagnostics for templates.

use std::io::Write;

// The options live in check_args.rs, which files.rs and fix_files.rs read too.
pub use super::check_args::{CheckArgs, Format};
// The refusal rule lives with the --fix of files, which checks.rs applies to templates too.
pub(crate) use super::fix_files::refusal;
use super::{Input, UsageError, gather, pieces_note, render_human};

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
        if super::files::compat_on(args.compat) {
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
        if super::files::compat_on(args.compat) {
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
