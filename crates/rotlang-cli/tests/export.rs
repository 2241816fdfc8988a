//! `rotlang export` from the command line: what each slicer gets, and the errors.

use std::process::Command;

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

#[test]
fn cura_gets_the_period_turned_to_its_axis() {
    let (code, out, err) = rotlang(&["export", "--to", "cura", "0, 90"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "infill_angles = [90,0]\ninfill_sparse_thickness = 0.2\nbottom_layers = 3\ntop_layers = 4\n"
    );
    assert!(err.contains("note[slicer::axis]"), "{err}");
    let (_, out, err) = rotlang(&[
        "export", "--to", "cura", "+30/50%", "--layers", "40", "--format", "json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(v["layers"], 40);
    assert_eq!(
        v["settings"]["infill_angles"]
            .as_str()
            .map(|l| l.split(',').count()),
        Some(40)
    );
    let codes: Vec<&str> = v["notes"]
        .as_array()
        .expect("notes")
        .iter()
        .filter_map(|n| n["code"].as_str())
        .collect();
    assert!(
        codes.contains(&"slicer::rounded") && codes.contains(&"slicer::per-layer-list"),
        "{codes:?} {err}"
    );
}

#[test]
fn superslicer_and_orcaslicer() {
    let (_, out, _) = rotlang(&["export", "--to", "superslicer", "+30"]);
    assert!(
        out.contains("fill_angle = 30\nfill_angle_increment = 30\nfill_angle_template = \n"),
        "{out}"
    );
    assert!(out.contains("fill_angle_cross = 0"), "{out}");
    let (_, out, _) = rotlang(&["export", "--to", "superslicer", "0, 15, 30"]);
    assert!(out.contains("fill_angle_template = 0,15,30"), "{out}");
    let (code, out, err) = rotlang(&["export", "--to", "orcaslicer", "0 90"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with("sparse_infill_rotate_template = 0, 90\n"),
        "{out}"
    );
    assert!(err.contains("slicer::rewritten"), "{err}");
    let (code, out, err) = rotlang(&[
        "export",
        "--to",
        "orcaslicer",
        "#14, +15R",
        "--format",
        "json",
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("slicer::inexpressible") && err.contains("solid"),
        "{err}"
    );
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(v["error"]["code"], "slicer::inexpressible");
}

#[test]
fn prusaslicer_ranges_and_its_project() {
    // No shells: one range per layer (shell layers would be one range).
    let (code, out, err) = rotlang(&[
        "export",
        "--to",
        "prusaslicer",
        "0, 90",
        "--layers",
        "3",
        "--bottom-shell-layers",
        "0",
        "--top-shell-layers",
        "0",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("fill_pattern = alignedrectilinear"), "{out}");
    assert!(
        out.contains("# 0..0.2 = 0\n# 0.2..0.4 = 90\n# 0.4..0.6 = 0\n"),
        "{out}"
    );
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../target")
        .join("export-test");
    std::fs::create_dir_all(&dir).expect("dir");
    let stl = dir.join("tri.stl");
    std::fs::write(&stl, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 1\nendloop\nendfacet\nendsolid\n").expect("stl");
    let project = dir.join("p.3mf");
    let (code, _, err) = rotlang(&[
        "export",
        "--to",
        "prusaslicer",
        "0, 90",
        "--layers",
        "3",
        "--bottom-shell-layers",
        "0",
        "--top-shell-layers",
        "0",
        "--mesh",
        stl.to_str().expect("utf-8"),
        "--out",
        project.to_str().expect("utf-8"),
    ]);
    assert_eq!(code, 0, "{err}");
    let mut zip = zip::ZipArchive::new(std::fs::File::open(&project).expect("3mf")).expect("a zip");
    let mut ranges = String::new();
    std::io::Read::read_to_string(
        &mut zip
            .by_name("Metadata/Prusa_Slicer_layer_config_ranges.xml")
            .expect("ranges"),
        &mut ranges,
    )
    .expect("text");
    assert_eq!(ranges.matches("<range ").count(), 3, "{ranges}");
    assert!(
        ranges.contains("<range min_z=\"0.2\" max_z=\"0.4\">"),
        "{ranges}"
    );
    assert!(
        ranges.contains("<option opt_key=\"fill_angle\">90</option>"),
        "{ranges}"
    );
    assert!(zip.by_name("3D/3dmodel.model").is_ok());
}

#[test]
fn usage_errors_and_bad_templates() {
    let (code, _, err) = rotlang(&["export", "--to", "cura", "0", "--mesh", "x.stl"]);
    assert_eq!(code, 2);
    assert!(err.contains("--mesh is for --to prusaslicer"), "{err}");
    let (code, _, err) = rotlang(&["export", "--to", "prusaslicer", "0", "--out", "x.3mf"]);
    assert_eq!(code, 2);
    assert!(err.contains("--mesh PART.stl"), "{err}");
    let (code, _, err) = rotlang(&[
        "export",
        "--to",
        "prusaslicer",
        "0",
        "--out",
        "/tmp/x.3mf",
        "--mesh",
        "/nonexistent.stl",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot read /nonexistent.stl"), "{err}");
    let (code, out, err) = rotlang(&["export", "--to", "cura", "+30X5", "--format", "json"]);
    assert_eq!(code, 1);
    assert!(err.contains("rotlang::unknown-sign"), "{err}");
    assert!(out.contains("\"errors\":1"), "{out}");
    let (code, _, err) = rotlang(&["export", "--to", "nowhere", "0"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn help_examples_run() {
    let (_, help, _) = rotlang(&["help", "export"]);
    for line in help
        .lines()
        .filter(|l| l.trim_start().starts_with("rotlang export"))
    {
        let cmd = line
            .trim_start()
            .split("  ")
            .next()
            .expect("command")
            .trim();
        if cmd.contains("--mesh") || cmd.contains("--profile") {
            continue; // need files
        }
        let args = shell_words(cmd);
        let argv: Vec<&str> = args.iter().skip(1).map(String::as_str).collect();
        let (code, _, err) = rotlang(&argv);
        assert_eq!(code, 0, "{cmd}: {err}");
    }
    let (_, help, _) = rotlang(&["help", "gcode"]);
    assert!(
        help.contains("rotlang gcode part.gcode --plot layers.svg"),
        "{help}"
    );
}

/// Splits a command line with single quotes (enough for the help's examples).
fn shell_words(s: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    for c in s.chars() {
        match c {
            '\'' => quoted = !quoted,
            ' ' if !quoted => {
                if !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                }
            }
            _ => cur.push(c),
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

#[test]
fn solid_templates_go_where_a_slicer_has_a_setting() {
    let (code, out, _) = rotlang(&["export", "--to", "cura", "0, 90", "--solid", "+30"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("skin_angles = [60,30,0,150,120,90]\n"),
        "{out}"
    );
    let (code, out, err) = rotlang(&["export", "--to", "orcaslicer", "0, 90", "--solid", "0 90"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("solid_infill_rotate_template = 0, 90\n"),
        "{out}"
    );
    let (code, _, err) = rotlang(&["export", "--to", "prusaslicer", "0", "--solid", "+30"]);
    assert_eq!(code, 1);
    assert!(err.contains("slicer::inexpressible"), "{err}");
    // Solid signs are errors in a solid template, reported against its own text.
    let (code, _, err) = rotlang(&["export", "--to", "cura", "0", "--solid", "+30M"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("<solid template>") && err.contains("solid-sign-in-solid-template"),
        "{err}"
    );
}
