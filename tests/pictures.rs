//! The pictures, rendered to pixels with resvg: the plot's line is where the angles say,
//! the preview's lines lie inside the region. The PNGs are kept in the test's temporary
//! directory (`target/tmp/pictures-*.png`) for a person to look at when a test fails.

use resvg::tiny_skia::{Pixmap, Transform};
use rotlang::eval::{Model, Options};
use rotlang::plot::{self, PlotOptions};

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
    let layout = plot::layout(&template, &model, options, &style);
    let picture = render(&svg, "plot");
    let line = hex(plot::LINE_COLOUR);
    let dots = hex(plot::POINT_COLOUR);
    let layers: Vec<_> = rotlang::eval::layers(&template, &model, options).collect();
    for l in layers.iter().step_by(7) {
        let x = layout.x((l.bottom + l.top) / 2.0);
        let y = layout.y_angle(l.angle);
        assert!(
            found(&picture, x, y, 2, line),
            "layer {}: no line at ({x}, {y}) for {}°",
            l.index,
            l.angle
        );
        let yd = layout.y_direction(l.angle.rem_euclid(180.0));
        assert!(
            found(&picture, x, yd, 2, dots),
            "layer {}: no point at ({x}, {yd})",
            l.index
        );
    }
    // And not everywhere: the line is absent well away from the angle (angles rise).
    let l = &layers[50];
    let x = layout.x((l.bottom + l.top) / 2.0);
    for dy in [-40.0, 40.0] {
        let y = layout.y_angle(l.angle) + dy;
        if y > layout.angles.y && y < layout.angles.y + layout.angles.h {
            assert!(
                !found(&picture, x, y, 1, line),
                "a line at ({x}, {y}), far from {}°",
                l.angle
            );
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

#[cfg(feature = "infill")]
mod preview {
    use super::*;
    use rotlang::infill::preview::{self, PreviewOptions};
    use rotlang::infill::{Pattern, Settings, shapes};

    fn inside(region: &rotlang::infill::MultiPolygon<f64>, x: f64, y: f64) -> bool {
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

/// The pictures checked in for the README are valid SVG with something drawn in them.
#[test]
fn readme_pictures_render() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/img");
    for name in ["plot", "preview", "preview-star"] {
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).expect("checked in");
        let picture = render(&svg, &format!("readme-{name}"));
        let coloured = picture
            .pixels()
            .iter()
            .filter(|c| {
                c.red().max(c.green()).max(c.blue()) - c.red().min(c.green()).min(c.blue()) > 80
            })
            .count();
        assert!(coloured > 1000, "{name}: {coloured} coloured pixels");
    }
}
