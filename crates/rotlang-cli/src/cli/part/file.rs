//! What a part is filled with: its templates, model, infill and walls, from the command
//! line, else from a profile (`--profile`) or the OrcaSlicer project the mesh comes from
//! (`rotlang preview project.3mf`: `Metadata/project_settings.config`, and the object's
//! overrides in `Metadata/model_settings.config`, read as `check` reads them).

use std::io::Write;
use std::path::Path;

use super::super::preview::PreviewArgs;
use super::super::{Input, UsageError};
use crate::eval::{Model, Options};
use crate::infill::{Pattern, Settings};
use crate::plot::num;
use crate::profile::{self, Profile};
use crate::{Parse, Target};

/// Everything the part is filled with.
pub(super) struct Plan {
    pub input: Input,
    pub parse: Parse,
    /// The solid template, when one turns the solid areas.
    pub solid: Option<(Input, Parse)>,
    pub model: Model,
    pub options: Options,
    pub solid_options: Options,
    pub settings: Settings,
    pub walls: u32,
    /// What came from the file, said on stderr.
    pub notes: Vec<String>,
}

/// The plan for the mesh `shape` (`project`: an OrcaSlicer project, whose settings apply
/// without --profile), `height` mm tall, under the template `text` (or --file), if given.
/// `Err(1)` when a template or the file has errors (reported on `err`).
pub(super) fn plan(
    args: &PreviewArgs,
    shape: &str,
    text: Option<&String>,
    (height, project): (f64, bool),
    err: &mut dyn Write,
) -> Result<Result<Plan, i32>, UsageError> {
    let io = |e: std::io::Error| UsageError(format!("cannot write to stderr: {e}"));
    let target: Target = args.target.into();
    let path = match (&args.profile.profile, project) {
        (Some(p), _) => Some(p.clone()),
        (None, true) => Some(shape.into()),
        (None, false) => None,
    };
    let file = match &path {
        Some(p) => {
            let file = profile::read(p).map_err(|e| UsageError(e.to_string()))?;
            if file.has_errors() {
                err.write_all(super::super::from_profile::errors_report(&file).as_bytes())
                    .map_err(io)?;
                return Ok(Err(1));
            }
            Some(file)
        }
        None => None,
    };
    let object = args.profile.object.as_deref();
    let own = file.as_ref().and_then(|f| f.object_settings(object));
    let mut notes = Vec::new();
    let color = args.color.enabled(false);
    // The sparse template: the command line's (or stdin, as for any shape, when neither
    // it nor a file says), else the file's (the object's own first). `rotlang preview
    // part.stl` passes an empty one: the file's, or every layer at the base direction.
    let given = match text {
        Some(t) => !t.is_empty(),
        None => args.file.is_some() || file.is_none(),
    };
    let input = if given {
        match super::super::paths::source(
            text,
            args.file.as_ref(),
            &Default::default(),
            target,
            None,
            err,
        )? {
            Ok(s) => s.input,
            Err(code) => return Ok(Err(code)),
        }
    } else {
        match (&file, &path) {
            (Some(f), Some(p)) => from_file(f, p, target, object),
            _ => Input {
                name: "<template>".into(),
                text: String::new(),
                path: None,
            },
        }
    };
    let Some(parse) = parsed(&input, target, color, err)? else {
        return Ok(Err(1));
    };
    let solid_input = match (&args.part.solid_template, &file, &path) {
        (Some(t), ..) => Some(Input {
            name: "--solid-template".into(),
            text: t.clone(),
            path: None,
        }),
        (None, Some(f), Some(p)) if !args.part.no_solid_template => {
            let found = from_file(f, p, Target::Solid, object);
            found.path.is_some().then_some(found)
        }
        _ => None,
    };
    let solid = match solid_input {
        Some(i) => match parsed(&i, Target::Solid, color, err)? {
            Some(parse) => Some((i, parse)),
            None => return Ok(Err(1)),
        },
        None => None,
    };
    // The model: --height or --model as given; else as tall as the mesh, in the file's
    // layers and shells unless the options say otherwise.
    let m = &args.model;
    let sparse_model = file.as_ref().map(|f| f.settings.model(own, target, height));
    let model = if m.height.is_some() || m.model.is_some() {
        m.build(None)?
    } else {
        let (h, first, bottom, top) = match &sparse_model {
            Some(pm) => (
                pm.model.layer_height(),
                pm.model.layer_bounds(0).map(|(_, t)| t),
                pm.model.bottom_shells(),
                pm.model.top_shells(),
            ),
            None => (0.2, None, 3, 4),
        };
        let model = Model::from_total_height(
            height.max(1e-3),
            m.layer_height.unwrap_or(h),
            m.first_layer_height.or(first),
        )
        .map_err(|e| UsageError(format!("invalid model: {e}")))?;
        model.with_shells(
            m.bottom_shell_layers.unwrap_or(bottom),
            m.top_shell_layers.unwrap_or(top),
        )
    };
    // A profile's direction turns an empty template only; --base replaces it.
    let options_for = |text: &str, t: Target| {
        let mut options = m.options();
        if options.base == 0.0
            && let Some(f) = &file
        {
            options.base = f.settings.model(own, t, height).options(text).base;
        }
        options
    };
    let options = options_for(&input.text, target);
    let solid_options = solid
        .as_ref()
        .map_or(options, |(i, _)| options_for(&i.text, Target::Solid));
    // The infill: each option given, else the file's, else the default.
    let mut settings = args.settings();
    let mut walls = args.part.walls.unwrap_or(2);
    if let (Some(f), Some(p)) = (&file, &path) {
        let from = f.part_infill(object);
        notes.extend(from.notes.iter().cloned());
        // The file's pattern names are rotlang's (`PartInfill`): they always parse.
        let pattern = |name: Option<&str>| name.and_then(|n| n.parse::<Pattern>().ok());
        let mut used = Vec::new();
        if let (None, Some(v)) = (args.pattern, pattern(from.pattern)) {
            settings.pattern = v;
            used.push(format!("sparse_infill_pattern {v}"));
        }
        if let (None, Some(v)) = (args.density, from.density) {
            settings.density = v;
            used.push(format!("sparse_infill_density {}%", num(v * 100.0, 3)));
        }
        if let (None, Some(v)) = (args.solid_pattern, pattern(from.solid_pattern)) {
            settings.solid_pattern = v;
            used.push(format!("internal_solid_infill_pattern {v}"));
        }
        if let (None, Some(v)) = (args.nozzle, from.line_width) {
            settings.nozzle = v;
            used.push(format!("line width {} mm", num(v, 4)));
        }
        if let (None, Some(v)) = (args.part.walls, from.walls) {
            walls = v;
            used.push(format!("wall_loops {v}"));
        }
        if let Some(pm) = sparse_model
            .as_ref()
            .filter(|_| m.height.is_none() && m.model.is_none())
        {
            notes.extend(pm.notes_for(&input.text));
        }
        let of = match (own, object) {
            (Some(_), Some(o)) => format!(" with object {o}'s overrides"),
            (None, Some(o)) => format!(" (object {o} overrides none of these)"),
            _ => String::new(),
        };
        let template = match (given, &solid) {
            (true, _) => String::new(),
            (false, _) => format!("{} `{}`, ", label(target), input.text),
        };
        let solid_text = match (&args.part.solid_template, &solid) {
            (None, Some((i, _))) => format!("{} `{}`, ", label(Target::Solid), i.text),
            (None, None)
                if args.part.no_solid_template
                    && from_file(f, p, Target::Solid, object).path.is_some() =>
            {
                format!(
                    "{} `{}` not used (--no-solid-template), ",
                    label(Target::Solid),
                    from_file(f, p, Target::Solid, object).text
                )
            }
            _ => String::new(),
        };
        used.insert(
            0,
            format!(
                "{template}{solid_text}{} layers of {} mm, B = {}, T = {}",
                model.len(),
                num(model.layer_height(), 4),
                model.bottom_shells(),
                model.top_shells()
            ),
        );
        notes.insert(0, format!("{}{of}: {}", p.display(), used.join(", ")));
        if object.is_none() && !f.objects.is_empty() {
            let names: Vec<&str> = f.objects.iter().map(|(n, _)| n.as_str()).collect();
            notes.push(format!(
                "objects with their own overrides: {} (--object NAME previews one with them)",
                names.join(", ")
            ));
        }
    }
    Ok(Ok(Plan {
        input,
        parse,
        solid,
        model,
        options,
        solid_options,
        settings,
        walls,
        notes: notes
            .iter()
            .map(|n| super::super::from_profile::printable(n))
            .collect(),
    }))
}

fn label(target: Target) -> &'static str {
    profile::TEMPLATE_KEYS
        .iter()
        .find(|(_, t)| *t == target)
        .map_or("template", |(k, _)| k)
}

/// The file's template of `target`: the object's own, else the project's (not another
/// object's); an empty one, with no path, when it has none (OrcaSlicer's default).
fn from_file(file: &Profile, path: &Path, target: Target, object: Option<&str>) -> Input {
    let found = file.part_template(target, object);
    match found {
        Some(f) => Input {
            name: format!("{}: {}", path.display(), f.label()),
            text: f.text.clone(),
            path: Some(path.to_owned()),
        },
        None => Input {
            name: "<template>".into(),
            text: String::new(),
            path: None,
        },
    }
}

/// `input` parsed, its diagnostics written to `err`; `None` when it has errors.
fn parsed(
    input: &Input,
    target: Target,
    color: bool,
    err: &mut dyn Write,
) -> Result<Option<Parse>, UsageError> {
    let parse = crate::parse(&input.text, target);
    if !parse.diagnostics.is_empty() {
        let report = super::super::render_diagnostics(input, &parse.diagnostics, color);
        err.write_all(report.as_bytes())
            .map_err(|e| UsageError(format!("cannot write to stderr: {e}")))?;
    }
    Ok((!parse.has_errors()).then_some(parse))
}

/// Whether a 3MF holds OrcaSlicer's settings (`Metadata/*.config`): a project.
pub(super) fn is_project(bytes: &[u8]) -> bool {
    rotlang_profile::profile::is_project(bytes)
}
