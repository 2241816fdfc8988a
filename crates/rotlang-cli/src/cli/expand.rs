//! `rotlang expand`: the angle and fill of every layer of a model, streamed.

use std::io::{BufWriter, ErrorKind, Write};
use std::path::PathBuf;

use super::model::{ModelArgs, Resolved};
use super::{ColorArg, Input, TargetArg, UsageError, args, diagnostic_json};
use crate::diagnostic::LineIndex;
use crate::eval::{self, Layer, Options};
use crate::number;

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang expand '5, 10!, +20'                       the 20 mm cube (100 × 0.2 mm, B=3, T=4)
  rotlang expand '+30/50%' --layers 300 --layer-height 0.12 --first-layer-height 0.2
  rotlang expand '+10L25%, -10l25%' --height 42 --wrap 180 --format csv > angles.csv
  rotlang expand 'B!, +30' --model part.json --format json
  rotlang expand '+30/50%' --model models.json:first-layer   one model of a map of models
  rotlang expand '+30/50%' --range 40..60            layers 40 to 59 only
  rotlang expand -- -50%Z1cm                          a template that begins with '-'
  rotlang expand --file profile.rot --base 45         from a file, infill direction 45°
  rotlang expand - < profile.rot                      `-` is stdin (also --file -)

A --model file is one JSON object, like an entry of the conformance models.json:
  {\"layer_heights\": [0.3, 0.2, 0.2], \"layer_height\": 0.2,
   \"bottom_shell_layers\": 3, \"top_shell_layers\": 4, \"description\": \"optional\"}
(the shell counts default to 3 and 4), or an object of such objects by name: then
--model FILE:NAME picks one.

Output columns: the layer index, its bottom and top height (mm, to the micrometre), the
angle (degrees, base included, to 1e-9°), the fill (sparse, or dense/solid/concentric/
monotonic/rectilinear for solid signs; solid for every layer with --target solid) and
the governing instruction: its text in the table; in CSV its byte offsets start,end
into the template and its text; in JSON {\"start\", \"end\", \"text\"}. It is empty
(null in JSON, `(holds)` in the table) when every instruction is spent and the angle
holds. JSON also echoes the template, the model and the options.

Exit status: 0 on success (warnings are printed to stderr), 1 when the template has
errors (nothing is expanded; with --format json the diagnostics are printed as JSON, as
`rotlang check --format json` does), 2 on a usage error (bad model, conflicting options).")]
pub struct ExpandArgs {
    /// The template to expand, e.g. '+30/50%'. Put `--` before one that begins with `-`.
    /// Without it, the template is read from --file or stdin; `-` is stdin. An existing
    /// file named here is read as --profile (.json, .jsonc, .ini, .3mf) or --file (.rot).
    #[arg(
        value_name = "TEMPLATE",
        allow_negative_numbers = true,
        conflicts_with = "file"
    )]
    pub template: Option<String>,
    /// Read the template from a file (newlines separate instructions); `-` is stdin.
    #[arg(long, short = 'f', value_name = "PATH")]
    pub file: Option<PathBuf>,
    /// Take the template (of --target) and the model from a profile: an OrcaSlicer preset
    /// (.json), an exported .ini or a .3mf project. Layer heights and shell counts come
    /// from the profile (notes on stderr name every default used); its infill direction
    /// is the angle of an empty template only, as in OrcaSlicer; the object is 20 mm tall
    /// unless --height, --layers or --model; a --base other than 0 is added to every angle
    /// instead.
    #[arg(long, value_name = "PATH", conflicts_with_all = ["template", "file"])]
    pub profile: Option<PathBuf>,
    /// With a .3mf project: the object whose overrides apply (its template, layer height,
    /// shells); `--profile project.3mf` alone lists the objects.
    #[arg(long, value_name = "NAME")]
    pub object: Option<String>,
    /// Which setting the template is for (solid signs are errors in a solid template).
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,

    #[command(flatten)]
    pub model: ModelArgs,

    /// The base infill direction in degrees, added to every angle (e.g. --base 45).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        value_parser = args::finite,
        allow_negative_numbers = true
    )]
    pub base: f64,
    /// The seed of the random joints `~` and `^`: the same seed gives the same angles.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = args::seed,
          allow_negative_numbers = true)]
    pub seed: u64,
    /// `rotlang`: the language as documented; `orcaslicer`: exactly the angles OrcaSlicer
    /// computes, for any text (valid or not); where it hangs, crashes or yields NaN the
    /// layers are reported on stderr and the angles stay finite.
    #[arg(long, value_name = "DIALECT", default_value_t)]
    pub dialect: eval::Dialect,
    /// Wrap the printed angles: `none` (90, 180, 270, 360, 450, ...), `360` (into
    /// [0, 360)), or `180` (into [0, 180): infill lines at θ and θ+180° are the same lines).
    #[arg(long, value_enum, default_value_t)]
    pub wrap: Wrap,
    /// Print only layers A to B-1 (`A..B`), A to B (`A..=B`), from A (`A..`), below B
    /// (`..B`), or layer N alone (`N`). Layers are numbered from 0.
    #[arg(long, value_name = "A..B", value_parser = parse_range)]
    pub range: Option<LayerRange>,
    /// `table`: aligned columns for people; `csv`:
    /// `index,bottom,top,angle,fill,start,end,instruction`; `json`: {"template": ...,
    /// "model": {...}, "options": {...}, "diagnostics": [...], "layers": [{"index":0,
    /// "bottom":0,"top":0.2,"angle":30,"fill":"sparse","instruction":{"start":0,"end":3,
    /// "text":"+30"}}, ...]}.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Colour the diagnostics printed to stderr.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Wrap {
    /// Angles as evaluated: not wrapped
    #[default]
    None,
    /// Into [0, 360)
    #[value(name = "360")]
    Full,
    /// Into [0, 180): the direction of the infill lines
    #[value(name = "180")]
    Half,
}

impl Wrap {
    fn number(self) -> number::Wrap {
        match self {
            Wrap::None => number::Wrap::None,
            Wrap::Full => number::Wrap::Turn,
            Wrap::Half => number::Wrap::HalfTurn,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Wrap::None => "none",
            Wrap::Full => "360",
            Wrap::Half => "180",
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Aligned columns for people
    #[default]
    Table,
    /// Comma-separated values with a header line
    Csv,
    /// One JSON object: {"template": ..., "layers": [...]}
    Json,
}

/// Layers `start..end` (end exclusive; `None`: to the top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerRange {
    pub start: usize,
    pub end: Option<usize>,
}

fn parse_range(text: &str) -> Result<LayerRange, String> {
    let t = text.trim();
    let number = |s: &str| -> Result<usize, String> {
        s.trim().parse::<usize>().map_err(|_| {
            format!("`{s}` is not a layer number: write A..B, A..=B, A.., ..B or N, with whole numbers from 0")
        })
    };
    let range = match t.split_once("..") {
        None => {
            let n = number(t)?;
            LayerRange {
                start: n,
                end: Some(n.saturating_add(1)),
            }
        }
        Some((a, b)) => {
            let start = if a.is_empty() { 0 } else { number(a)? };
            let end = match b.strip_prefix('=') {
                Some(b) => Some(number(b)?.saturating_add(1)),
                None if b.is_empty() => None,
                None => Some(number(b)?),
            };
            LayerRange { start, end }
        }
    };
    if range.end.is_some_and(|e| e <= range.start) {
        return Err(format!("`{t}` is empty: the end must be above the start"));
    }
    Ok(range)
}

/// Runs the expansion; returns the exit code.
pub fn run(args: &ExpandArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    // The model first: a usage error should not wait for stdin.
    let mut resolved = args.model.resolve()?;
    let mut base = args.base;
    // The template by the one rule of every command (`expand profile.json` reads the
    // profile, `expand nosuch.json` is no such file).
    let profile = super::paths::ProfileArgs {
        profile: args.profile.clone(),
        object: args.object.clone(),
    };
    let source = match super::paths::source(
        args.template.as_ref(),
        args.file.as_ref(),
        &profile,
        args.target.into(),
        args.model.height,
        err,
    )? {
        Ok(s) => s,
        Err(code) => return Ok(code),
    };
    if let Some(p) = source.profile {
        if args.model.model.is_none() && args.model.layers.is_none() {
            resolved = Resolved {
                model: p.model,
                source: source.input.name.clone(),
            };
        }
        // The profile's direction (for an empty template), unless --base replaces it.
        if base == 0.0 {
            base = p.base;
        }
    }
    let input = source.input;
    let len = resolved.model.len();
    let (start, end) = match args.range {
        None => (0, len),
        Some(r) => {
            let end = r.end.unwrap_or(len);
            if r.start >= len || end > len {
                return Err(UsageError(format!(
                    "--range {}..{end} is outside the model: its layers are 0 to {}",
                    r.start,
                    len - 1
                )));
            }
            (r.start, end)
        }
    };
    let options = Options {
        base,
        seed: args.seed,
    };
    let writer = Writer {
        text: &input.text,
        wrap: args.wrap.number(),
        solid_target: args.target == TargetArg::Solid,
        start,
        end,
    };
    if args.dialect == eval::Dialect::OrcaSlicer {
        // No grammar, so no syntax diagnostics: the JSON's are the dialect's findings (a
        // hang, undefined behaviour, NaN layers), known once the layers are written.
        return super::dialect::expand(&input.text, &resolved.model, options, err, |layers| {
            match args.format {
                Format::Csv => writer.csv(layers, out),
                Format::Table => writer.table(layers, out),
                Format::Json => {
                    let header = json_header(args, options, &input, None, &resolved, start, end);
                    writer.json(&mut *layers, &header, out)?;
                    let index = LineIndex::new(&input.text);
                    let findings: Vec<_> = layers
                        .findings()
                        .iter()
                        .map(|f| super::dialect::finding_json(&index, &input.text, f))
                        .collect();
                    writeln!(
                        out,
                        ",\"diagnostics\":{}}}",
                        serde_json::Value::from(findings)
                    )
                }
            }
        });
    }
    // The IR is not kept: a megabyte template costs a small multiple of its size.
    let (parse, layers) =
        eval::parse_layers(&input.text, args.target.into(), &resolved.model, options);
    let write_error = |e: std::io::Error| UsageError(format!("cannot write output: {e}"));
    let json = args.format == Format::Json;
    if parse.has_errors() && json {
        // The same object `check --format json` prints.
        writeln!(out, "{}", super::report_json(&input, &parse)).map_err(write_error)?;
    }
    if !parse.diagnostics.is_empty() {
        err.write_all(report(&input, &parse.diagnostics, args.color).as_bytes())
            .map_err(write_error)?;
    }
    if parse.has_errors() {
        return Ok(1);
    }
    let result = match args.format {
        Format::Csv => writer.csv(layers, out),
        Format::Table => writer.table(layers, out),
        Format::Json => {
            let header = json_header(args, options, &input, Some(&parse), &resolved, start, end);
            writer
                .json(layers, &header, out)
                .and_then(|()| out.write_all(b"}\n"))
        }
    };
    match result {
        Ok(()) => Ok(0),
        // The reader went away (`| head`): what it wanted was written.
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(0),
        Err(e) => Err(UsageError(format!("cannot write output: {e}"))),
    }
}

/// The one place diagnostics are rendered for `expand`.
fn report(input: &Input, diagnostics: &[crate::Diagnostic], color: ColorArg) -> String {
    super::render_diagnostics(input, diagnostics, color.enabled(false))
}

/// Everything of the JSON object before its `layers`: the template, model and options.
fn json_header(
    args: &ExpandArgs,
    options: Options,
    input: &Input,
    parse: Option<&crate::Parse>,
    resolved: &Resolved,
    start: usize,
    end: usize,
) -> String {
    let model = &resolved.model;
    let num = |x: f64| -> serde_json::Value {
        serde_json::from_str(number::height(x).as_str()).unwrap_or(serde_json::Value::Null)
    };
    let first = model.layer_bounds(0).map_or(0.0, |(b, t)| t - b);
    let index = LineIndex::new(&input.text);
    let mut head = serde_json::json!({
        "template": input.text,
        "name": input.name,
        "target": match args.target { TargetArg::Sparse => "sparse", TargetArg::Solid => "solid" },
        "model": {
            "source": resolved.source,
            "layers": model.len(),
            "layer_height": num(model.layer_height()),
            "first_layer_height": num(first),
            "height": num(model.object_height()),
            "bottom_shell_layers": model.bottom_shells(),
            "top_shell_layers": model.top_shells(),
        },
        "options": {
            "dialect": match args.dialect { eval::Dialect::Rotlang => "rotlang", eval::Dialect::OrcaSlicer => "orcaslicer" },
            "base": serde_json::from_str::<serde_json::Value>(number::angle(options.base).as_str()).unwrap_or_default(),
            "seed": args.seed,
            "wrap": args.wrap.name(),
            "range": {"start": start, "end": end},
        },
    });
    if let Some(parse) = parse {
        head["diagnostics"] = parse
            .diagnostics
            .iter()
            .map(|d| diagnostic_json(&index, d))
            .collect();
    }
    // The object without its closing brace, for `"layers"` to follow.
    let mut s = head.to_string();
    s.pop();
    s
}

/// Writes layers in each format. Every layer is written as it is evaluated: memory stays
/// constant however many layers.
struct Writer<'t> {
    text: &'t str,
    wrap: number::Wrap,
    /// With --target solid every layer is solid infill (the evaluator only knows the
    /// solid signs of sparse templates).
    solid_target: bool,
    start: usize,
    end: usize,
}

/// The last instruction looked up and its rendering: consecutive layers mostly share one.
struct Cached {
    span: Option<crate::Span>,
    text: String,
}

impl Writer<'_> {
    fn fill(&self, l: &Layer) -> &'static str {
        if self.solid_target && l.fill == crate::Fill::Sparse {
            "solid"
        } else {
            l.fill.name()
        }
    }

    fn instruction(&self, l: &Layer) -> &str {
        l.instruction
            .and_then(|s| self.text.get(s.range()))
            .unwrap_or("")
    }

    fn layers<I: Iterator<Item = Layer>>(&self, layers: I) -> impl Iterator<Item = Layer> {
        layers.skip(self.start).take(self.end - self.start)
    }

    fn csv(&self, layers: impl Iterator<Item = Layer>, out: &mut dyn Write) -> std::io::Result<()> {
        // Our own buffer, so that each small write is a static call into it and only full
        // buffers go through `dyn Write`.
        let mut out = BufWriter::with_capacity(1 << 16, out);
        out.write_all(b"index,bottom,top,angle,fill,start,end,instruction\n")?;
        let mut cached = Cached {
            span: None,
            text: ",,\n".into(),
        };
        // A layer's bottom is the top below it, bitwise: formatted once.
        let mut below = (f64::NAN, number::height(0.0));
        for l in self.layers(layers) {
            out.write_all(number::integer(l.index as u64).as_str().as_bytes())?;
            out.write_all(b",")?;
            let bottom = if l.bottom.to_bits() == below.0.to_bits() {
                below.1
            } else {
                number::height(l.bottom)
            };
            out.write_all(bottom.as_str().as_bytes())?;
            out.write_all(b",")?;
            let top = number::height(l.top);
            out.write_all(top.as_str().as_bytes())?;
            below = (l.top, top);
            out.write_all(b",")?;
            let angle = number::wrap(l.angle, self.wrap);
            out.write_all(number::angle(angle).as_str().as_bytes())?;
            out.write_all(b",")?;
            out.write_all(self.fill(&l).as_bytes())?;
            out.write_all(b",")?;
            if cached.span != l.instruction {
                cached.span = l.instruction;
                cached.text = match l.instruction {
                    Some(s) => format!(
                        "{},{},{}\n",
                        s.start,
                        s.end,
                        csv_field(self.instruction(&l))
                    ),
                    None => ",,\n".into(),
                };
            }
            out.write_all(cached.text.as_bytes())?;
        }
        out.flush()
    }

    fn json(
        &self,
        layers: impl Iterator<Item = Layer>,
        header: &str,
        out: &mut dyn Write,
    ) -> std::io::Result<()> {
        let mut out = BufWriter::with_capacity(1 << 16, out);
        out.write_all(header.as_bytes())?;
        out.write_all(b",\"layers\":[")?;
        let mut cached = Cached {
            span: None,
            text: "null}".into(),
        };
        for (i, l) in self.layers(layers).enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            // The number helper prints finite numbers in plain decimal form, which is
            // valid JSON (angles are always finite). Pieces, not `write!`: this loop runs
            // once per layer.
            out.write_all(b"\n{\"index\":")?;
            out.write_all(number::integer(l.index as u64).as_str().as_bytes())?;
            out.write_all(b",\"bottom\":")?;
            out.write_all(number::height(l.bottom).as_str().as_bytes())?;
            out.write_all(b",\"top\":")?;
            out.write_all(number::height(l.top).as_str().as_bytes())?;
            out.write_all(b",\"angle\":")?;
            let angle = number::wrap(l.angle, self.wrap);
            out.write_all(number::angle(angle).as_str().as_bytes())?;
            out.write_all(b",\"fill\":\"")?;
            out.write_all(self.fill(&l).as_bytes())?;
            out.write_all(b"\",\"instruction\":")?;
            if cached.span != l.instruction {
                cached.span = l.instruction;
                cached.text = match l.instruction {
                    Some(s) => format!(
                        "{{\"start\":{},\"end\":{},\"text\":{}}}}}",
                        s.start,
                        s.end,
                        serde_json::Value::from(self.instruction(&l))
                    ),
                    None => "null}".into(),
                };
            }
            out.write_all(cached.text.as_bytes())?;
        }
        // The caller closes the object (after what only the layers tell: the findings
        // of the OrcaSlicer dialect).
        out.write_all(b"\n]")?;
        out.flush()
    }

    fn table(
        &self,
        layers: impl Iterator<Item = Layer>,
        out: &mut dyn Write,
    ) -> std::io::Result<()> {
        let mut out = BufWriter::with_capacity(1 << 16, out);
        // Wide enough for the last index shown: 100,000 layers need six digits.
        let width = self.end.saturating_sub(1).to_string().len().max(5);
        writeln!(
            out,
            "{:>width$}  {:>10}  {:>10}  {:>14}  {:<11}  instruction",
            "layer", "bottom", "top", "angle", "fill"
        )?;
        for l in self.layers(layers) {
            let instruction = l
                .instruction
                .and_then(|s| self.text.get(s.range()))
                .unwrap_or("(holds)");
            writeln!(
                out,
                "{:>width$}  {:>10}  {:>10}  {:>14}  {:<11}  {}",
                l.index,
                number::height(l.bottom),
                number::height(l.top),
                number::angle(number::wrap(l.angle, self.wrap)),
                self.fill(&l),
                instruction.trim()
            )?;
        }
        out.flush()
    }
}

/// A CSV field: quoted when it holds a quote, comma or line break (`"` is the inch unit).
fn csv_field(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains(['"', ',', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: ExpandArgs,
    }

    /// Runs `rotlang expand ARGS…`: (exit code or usage error, stdout, stderr).
    fn expand(argv: &[&str]) -> (Result<i32, String>, String, String) {
        let cli = Cli::try_parse_from(std::iter::once("expand").chain(argv.iter().copied()))
            .unwrap_or_else(|e| panic!("{argv:?}: {e}"));
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let code = run(&cli.args, &mut out, &mut err).map_err(|e| e.0);
        let s = |b: Vec<u8>| String::from_utf8(b).expect("utf-8 output");
        (code, s(out), s(err))
    }

    #[test]
    fn csv_of_the_default_cube() {
        let (code, out, err) = expand(&["5, 10!, +20", "--format", "csv"]);
        assert_eq!((code, err.as_str()), (Ok(0), ""));
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), 101);
        assert_eq!(
            lines[0],
            "index,bottom,top,angle,fill,start,end,instruction"
        );
        assert_eq!(lines[1], "0,0,0.2,5,sparse,0,1,5");
        assert_eq!(lines[2], "1,0.2,0.4,10,sparse,3,6,10!");
        assert_eq!(lines[5].split(',').nth(3), Some("25"));
    }

    #[test]
    fn json_is_one_valid_object() {
        let (code, out, _) = expand(&[
            "+30/3!", "--layers", "5", "--format", "json", "--wrap", "360",
        ]);
        assert_eq!(code, Ok(0));
        let value: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
        let layers = value["layers"].as_array().expect("layers");
        assert_eq!(layers.len(), 5);
        assert_eq!(layers[0]["index"], 0);
        assert_eq!(layers[0]["fill"], "sparse");
        assert_eq!(
            layers[0]["instruction"],
            serde_json::json!({"start": 0, "end": 6, "text": "+30/3!"})
        );
        assert_eq!(layers[2]["angle"], 30.0);
        // Spent: the angle holds and no instruction governs.
        assert_eq!(layers[4]["instruction"], serde_json::Value::Null);
    }

    #[test]
    fn table_shows_instruction_text_and_wraps() {
        let (code, out, _) = expand(&["+90, M", "--layers", "4", "--wrap", "180"]);
        assert_eq!(code, Ok(0));
        let rows: Vec<&str> = out.lines().collect();
        assert!(rows[0].contains("layer") && rows[0].contains("instruction"));
        assert!(rows[1].ends_with("sparse       +90"), "{rows:?}");
        assert!(
            rows[2].contains(" 90  ") && rows[2].contains("monotonic"),
            "{rows:?}"
        );
        assert!(rows[3].contains("  0  "), "{rows:?}");
    }

    #[test]
    fn errors_exit_1_and_warnings_go_to_stderr() {
        let (code, out, err) = expand(&["+30X5"]);
        assert_eq!(code, Ok(1));
        assert!(out.is_empty());
        assert!(err.contains("error"), "{err}");
        let (code, out, err) = expand(&["10,,20", "--format", "csv"]);
        assert_eq!(code, Ok(0));
        assert!(err.contains("warning"), "{err}");
        assert_eq!(out.lines().count(), 101);
    }

    #[test]
    fn usage_errors() {
        for argv in [
            &["0", "--layers", "10", "--layer-height=-1"][..],
            &["0", "--layer-height", "0.1"],
            &["0", "--model", "/nonexistent/model.json"],
        ] {
            let (code, _, _) = expand(argv);
            assert!(code.is_err(), "{argv:?}: {code:?}");
        }
        assert!(Cli::try_parse_from(["expand", "0", "--layers", "5", "--height", "3"]).is_err());
        for bad in [
            ["--layers", "0"],
            ["--layers", "-5"],
            ["--seed", "-1"],
            ["--base", "nan"],
            ["--height", "nan"],
        ] {
            let Err(e) = Cli::try_parse_from(["expand", "0", bad[0], bad[1]]) else {
                panic!("{bad:?} is refused");
            };
            assert!(e.to_string().contains("must be"), "{e}");
        }
        // Huge numbers are refused, by the parser or against the model, without overflow.
        for range in [usize::MAX.to_string(), format!("0..={}", usize::MAX)] {
            match Cli::try_parse_from(["expand", "0", "--range", &range]) {
                Err(_) => {}
                Ok(cli) => {
                    let code = run(&cli.args, &mut Vec::new(), &mut Vec::new());
                    assert!(code.is_err(), "{range}");
                }
            }
        }
        for range in ["5..5", "x..3", "3..1", "-1..3", ""] {
            assert!(Cli::try_parse_from(["expand", "0", "--range", range]).is_err());
        }
        let (code, _, _) = expand(&["0", "--range", "90..101"]);
        assert!(
            code.expect_err("past the top")
                .contains("layers are 0 to 99")
        );
        assert!(Cli::try_parse_from(["expand", "0", "--file", "x.rot"]).is_err());
    }

    #[test]
    fn model_files_are_validated() {
        let dir = std::env::temp_dir().join(format!("rotlang-expand-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let write = |name: &str, text: &str| {
            let path = dir.join(name);
            std::fs::write(&path, text).expect("write");
            path.display().to_string()
        };
        let good = write(
            "good.json",
            r#"{"description": "x", "layer_heights": [0.3, 0.2, 0.2], "layer_height": 0.2,
                "bottom_shell_layers": 1, "top_shell_layers": 2}"#,
        );
        let (code, out, _) = expand(&["+10B", "--model", &good, "--format", "csv"]);
        assert_eq!(code, Ok(0));
        assert_eq!(
            out.lines().nth(3).and_then(|l| l.split(',').nth(2)),
            Some("0.7")
        );
        // B = 1 from the file: one layer turning 10°.
        assert_eq!(
            out.lines().nth(2).and_then(|l| l.split(',').nth(3)),
            Some("20")
        );
        let (_, out, _) = expand(&[
            "+10B",
            "--model",
            &good,
            "--bottom-shell-layers",
            "2",
            "--format",
            "csv",
        ]);
        // B = 2: 20° over layers of 0.3 and 0.2 mm, by progress in height.
        assert_eq!(
            out.lines().nth(1).and_then(|l| l.split(',').nth(3)),
            Some("12")
        );
        assert_eq!(
            out.lines().nth(2).and_then(|l| l.split(',').nth(3)),
            Some("20")
        );
        for (name, text, says) in [
            (
                "missing.json",
                r#"{"layer_heights": [0.2]}"#,
                "missing field",
            ),
            (
                "typo.json",
                r#"{"layer_heights": [0.2], "layer_hieght": 0.2}"#,
                "unknown field",
            ),
            (
                "zero.json",
                r#"{"layer_heights": [0.2, 0], "layer_height": 0.2, "bottom_shell_layers": 3, "top_shell_layers": 4}"#,
                "layer 1",
            ),
            (
                "empty.json",
                r#"{"layer_heights": [], "layer_height": 0.2, "bottom_shell_layers": 3, "top_shell_layers": 4}"#,
                "no layers",
            ),
            ("list.json", "[0.2, 0.2]", "expected one JSON object"),
        ] {
            let path = write(name, text);
            let (code, _, _) = expand(&["0", "--model", &path]);
            let message = code.expect_err(name);
            assert!(message.contains(says), "{name}: {message}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
