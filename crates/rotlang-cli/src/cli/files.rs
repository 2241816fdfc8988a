//! `rotlang check PATH…` and `--compat orcaslicer`: templates in files (OrcaSlicer presets,
//! `.ini` exports, `.3mf` projects, folders of them) and the OrcaSlicer compat lint; and
//! `rotlang expand --profile PATH`.
//!
//! Every diagnostic is moved from the template into the file (through JSON and XML
//! escapes), so reports show the file, the line and column in it, and the key (and object).

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use super::check::{CheckArgs, Format};
// `--compat` is a check option; its rules are here for the files that use them.
pub(crate) use super::check_args::{CompatArg, compat_on};
// What `--profile PATH` reads, for expand, plot, preview, explain and export.
pub(crate) use super::from_profile::{ProfileTemplate, printable, profile_template};
use super::{Input, UsageError, diagnostic_json, render_human};
use crate::Target;
use crate::diagnostic::{Diagnostic, LineIndex, Severity};
use crate::dialect::compat;
use crate::eval::{Model, Options};
use crate::profile::{self, DEFAULT_OBJECT_HEIGHT, Found, Kind, Profile, ProfileError};

/// Whether `check` names files or folders (by the one path rule of
/// [`super::paths::looks_like_path`]) or a --file that is not a template: what `--fix`
/// does not work on.
pub(crate) fn has_paths(args: &CheckArgs) -> bool {
    args.templates
        .iter()
        .any(|t| super::paths::looks_like_path(t))
        || args
            .files
            .iter()
            .any(|f| Kind::from_extension(f).is_some_and(|k| k != Kind::Template))
}

/// One text diagnostics point into (a template argument, a file, a 3mf entry).
struct Unit {
    input: Input,
    diagnostics: Vec<Diagnostic>,
    /// Per template in this text: its JSON report (for `--format json`).
    reports: Vec<serde_json::Value>,
    /// Diagnostics found beyond the [`crate::MAX_DIAGNOSTICS`] shown per text (counted in
    /// the summary, not listed): a file of 100,000 faulty values reports as `-f` does.
    omitted: usize,
}

#[derive(Default)]
struct Run {
    /// Whether the JSON reports are wanted (`--format json`): built only then, since a
    /// file of 200,000 templates would otherwise hold 200,000 JSON objects for nothing.
    json: bool,
    units: Vec<Unit>,
    file_errors: Vec<ProfileError>,
    /// Information for the human report (`note: ...` lines).
    notes: Vec<String>,
    templates: usize,
    files: usize,
    errors: usize,
    warnings: usize,
}

pub(crate) fn check(args: &CheckArgs, out: &mut dyn Write) -> Result<i32, UsageError> {
    let target: Target = args.target.into();
    let compat = args.compat;
    let mut run = Run {
        json: args.format == Format::Json,
        ..Run::default()
    };
    let many = args.templates.len() > 1;
    for (i, arg) in args.templates.iter().enumerate() {
        let path = Path::new(arg);
        if !super::paths::looks_like_path(arg) {
            let name = if many {
                format!("<template {}>", i + 1)
            } else {
                "<template>".to_owned()
            };
            run.template(name, arg.clone(), None, target, compat);
        } else if path.is_dir() {
            let (files, errors) = profile::files_under(path);
            if files.is_empty() && errors.is_empty() {
                run.notes.push(format!(
                    "{}: no .rot, .json, .jsonc, .ini or .3mf file in this folder",
                    path.display()
                ));
            }
            run.file_errors.extend(errors);
            for file in files {
                run.file(&file, target, compat);
            }
        } else if path.exists() {
            run.file(path, target, compat);
        } else {
            // A path that is not there: said as such, not read as a template.
            run.files += 1;
            run.file_errors.push(ProfileError {
                path: path.to_owned(),
                message: "no such file or folder".into(),
            });
        }
    }
    for path in &args.files {
        run.file(path, target, compat);
    }
    if args.templates.is_empty() && args.files.is_empty() {
        let input = super::gather(&[], &[])?.remove(0);
        run.template(input.name, input.text, None, target, compat);
    }
    run.report(args, out)?;
    let failed =
        run.errors > 0 || !run.file_errors.is_empty() || (args.deny_warnings && run.warnings > 0);
    Ok(i32::from(failed))
}

/// Exact counts of one template's diagnostics, whatever the cap on those listed.
#[derive(Clone, Copy)]
struct Counts {
    errors: usize,
    warnings: usize,
    omitted: usize,
}

impl Counts {
    fn of(parse: &crate::Parse, lint: &[Diagnostic]) -> Counts {
        let lint_errors = lint.iter().filter(|d| d.is_error()).count();
        Counts {
            errors: parse.errors + lint_errors,
            warnings: parse.warnings + lint.len() - lint_errors,
            omitted: parse.omitted,
        }
    }
}

impl Unit {
    /// Keeps of `diagnostics` what the text's listing has room for; the number dropped.
    fn keep(&mut self, diagnostics: &mut Vec<Diagnostic>) -> usize {
        let room = crate::MAX_DIAGNOSTICS.saturating_sub(self.diagnostics.len());
        // A parse's own "N not shown" entry is counted in its `omitted` already.
        let dropped = diagnostics
            .iter()
            .skip(room)
            .filter(|d| d.code != "rotlang::too-many-diagnostics")
            .count();
        diagnostics.truncate(room);
        self.omitted += dropped;
        dropped
    }
}

impl Run {
    fn template(
        &mut self,
        name: String,
        text: String,
        path: Option<PathBuf>,
        target: Target,
        compat: Option<CompatArg>,
    ) {
        let parse = crate::check(&text, target);
        // A template with errors gets those alone (as in the language server).
        let found = if compat_on(compat) && !parse.has_errors() {
            compat::compat(&text, target, &Model::cube20(), Options::default())
        } else {
            Vec::new()
        };
        let counts = Counts::of(&parse, &found);
        let mut diagnostics = parse.diagnostics;
        diagnostics.extend(found);
        self.add(counts);
        self.templates += 1;
        let index = LineIndex::new(&text);
        let report = self.json.then(|| serde_json::json!({
            "input": text, "name": name, "file": path.as_ref().map(|p| p.display().to_string()),
            "key": null, "object": null,
            "diagnostics": diagnostics.iter().map(|d| diagnostic_json(&index, d)).collect::<Vec<_>>(),
            "errors": counts.errors, "warnings": counts.warnings, "omitted": counts.omitted,
        }));
        self.units.push(Unit {
            input: Input { name, text, path },
            diagnostics,
            reports: report.into_iter().collect(),
            omitted: counts.omitted,
        });
    }

    fn add(&mut self, counts: Counts) {
        self.errors += counts.errors;
        self.warnings += counts.warnings;
    }

    fn count(&mut self, diagnostics: &[Diagnostic]) {
        for d in diagnostics {
            match d.severity {
                Severity::Error => self.errors += 1,
                Severity::Warning => self.warnings += 1,
            }
        }
    }

    fn file(&mut self, path: &Path, target: Target, compat: Option<CompatArg>) {
        self.files += 1;
        let profile = match profile::read(path) {
            Ok(p) => p,
            Err(e) => {
                self.file_errors.push(e);
                return;
            }
        };
        if profile.kind == Some(Kind::Template) {
            let text = profile.templates[0].text.clone();
            let name = path.display().to_string();
            self.template(name, text, Some(path.to_owned()), target, compat);
            return;
        }
        self.profile(profile, compat);
    }

    fn profile(&mut self, profile: Profile, compat: Option<CompatArg>) {
        let mut units: Vec<Unit> = profile
            .sources
            .iter()
            .map(|s| Unit {
                input: Input {
                    name: s.name.clone(),
                    text: s.text.clone(),
                    path: Some(profile.path.clone()),
                },
                diagnostics: Vec::new(),
                reports: Vec::new(),
                omitted: 0,
            })
            .collect();
        let file = profile.path.display().to_string();
        if profile.templates.is_empty() && !profile.has_errors() {
            self.notes
                .push(format!("{file}: no infill rotation template in this file"));
        }
        let mut model_notes: BTreeMap<String, ()> = BTreeMap::new();
        // One line index per text, not per template: a file of many templates stays linear.
        let indexes: Vec<LineIndex> = profile
            .sources
            .iter()
            .map(|s| LineIndex::new(&s.text))
            .collect();
        for found in &profile.templates {
            let parse = crate::check(&found.text, found.target);
            let mut lint = Vec::new();
            if compat_on(compat) && !parse.has_errors() {
                let pm =
                    profile.model(found.target, found.object.as_deref(), DEFAULT_OBJECT_HEIGHT);
                let found_here = pm.compat(&found.text, found.target);
                // The model's defaults explain the findings' layers and angles: said where
                // there are findings, not for every clean preset.
                if !found_here.is_empty() {
                    for n in &pm.notes_for(&found.text) {
                        model_notes.insert(printable(&format!("{file}: {n}")), ());
                    }
                }
                lint = found_here;
            }
            let counts = Counts::of(&parse, &lint);
            self.templates += 1;
            self.add(counts);
            let unit = &mut units[found.source];
            unit.omitted += parse.omitted;
            let mut diagnostics = parse.diagnostics;
            diagnostics.extend(lint);
            let omitted = unit.keep(&mut diagnostics) + parse.omitted;
            let moved: Vec<Diagnostic> = diagnostics
                .into_iter()
                .map(|d| into_file(d, found))
                .collect();
            let index = &indexes[found.source];
            if self.json {
                unit.reports.push(serde_json::json!({
                "input": found.text, "name": format!("{}: {}", unit.input.name, found.label()),
                "file": file, "source": unit.input.name, "key": found.key, "object": found.object,
                "target": match found.target { Target::Sparse => "sparse", Target::Solid => "solid" },
                "diagnostics": moved.iter().map(|d| diagnostic_json(index, d)).collect::<Vec<_>>(),
                "errors": counts.errors, "warnings": counts.warnings, "omitted": omitted,
            }));
            }
            unit.diagnostics.extend(moved);
        }
        for note in &profile.notes {
            let d = if note.error {
                Diagnostic::error("profile::invalid", note.message.clone())
            } else {
                Diagnostic::warning("profile::value", note.message.clone())
            }
            .with_primary(note.span, "here");
            self.count(std::slice::from_ref(&d));
            let unit = &mut units[note.source];
            let index = &indexes[note.source];
            let mut one = vec![d];
            let omitted = unit.keep(&mut one);
            if self.json {
                unit.reports.push(serde_json::json!({
                    "name": unit.input.name, "file": file, "source": unit.input.name,
                    "key": note.key, "object": null,
                    "diagnostics": one.iter().map(|d| diagnostic_json(index, d)).collect::<Vec<_>>(),
                    "errors": usize::from(note.error), "warnings": usize::from(!note.error),
                    "omitted": omitted,
                }));
            }
            unit.diagnostics.extend(one);
        }
        self.notes.extend(model_notes.into_keys());
        self.units.extend(units);
    }

    /// How many diagnostics were found and not listed, in every text.
    fn omitted_total(&self) -> usize {
        self.units.iter().map(|u| u.omitted).sum()
    }

    fn report(&self, args: &CheckArgs, out: &mut dyn Write) -> Result<(), UsageError> {
        let io = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
        match args.format {
            Format::Json => {
                for unit in &self.units {
                    for r in &unit.reports {
                        writeln!(out, "{r}").map_err(io)?;
                    }
                }
                for e in &self.file_errors {
                    let obj = serde_json::json!({"file": e.path.display().to_string(), "error": e.message});
                    writeln!(out, "{obj}").map_err(io)?;
                }
                // The notes the human report ends with (defaults used, files without a
                // template), one object each.
                for n in &self.notes {
                    writeln!(out, "{}", serde_json::json!({ "note": n })).map_err(io)?;
                }
            }
            Format::Human => {
                let reports: Vec<(&Input, &[Diagnostic])> = self
                    .units
                    .iter()
                    .filter(|u| !u.diagnostics.is_empty())
                    .map(|u| (&u.input, u.diagnostics.as_slice()))
                    .collect();
                out.write_all(render_human(&reports, args.color.enabled(true)).as_bytes())
                    .map_err(io)?;
                for e in &self.file_errors {
                    writeln!(out, "error: {e}").map_err(io)?;
                }
                for n in &self.notes {
                    writeln!(out, "note: {n}").map_err(io)?;
                }
                for u in self.units.iter().filter(|u| u.omitted > 0) {
                    writeln!(
                        out,
                        "note: {}: {} more diagnostics not shown (the first {} are)",
                        u.input.name,
                        u.omitted,
                        crate::MAX_DIAGNOSTICS
                    )
                    .map_err(io)?;
                }
                writeln!(out, "{}", self.summary()).map_err(io)?;
            }
        }
        Ok(())
    }

    fn summary(&self) -> String {
        let plural = |n: usize, w: &str| {
            if n == 1 {
                format!("1 {w}")
            } else {
                format!("{n} {w}s")
            }
        };
        let mut what = plural(self.templates, "template");
        if self.files > 0 {
            what.push_str(&format!(" in {}", plural(self.files, "file")));
        }
        let mut parts = vec![what];
        if self.errors > 0 {
            parts.push(plural(self.errors, "error"));
        }
        if self.warnings > 0 {
            parts.push(plural(self.warnings, "warning"));
        }
        if !self.file_errors.is_empty() {
            parts.push(format!(
                "{} not readable",
                plural(self.file_errors.len(), "file")
            ));
        }
        let failed = self.errors > 0 || !self.file_errors.is_empty();
        let head = if failed { "failed" } else { "ok" };
        if parts.len() == 1 {
            parts.push("no problems".to_owned());
        }
        let omitted = self.omitted_total();
        let tail = if omitted > 0 {
            format!(" ({omitted} not shown)")
        } else {
            String::new()
        };
        format!("{head}: {}{tail}", parts.join(", "))
    }
}

/// A template's diagnostic moved into the file it came from: spans through the offset
/// map, and the message naming the key (and object).
pub(crate) fn into_file(mut d: Diagnostic, found: &Found) -> Diagnostic {
    for l in &mut d.labels {
        l.span = found.span_in_source(l.span);
    }
    if let Some(fix) = &mut d.fix {
        // A fix inside an escape cannot be applied to the file as it stands.
        let moved = found.span_in_source(fix.span);
        if moved.len() == fix.span.len() {
            fix.span = moved;
        } else {
            d.fix = None;
        }
    }
    if found.key.is_some() {
        d.message = format!("{}: {}", found.label(), d.message);
    }
    d
}
