//! `rotlang gcode`: the infill direction a slicer printed on every layer, against the
//! template.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use crate::eval::Dialect;
use crate::gcode::{self, Comparison, Expected, Flavor, Layer, Scan};
use crate::number;

use super::{UsageError, args};

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang gcode part.gcode                          against the settings the file carries
  rotlang gcode part.gcode --template '0, 90'       against any template
  rotlang gcode part.gcode --format csv > layers.csv
  rotlang gcode part.gcode --plot layers.svg        measured dots over the template's line
  rotlang gcode - < part.gcode                      `-` is stdin

Reads G-code from OrcaSlicer, Bambu Studio, PrusaSlicer, SuperSlicer and Cura (their
layer-change and feature comments), streaming: any size in constant memory. For every
layer it measures the direction of the sparse infill and of the solid infill (degrees
counter-clockwise from +X, in [0, 180): the dominant direction of the feature's
extrusion moves) and how straight it is (the share of the length within 5° of it).

The expected direction comes from --template (read in OrcaSlicer's dialect for a file
of OrcaSlicer or Bambu Studio, rotlang's otherwise; see --dialect), or else from the
settings the file carries: OrcaSlicer's sparse_infill_rotate_template, PrusaSlicer's
fill_angle (crossed on every other layer for rectilinear), SuperSlicer's
fill_angle_template, Cura's infill_angles (;SETTING_3). The model is the file's own
layers, with the shell counts of its settings (or --bottom-shell-layers and
--top-shell-layers).

Columns: layer, z (mm), sparse direction, straightness, expected, difference
(measured − expected, in (−90, 90]), solid direction, and `ok`, `off` or `shell` (no
sparse infill). CSV: index,z,height,sparse,straightness,expected,difference,solid,match.
JSON: {\"file\", \"slicer\", \"generator\", \"expected\", \"tolerance\", \"compared\",
\"matched\", \"bytes\", \"layers\": [...], \"notes\": [...]}.

Exit status: 0 when every sparse layer matches (or nothing is compared), 1 when some do
not, 2 on a usage error (unreadable file, a template with errors).")]
pub struct GcodeArgs {
    /// The G-code file; `-` is stdin.
    #[arg(value_name = "FILE.gcode")]
    pub file: PathBuf,
    /// Compare with this template instead of the file's settings.
    #[arg(long, short = 't', value_name = "TEMPLATE", allow_hyphen_values = true)]
    pub template: Option<String>,
    /// How to read --template: `orcaslicer` (the default for OrcaSlicer and Bambu Studio
    /// files) or `rotlang` (the default for the others).
    #[arg(long, value_name = "DIALECT")]
    pub dialect: Option<Dialect>,
    /// The base direction in degrees added to --template's angles.
    #[arg(long, value_name = "DEG", default_value_t = 0.0, value_parser = args::finite,
          allow_negative_numbers = true)]
    pub base: f64,
    /// The largest difference (degrees) that still matches.
    #[arg(long, value_name = "DEG", default_value_t = 1.0, value_parser = args::finite)]
    pub tolerance: f64,
    /// The bottom shell layer count of the model [default: the file's settings, or 3].
    #[arg(long, value_name = "N", value_parser = args::shells)]
    pub bottom_shell_layers: Option<u32>,
    /// The top shell layer count of the model [default: the file's settings, or 4].
    #[arg(long, value_name = "N", value_parser = args::shells)]
    pub top_shell_layers: Option<u32>,
    /// `table`, `csv` or `json`.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Also draw the measured directions over the template's line (SVG).
    #[arg(long, value_name = "OUT.svg")]
    pub plot: Option<PathBuf>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    #[default]
    Table,
    Csv,
    Json,
}

fn io(e: std::io::Error) -> UsageError {
    UsageError(format!("cannot write output: {e}"))
}

/// Runs the command; returns the exit code.
pub fn run(args: &GcodeArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    let name = args.file.display().to_string();
    let scanned = if args.file.as_os_str() == "-" {
        gcode::scan_all(std::io::stdin().lock(), &Default::default())
    } else {
        let file = std::fs::File::open(&args.file)
            .map_err(|e| UsageError(format!("cannot read {name}: {e}")))?;
        gcode::scan_all(file, &Default::default())
    }
    .map_err(|e| UsageError(format!("cannot read {name}: {e}")))?;
    let mut notes = Vec::new();
    if scanned.layers.is_empty() {
        return Err(UsageError(format!(
            "{name}: no layers found: no layer-change comments (;LAYER_CHANGE, ; CHANGE_LAYER, \
             ;LAYER:n) [{}]",
            "slicer::no-layers"
        )));
    }
    if scanned.flavor == Flavor::Unknown {
        notes.push("the file names no known slicer in its header: layers and features are read from the comments found".to_owned());
    }
    let model = gcode::model(&scanned.layers, &scanned.settings).map_err(UsageError)?;
    let (bottom, top) = (
        args.bottom_shell_layers.unwrap_or(model.bottom_shells()),
        args.top_shell_layers.unwrap_or(model.top_shells()),
    );
    let model = model.with_shells(bottom, top);
    let (expected, source) = match &args.template {
        Some(t) => {
            let dialect = args.dialect.unwrap_or(if scanned.flavor.is_orca_family() {
                Dialect::OrcaSlicer
            } else {
                Dialect::Rotlang
            });
            (
                Some(Expected::Template {
                    text: t.clone(),
                    dialect,
                    base: args.base,
                    seed: 0,
                }),
                format!("--template {t} ({} reading)", dialect.name()),
            )
        }
        None => match gcode::expected_from_settings(scanned.flavor, &scanned.settings) {
            Some((e, source, more)) => {
                notes.extend(more);
                (Some(e), source)
            }
            None => (
                None,
                "nothing to compare (no settings; pass --template)".to_owned(),
            ),
        },
    };
    let comparison = match &expected {
        Some(e) => {
            gcode::compare(&scanned.layers, &model, e, args.tolerance).map_err(UsageError)?
        }
        None => unchecked(&scanned.layers, args.tolerance),
    };
    let written = match args.format {
        Format::Table => table(&scanned, &comparison, &source, &notes, out),
        Format::Csv => csv(&comparison, out),
        Format::Json => {
            let v = serde_json::json!({
                "file": name,
                "slicer": scanned.flavor.name(),
                "generator": scanned.generator,
                "expected": source,
                "tolerance": comparison.tolerance,
                "compared": comparison.compared,
                "matched": comparison.matched,
                "bytes": scanned.bytes,
                "layers": comparison.rows,
                "notes": notes,
            });
            writeln!(out, "{v}")
        }
    };
    written.map_err(io)?;
    if args.format != Format::Table {
        for n in &notes {
            writeln!(err, "note: {n}").map_err(io)?;
        }
    }
    if let Some(path) = &args.plot {
        let svg = plot(&comparison, &model, &source);
        std::fs::write(path, svg)
            .map_err(|e| UsageError(format!("cannot write {}: {e}", path.display())))?;
    }
    Ok(if comparison.matched == comparison.compared {
        0
    } else {
        1
    })
}

fn unchecked(layers: &[Layer], tolerance: f64) -> Comparison {
    Comparison {
        rows: layers
            .iter()
            .map(|l| gcode::Row {
                index: l.index,
                z: l.z,
                height: l.height,
                sparse: l.sparse,
                solid: l.solid,
                expected: None,
                difference: None,
                matches: None,
            })
            .collect(),
        compared: 0,
        matched: 0,
        tolerance,
    }
}

fn opt(v: Option<f64>, f: impl Fn(f64) -> String) -> String {
    v.map_or_else(|| "-".to_owned(), f)
}

fn deg(v: f64) -> String {
    format!("{v:.2}")
}

fn table(
    scan: &Scan,
    c: &Comparison,
    source: &str,
    notes: &[String],
    out: &mut dyn Write,
) -> std::io::Result<()> {
    writeln!(
        out,
        "{} · {} layers · expected: {source}",
        scan.generator.as_deref().unwrap_or(scan.flavor.name()),
        c.rows.len()
    )?;
    for n in notes {
        writeln!(out, "note: {n}")?;
    }
    writeln!(
        out,
        "{:>5} {:>8} {:>8} {:>8} {:>9} {:>7} {:>8}  match",
        "layer", "z", "sparse", "straight", "expected", "diff", "solid"
    )?;
    for r in &c.rows {
        let verdict = match r.matches {
            Some(true) => "ok",
            Some(false) => "OFF",
            None if r.solid.is_some() => "shell",
            None => "-",
        };
        writeln!(
            out,
            "{:>5} {:>8} {:>8} {:>8} {:>9} {:>7} {:>8}  {verdict}",
            r.index,
            opt(r.z, |z| number::height(z).as_str().to_owned()),
            opt(r.sparse.map(|d| d.direction), deg),
            opt(r.sparse.map(|d| d.straightness), |s| format!("{s:.2}")),
            opt(r.expected, deg),
            opt(r.difference, deg),
            opt(r.solid.map(|d| d.direction), deg),
        )?;
    }
    writeln!(
        out,
        "matched {} of {} sparse layers within {}°",
        c.matched,
        c.compared,
        number::angle(c.tolerance).as_str()
    )
}

fn csv(c: &Comparison, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(
        out,
        "index,z,height,sparse,straightness,expected,difference,solid,match"
    )?;
    let f = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.4}"));
    for r in &c.rows {
        writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            r.index,
            f(r.z),
            f(r.height),
            f(r.sparse.map(|d| d.direction)),
            f(r.sparse.map(|d| d.straightness)),
            f(r.expected),
            f(r.difference),
            f(r.solid.map(|d| d.direction)),
            r.matches.map_or("", |m| if m { "ok" } else { "off" })
        )?;
    }
    Ok(())
}

/// The picture: layers across, direction (0–180°) up; the expected line, the measured
/// sparse dots (red when off), the solid dots (grey squares), shell layers shaded.
fn plot(c: &Comparison, model: &crate::eval::Model, source: &str) -> String {
    let (w, h, left, top, right, bottom) = (900.0, 420.0, 60.0, 40.0, 20.0, 50.0);
    let n = c.rows.len().max(1) as f64;
    let pw = w - left - right;
    let ph = h - top - bottom;
    let x = |i: f64| left + (i + 0.5) / n * pw;
    let y = |d: f64| top + (1.0 - d / 180.0) * ph;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12\">"
    );
    let _ = writeln!(s, "<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>");
    let esc = |t: &str| t.replace('&', "&amp;").replace('<', "&lt;");
    let _ = writeln!(
        s,
        "<text x=\"{left}\" y=\"20\">measured infill direction per layer · expected: {}</text>",
        esc(source)
    );
    // Shell layers: solid infill and no sparse infill.
    let bw = pw / n;
    for r in &c.rows {
        if r.sparse.is_none() && r.solid.is_some() {
            let _ = writeln!(
                s,
                "<rect class=\"shell\" x=\"{:.2}\" y=\"{top}\" width=\"{:.2}\" height=\"{ph}\" fill=\"#eee\"/>",
                x(r.index as f64) - bw / 2.0,
                bw
            );
        }
    }
    for d in [0.0, 45.0, 90.0, 135.0, 180.0] {
        let _ = writeln!(
            s,
            "<line x1=\"{left}\" x2=\"{0}\" y1=\"{1:.2}\" y2=\"{1:.2}\" stroke=\"#ccc\"/><text x=\"{2}\" y=\"{3:.2}\" text-anchor=\"end\">{d}°</text>",
            w - right,
            y(d),
            left - 6.0,
            y(d) + 4.0
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">layer (0 to {}; B = {}, T = {})</text>",
        left + pw / 2.0,
        h - 15.0,
        c.rows.len().saturating_sub(1),
        model.bottom_shells(),
        model.top_shells()
    );
    // The expected line, broken where it wraps past 0/180.
    let mut path = String::new();
    let mut last: Option<f64> = None;
    for r in &c.rows {
        if let Some(e) = r.expected {
            let jump = last.is_none_or(|l| (l - e).abs() > 90.0);
            let _ = write!(
                path,
                "{}{:.2},{:.2} ",
                if jump { "M" } else { "L" },
                x(r.index as f64),
                y(e)
            );
            last = Some(e);
        }
    }
    if !path.is_empty() {
        let _ = writeln!(
            s,
            "<path class=\"expected\" d=\"{}\" fill=\"none\" stroke=\"#2060c0\" stroke-width=\"1.5\"/>",
            path.trim_end()
        );
    }
    for r in &c.rows {
        if let Some(d) = r.solid {
            let _ = writeln!(
                s,
                "<rect class=\"solid\" x=\"{:.2}\" y=\"{:.2}\" width=\"4\" height=\"4\" fill=\"#888\"/>",
                x(r.index as f64) - 2.0,
                y(d.direction) - 2.0
            );
        }
        if let Some(d) = r.sparse {
            let colour = if r.matches == Some(false) {
                "#d02020"
            } else {
                "#202020"
            };
            let _ = writeln!(
                s,
                "<circle class=\"sparse\" cx=\"{:.2}\" cy=\"{:.2}\" r=\"2.5\" fill=\"{colour}\"/>",
                x(r.index as f64),
                y(d.direction)
            );
        }
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"20\" text-anchor=\"end\">{} of {} sparse layers match</text>",
        w - right,
        c.matched,
        c.compared
    );
    s.push_str("</svg>\n");
    s
}
