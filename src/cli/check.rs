//! `rotlang check`: diagnostics for templates.

use std::io::Write;
use std::path::PathBuf;

use super::{ColorArg, Input, TargetArg, UsageError, diagnostic_json, gather, render_human};
use crate::diagnostic::LineIndex;

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
  rotlang check --compat orcaslicer process.json   where OrcaSlicer reads it differently

Exit status: 0 when every input is clean or has only warnings, 1 when any has an
error or a file cannot be read (the other files are still checked), 2 on a usage error.")]
pub struct CheckArgs {
    /// Templates to check, each one input, or files and folders: an argument naming an
    /// existing path is read as a profile (.json, .jsonc, .ini, .3mf) or template (.rot).
    /// Put `--` before a template that begins with `-`.
    #[arg(value_name = "TEMPLATE", allow_negative_numbers = true)]
    pub templates: Vec<String>,
    /// Read a template from a file (one template per file; newlines are separators). Repeatable.
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
    /// Also compare with a slicer's own reading (`orcaslicer`): where its angles part from
    /// rotlang's on the model (the profile's own, or the 20 mm cube), where it hangs or
    /// computes NaN angles, and constructs it reads differently.
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
pub fn run(args: &CheckArgs, out: &mut dyn Write) -> Result<i32, UsageError> {
    // Files, folders (an argument naming an existing path is one) and the compat lint.
    if super::files::wanted(args) {
        return super::files::check(args, out);
    }
    let inputs = gather(&args.templates, &args.files)?;
    let parses: Vec<_> = inputs
        .iter()
        .map(|i| crate::check(&i.text, args.target.into()))
        .collect();
    let failed =
        |p: &crate::Parse| p.has_errors() || (args.deny_warnings && !p.diagnostics.is_empty());
    let code = i32::from(parses.iter().any(failed));
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    match args.format {
        Format::Json => {
            for (input, parse) in inputs.iter().zip(&parses) {
                let index = LineIndex::new(&input.text);
                let diagnostics: Vec<_> = parse
                    .diagnostics
                    .iter()
                    .map(|d| diagnostic_json(&index, d))
                    .collect();
                let obj = serde_json::json!({
                    "input": input.text, "name": input.name, "diagnostics": diagnostics,
                    "errors": parse.errors, "warnings": parse.warnings, "omitted": parse.omitted,
                });
                writeln!(out, "{obj}").map_err(io)?;
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
            let mut summary = summary(inputs.len(), errors, warnings);
            if omitted > 0 {
                summary.push_str(&format!(" ({omitted} not shown)"));
            }
            writeln!(out, "{summary}").map_err(io)?;
        }
    }
    Ok(code)
}

fn summary(inputs: usize, errors: usize, warnings: usize) -> String {
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
        (0, w) => format!("ok: {what}, {}", plural(w, "warning")),
        (e, 0) => format!("failed: {what}, {}", plural(e, "error")),
        (e, w) => format!(
            "failed: {what}, {}, {}",
            plural(e, "error"),
            plural(w, "warning")
        ),
    }
}
