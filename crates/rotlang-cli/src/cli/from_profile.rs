//! `--profile PATH` (expand, plot, preview, explain, export): the template of a profile,
//! preset or project with its model, its notes and its errors.

use std::path::Path;

use super::{Input, UsageError, render_human};
use crate::Target;
use crate::diagnostic::Diagnostic;
use crate::eval::Model;
use crate::profile::{self, DEFAULT_OBJECT_HEIGHT, Profile};

/// `rotlang expand --profile PATH` (and `plot`, `preview`, `explain`): the template of
/// `target` in the file (the project's own for a 3mf, or `object`'s), on the profile's
/// model unless the command line gives one, with the profile's direction where it applies
/// (an empty template).
pub(crate) struct ProfileTemplate {
    pub text: String,
    pub model: Model,
    /// The base of this template in either reading ([`profile::ProfileModel::options`]).
    pub base: f64,
    pub notes: Vec<String>,
    /// The file's errors as `check` reports them (`profile::invalid`): the command stops
    /// with exit 1 after printing them.
    pub errors: Option<String>,
}

pub(crate) fn profile_template(
    path: &Path,
    target: Target,
    object: Option<&str>,
    height: Option<f64>,
) -> Result<ProfileTemplate, UsageError> {
    let profile = profile::read(path).map_err(|e| UsageError(e.to_string()))?;
    let names: Vec<&str> = profile.objects.iter().map(|(n, _)| n.as_str()).collect();
    let found = match object {
        Some(o) => {
            if !names.contains(&o) {
                let known = if names.is_empty() {
                    "it has no per-object settings".to_owned()
                } else {
                    format!("its objects: {}", names.join(", "))
                };
                return Err(UsageError(format!(
                    "{}: no object `{o}`; {known}",
                    path.display()
                )));
            }
            // The object's own template, else the project's.
            match profile
                .templates
                .iter()
                .find(|f| f.target == target && f.object.as_deref() == Some(o))
            {
                Some(f) => Ok(f),
                None => profile.template(target),
            }
        }
        None => profile.template(target),
    };
    let found = match found {
        Ok(f) => f,
        Err(why) if profile.has_errors() => {
            let _ = why;
            return Ok(ProfileTemplate {
                text: String::new(),
                model: Model::cube20(),
                base: 0.0,
                notes: Vec::new(),
                errors: Some(errors_report(&profile)),
            });
        }
        Err(why) => return Err(UsageError(format!("{}: {why}", path.display()))),
    };
    let pm = profile.model(
        target,
        object.or(found.object.as_deref()),
        height.unwrap_or(DEFAULT_OBJECT_HEIGHT),
    );
    let base = pm.options(&found.text).base;
    let mut notes: Vec<String> = pm
        .notes_for(&found.text)
        .iter()
        .map(|n| printable(n))
        .collect();
    let direction = match (&pm.direction.key, found.text.is_empty()) {
        (Some(key), true) => format!(", {key} {}°", pm.direction.degrees),
        (None, true) => format!(", OrcaSlicer's default direction {}°", pm.direction.degrees),
        // The direction turns an empty template only: name it where the file sets it.
        (Some(key), false) => format!(
            ", {key} {}° not applied (it turns an empty template only)",
            pm.direction.degrees
        ),
        (None, false) => String::new(),
    };
    let label = match (object, &found.object) {
        (Some(o), None) => format!("{} (for object {o})", found.label()),
        _ => found.label(),
    };
    notes.insert(
        0,
        format!(
            "{}: {label} `{}` ({} layers of {} mm, B = {}, T = {}{direction})",
            path.display(),
            found.text,
            pm.model.len(),
            pm.model.layer_height(),
            pm.model.bottom_shells(),
            pm.model.top_shells()
        ),
    );
    notes[0] = printable(&notes[0]);
    if object.is_none() && !names.is_empty() {
        notes.push(format!(
            "{}: objects {} (--object NAME applies an object's overrides)",
            path.display(),
            names.join(", ")
        ));
    }
    Ok(ProfileTemplate {
        text: found.text.clone(),
        model: pm.model,
        base,
        notes,
        errors: profile.has_errors().then(|| errors_report(&profile)),
    })
}

/// A note as printed on a terminal: control characters from the file (a NUL in `inherits`,
/// an escape sequence) written as escapes (`\u{0}`), so they neither vanish nor drive the
/// terminal.
pub(crate) fn printable(note: &str) -> String {
    if !note.contains(char::is_control) {
        return note.to_owned();
    }
    note.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// A profile's errors as `check` reports them (`error[profile::invalid]`, with the line).
pub(crate) fn errors_report(profile: &Profile) -> String {
    let mut units: Vec<(Input, Vec<Diagnostic>)> = profile
        .sources
        .iter()
        .map(|s| {
            let input = Input {
                name: s.name.clone(),
                text: s.text.clone(),
                path: Some(profile.path.clone()),
            };
            (input, Vec::new())
        })
        .collect();
    for note in profile.notes.iter().filter(|n| n.error) {
        if let Some((_, ds)) = units.get_mut(note.source) {
            ds.push(
                Diagnostic::error("profile::invalid", note.message.clone())
                    .with_primary(note.span, "here"),
            );
        }
    }
    let reports: Vec<(&Input, &[Diagnostic])> = units
        .iter()
        .filter(|(_, ds)| !ds.is_empty())
        .map(|(i, ds)| (i, ds.as_slice()))
        .collect();
    format!(
        "{}{}: not read: fix the errors first (`rotlang check` reports the same)\n",
        render_human(&reports, false),
        profile.path.display()
    )
}
