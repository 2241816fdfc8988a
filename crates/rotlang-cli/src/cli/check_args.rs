//! The options of `rotlang check` (`CheckArgs`), read by the check of templates
//! (check.rs), of files (files.rs) and their fixes (fix_files.rs).

use std::path::PathBuf;

use super::{ColorArg, TargetArg};

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
slicing). It runs on every input, whatever its size, as in the language server.

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
    pub compat: Option<CompatArg>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    #[default]
    Human,
    Json,
}

/// `--compat`: which slicer to compare with (OrcaSlicer unless `none`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CompatArg {
    /// OrcaSlicer's own reading (SEMANTICS section 10): the default
    Orcaslicer,
    /// rotlang's reading alone
    None,
}

/// Whether the OrcaSlicer lint runs: always, unless `--compat none`. It runs on inputs of
/// every size, as the language server's does, so `check` and the editor give one answer; its
/// memory stays within 16× the text (`tests/profile_memory.rs`) and it about doubles the
/// time of `check` on a template of megabytes.
pub(crate) fn compat_on(compat: Option<CompatArg>) -> bool {
    compat != Some(CompatArg::None)
}
