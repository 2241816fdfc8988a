//! The pictures, rendered to pixels with resvg: the plot's line is where the angles say,
//! the preview's lines lie inside the region. The PNGs are kept in the test's temporary
//! directory (`target/tmp/pictures-*.png`) for a person to look at when a test fails.

use resvg::tiny_skia::{Pixmap, Transform};
use rotlang::eval::{Model, Options};
use rotlang_geometry::plot::{self, PlotOptions};

fn render(svg: &str, name: &str) -> Pixmap {
    let tree =
        resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default()).expect("valid SVG");
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).expect("a picture of some size");
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    let path =
        std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("pictures-{name}.png"));
    pixmap.save_png(&path).expect("the PNG is written");
    pixmap
}

fn pixel(p: &Pixmap, x: f64, y: f64) -> (u8, u8, u8) {
    let (x, y) = (x.round() as u32, y.round() as u32);
    let c = p
        .pixel(x.min(p.width() - 1), y.min(p.height() - 1))
        .expect("inside the picture");
    (c.red(), c.green(), c.blue())
}

fn hex(colour: &str) -> (u8, u8, u8) {
    let v = u32::from_str_radix(colour.trim_start_matches('#'), 16).unwrap();
    ((v >> 16) as u8, (v >> 8) as u8, v as u8)
}

fn near(a: (u8, u8, u8), b: (u8, u8, u8)) -> bool {
    let d = |x: u8, y: u8| (x as i32 - y as i32).abs();
    d(a.0, b.0) + d(a.1, b.1) + d(a.2, b.2) < 60
}

/// Whether a pixel of colour `colour` lies within `r` pixels of (x, y).
fn found(p: &Pixmap, x: f64, y: f64, r: i32, colour: (u8, u8, u8)) -> bool {
    (-r..=r).any(|dx| (-r..=r).any(|dy| near(pixel(p, x + dx as f64, y + dy as f64), colour)))
}

/// An axis's ticks: (value, pixel).
type Ticks = Vec<(f64, f64)>;

/// The axes as the picture labels them, read from the SVG's text (not from
/// `plot::layout`, which draws them): each angle tick is a grid line followed by its label,
/// each height label is centred under its x. Returns (angle ticks, direction ticks, height
/// ticks) as (value, pixel) pairs; the last five angle-like ticks belong to the direction
/// panel.
fn axes(svg: &str) -> (Ticks, Ticks, Ticks) {
    let attr = |tag: &str, name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let at = tag.find(&key).expect("attribute") + key.len();
        tag[at..tag[at..].find('"').unwrap() + at].parse().unwrap()
    };
    let mut ticks = Vec::new();
    let marker = "stroke=\"#ddd\"/><text";
    for (i, _) in svg.match_indices(marker) {
        let line = &svg[svg[..i].rfind("<line").unwrap()..i];
        let text = &svg[i + marker.len()..];
        let label = &text[text.find('>').unwrap() + 1..text.find("</text>").unwrap()];
        let value: f64 = label
            .trim_end_matches('°')
            .parse()
            .expect("a number of degrees");
        ticks.push((value, attr(line, "y1")));
    }
    let directions = ticks.split_off(ticks.len() - 5);
    let mut heights = Vec::new();
    for (i, _) in svg.match_indices("text-anchor=\"middle\">") {
        let tag = &svg[svg[..i].rfind("<text").unwrap()..i];
        let rest = &svg[i + "text-anchor=\"middle\">".len()..];
        if let Ok(z) = rest[..rest.find('<').unwrap()].parse::<f64>() {
            heights.push((z, attr(tag, "x")));
        }
    }
    (ticks, directions, heights)
}

/// The pixel of `value` on an axis given by its ticks (linear between the first and last).
/// The chart of a sparse template on the 20 mm cube, with the default options and style.
fn default_plot(text: &str) -> String {
    let template = rotlang::parse(text, rotlang::Target::Sparse).template;
    plot::svg(
        &template,
        &Model::cube20(),
        Options::default(),
        text,
        &PlotOptions::default(),
    )
}

fn on_axis(ticks: &[(f64, f64)], value: f64) -> f64 {
    let (a, b) = (ticks[0], ticks[ticks.len() - 1]);
    a.1 + (value - a.0) / (b.0 - a.0) * (b.1 - a.1)
}

#[test]
fn plot_line_and_points_are_where_the_angles_say() {
    let text = "+2, 0*, +3";
    let template = rotlang::parse(text, rotlang::Target::Sparse).template;
    let model = Model::cube20();
    let options = Options {
        base: 10.0,
        seed: 0,
    };
    let style = PlotOptions::default();
    let svg = plot::svg(&template, &model, options, text, &style);
    let (angle_ticks, direction_ticks, height_ticks) = axes(&svg);
    // The height axis spans the 20 mm cube; directions are labelled over 180°.
    assert_eq!(height_ticks.first().map(|t| t.0), Some(0.0));
    assert_eq!(height_ticks.last().map(|t| t.0), Some(20.0));
    let from = direction_ticks[0].0;
    assert_eq!(direction_ticks[4].0, from + 180.0);
    let picture = render(&svg, "plot");
    let line = hex(plot::LINE_COLOUR);
    let dots = hex(plot::POINT_COLOUR);
    let layers: Vec<_> = rotlang::eval::layers(&template, &model, options).collect();
    for l in layers.iter().step_by(7) {
        let x = on_axis(&height_ticks, (l.bottom + l.top) / 2.0);
        let y = on_axis(&angle_ticks, l.angle);
        assert!(
            found(&picture, x, y, 2, line),
            "layer {}: no line at ({x}, {y}) for {}°",
            l.index,
            l.angle
        );
        let yd = on_axis(&direction_ticks, (l.angle - from).rem_euclid(180.0) + from);
        assert!(
            found(&picture, x, yd, 2, dots),
            "layer {}: no point at ({x}, {yd})",
            l.index
        );
    }
    // And not everywhere: the line is absent well away from the angle (angles rise).
    let l = &layers[50];
    let x = on_axis(&height_ticks, (l.bottom + l.top) / 2.0);
    let (top, bottom) = (angle_ticks.last().unwrap().1, angle_ticks[0].1);
    for dy in [-40.0, 40.0] {
        let y = on_axis(&angle_ticks, l.angle) + dy;
        if y > top && y < bottom {
            assert!(
                !found(&picture, x, y, 1, line),
                "a line at ({x}, {y}), far from {}°",
                l.angle
            );
        }
    }
}

/// A ±10° wobble is drawn on −90° to 90°, where it is one continuous band around 0°, not
/// split between 0° and 180° (the axis says so); turns around 90° stay on 0° to 180°.
#[test]
fn plot_wobble_around_zero_is_not_split_at_the_seam() {
    let text = "+10L25%, -10l25%, -10L25%, +10l25%";
    let template = rotlang::parse(text, rotlang::Target::Sparse).template;
    let model = Model::cube20();
    let svg = default_plot(text);
    assert!(svg.contains("mod 180, in [−90, 90)"));
    let (_, direction_ticks, height_ticks) = axes(&svg);
    let labels: Vec<f64> = direction_ticks.iter().map(|t| t.0).collect();
    assert_eq!(labels, [-90.0, -45.0, 0.0, 45.0, 90.0]);
    let picture = render(&svg, "plot-wobble");
    let dots = hex(plot::POINT_COLOUR);
    let layers: Vec<_> = rotlang::eval::layers(&template, &model, Options::default()).collect();
    let mut negative = 0;
    for l in layers.iter().step_by(5) {
        assert!(l.angle.abs() <= 10.0 + 1e-9);
        negative += usize::from(l.angle < -1.0);
        let x = on_axis(&height_ticks, (l.bottom + l.top) / 2.0);
        let y = on_axis(&direction_ticks, l.angle);
        assert!(
            found(&picture, x, y, 2, dots),
            "layer {} at {}°: no point at ({x}, {y})",
            l.index,
            l.angle
        );
        // Nothing at the panel's edges, where [0, 180) would have put half of them.
        for edge in [-88.0, 88.0] {
            let y = on_axis(&direction_ticks, edge);
            assert!(
                !found(&picture, x, y, 1, dots),
                "layer {}: a point at {edge}°",
                l.index
            );
        }
    }
    assert!(negative > 3, "the wobble goes below 0°");
    assert!(default_plot("+80L50%, -10").contains("mod 180, in [0, 180)"));
}

/// Instruction labels are whole (`30M`, not `3…`) and do not run into each other.
#[test]
fn plot_labels_are_whole_and_apart() {
    let svg = default_plot("30M, 90, +45/8, 0, +30/50%");
    let mut labels = Vec::new();
    for (i, _) in svg.match_indices("font-size=\"11\">") {
        let tag = &svg[svg[..i].rfind("<text").unwrap()..i];
        let rest = &svg[i + "font-size=\"11\">".len()..];
        let label = rest[..rest.find('<').unwrap()].to_owned();
        let num = |name: &str| -> f64 {
            let key = format!(" {name}=\"");
            let at = tag.find(&key).unwrap() + key.len();
            tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
        };
        labels.push((label, num("x"), num("y")));
    }
    for want in ["30M", "90", "+45/8", "0", "+30/50%"] {
        assert!(
            labels.iter().any(|l| l.0 == want),
            "no label {want}: {labels:?}"
        );
    }
    assert!(!svg.contains('…'));
    // Labels on one row: each ends (at 7 px a character, more than 11 px sans-serif
    // takes) before the next begins.
    for a in &labels {
        for b in &labels {
            if a.2 == b.2 && a.1 < b.1 {
                assert!(
                    a.1 + 7.0 * a.0.chars().count() as f64 <= b.1,
                    "{a:?} runs into {b:?}"
                );
            }
        }
    }
}

#[test]
fn plot_marks_solid_layers() {
    let text = "0M3, +30";
    let template = rotlang::parse(text, rotlang::Target::Sparse).template;
    let model = Model::cube20();
    let style = PlotOptions::default();
    let svg = plot::svg(&template, &model, Options::default(), text, &style);
    let layout = plot::layout(&template, &model, Options::default(), &style);
    let picture = render(&svg, "plot-solid");
    let solid = hex(plot::SOLID_COLOUR);
    let layers: Vec<_> = rotlang::eval::layers(&template, &model, Options::default()).collect();
    for l in &layers[..12] {
        let x = layout.x((l.bottom + l.top) / 2.0);
        let y = layout.y_direction(l.angle.rem_euclid(180.0));
        let is_solid = l.fill != rotlang::Fill::Sparse;
        assert_eq!(
            found(&picture, x, y, 1, solid),
            is_solid,
            "layer {} ({:?})",
            l.index,
            l.fill
        );
    }
}

mod preview {
    use super::*;
    use rotlang_geometry::infill::preview::{self, PreviewOptions};
    use rotlang_geometry::infill::{Pattern, Settings, shapes};

    fn inside(region: &rotlang_geometry::infill::MultiPolygon<f64>, x: f64, y: f64) -> bool {
        let mut inside = false;
        for p in &region.0 {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                for w in ring.0.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    if (a.y <= y) != (b.y <= y) && a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y) > x {
                        inside = !inside;
                    }
                }
            }
        }
        inside
    }

    #[test]
    fn preview_lines_lie_inside_the_region() {
        let text = "+45, 30O";
        let template = rotlang::parse(text, rotlang::Target::Sparse).template;
        let model = Model::cube20();
        let region = shapes::ring_shape(10.0, 5.0);
        for pattern in [Pattern::Grid, Pattern::Gyroid, Pattern::Hexagons] {
            let settings = Settings {
                pattern,
                ..Settings::default()
            };
            let options = PreviewOptions {
                columns: 2,
                ..PreviewOptions::default()
            };
            let svg = preview::render(
                &template,
                &model,
                Options::default(),
                text,
                &region,
                &settings,
                0..2,
                &options,
            )
            .expect("the preview is drawn");
            let picture = render(&svg, &format!("preview-{pattern}"));
            for panel in 0..2 {
                let (scale, offset) = preview::transform(&region, panel, &options);
                // Half the line's width and a pixel of anti-aliasing, in mm.
                let slack = (0.4 * scale / 2.0 + 1.5) / scale;
                let mut coloured = 0;
                let size = options.panel;
                let (x0, y0) = (offset.x - 10.0 * scale, offset.y - 10.0 * scale);
                for py in (y0 as i64 - 5)..(y0 + size) as i64 {
                    for px in (x0 as i64 - 5)..(x0 + size) as i64 {
                        let (r, g, b) = pixel(&picture, px as f64, py as f64);
                        let saturation = r.max(g).max(b) - r.min(g).min(b);
                        if saturation < 80 {
                            continue;
                        }
                        coloured += 1;
                        let (x, y) = (
                            (px as f64 - offset.x) / scale,
                            -(py as f64 - offset.y) / scale,
                        );
                        let ok = [
                            (0.0, 0.0),
                            (slack, 0.0),
                            (-slack, 0.0),
                            (0.0, slack),
                            (0.0, -slack),
                        ]
                        .iter()
                        .any(|(dx, dy)| inside(&region, x + dx, y + dy));
                        assert!(
                            ok,
                            "{pattern} panel {panel}: a line pixel at ({x:.2}, {y:.2}) mm, outside the ring"
                        );
                    }
                }
                assert!(
                    coloured > 2000,
                    "{pattern} panel {panel}: only {coloured} line pixels"
                );
                // The hole's middle is not drawn on.
                let (r, g, b) = pixel(&picture, offset.x, offset.y);
                assert!(
                    r.max(g).max(b) - r.min(g).min(b) < 80,
                    "the hole is coloured"
                );
            }
        }
    }
}

/// The README's pictures are what its own commands draw: each `cargo run --release -- …`
/// line of its pictures section is run (with the binary under test, its `--out` moved to a
/// temporary file) and the output compared byte for byte with the checked-in SVG, which
/// must also render with something drawn in it. A change to the drawing code that is not
/// followed by regenerating the pictures fails here.
#[test]
fn readme_pictures_are_what_its_commands_draw() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let section = &readme[readme
        .find("## Pictures: `rotlang plot` and `rotlang preview`")
        .expect("the pictures section")..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |i| i + 3)];
    let mut checked = Vec::new();
    for line in section.lines() {
        let Some(args) = line.strip_prefix("cargo run --release -- ") else {
            continue;
        };
        let mut words = shell_words(args);
        let out = words
            .iter()
            .position(|w| w == "--out")
            .expect("the command writes a file");
        let target = words[out + 1].clone();
        let temp = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("readme-{}", target.replace('/', "-")));
        words[out + 1] = temp.to_string_lossy().into_owned();
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(&words)
            .status()
            .expect("rotlang runs");
        assert!(status.success(), "{line}");
        let drawn = std::fs::read(&temp).expect("the picture is written");
        let checked_in = std::fs::read(root.join(&target)).expect("checked in");
        assert!(
            drawn == checked_in,
            "{target} is not what `{line}` draws now: run the README's command again"
        );
        let svg = String::from_utf8(drawn).expect("UTF-8");
        let picture = render(&svg, &format!("readme-{}", target.replace('/', "-")));
        let coloured = picture
            .pixels()
            .iter()
            .filter(|c| {
                c.red().max(c.green()).max(c.blue()) - c.red().min(c.green()).min(c.blue()) > 80
            })
            .count();
        assert!(coloured > 1000, "{target}: {coloured} coloured pixels");
        // Every picture the section shows is one of those regenerated.
        checked.push(target);
    }
    for (i, _) in section.match_indices("](docs/img/") {
        let rest = &section[i + 2..];
        let shown = &rest[..rest.find(')').unwrap()];
        assert!(
            checked.iter().any(|c| c == shown),
            "{shown} is shown but no command draws it"
        );
    }
    assert!(checked.len() >= 2, "{checked:?}");
}

/// Words of a shell command line: spaces separate them, single quotes hold spaces.
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let (mut quoted, mut started) = (false, false);
    for c in line.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                started = true;
            }
            ' ' if !quoted => {
                if started {
                    words.push(std::mem::take(&mut word));
                }
                started = false;
            }
            c => {
                word.push(c);
                started = true;
            }
        }
    }
    if started {
        words.push(word);
    }
    words
}

#[path = "support/project.rs"]
mod project;

/// Every example in `rotlang plot --help` and `rotlang preview --help` runs and succeeds
/// (two once failed with a parse error), in a directory holding the files they name, and
/// `--size` resizes a shape file (it was silently ignored).
#[test]
fn every_help_example_of_plot_and_preview_runs() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("help-examples");
    std::fs::create_dir_all(&dir).unwrap();
    let square = |k: f64| {
        format!(
            "<svg xmlns='http://www.w3.org/2000/svg'><path d='M 0 0 L {k} 0 L {k} {k} L 0 {k} Z'/></svg>"
        )
    };
    std::fs::write(dir.join("part.svg"), square(10.0)).unwrap();
    std::fs::write(
        dir.join("outline.json"),
        "[[[[0, 0], [30, 0], [30, 30], [0, 30]]]]",
    )
    .unwrap();
    std::fs::write(dir.join("profile.rot"), "+10L25%, -10l25%\n").unwrap();
    std::fs::write(
        dir.join("part.stl"),
        rotlang_geometry::mesh::shapes::tube(15.0, 5.0, 10.0, 64).to_binary_stl(),
    )
    .unwrap();
    std::fs::write(
        dir.join("part.json"),
        r#"{"layer_height": 0.2, "layer_heights": [0.3, 0.2, 0.2, 0.2, 0.2]}"#,
    )
    .unwrap();
    let bracket = rotlang_geometry::mesh::shapes::step([30.0, 10.0, 5.0], [10.0, 10.0, 10.0]);
    std::fs::write(
        dir.join("project.3mf"),
        project::project(
            &[project::Object {
                name: "Bracket",
                mesh: &bracket,
                at: [0.0, 0.0],
                overrides: &[("sparse_infill_density", "25%")],
            }],
            r#"{"sparse_infill_rotate_template": "+30/50%", "wall_loops": "3"}"#,
        ),
    )
    .unwrap();
    let bin = env!("CARGO_BIN_EXE_rotlang");
    let mut ran = 0;
    for command in ["plot", "preview"] {
        let help = std::process::Command::new(bin)
            .args([command, "--help"])
            .output()
            .expect("rotlang runs");
        let help = String::from_utf8(help.stdout).unwrap();
        let examples = &help[help.find("Examples:").expect("examples")..];
        for line in examples.lines().skip(1) {
            let Some(rest) = line.trim_start().strip_prefix("rotlang ") else {
                if line.trim().is_empty() {
                    break;
                }
                continue;
            };
            // A comment after three spaces describes the example.
            let rest = rest.split("   ").next().unwrap().trim();
            let mut words = shell_words(rest);
            if let Some(at) = words.iter().position(|w| w == ">") {
                words.splice(at..at + 2, ["--out".to_string(), words[at + 1].clone()]);
            }
            let output = std::process::Command::new(bin)
                .args(&words)
                .current_dir(&dir)
                .output()
                .expect("rotlang runs");
            assert!(
                output.status.success(),
                "`rotlang {rest}` failed: {}",
                String::from_utf8_lossy(&output.stderr)
            );
            ran += 1;
        }
    }
    assert!(ran >= 8, "{ran} examples");
    // --size 40 makes the 10 mm square of part.svg 40 mm wide: four times the lines.
    let lines = |size: Option<&str>| {
        let mut args = vec![
            "preview", "0", "--shape", "part.svg", "--layers", "0", "--format", "json",
        ];
        if let Some(s) = size {
            args.extend(["--size", s]);
        }
        let out = std::process::Command::new(bin)
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(out.status.success());
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["layers"][0]["length"].as_f64().unwrap()
    };
    let (own, resized) = (lines(None), lines(Some("40")));
    assert!(
        resized > 10.0 * own,
        "{own} mm, then {resized} mm at --size 40"
    );
}

/// Every template the benches evaluate parses without an error (one once had a parse
/// error, so its bench measured the instructions that were left).
#[test]
fn every_bench_template_parses() {
    let crates = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let benches = std::fs::read_dir(&crates).unwrap().flat_map(|c| {
        std::fs::read_dir(c.unwrap().path().join("benches"))
            .into_iter()
            .flatten()
    });
    let mut seen = 0;
    for entry in benches {
        let path = entry.unwrap().path();
        // Bench sources only: benches/polyslice/ is the Polyslice comparison (node).
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        // Templates are the string constants and literals given to parse or parse_layers.
        for (i, _) in text.match_indices("TEMPLATE: &str = \"") {
            let rest = &text[i + "TEMPLATE: &str = \"".len()..];
            let template = &rest[..rest.find('"').unwrap()];
            let parse = rotlang::parse(template, rotlang::Target::Sparse);
            assert!(
                !parse.has_errors(),
                "{}: {template:?}: {:?}",
                path.display(),
                parse.diagnostics
            );
            seen += 1;
        }
        for (i, _) in text.match_indices("parse(\"") {
            let rest = &text[i + "parse(\"".len()..];
            let template = &rest[..rest.find('"').unwrap()];
            let parse = rotlang::parse(template, rotlang::Target::Sparse);
            assert!(!parse.has_errors(), "{}: {template:?}", path.display());
            seen += 1;
        }
    }
    assert!(seen >= 1, "no bench template found");
}

/// `rotlang preview --shape part.stl`: every layer is the mesh's section at its middle
/// (a tube's ring, with its hole), filled inside its walls, the shells solid; the summary
/// covers the whole part, and two templates give two summaries to compare.
#[test]
fn preview_of_a_mesh_fills_its_sections() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("mesh-preview");
    std::fs::create_dir_all(&dir).unwrap();
    let stl = dir.join("tube.stl");
    std::fs::write(
        &stl,
        rotlang_geometry::mesh::shapes::tube(15.0, 5.0, 10.0, 64).to_binary_stl(),
    )
    .unwrap();
    let run = |template: &str, pattern: &str| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(["preview", template, "--shape"])
            .arg(&stl)
            .args([
                "--pattern",
                pattern,
                "--layers",
                "0..50",
                "--format",
                "json",
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.contains("50 layers"), "{stderr}");
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let v = run("+45", "grid");
    let layers = v["layers"].as_array().unwrap();
    assert_eq!(layers.len(), 50);
    for l in layers {
        let i = l["index"].as_u64().unwrap();
        let section = l["section"].as_array().unwrap();
        assert_eq!(section.len(), 1, "layer {i}: one ring");
        assert_eq!(
            section[0].as_array().unwrap().len(),
            2,
            "layer {i}: with its hole"
        );
        let solid = !(3..46).contains(&i);
        assert_eq!(l["density"].as_f64().unwrap() == 1.0, solid, "layer {i}");
        // The two wall loops' middle lines, outermost first: the outline moved in and the
        // hole out by 0.2 mm, then by 0.6 mm (the 64-gon's chords within 0.03 mm).
        let walls = l["walls"].as_array().unwrap();
        let radii: Vec<(f64, f64)> = walls
            .iter()
            .map(|ring| {
                let ring = ring.as_array().unwrap();
                assert_eq!(ring.first(), ring.last(), "layer {i}: closed");
                ring.iter()
                    .map(|p| p[0].as_f64().unwrap().hypot(p[1].as_f64().unwrap()))
                    .fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| {
                        (lo.min(r), hi.max(r))
                    })
            })
            .collect();
        for ((lo, hi), want) in radii.iter().zip([14.8, 5.2, 14.4, 5.6]) {
            assert!(
                (lo - want).abs() < 0.03 && (hi - want).abs() < 0.03,
                "layer {i}: walls at {radii:?}"
            );
        }
        assert_eq!(radii.len(), 4, "layer {i}");
        // Every point of the infill lies in the ring less two walls and half a nozzle.
        for line in l["polylines"].as_array().unwrap() {
            for p in line.as_array().unwrap() {
                let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
                let r = x.hypot(y);
                assert!(
                    r > 5.0 + 0.95 && r < 15.0 - 0.95,
                    "layer {i}: {x}, {y} at r {r}"
                );
            }
        }
    }
    let summary = &v["summary"];
    assert_eq!(summary["layers"], 50);
    let other = run("0, 90", "lines");
    let (a, b) = (
        summary["extrusion_mm"].as_f64().unwrap(),
        other["summary"]["extrusion_mm"].as_f64().unwrap(),
    );
    assert!(a > 0.0 && b > 0.0 && a != b, "{a} {b}");
    assert!(summary["time_s"].as_f64().unwrap() > a / 100.0);
    // The picture draws the walls in grey round the infill, with a legend for them: on
    // the line through the tube's centre, the outer wall's middle (r 14.8) is grey.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["preview", "+45", "--shape"])
        .arg(&stl)
        .args(["--layers", "20..21"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let svg = String::from_utf8(out.stdout).unwrap();
    assert!(svg.contains(">walls</text>"), "the legend names the walls");
    let section = rotlang_geometry::slice::Slicer::new(&rotlang_geometry::mesh::shapes::tube(
        15.0, 5.0, 10.0, 64,
    ))
    .section(4.1)
    .region;
    let options = rotlang_geometry::infill::preview::PreviewOptions::default();
    let (scale, offset) = rotlang_geometry::infill::preview::transform(&section, 0, &options);
    let picture = render(&svg, "mesh-walls");
    let grey = hex("#b8b8b8");
    for x in [-14.8, 14.8] {
        let (px, py) = (x * scale + offset.x, offset.y);
        assert!(found(&picture, px, py, 1, grey), "a wall at x {x}");
    }
    // Between the walls and the hole's walls, infill, not wall grey.
    let (px, py) = (10.0 * scale + offset.x, offset.y);
    assert!(!found(&picture, px, py, 1, grey), "no wall at x 10");
}

/// `preview --3d`: the part's layers stacked in an isometric SVG (or an HTML page holding
/// it), one group per layer from the bottom up; rendered, the bottom layers' blue lies
/// below the top layers' red.
#[test]
fn preview_3d_stacks_the_layers_of_a_mesh() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("mesh-3d");
    std::fs::create_dir_all(&dir).unwrap();
    let stl = dir.join("cylinder.stl");
    std::fs::write(
        &stl,
        rotlang_geometry::mesh::shapes::tube(10.0, 0.0, 8.0, 48).to_binary_stl(),
    )
    .unwrap();
    for (file, html) in [("cylinder.svg", false), ("cylinder.html", true)] {
        let picture = dir.join(file);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(["preview", "+30", "--shape"])
            .arg(&stl)
            .arg("--3d")
            .arg(&picture)
            .args(["--format", "json"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = std::fs::read_to_string(&picture).unwrap();
        assert_eq!(text.starts_with("<!doctype html>"), html);
        let svg = &text[text.find("<svg").unwrap()..text.rfind("</svg>").unwrap() + 6];
        let heights: Vec<f64> = svg
            .match_indices("<g data-z=\"")
            .map(|(i, m)| {
                let rest = &svg[i + m.len()..];
                rest[..rest.find('"').unwrap()].parse().unwrap()
            })
            .collect();
        // 8 mm at 0.2 mm: 40 layers, each cut at its middle.
        assert_eq!(heights.len(), 40, "{heights:?}");
        assert!((heights[0] - 0.1).abs() < 1e-9 && (heights[39] - 7.9).abs() < 1e-9);
        assert!(heights.windows(2).all(|w| w[0] < w[1]));
        let pixmap = render(svg, &format!("3d-{file}"));
        // The mean row of blue pixels lies below (a larger y) that of red ones.
        let (mut blue, mut red) = ((0.0, 0usize), (0.0, 0usize));
        for (i, c) in pixmap.pixels().iter().enumerate() {
            let y = (i as u32 / pixmap.width()) as f64;
            let (r, g, b) = (c.red() as i32, c.green() as i32, c.blue() as i32);
            if b > r + 60 && b > g + 60 {
                blue = (blue.0 + y, blue.1 + 1);
            }
            if r > b + 60 && r > g + 60 {
                red = (red.0 + y, red.1 + 1);
            }
        }
        assert!(blue.1 > 50 && red.1 > 50, "{blue:?} {red:?}");
        assert!(blue.0 / blue.1 as f64 > red.0 / red.1 as f64);
    }
}

/// `rotlang preview project.3mf --object NAME` (the mesh in the template's place): the
/// named object of a 3MF's build, placed as on the plate; a name it does not hold is a
/// usage error listing those it holds.
#[test]
fn preview_of_a_3mf_object() {
    use std::io::Write;
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("mesh-3mf");
    std::fs::create_dir_all(&dir).unwrap();
    let object = |id: u32, name: &str, mesh: &rotlang_geometry::mesh::Mesh| {
        let mut s = format!(r#"<object id="{id}" name="{name}" type="model"><mesh><vertices>"#);
        for v in &mesh.vertices {
            s.push_str(&format!(
                r#"<vertex x="{}" y="{}" z="{}"/>"#,
                v[0], v[1], v[2]
            ));
        }
        s.push_str("</vertices><triangles>");
        for t in &mesh.triangles {
            s.push_str(&format!(
                r#"<triangle v1="{}" v2="{}" v3="{}"/>"#,
                t[0], t[1], t[2]
            ));
        }
        s + "</triangles></mesh></object>"
    };
    let model = format!(
        r#"<?xml version="1.0"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>{}{}</resources><build><item objectid="1" transform="1 0 0 0 1 0 0 0 1 50 0 0"/><item objectid="2"/></build></model>"#,
        object(
            1,
            "Box",
            &rotlang_geometry::mesh::shapes::cuboid([20.0, 20.0, 6.0])
        ),
        object(
            2,
            "Tube",
            &rotlang_geometry::mesh::shapes::tube(8.0, 4.0, 6.0, 48)
        ),
    );
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    zip.start_file("3D/3dmodel.model", zip::write::SimpleFileOptions::default())
        .unwrap();
    zip.write_all(model.as_bytes()).unwrap();
    let path = dir.join("project.3mf");
    std::fs::write(&path, zip.finish().unwrap().into_inner()).unwrap();
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .arg("preview")
            .arg(&path)
            .args(["--layers", "10", "--format", "json"])
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&["--object", "Box"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let section = &v["layers"][0]["section"];
    assert_eq!(section.as_array().unwrap().len(), 1);
    // The box, moved 50 mm along x by its build item.
    let xs: Vec<f64> = section[0][0]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p[0].as_f64().unwrap())
        .collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(
        (lo - 50.0).abs() < 1e-6 && (hi - 70.0).abs() < 1e-6,
        "{lo} {hi}"
    );
    // Both objects without --object: two islands, the tube's with its hole.
    let out = run(&[]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["layers"][0]["section"].as_array().unwrap().len(), 2);
    let out = run(&["--object", "Boat"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("Box, Tube"));
}

/// Issue 17: `rotlang preview` draws the layers a slicer prints solid as solid: the bottom
/// and top shells of the model, where the template says sparse (the template still turns
/// them), and says what the colours mean in a legend.
#[test]
fn preview_prints_shell_layers_solid_with_a_legend() {
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(args)
            .output()
            .expect("rotlang runs");
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    // The 20 mm cube: 100 layers, 3 bottom and 4 top shell layers.
    let json: serde_json::Value = serde_json::from_str(&run(&[
        "preview",
        "+30",
        "--pattern",
        "grid",
        "--layers",
        "0..100",
        "--format",
        "json",
    ]))
    .unwrap();
    let layers = json["layers"].as_array().unwrap();
    assert_eq!(layers.len(), 100);
    for l in layers {
        let i = l["index"].as_u64().unwrap();
        let shell = !(3..96).contains(&i);
        assert_eq!(l["fill"], "sparse", "the template's fill");
        assert_eq!(
            l["printed"],
            if shell { "solid" } else { "sparse" },
            "layer {i}"
        );
        assert_eq!(
            l["pattern"],
            if shell { "lines" } else { "grid" },
            "layer {i}"
        );
        let angle = l["angle"].as_f64().unwrap();
        assert!(
            (angle - 30.0 * (i + 1) as f64).abs() < 1e-9,
            "the template turns shells too"
        );
    }
    let svg = run(&["preview", "+30", "--layers", "1..5"]);
    assert!(
        svg.contains("shell, solid (lines)") && svg.contains("lines 20%"),
        "{svg}"
    );
    assert!(svg.contains("print order: first (blue) to last (red)"));
    assert!(svg.contains(r#"fill="url(#print-order)""#));
}
