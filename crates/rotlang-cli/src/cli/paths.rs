//! One rule, for every command, for telling a file from a template in an argument.
//!
//! An argument is a path when it looks like one: it ends in an extension rotlang reads
//! (`.rot`, `.json`, `.jsonc`, `.ini`, `.3mf`), or it has a path separator next to a name
//! (`profiles/`, `./a`, `~/presets`, `C:\x`; with a space in it only when it exists), or
//! it names an existing folder. Everything
//! else is a template, even `/` alone (a joint sign) and `+30/50%` (no name in it). A path
//! that does not exist is "no such file", never a template with unknown signs. `--file`
//! and `--profile` force the choice.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use super::UsageError;
use crate::profile::Kind;

/// Whether `arg` is read as a path (see the module documentation).
pub fn looks_like_path(arg: &str) -> bool {
    if arg == "-" || arg.is_empty() {
        return false;
    }
    let path = Path::new(arg);
    if Kind::from_extension(path).is_some() {
        return true;
    }
    // A separator next to a name; with a space in it (`+45/10 layers`, a template with a
    // typo), only when it exists.
    if arg.contains(['/', '\\'])
        && arg.split(['/', '\\']).any(is_name)
        && (!arg.contains(char::is_whitespace) || path.exists())
    {
        return true;
    }
    is_name(arg) && path.is_dir()
}

/// A file or folder name, not a piece of a template: `.`, `..`, `~…`, or a word of two
/// letters or more that is not a unit of the language (`mm`, `cm`).
fn is_name(part: &str) -> bool {
    if matches!(part, "." | "..") || part.starts_with('~') {
        return true;
    }
    part.split(|c: char| !c.is_alphabetic())
        .any(|word| word.chars().count() >= 2 && !matches!(word, "mm" | "cm"))
}

/// The error for a path that is not there: said first, before anything is read.
pub fn missing(arg: &str) -> Option<UsageError> {
    let path = Path::new(arg);
    (!path.exists()).then(|| {
        UsageError(format!(
            "{arg}: no such file or folder (an argument ending in .rot, .json, .jsonc, .ini \
             or .3mf, or with a folder name, is a path; pass a template in quotes, e.g. \
             rotlang check '+30/50%')"
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::looks_like_path;

    #[test]
    fn paths_and_templates() {
        for path in [
            "nosuch.json",
            "a.rot",
            "process/0.20mm Rotating Gyroid.json",
            "profiles/",
            "./x",
            "~/presets",
            "/tmp",
            "../up",
            "C:\\presets",
            "PROJECT.3MF",
        ] {
            assert!(looks_like_path(path), "{path}");
        }
        for template in [
            "/",
            "+30/50%",
            "+30/5mm",
            "+10/B",
            "0 90",
            "-",
            "",
            "10!, 5*",
            "+30/ 50%",
            "B!, +30",
            "+10L25%, -10l25%",
            "+30/2cm",
            "+45/10 layers",
        ] {
            assert!(!looks_like_path(template), "{template}");
        }
    }
}

/// `--profile` and `--object`, for the commands that draw or explain one template.
#[derive(clap::Args, Debug, Default, Clone)]
pub struct ProfileArgs {
    /// Take the template (of --target) and the model from a profile: an OrcaSlicer preset
    /// (.json), an exported .ini or a .3mf project, as `expand --profile` does (its layer
    /// heights and shell counts; its infill direction turns an empty template only).
    #[arg(long, value_name = "PATH")]
    pub profile: Option<PathBuf>,
    /// With a .3mf project: the object whose overrides apply (its template, layer height,
    /// shells); `--profile project.3mf` alone lists the objects. In `preview` with a
    /// .3mf mesh as --shape, also the object drawn (default: every object, as on the plate).
    #[arg(long, value_name = "NAME")]
    pub object: Option<String>,
}

/// Where one command's template comes from.
pub enum Choice {
    Text(String),
    File(PathBuf),
    Profile(PathBuf),
}

/// The choice for a command of one template: `--profile`, `--file`, or the argument by
/// the one rule (a path that is missing or a folder is a usage error, said first).
pub fn choose(
    template: Option<&String>,
    file: Option<&PathBuf>,
    profile: Option<&PathBuf>,
    err: &mut dyn Write,
) -> Result<Option<Choice>, UsageError> {
    if let Some(p) = profile {
        return Ok(Some(Choice::Profile(p.clone())));
    }
    if let Some(f) = file {
        return Ok(Some(Choice::File(f.clone())));
    }
    let Some(t) = template else { return Ok(None) };
    if !looks_like_path(t) {
        if t != "-" && Path::new(t).is_file() {
            writeln!(
                err,
                "note: `{t}` is read as a template, but it is also a file: to read the file, \
                 pass --file {0} (a template) or --profile {0} (a profile)",
                super::shell_quote(t)
            )
            .map_err(|e| UsageError(e.to_string()))?;
        }
        return Ok(Some(Choice::Text(t.clone())));
    }
    if let Some(e) = missing(t) {
        return Err(e);
    }
    let path = PathBuf::from(t);
    if path.is_dir() {
        return Err(UsageError(format!(
            "{t} is a folder: this command reads one template (`rotlang check {}` checks \
             every profile in it)",
            super::shell_quote(t)
        )));
    }
    Ok(Some(match Kind::from_extension(&path) {
        Some(Kind::Template) => Choice::File(path),
        Some(_) => Choice::Profile(path),
        None => match sniff(&path) {
            Kind::Template => Choice::File(path),
            _ => Choice::Profile(path),
        },
    }))
}

/// The kind of a file by its first bytes (a bounded read: `/dev/zero` is a path too).
fn sniff(path: &Path) -> Kind {
    let mut head = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(4096).read_to_end(&mut head);
    }
    Kind::detect(path, &head)
}

/// The template of a one-template command, and the profile it came from, if any.
pub(crate) struct Source {
    pub input: super::Input,
    pub profile: Option<super::files::ProfileTemplate>,
}

/// Reads what [`choose`] chose: the profile's notes go to `err`; a profile with errors is
/// reported as `check` reports it and gives `Err(1)`.
pub(crate) fn source(
    template: Option<&String>,
    file: Option<&PathBuf>,
    profile: &ProfileArgs,
    target: crate::Target,
    height: Option<f64>,
    err: &mut dyn Write,
) -> Result<Result<Source, i32>, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write to stderr: {e}"));
    if profile.object.is_some()
        && profile.profile.is_none()
        && !matches!(template, Some(t) if looks_like_path(t))
    {
        return Err(UsageError(
            "--object needs a profile (--profile project.3mf)".into(),
        ));
    }
    if profile.profile.is_some() && (template.is_some() || file.is_some()) {
        return Err(UsageError(
            "--profile takes the template from the profile: give no template or --file".into(),
        ));
    }
    let choice = choose(template, file, profile.profile.as_ref(), err)?;
    let (templates, files): (Vec<String>, Vec<PathBuf>) = match choice {
        Some(Choice::Profile(path)) => {
            let p =
                super::files::profile_template(&path, target, profile.object.as_deref(), height)?;
            if let Some(report) = &p.errors {
                err.write_all(report.as_bytes()).map_err(io)?;
                return Ok(Err(1));
            }
            for note in &p.notes {
                writeln!(err, "note: {note}").map_err(io)?;
            }
            let input = super::Input {
                name: path.display().to_string(),
                text: p.text.clone(),
                path: Some(path),
            };
            return Ok(Ok(Source {
                input,
                profile: Some(p),
            }));
        }
        Some(Choice::File(f)) => (Vec::new(), vec![f]),
        Some(Choice::Text(t)) => (vec![t], Vec::new()),
        None => (Vec::new(), Vec::new()),
    };
    let input = super::gather(&templates, &files)?
        .into_iter()
        .next()
        .ok_or_else(|| UsageError("no template given".into()))?;
    Ok(Ok(Source {
        input,
        profile: None,
    }))
}
