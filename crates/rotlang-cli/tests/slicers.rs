//! rotlang on real slicers: every template is exported with `rotlang export`, sliced by
//! CuraEngine 4.13 and PrusaSlicer 2.5 (Debian's `cura-engine` and `prusa-slicer`,
//! installed through `scripts/ensure`), and read back with `rotlang gcode`: every sparse
//! layer must run the way the template says, within 1° (Cura: within its whole-degree
//! rounding, so 1.5°).
//!
//! CuraEngine needs Cura's printer definitions; they come from Debian's `cura` package
//! (the two JSON files only: `scripts/ensure deb-files`, not the application and its
//! hundred dependencies). Cura's settings that are formulas in the definitions are not
//! evaluated by CuraEngine, so the test sets the few the layers depend on.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

const TEMPLATES: [&str; 5] = ["0, 90", "+30/50%", "+45#3", "0, 15, 30", "+10L25%, -10l25%"];
/// 30 layers of 0.2 mm: 6 mm parts, two bottom and two top shell layers.
const LAYERS: usize = 30;
const HEIGHT: f64 = 6.0;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn work() -> PathBuf {
    let dir = root().join("target").join("slicers-test");
    std::fs::create_dir_all(&dir).expect("target/slicers-test");
    dir
}

/// Installs the slicers (once per run); `false` to skip outside CI when it cannot.
fn slicers() -> bool {
    static READY: OnceLock<bool> = OnceLock::new();
    *READY.get_or_init(|| {
        let ensure = |args: &[&str]| {
            Command::new(root().join("scripts/ensure"))
                .args(args)
                .status()
                .expect("scripts/ensure runs")
        };
        let apt = ensure(&["apt", "prusa-slicer", "cura-engine"]);
        let defs = work().join("cura");
        let files = ensure(&[
            "deb-files",
            "cura=4.13.0-1",
            defs.to_str().expect("utf-8 path"),
            DEFINITIONS[0],
            DEFINITIONS[1],
        ]);
        for s in [apt, files] {
            if s.code() == Some(77) {
                assert!(
                    std::env::var_os("CI").is_none(),
                    "the slicers cannot be installed here, and CI must run this test"
                );
                eprintln!("skipped: the slicers cannot be installed here (not root?)");
                return false;
            }
            assert!(s.success(), "scripts/ensure failed: {s}");
        }
        true
    })
}

const DEFINITIONS: [&str; 2] = [
    "usr/share/cura/resources/definitions/fdmprinter.def.json",
    "usr/share/cura/resources/definitions/fdmextruder.def.json",
];

/// An ASCII STL of a prism over `outline` (counter-clockwise), `height` mm tall.
fn prism(path: &Path, outline: &[(f64, f64)], height: f64) {
    let mut s = String::from("solid part\n");
    let mut facet = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        s.push_str(" facet normal 0 0 0\n  outer loop\n");
        for v in [a, b, c] {
            s.push_str(&format!("   vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        s.push_str("  endloop\n endfacet\n");
    };
    let n = outline.len();
    let (cx, cy) = (
        outline.iter().map(|p| p.0).sum::<f64>() / n as f64,
        outline.iter().map(|p| p.1).sum::<f64>() / n as f64,
    );
    for i in 0..n {
        let (p, q) = (outline[i], outline[(i + 1) % n]);
        facet([cx, cy, 0.0], [q.0, q.1, 0.0], [p.0, p.1, 0.0]);
        facet([cx, cy, height], [p.0, p.1, height], [q.0, q.1, height]);
        facet([p.0, p.1, 0.0], [q.0, q.1, 0.0], [q.0, q.1, height]);
        facet([p.0, p.1, 0.0], [q.0, q.1, height], [p.0, p.1, height]);
    }
    s.push_str("endsolid part\n");
    std::fs::write(path, s).expect("write the STL");
}

/// The cube, and an irregular convex part (nine corners at uneven radii and angles).
fn meshes() -> Vec<(&'static str, PathBuf)> {
    let dir = work();
    let cube = dir.join("cube.stl");
    prism(
        &cube,
        &[(0.0, 0.0), (20.0, 0.0), (20.0, 20.0), (0.0, 20.0)],
        HEIGHT,
    );
    let odd = dir.join("irregular.stl");
    let corners: Vec<(f64, f64)> = [
        (0.0, 14.0),
        (37.0, 11.0),
        (75.0, 15.5),
        (118.0, 12.0),
        (160.0, 13.0),
        (200.0, 16.0),
        (241.0, 10.5),
        (283.0, 14.5),
        (322.0, 12.5),
    ]
    .iter()
    .map(|&(a, r): &(f64, f64)| {
        (
            20.0 + r * a.to_radians().cos(),
            20.0 + r * a.to_radians().sin(),
        )
    })
    .collect();
    prism(&odd, &corners, HEIGHT);
    vec![("cube", cube), ("irregular", odd)]
}

fn rotlang(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(args)
        .output()
        .expect("rotlang runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const MODEL: [&str; 8] = [
    "--layers",
    "30",
    "--layer-height",
    "0.2",
    "--bottom-shell-layers",
    "2",
    "--top-shell-layers",
    "2",
];

/// Reads a sliced file back: (matched, compared) with the template, asserting all match.
fn read_back(gcode: &Path, template: &str, tolerance: &str, what: &str) -> serde_json::Value {
    let (code, out, err) = rotlang(&[
        "gcode",
        gcode.to_str().expect("utf-8"),
        "--template",
        template,
        "--tolerance",
        tolerance,
        "--format",
        "json",
    ]);
    let v: serde_json::Value =
        serde_json::from_str(&out).unwrap_or_else(|e| panic!("{what}: {e}\n{out}\n{err}"));
    let layers = v["layers"].as_array().expect("layers");
    assert_eq!(layers.len(), LAYERS, "{what}: one row per layer");
    let (matched, compared) = (
        v["matched"].as_u64().expect("matched"),
        v["compared"].as_u64().expect("compared"),
    );
    let off: Vec<_> = layers
        .iter()
        .filter(|l| l["matches"] == false)
        .map(|l| {
            (
                l["index"].clone(),
                l["sparse"]["direction"].clone(),
                l["expected"].clone(),
            )
        })
        .collect();
    assert!(off.is_empty(), "{what}: layers off the template: {off:?}");
    // Every layer between the shells has sparse infill, and the 2 + 2 shell layers are
    // solid: the export kept the slicer's shells whole.
    assert_eq!(
        compared,
        (LAYERS - 2 - 2) as u64,
        "{what}: {compared} sparse layers"
    );
    for i in [0, 1, LAYERS - 2, LAYERS - 1] {
        let l = &layers[i];
        assert!(
            l["sparse"].is_null() && !l["solid"].is_null(),
            "{what}: layer {i} is a shell: {l}"
        );
    }
    assert_eq!(code, 0, "{what}: {err}");
    eprintln!("{what}: {matched} of {compared} sparse layers match");
    v
}

#[test]
fn cura_engine_prints_every_template_as_exported() {
    if !slicers() {
        return;
    }
    let defs = work()
        .join("cura")
        .join("usr/share/cura/resources/definitions");
    for (mesh_name, mesh) in meshes() {
        for template in TEMPLATES {
            // The shells get a solid template of their own: Cura's skin_angles.
            let mut args = vec![
                "export", "--to", "cura", "--format", "json", template, "--solid", "+30",
            ];
            args.extend(MODEL);
            let (code, out, err) = rotlang(&args);
            assert_eq!(code, 0, "{err}");
            let v: serde_json::Value = serde_json::from_str(&out).expect("json");
            let angles = v["settings"]["infill_angles"]
                .as_str()
                .expect("infill_angles");
            let skin = v["settings"]["skin_angles"].as_str().expect("skin_angles");
            let max_error = v["max_error"].as_f64().expect("max_error");
            assert!(max_error <= 0.5, "{template}: rounded by {max_error}");
            let gcode = work().join(format!("cura-{mesh_name}-{}.gcode", slug(template)));
            let setting = |k: &str, v: &str| ["-s".to_owned(), format!("{k}={v}")];
            let mut cmd = Command::new("CuraEngine");
            cmd.arg("slice")
                .arg("-j")
                .arg(defs.join("fdmprinter.def.json"));
            for (k, val) in [
                ("infill_pattern", "lines"),
                ("infill_angles", angles),
                ("skin_angles", skin),
                ("infill_sparse_density", "20"),
                ("infill_line_distance", "2"),
                ("layer_height", "0.2"),
                ("layer_height_0", "0.2"),
                ("infill_sparse_thickness", "0.2"),
                ("bottom_layers", "2"),
                ("initial_bottom_layers", "2"),
                ("top_layers", "2"),
                ("machine_center_is_zero", "false"),
            ] {
                cmd.args(setting(k, val));
            }
            cmd.arg("-e0")
                .arg("-j")
                .arg(defs.join("fdmextruder.def.json"))
                .arg("-l")
                .arg(&mesh)
                .arg("-o")
                .arg(&gcode);
            let out = cmd.output().expect("CuraEngine runs");
            assert!(
                out.status.success(),
                "CuraEngine failed on {template}: {}",
                String::from_utf8_lossy(&out.stderr)
                    .lines()
                    .rev()
                    .take(5)
                    .collect::<Vec<_>>()
                    .join("\n")
            );
            // Whole degrees: up to 0.5° of rounding, plus the measurement's 1°.
            let what = format!("cura {mesh_name} `{template}`");
            let v = read_back(&gcode, template, "1.5", &what);
            if template == "0, 15, 30" {
                settings_as_cura_writes_them(&gcode, angles);
            }
            // `+30` turns the solid layers too: 30° × (layer + 1).
            for i in [0, 1, LAYERS - 2, LAYERS - 1] {
                let solid = v["layers"][i]["solid"]["direction"]
                    .as_f64()
                    .expect("solid");
                let want = (30.0 * (i + 1) as f64).rem_euclid(180.0);
                let off = (solid - want + 90.0).rem_euclid(180.0) - 90.0;
                assert!(
                    off.abs() <= 1.0,
                    "{what}: solid layer {i} at {solid}°, not {want}°"
                );
            }
        }
    }
}

#[test]
fn prusa_slicer_prints_every_template_from_its_3mf_project() {
    if !slicers() {
        return;
    }
    for (mesh_name, mesh) in meshes() {
        for template in TEMPLATES {
            let project = work().join(format!("prusa-{mesh_name}-{}.3mf", slug(template)));
            let gcode = project.with_extension("gcode");
            let mut args = vec![
                "export",
                "--to",
                "prusaslicer",
                template,
                "--mesh",
                mesh.to_str().expect("utf-8"),
                "--out",
                project.to_str().expect("utf-8"),
            ];
            args.extend(MODEL);
            let (code, _, err) = rotlang(&args);
            assert_eq!(code, 0, "{err}");
            let out = Command::new("prusa-slicer")
                .arg("--export-gcode")
                .arg(&project)
                .arg("-o")
                .arg(&gcode)
                .output()
                .expect("prusa-slicer runs");
            assert!(
                out.status.success() && gcode.exists(),
                "prusa-slicer failed on {template} ({}): {}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
                    .lines()
                    .rfind(|l| !l.contains("[trace]"))
                    .unwrap_or("")
            );
            read_back(
                &gcode,
                template,
                "1",
                &format!("prusaslicer {mesh_name} `{template}`"),
            );
        }
    }
}

/// PrusaSlicer's G-code carries its settings: without --template, `rotlang gcode` reads
/// fill_angle and the crossing of `rectilinear` from them, and finds them printed.
#[test]
fn prusa_slicer_settings_are_read_from_its_gcode() {
    if !slicers() {
        return;
    }
    let (_, cube) = meshes().remove(0);
    let config = work().join("crossed.ini");
    std::fs::write(
        &config,
        "fill_angle = 30\nfill_pattern = rectilinear\nfill_density = 20%\nlayer_height = 0.2\n\
         first_layer_height = 0.2\nbottom_solid_layers = 2\ntop_solid_layers = 2\n",
    )
    .expect("ini");
    let gcode = work().join("crossed.gcode");
    let status = Command::new("prusa-slicer")
        .arg("--export-gcode")
        .arg("--load")
        .arg(&config)
        .arg("-o")
        .arg(&gcode)
        .arg(&cube)
        .output()
        .expect("prusa-slicer runs")
        .status;
    assert!(status.success());
    let (code, out, err) = rotlang(&["gcode", gcode.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("PrusaSlicer 2.5"), "{out}");
    assert!(
        out.contains("fill_angle = 30 (rectilinear, crossed)"),
        "{out}"
    );
    // A wrong template is found out, on every other layer.
    let (code, out, _) = rotlang(&["gcode", gcode.to_str().expect("utf-8"), "--template", "30"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("OFF"), "{out}");
}

/// Cura's own front end (not CuraEngine) ends its G-code with its profile in `;SETTING_3`
/// lines: JSON of INI text, escaped once more, in pieces of 80 characters. Written here
/// as Cura 4 writes them, `rotlang gcode` reads `infill_angles` from them.
fn settings_as_cura_writes_them(gcode: &Path, angles: &str) {
    let profile = serde_json::json!({
        "global_quality": "[general]\nversion = 4\nname = test\n\n[values]\nlayer_height = 0.2\n",
        "extruder_quality": [format!(
            "[general]\nversion = 4\n\n[values]\ninfill_angles = {angles}\ninfill_pattern = lines\n"
        )],
    })
    .to_string();
    let escaped = profile.replace('\\', "\\\\").replace('\n', "\\n");
    let mut text = std::fs::read_to_string(gcode).expect("the G-code");
    for chunk in escaped.as_bytes().chunks(80) {
        text.push_str(";SETTING_3 ");
        text.push_str(std::str::from_utf8(chunk).expect("ASCII"));
        text.push('\n');
    }
    let with = gcode.with_extension("settings.gcode");
    std::fs::write(&with, text).expect("write");
    let (code, out, err) = rotlang(&["gcode", with.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(&format!("expected: infill_angles = {angles}")),
        "{out}"
    );
    assert!(
        out.contains("matched 26 of 26 sparse layers within 1°"),
        "{out}"
    );
}

fn slug(t: &str) -> String {
    t.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}
