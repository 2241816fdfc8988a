//! `rotlang explain`: a diagnostic code, or a template in plain words.

use std::io::Write;

use super::model::ModelArgs;
use super::{Input, TargetArg, UsageError, render_human};

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang explain rotlang::unknown-sign      a diagnostic code: what, why, example, fix
  rotlang explain space-splits-instruction   the `rotlang::` prefix may be left out
  rotlang explain --list                     every code with its summary
  rotlang explain '+10L25%, -10l25%'         a template in words, with its layer ranges
  rotlang explain 'B!, +30' --layers 50      ... on a model of 50 layers of 0.2 mm
  rotlang explain -- -30/50%                 a template that begins with '-'
  rotlang explain - < profile.rot            `-` is stdin
  rotlang explain --profile process.json     the template of a preset, on its model
  rotlang explain --dialect orcaslicer '0 90'  ... and how OrcaSlicer reads it

Exit status: 0 when explained, 1 when a template has errors (what parses is still
explained), 2 on a usage error (such as an unknown code).")]
pub struct ExplainArgs {
    /// A diagnostic code (`rotlang::unknown-sign`, or `unknown-sign`) or a template.
    /// Without it, the template is read from stdin; `-` is stdin.
    #[arg(value_name = "CODE|TEMPLATE", allow_negative_numbers = true)]
    pub what: Option<String>,
    /// List every diagnostic code with its summary.
    #[arg(long, conflicts_with = "what")]
    pub list: bool,
    /// Which setting the template is for.
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub profile: super::paths::ProfileArgs,
    /// `orcaslicer`: also say how OrcaSlicer reads the template on the model: its first
    /// angles, and where it parts from rotlang's reading (the compat lint), for any text.
    #[arg(long, value_name = "DIALECT", default_value_t)]
    pub dialect: crate::eval::Dialect,
}

pub fn run(
    args: &ExplainArgs,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<i32, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    if args.list {
        let width = crate::explain::codes()
            .iter()
            .map(|d| d.code.len())
            .max()
            .unwrap_or(0);
        for d in crate::explain::codes() {
            writeln!(out, "{:<width$}  {:<7}  {}", d.code, d.severity, d.summary).map_err(io)?;
        }
        return Ok(0);
    }
    if let Some(what) = &args.what {
        if let Some(doc) = crate::explain::code(what) {
            out.write_all(code_text(doc).as_bytes()).map_err(io)?;
            return Ok(0);
        }
        let w = what.trim();
        let code_like = w.contains("::")
            || (w.len() > 3
                && w.contains('-')
                && w.bytes().all(|b| b.is_ascii_lowercase() || b == b'-'));
        if let Some(why) = retired(w) {
            writeln!(out, "{why}").map_err(io)?;
            return Ok(0);
        }
        let near = nearest_code(w);
        if code_like || near.is_some() {
            let hint = match near {
                Some(code) => format!("did you mean `{code}`? "),
                None => String::new(),
            };
            return Err(UsageError(format!(
                "no diagnostic code `{w}`; {hint}`rotlang explain --list` lists them"
            )));
        }
    }
    let target = args.target.into();
    // The model first: a usage error should not wait for stdin.
    let mut model = args.model.resolve()?.model;
    let source = match super::paths::source(
        args.what.as_ref(),
        None,
        &args.profile,
        target,
        args.model.height,
        err,
    )? {
        Ok(s) => s,
        Err(code) => return Ok(code),
    };
    let mut options = crate::eval::Options::default();
    if let Some(p) = source.profile {
        options.base = p.base;
        if args.model.model.is_none() && args.model.layers.is_none() && args.model.height.is_none()
        {
            model = p.model;
        }
    }
    let input = source.input;
    let parse = crate::parse(&input.text, target);
    let orcaslicer = match args.dialect {
        crate::eval::Dialect::OrcaSlicer => orcaslicer_words(&input.text, target, &model, options),
        crate::eval::Dialect::Rotlang => String::new(),
    };
    if parse.has_errors() {
        // The errors first; then what parses, if anything does.
        writeln!(out, "The template has errors:\n").map_err(io)?;
        out.write_all(render_human(&[(&input, &parse.diagnostics)], false).as_bytes())
            .map_err(io)?;
        let word = input.text.trim();
        if !word.is_empty() && word.bytes().all(|b| b.is_ascii_lowercase() || b == b'-') {
            writeln!(
                out,
                "(Nor is `{word}` a diagnostic code: `rotlang explain --list` lists them.)"
            )
            .map_err(io)?;
        }
        if !parse.template.instructions.is_empty() {
            writeln!(out).map_err(io)?;
            let text = crate::explain::template(&input.text, target, &model);
            out.write_all(text.as_bytes()).map_err(io)?;
        }
        out.write_all(orcaslicer.as_bytes()).map_err(io)?;
        return Ok(1);
    }
    let text = crate::explain::template(&input.text, target, &model);
    out.write_all(text.as_bytes()).map_err(io)?;
    out.write_all(orcaslicer.as_bytes()).map_err(io)?;
    Ok(0)
}

/// How OrcaSlicer reads `text` on `model`: its first angles, and the compat findings.
fn orcaslicer_words(
    text: &str,
    target: crate::Target,
    model: &crate::eval::Model,
    options: crate::eval::Options,
) -> String {
    const SHOWN: usize = 8;
    let angles: Vec<String> = crate::dialect::orcaslicer::layers(text, model, options)
        .take(SHOWN)
        .map(|l| format!("{}°", crate::number::round_angle(l.angle)))
        .collect();
    let end = if model.len() > SHOWN { ", ..." } else { "." };
    let mut s = format!(
        "\nIn OrcaSlicer (`--dialect orcaslicer`): layers from 0 at {}{end}\n",
        angles.join(", ")
    );
    let found = crate::dialect::compat::compat(text, target, model, options);
    if found.is_empty() {
        s.push_str("It reads the template as rotlang does on this model.\n");
    } else {
        s.push_str("Where it parts from rotlang's reading:\n");
        for d in found {
            s.push_str(&format!("- {} [{}]\n", d.message, d.code));
        }
    }
    s
}

/// A code rotlang no longer reports, and why (old reports and scripts still name it).
fn retired(w: &str) -> Option<&'static str> {
    let direction = concat!("orcaslicer::", "direction-ignored");
    (w == direction || w == "direction-ignored").then_some(concat!(
        "orcaslicer::",
        "direction-ignored (retired): it said that OrcaSlicer ignores a ",
        "profile's infill direction when a template is set while rotlang added it to every ",
        "angle. rotlang now reads a profile as OrcaSlicer does, in every tool: the direction ",
        "(sparse_infill_direction, infill_direction, solid_infill_direction) is the angle of ",
        "an empty template only, so the two readings never part on it."
    ))
}

/// The documented code `w` most likely means: the code whose name after `::` is `w`, or
/// one within two edits of it (a typo).
fn nearest_code(w: &str) -> Option<&'static str> {
    if w.len() < 4
        || !w
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b == b'-' || b == b':')
    {
        return None;
    }
    let name = w.rsplit("::").next().unwrap_or(w);
    let codes = crate::explain::codes();
    codes
        .iter()
        .map(|d| d.code)
        .find(|c| c.rsplit("::").next() == Some(name))
        .or_else(|| {
            codes
                .iter()
                .map(|d| {
                    (
                        edits(name, d.code.rsplit("::").next().unwrap_or(d.code)),
                        d.code,
                    )
                })
                .filter(|(n, _)| *n <= 2)
                .min()
                .map(|(_, c)| c)
        })
}

/// The edit distance of two short words (Levenshtein).
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (prev + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            prev = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// A code's page: summary, explanation, the example as `rotlang check` reports it, fix.
fn code_text(doc: &crate::explain::CodeDoc) -> String {
    let mut s = format!(
        "{} ({}): {}\n\n{}\n\nExample: {}\n",
        doc.code,
        doc.severity,
        doc.summary,
        wrap(doc.explanation, 88),
        // Examples that are descriptions, not templates.
        if doc.code == "rotlang::too-many-diagnostics" || doc.example.starts_with('(') {
            doc.example.to_owned()
        } else {
            format!("`{}`", doc.example.replace('\u{feff}', "<U+FEFF>"))
        }
    );
    let target = if doc.code == "rotlang::solid-sign-in-solid-template" {
        crate::Target::Solid
    } else {
        crate::Target::Sparse
    };
    if doc.code.starts_with("orcaslicer::") {
        s.push_str(&format!(
            "    (as `rotlang expand --dialect orcaslicer '{}'` reports it)\n",
            doc.example
        ));
    } else if doc.code != "rotlang::too-many-diagnostics" {
        let input = Input {
            name: "<template>".into(),
            text: doc.example.to_owned(),
            path: None,
        };
        let parse = crate::parse(doc.example, target);
        let shown: Vec<_> = parse
            .diagnostics
            .iter()
            .filter(|d| d.code == doc.code)
            .take(1)
            .cloned()
            .collect();
        let report = render_human(&[(&input, &shown)], false);
        for line in report.lines() {
            s.push_str(&format!("    {line}\n").replace("    \n", "\n"));
        }
    }
    s.push_str(&format!("Fix: {}\n", wrap(doc.fix, 88)));
    s
}

/// Words wrapped at `width` columns.
fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = 0;
    for word in text.split_whitespace() {
        let n = word.chars().count();
        if line > 0 && line + 1 + n > width {
            out.push('\n');
            line = 0;
        } else if line > 0 {
            out.push(' ');
            line += 1;
        }
        out.push_str(word);
        line += n;
    }
    out
}
