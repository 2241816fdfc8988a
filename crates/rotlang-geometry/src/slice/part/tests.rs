use super::*;
use crate::mesh::shapes;
use geo::{Area, BoundingRect};

fn template(text: &str, target: crate::Target) -> Template {
    let parse = crate::parse(text, target);
    assert!(!parse.has_errors(), "{text}: {:?}", parse.diagnostics);
    parse.template
}

/// Every layer of `mesh` at 0.2 mm with 3 bottom and 4 top shell layers.
fn layers(mesh: &Mesh, sparse: &str, solid: Option<&str>) -> Vec<PartLayer> {
    let sparse = template(sparse, crate::Target::Sparse);
    let solid = solid.map(|s| template(s, crate::Target::Solid));
    let model = model_for(mesh, 0.2, None).unwrap().with_shells(3, 4);
    let mut part = Part::new(
        mesh,
        &sparse,
        &model,
        eval::Options::default(),
        Settings::default(),
        PartOptions::default(),
    );
    if let Some(solid) = &solid {
        part = part.with_solid_template(solid, eval::Options::default());
    }
    let mut out = Vec::new();
    while let Some(layer) = part.next() {
        // Memory: the sections of B + T + 1 layers at most.
        assert!(part.window.len() <= 3 + 4 + 1, "{}", part.window.len());
        out.push(layer.unwrap());
    }
    out
}

/// The x range of every point of `paths`.
fn x_range(paths: &Toolpaths) -> (f64, f64) {
    paths
        .polylines
        .iter()
        .flat_map(|p| p.0.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.x), hi.max(c.x))
        })
}

#[test]
fn a_cube_is_filled_inside_its_walls_with_solid_shells() {
    let cube = shapes::cuboid([20.0, 20.0, 10.0]);
    let layers = layers(&cube, "+45", None);
    assert_eq!(layers.len(), 50);
    let mut summary = Summary::default();
    for l in &layers {
        summary.add(l, 100.0, 200.0);
        // Two walls of 0.4 mm: a 18.4 mm square left for the infill.
        let a = l.infill_area.unsigned_area();
        assert!(
            (a - 18.4 * 18.4).abs() < 1e-6,
            "layer {}: {a}",
            l.layer.index
        );
        // The first 3 and last 4 layers solid throughout, the others sparse throughout.
        let solid = !(3..46).contains(&l.layer.index);
        assert_eq!(l.all_solid(), solid, "layer {}", l.layer.index);
        assert_eq!(
            l.solid.region.0.is_empty(),
            !solid,
            "layer {}",
            l.layer.index
        );
        assert_eq!(l.params().density == 1.0, solid, "layer {}", l.layer.index);
        let area = if solid { &l.solid } else { &l.sparse };
        assert!((area.region.unsigned_area() - a).abs() < 1e-6);
        assert!(!area.paths.polylines.is_empty());
    }
    assert_eq!(summary.layers, 50);
    assert!(summary.extrusion > 0.0 && summary.time > summary.extrusion / 100.0);
    assert!(summary.solid_extrusion > 0.0 && summary.solid_extrusion < summary.extrusion);
}

/// A 30 × 10 mm block 10 mm tall with a 10 × 10 mm tower on its left end, 10 mm taller:
/// the block's top beside the tower is solid on the 4 layers under it (and only there),
/// turned by the solid template; the tower above stays sparse (the block under it covers
/// it: no bottom surface), except its own top.
#[test]
fn the_top_of_a_step_is_solid_and_the_tower_above_it_sparse() {
    let step = shapes::step([30.0, 10.0, 10.0], [10.0, 10.0, 10.0]);
    let layers = layers(&step, "0", Some("90"));
    assert_eq!(layers.len(), 100);
    for l in &layers {
        let i = l.layer.index;
        let solid_area = l.solid.region.unsigned_area();
        match i {
            0..=2 | 96..=99 => assert!(l.all_solid(), "layer {i}"),
            46..=49 => {
                // The block less its walls is x 0.8..29.2, y 0.8..9.2; the tower covers
                // x < 10 of it.
                assert!(
                    (solid_area - 19.2 * 8.4).abs() < 1e-6,
                    "layer {i}: {solid_area}"
                );
                let sparse = l.sparse.region.unsigned_area();
                assert!((sparse - 9.2 * 8.4).abs() < 1e-6, "layer {i}: {sparse}");
                let rect = l.solid.region.bounding_rect().unwrap();
                assert!((rect.min().x - 10.0).abs() < 1e-9, "layer {i}: {rect:?}");
                // Solid lines on the right at 90° (the solid template), sparse lines on
                // the left at 0°.
                let (lo, _) = x_range(&l.solid.paths);
                let (_, hi) = x_range(&l.sparse.paths);
                assert!(lo > 10.0 && hi < 10.0, "layer {i}: {lo} {hi}");
                assert_eq!((l.solid.params.angle, l.sparse.params.angle), (90.0, 0.0));
                assert_eq!(
                    (l.solid.params.density, l.sparse.params.density),
                    (1.0, 0.2)
                );
                assert_eq!((l.solid.fill, l.sparse.fill), (Fill::Solid, Fill::Sparse));
                // Both areas' paths, with the move between them.
                assert_eq!(
                    l.paths.polylines.len(),
                    l.solid.paths.polylines.len() + l.sparse.paths.polylines.len()
                );
                assert!(l.paths.travel > l.solid.paths.travel + l.sparse.paths.travel);
            }
            _ => {
                assert!(l.solid.region.0.is_empty(), "layer {i}: {solid_area}");
                assert!(!l.sparse.paths.polylines.is_empty(), "layer {i}");
            }
        }
    }
}

/// A slab over a narrower column: its underside beside the column is a bottom surface,
/// solid on the slab's first 3 layers; over the column it is sparse.
#[test]
fn an_overhang_is_solid_underneath() {
    let t = shapes::overhang(10.0, 30.0, 10.0, 4.0);
    let layers = layers(&t, "+30", None);
    assert_eq!(layers.len(), 70);
    for l in &layers[50..] {
        let i = l.layer.index;
        let solid = l.solid.region.unsigned_area();
        match i {
            50..=52 => {
                // The slab less its walls: 28.4 × 8.4; the column under it covers
                // x 10..20 of it.
                assert!((solid - 18.4 * 8.4).abs() < 1e-6, "layer {i}: {solid}");
                assert!(!l.sparse.region.0.is_empty());
                // Turned by the sparse template without a solid one.
                assert_eq!(l.solid.params.angle, l.layer.angle);
            }
            66..=69 => assert!(l.all_solid(), "layer {i}"),
            _ => assert!(l.solid.region.0.is_empty(), "layer {i}: {solid}"),
        }
    }
}

/// A solid sign still makes its whole layer solid, with its own fill; a torus (every
/// layer's section has sloped walls) gets no slivers narrower than a line as solid.
#[test]
fn solid_signs_make_whole_layers_solid_and_slopes_no_slivers() {
    let cube = shapes::cuboid([20.0, 20.0, 10.0]);
    let layers = layers(&cube, "0, 90M", Some("45"));
    for l in &layers[3..46] {
        let m = l.layer.index % 2 == 1;
        assert_eq!(l.all_solid(), m, "layer {}", l.layer.index);
        if m {
            assert_eq!(l.solid.fill, Fill::Monotonic);
            assert_eq!(l.solid.params.angle, 90.0);
        }
    }
    // A torus 6 mm tall (minor radius 3): near its bottom and top the section widens or
    // narrows fast, and solid rings (inside and outside) join the solid layers; along its
    // flanks each layer overhangs the one under it by less than half a line, which is no
    // surface (a slicer's walls cover it): no solid there.
    let torus = shapes::torus(10.0, 3.0, 96, 48);
    let layers = layers_of(&torus);
    assert_eq!(layers.len(), 30);
    for l in &layers {
        let i = l.layer.index;
        let (all, solid) = (
            l.infill_area.unsigned_area(),
            l.solid.region.unsigned_area(),
        );
        match i {
            0 | 29 => assert_eq!(all, 0.0),
            1 | 2 | 26..=28 => assert!(l.all_solid(), "layer {i}"),
            3 | 24 | 25 => {
                assert_eq!(l.solid.region.0.len(), 2, "layer {i}: two rings");
                assert!(
                    solid > 0.1 * all && solid < 0.6 * all,
                    "layer {i}: {solid} of {all}"
                );
            }
            _ => assert_eq!(solid, 0.0, "layer {i}"),
        }
    }
}

fn layers_of(mesh: &Mesh) -> Vec<PartLayer> {
    layers(mesh, "+15", None)
}

/// The wall loops are each wall's middle line: a cube's two loops are squares 0.2 and
/// 0.6 mm inside its section, closed, and the infill area starts where the inner one's
/// line ends; a cylinder with a hole gets a loop round the hole as well.
#[test]
fn wall_loops_are_the_walls_middle_lines() {
    let cube = shapes::cuboid([20.0, 20.0, 2.0]);
    for l in layers(&cube, "+45", None) {
        let loops = l.wall_loops();
        assert_eq!(loops.len(), 2, "layer {}", l.layer.index);
        for (k, ring) in loops.iter().enumerate() {
            assert_eq!(ring.0.first(), ring.0.last(), "closed");
            let r = ring.bounding_rect().unwrap();
            let inside = 0.2 + 0.4 * k as f64;
            for (got, want) in [
                (r.min().x, inside),
                (r.min().y, inside),
                (r.max().x, 20.0 - inside),
                (r.max().y, 20.0 - inside),
            ] {
                assert!((got - want).abs() < 1e-9, "loop {k}: {got} vs {want}");
            }
        }
        // Half a line inside the inner loop: the infill area's edge.
        let area = l.infill_area.bounding_rect().unwrap();
        let inner = loops[1].bounding_rect().unwrap();
        assert!((area.min().x - inner.min().x - 0.2).abs() < 1e-9);
    }
    // No walls asked, none drawn.
    let sparse = template("+45", crate::Target::Sparse);
    let model = model_for(&cube, 0.2, None).unwrap();
    let options = PartOptions {
        walls: 0,
        ..PartOptions::default()
    };
    let mut part = Part::new(
        &cube,
        &sparse,
        &model,
        eval::Options::default(),
        Settings::default(),
        options,
    );
    assert!(part.next().unwrap().unwrap().wall_loops().is_empty());
    // A ring of outer radius 8 and hole radius 3: each wall has an outline loop and a
    // loop round the hole, outermost first.
    let tube = shapes::tube(8.0, 3.0, 4.0, 96);
    let l = &layers(&tube, "+45", None)[5];
    let loops = l.wall_loops();
    assert_eq!(loops.len(), 4);
    let width = |r: &LineString<f64>| {
        let b = r.bounding_rect().unwrap();
        b.max().x - b.min().x
    };
    assert!(width(&loops[0]) > width(&loops[2]) && width(&loops[0]) > 15.0);
    assert!(width(&loops[1]) < 7.0 && width(&loops[1]) < width(&loops[3]));
}
