//! Profiles, presets and projects: the fixtures of `tests/fixtures/profiles/` read by the
//! library and by `rotlang check` / `rotlang expand --profile`, and hostile files (corrupt,
//! truncated and bomb archives, text that is not UTF-8, huge files, wrong JSON types): an
//! error for that file, the other files still checked, never a panic.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

use proptest::prelude::*;
use rotlang::Target;
use rotlang_profile::profile::{self, Kind};

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/fixtures/profiles");

fn fixture(name: &str) -> PathBuf {
    Path::new(FIXTURES).join(name)
}

fn rotlang(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(args)
        .output()
        .expect("run rotlang");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A scratch folder removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("rotlang-profiles-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    fn file(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut z = zip::ZipWriter::new(&mut out);
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated);
        for (name, bytes) in entries {
            z.start_file(*name, options).unwrap();
            z.write_all(bytes).unwrap();
        }
        z.finish().unwrap();
    }
    out.into_inner()
}

#[test]
fn the_project_fixture() {
    let p = profile::read(&fixture("project.3mf")).unwrap();
    assert_eq!(p.kind, Some(Kind::ThreeMf));
    let found: Vec<(String, Option<String>, &str)> = p
        .templates
        .iter()
        .map(|f| (f.label(), f.object.clone(), f.text.as_str()))
        .collect();
    assert_eq!(
        found,
        [
            ("sparse_infill_rotate_template".to_owned(), None, "+90/5mm"),
            ("solid_infill_rotate_template".to_owned(), None, ""),
            (
                "sparse_infill_rotate_template (object Lid & hinge)".to_owned(),
                Some("Lid & hinge".to_owned()),
                "0, 1:4"
            ),
            (
                "solid_infill_rotate_template (object Lid & hinge / part Hinge)".to_owned(),
                Some("Lid & hinge / part Hinge".to_owned()),
                "+15#10"
            ),
        ]
    );
    // `&#x2B;15#10`: the `#` of the template is the file's `#`; the `+` is the reference.
    let hinge = &p.templates[3];
    let xml = &p.sources[hinge.source].text;
    assert_eq!(
        &xml[hinge.span_in_source(rotlang::Span::new(0, 1)).range()],
        "&#x2B;"
    );
    assert_eq!(
        &xml[hinge.span_in_source(rotlang::Span::new(3, 4)).range()],
        "#"
    );
    // The project's model; the Lid's own layer height overrides it.
    let m = p.model(Target::Sparse, None, 20.0);
    assert_eq!((m.model.layer_height(), m.model.top_shells()), (0.2, 5));
    assert_eq!(m.model.layer_bounds(0), Some((0.0, 0.3)));
    let lid = p.model(Target::Sparse, Some("Lid & hinge"), 20.0);
    assert_eq!(lid.model.layer_height(), 0.16);
}

/// A part's template takes every model key it does not set from its object, then from
/// the project: part → object → project.
#[test]
fn parts_inherit_from_their_object_then_the_project() {
    let project =
        br#"{"layer_height": "0.2", "top_shell_layers": "6", "sparse_infill_direction": "10"}"#;
    let model = br#"<?xml version="1.0" encoding="UTF-8"?>
<config>
  <object id="1">
    <metadata key="name" value="Box"/>
    <part id="2" subtype="normal_part">
      <metadata key="name" value="Plain"/>
      <metadata key="sparse_infill_rotate_template" value="0, 90"/>
    </part>
    <part id="3" subtype="normal_part">
      <metadata key="name" value="Own"/>
      <metadata key="bottom_shell_layers" value="7"/>
      <metadata key="sparse_infill_rotate_template" value="+30/5"/>
    </part>
    <metadata key="layer_height" value="0.12"/>
  </object>
</config>
"#;
    let bytes = zip_of(&[
        ("Metadata/project_settings.config", project),
        ("Metadata/model_settings.config", model),
    ]);
    let p = profile::parse(Path::new("parts.3mf"), &bytes).unwrap();
    let object = |f: &profile::Found| f.object.clone().unwrap();
    let plain = p.model(Target::Sparse, Some(&object(&p.templates[0])), 20.0);
    assert_eq!(object(&p.templates[0]), "Box / part Plain");
    // The object's 0.12 mm (set after its parts), the project's top shells and direction.
    assert_eq!(plain.model.layer_height(), 0.12);
    assert_eq!(plain.model.top_shells(), 6);
    assert_eq!(plain.direction.degrees, 10.0);
    let own = p.model(Target::Sparse, Some(&object(&p.templates[1])), 20.0);
    assert_eq!(own.model.layer_height(), 0.12);
    assert_eq!((own.model.bottom_shells(), own.model.top_shells()), (7, 6));
    // The object itself keeps its own keys and not its part's.
    let object_model = p.model(Target::Sparse, Some("Box"), 20.0);
    assert_eq!(object_model.model.bottom_shells(), 3);
}

#[test]
fn presets_inherit_from_their_parents() {
    let p = profile::read(&fixture("orca/process/0.28mm Draft @Rotlang.json")).unwrap();
    let m = p.model(Target::Sparse, None, 20.0);
    assert_eq!(m.model.layer_height(), 0.28);
    assert_eq!(
        m.model.bottom_shells(),
        3,
        "from fdm_process_rotlang_common.json"
    );
    assert_eq!(m.direction.degrees, 30.0, "a number, not a string");
    assert!(m.notes.is_empty(), "{:?}", m.notes);
    let inherited = &p.settings.values["bottom_shell_layers"];
    assert!(
        inherited
            .inherited_from
            .as_ref()
            .unwrap()
            .ends_with("fdm_process_rotlang_common.json")
    );
    // The parent is not beside this one: each default is a note that says so.
    let p = profile::read(&fixture("user-overrides.jsonc")).unwrap();
    let m = p.model(Target::Sparse, None, 20.0);
    assert_eq!(m.model.layer_height(), 0.16);
    assert_eq!(m.notes.len(), 3, "{:?}", m.notes);
    assert!(
        m.direction.note.is_some(),
        "the direction's default, for an empty template"
    );
    assert!(
        m.notes[0].contains("parent preset `0.20mm Standard @Rotlang` (inherits) was not found")
    );
}

#[test]
fn check_runs_over_the_fixture_folder() {
    let (code, out, err) = rotlang(&["check", "--compat", "none", "--color", "never", FIXTURES]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.ends_with("ok: 15 templates in 8 files, no problems\n"),
        "{out}"
    );
    let (code, out, _) = rotlang(&[
        "check",
        "--compat",
        "orcaslicer",
        "--color",
        "never",
        FIXTURES,
    ]);
    assert_eq!(code, 0, "warnings only: {out}");
    // File, line:column in the file (inside the 3mf entry), key and object.
    assert!(out.contains("warning[orcaslicer::fraction]: sparse_infill_rotate_template (object Lid & hinge): OrcaSlicer has no `α:β` angles: it reads `1:4` as 1°"), "{out}");
    assert!(
        out.contains("project.3mf!Metadata/model_settings.config:14:61"),
        "{out}"
    );
    assert!(
        out.contains("warning[orcaslicer::space-separated-list]: solid_infill_rotate_template"),
        "{out}"
    );
    assert!(out.contains("0.12mm Fine @Rotlang.json:12:39"), "{out}");
    assert!(
        out.contains("warning[orcaslicer::text-after-bang]"),
        "{out}"
    );
    assert!(out.contains("user-overrides.jsonc:8:49"), "{out}");
    assert!(
        out.contains("note: ") && out.contains("OrcaSlicer's default 3 is used"),
        "{out}"
    );
    // OrcaSlicer's default direction turns no template here: no note about it.
    assert!(!out.contains("default 45° is used"), "{out}");
    // 9 findings on the templates; a profile's direction turns an empty template only, in
    // both readings, so the two never part on it.
    assert!(!out.contains("direction-ignored"), "{out}");
    assert!(
        out.ends_with("ok: 15 templates in 8 files, 9 warnings\n"),
        "{out}"
    );
}

#[test]
fn check_json_names_file_key_and_object() {
    let (code, out, _) = rotlang(&[
        "check",
        "--compat",
        "orcaslicer",
        "--format",
        "json",
        &fixture("project.3mf").display().to_string(),
    ]);
    assert_eq!(code, 0);
    let reports: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), 4);
    let lid = &reports[2];
    assert_eq!(lid["key"], "sparse_infill_rotate_template");
    assert_eq!(lid["object"], "Lid & hinge");
    assert!(lid["file"].as_str().unwrap().ends_with("project.3mf"));
    assert!(
        lid["source"]
            .as_str()
            .unwrap()
            .ends_with("project.3mf!Metadata/model_settings.config")
    );
    let codes: Vec<&str> = lid["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"orcaslicer::fraction"), "{codes:?}");
    // Line and column of the primary label in the entry (1-based, as people count).
    let fraction = lid["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["code"] == "orcaslicer::fraction")
        .unwrap();
    assert_eq!(
        (fraction["line"].as_u64(), fraction["column"].as_u64()),
        (Some(14), Some(61))
    );
}

#[test]
fn an_argument_naming_a_file_is_a_file() {
    let dir = Scratch::new("names");
    let json = dir.file("p.json", br#"{"sparse_infill_rotate_template": "+30X5"}"#);
    let (code, out, _) = rotlang(&["check", "--color", "never", &json.display().to_string()]);
    assert_eq!(code, 1);
    assert!(
        out.contains(
            "error[rotlang::unknown-sign]: sparse_infill_rotate_template: unknown sign `X`"
        ),
        "{out}"
    );
    assert!(out.contains("p.json:1:39"), "{out}");
    // A path that is not there: no such file (issue 16.5), not a template.
    let (code, out, _) = rotlang(&["check", "--color", "never", "missing.json"]);
    assert_eq!(code, 1);
    assert!(
        out.contains("error: missing.json: no such file or folder"),
        "{out}"
    );
    assert!(!out.contains("unknown sign"), "{out}");
}

#[test]
fn expand_with_a_profile() {
    let ini = fixture("export.ini").display().to_string();
    let (code, out, err) = rotlang(&["expand", "--profile", &ini, "--format", "csv"]);
    assert_eq!(code, 0, "{err}");
    // `5, 10!, +20` on 0.3 + 0.24 mm layers; sparse_infill_direction 45 turns an empty
    // template only, as in OrcaSlicer.
    let rows: Vec<&str> = out.lines().skip(1).take(3).collect();
    assert_eq!(
        rows,
        [
            "0,0,0.3,5,sparse,0,1,5",
            "1,0.3,0.54,10,sparse,3,6,10!",
            "2,0.54,0.78,30,sparse,8,11,+20"
        ]
    );
    assert!(
        err.contains("(84 layers of 0.24 mm, B = 4, T = 5, sparse_infill_direction 45° not applied (it turns an empty template only))"),
        "{err}"
    );
    // The profile's model unless the command line gives one; --base replaces the direction.
    let (_, out, _) = rotlang(&[
        "expand",
        "--profile",
        &ini,
        "--layers",
        "2",
        "--base",
        "10",
        "--format",
        "csv",
    ]);
    assert_eq!(out.lines().count(), 3);
    assert!(out.contains("\n0,0,0.2,15,"), "{out}");
    let (code, _, err) = rotlang(&[
        "expand",
        "--profile",
        &fixture("orca/filament/Generic PLA @Rotlang.json")
            .display()
            .to_string(),
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("no `sparse_infill_rotate_template` in this file"),
        "{err}"
    );
}

/// OrcaSlicer uses the infill direction only for an empty template, and so does rotlang's
/// reading of a profile (issue 16.3): `expand` in both dialects and the compat lint give
/// the same angles, and name the key as the file spells it.
#[test]
fn the_direction_turns_an_empty_template_only() {
    let dir = Scratch::new("direction");
    let dir45 = dir.file(
        "dir45.json",
        br#"{"sparse_infill_rotate_template": "0, 90", "sparse_infill_direction": "45", "layer_height": "0.2", "initial_layer_print_height": "0.2", "bottom_shell_layers": "3", "top_shell_layers": "4"}"#,
    );
    let empty = dir.file(
        "empty.json",
        br#"{"sparse_infill_rotate_template": "", "infill_direction": "30"}"#,
    );
    let spaced = dir.file(
        "spaced.json",
        br#"{"sparse_infill_rotate_template": "0 90", "infill_direction": "45"}"#,
    );
    let unset = dir.file(
        "unset.json",
        br#"{"sparse_infill_rotate_template": "0, 90"}"#,
    );
    let angles = |path: &Path, dialect: &str| {
        let (code, out, err) = rotlang(&[
            "expand",
            "--profile",
            &path.display().to_string(),
            "--dialect",
            dialect,
            "--format",
            "csv",
        ]);
        assert_eq!(code, 0, "{err}");
        out.lines()
            .skip(1)
            .take(2)
            .map(|row| row.split(',').nth(3).unwrap().to_owned())
            .collect::<Vec<_>>()
    };
    for dialect in ["orcaslicer", "rotlang"] {
        assert_eq!(angles(&dir45, dialect), ["0", "90"], "{dialect}");
        assert_eq!(
            angles(&unset, dialect),
            ["0", "90"],
            "{dialect}: no default 45°"
        );
        assert_eq!(angles(&empty, dialect), ["30", "30"], "{dialect}");
        assert_eq!(angles(&spaced, dialect)[0], "0", "{dialect}");
    }
    let (_, _, err) = rotlang(&["expand", "--profile", &dir45.display().to_string()]);
    assert!(
        err.contains("sparse_infill_direction 45° not applied (it turns an empty template only)"),
        "{err}"
    );
    let (_, _, err) = rotlang(&["expand", "--profile", &empty.display().to_string()]);
    assert!(err.contains(", infill_direction 30°)"), "{err}");
    let (_, _, err) = rotlang(&["expand", "--profile", &unset.display().to_string()]);
    assert!(!err.contains("45°"), "a default that turns nothing: {err}");
    let check = |path: &Path| {
        rotlang(&[
            "check",
            "--compat",
            "orcaslicer",
            "--color",
            "never",
            &path.display().to_string(),
        ])
    };
    let (code, out, _) = check(&dir45);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.ends_with("ok: 1 template in 1 file, no problems\n"),
        "{out}"
    );
    // `0 90`: OrcaSlicer 0, 0; rotlang 0, 90. Layer 0 agrees; layer 1 is 90° apart.
    let (_, out, _) = check(&spaced);
    assert!(
        out.contains("OrcaSlicer turns layer 1 to 0°, rotlang to 90°"),
        "{out}"
    );
    assert!(
        !out.contains("direction-ignored") && !out.contains("45°"),
        "{out}"
    );
}

/// A template key holding another type: `expand` says what `check` says, not "no key".
#[test]
fn expand_names_a_template_of_the_wrong_type() {
    let dir = Scratch::new("types");
    let types = dir.file("types.json", br#"{"sparse_infill_rotate_template": 5}"#);
    // Reported as `check` reports it, exit 1 (issue 16.5).
    let (code, _, err) = rotlang(&["expand", "--profile", &types.display().to_string()]);
    assert_eq!(code, 1);
    assert!(
        err.contains("error[profile::invalid]: `sparse_infill_rotate_template` should be a template (a string), not `5`"),
        "{err}"
    );
    assert!(err.contains("types.json:1:35"), "{err}");
    let (_, out, _) = rotlang(&["check", "--color", "never", &types.display().to_string()]);
    assert!(
        out.contains("`sparse_infill_rotate_template` should be a template (a string), not `5`"),
        "{out}"
    );
    let p = profile::read(&types).unwrap();
    assert!(p.template(Target::Sparse).is_err());
    assert_eq!(
        p.template(Target::Solid).unwrap_err(),
        "no `solid_infill_rotate_template` in this file"
    );
}

#[test]
fn hostile_files_fail_alone() {
    let dir = Scratch::new("hostile");
    let good = dir.file(
        "good.json",
        "\u{feff}{\r\n  \"sparse_infill_rotate_template\": \"0, 90\"\r\n}\r\n".as_bytes(),
    );
    let project = std::fs::read(fixture("project.3mf")).unwrap();
    let truncated = dir.file("truncated.3mf", &project[..project.len() / 2]);
    let mut flipped = project.clone();
    for b in flipped.iter_mut().skip(200).step_by(97) {
        *b ^= 0x5a;
    }
    let corrupt = dir.file("corrupt.3mf", &flipped);
    let not_zip = dir.file("fake.3mf", b"PK\x03\x04 this is not a zip archive");
    let bomb = dir.file(
        "bomb.3mf",
        &zip_of(&[("Metadata/project_settings.config", &vec![b' '; 20 << 20])]),
    );
    let latin1 = dir.file(
        "latin1.json",
        b"{\"sparse_infill_rotate_template\": \"45\xb0\"}",
    );
    let types = dir.file(
        "types.json",
        br#"{"sparse_infill_rotate_template": ["0", 90], "layer_height": {"x": 1}}"#,
    );
    let empty_zip = dir.file("empty.3mf", &zip_of(&[("3D/3dmodel.model", b"<model/>")]));
    let bad_xml = dir.file(
        "badxml.3mf",
        &zip_of(&[(
            "Metadata/model_settings.config",
            b"<config><object id=\"1\"><metadata key=\"a\" value=\"b\"/></part></config>",
        )]),
    );
    let huge = dir.0.join("huge.ini");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(profile::MAX_FILE_BYTES + 1)
        .unwrap();
    let path = |p: &PathBuf| p.display().to_string();
    let args = [
        &good, &truncated, &corrupt, &not_zip, &bomb, &latin1, &types, &empty_zip, &bad_xml, &huge,
    ];
    let mut argv = vec!["check".to_owned(), "--color".to_owned(), "never".to_owned()];
    argv.extend(args.iter().map(|p| path(p)));
    let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
    let (code, out, err) = rotlang(&argv);
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.is_empty(), "{err}");
    for (file, message) in [
        ("truncated.3mf", "not a readable 3mf (zip) archive"),
        ("fake.3mf", "not a readable 3mf (zip) archive"),
        ("bomb.3mf", "more than the 16 MiB a settings file can be"),
        ("latin1.json", "not UTF-8 text (invalid byte at offset 37)"),
        ("empty.3mf", "not an OrcaSlicer project"),
        ("badxml.3mf", "invalid XML at 1:53"),
        ("huge.ini", "larger than 64 MiB"),
    ] {
        assert!(
            out.lines()
                .any(|l| l.starts_with("error: ") && l.contains(file) && l.contains(message)),
            "{file}: {message}\n{out}"
        );
    }
    assert!(out.contains("corrupt.3mf"), "{out}");
    assert!(out.contains("error[profile::invalid]: `sparse_infill_rotate_template` should be a template (a string), not `90`"), "{out}");
    assert!(
        out.contains("warning[profile::value]: `layer_height` should be a string or a number"),
        "{out}"
    );
    // good.json (BOM, CRLF) is read and is clean.
    assert!(!out.contains("good.json"), "{out}");
}

/// Attributes are read by an XML reader: a `key="…"` inside another attribute's value is
/// text, entities are decoded, and the template keeps its place in the file.
#[test]
fn xml_attributes_are_read_as_xml() {
    let model = br#"<config><object id="1">
<metadata value=' key="sparse_infill_rotate_template"' key="layer_height"/>
<metadata key="solid_infill_rotate_template" value="&quot;0&quot;, &#x2B;30/50%"/>
</object></config>"#;
    let bytes = zip_of(&[("Metadata/model_settings.config", model)]);
    let p = profile::parse(Path::new("attrs.3mf"), &bytes).unwrap();
    let found: Vec<(&str, &str)> = p
        .templates
        .iter()
        .map(|f| (f.key.as_deref().unwrap(), f.text.as_str()))
        .collect();
    assert_eq!(found, [("solid_infill_rotate_template", "\"0\", +30/50%")]);
    let xml = &p.sources[p.templates[0].source].text;
    let at = |a, b| {
        &xml[p.templates[0]
            .span_in_source(rotlang::Span::new(a, b))
            .range()]
    };
    assert_eq!((at(0, 1), at(5, 6)), ("&quot;", "&#x2B;"));
    // The value of `layer_height` is the text that looked like a key.
    let object = &p.objects[0].1.values["layer_height"];
    assert_eq!(object.value, " key=\"sparse_infill_rotate_template\"");
    // A duplicate attribute is not XML: an error for the file.
    let dup = zip_of(&[(
        "Metadata/model_settings.config",
        br#"<config><object id="1"><metadata key="a" key="b" value="c"/></object></config>"#
            .as_slice(),
    )]);
    let e = profile::parse(Path::new("dup.3mf"), &dup).unwrap_err();
    assert!(e.message.contains("invalid XML attribute"), "{e}");
}

/// A preset is a flat object: a template key inside a nested object is not its template.
#[test]
fn only_top_level_keys_are_preset_keys() {
    let doc = br#"{"x": {"sparse_infill_rotate_template": "0 90", "layer_height": "0.1"}, "list": [{"solid_infill_rotate_template": "5"}], "sparse_infill_rotate_template": "+30/5", "layer_height": "0.16"}"#;
    let p = profile::parse(Path::new("nested.json"), doc).unwrap();
    let found: Vec<&str> = p.templates.iter().map(|f| f.text.as_str()).collect();
    assert_eq!(found, ["+30/5"]);
    assert_eq!(p.settings.values["layer_height"].value, "0.16");
    assert!(
        rotlang_profile::profile::json::find_templates(
            r#"{"x":{"sparse_infill_rotate_template":"0"}}"#
        )
        .is_empty()
    );
    // Arrays of values (per extruder) are still read.
    let p = profile::parse(
        Path::new("array.json"),
        br#"{"sparse_infill_rotate_template": ["0, 90"], "layer_height": ["0.1", "0.2"]}"#,
    )
    .unwrap();
    assert_eq!(p.templates[0].text, "0, 90");
    assert_eq!(p.settings.values["layer_height"].value, "0.1");
}

/// An archive of more entries than a project holds is refused before its directory is read.
#[test]
fn archives_of_too_many_entries_are_refused() {
    let names: Vec<String> = (0..=profile::MAX_ENTRIES)
        .map(|i| format!("e{i}"))
        .collect();
    let mut entries: Vec<(&str, &[u8])> = names.iter().map(|n| (n.as_str(), &b""[..])).collect();
    entries.push(("Metadata/project_settings.config", b"{}"));
    let bytes = zip_of(&entries);
    let e = profile::parse(Path::new("many.3mf"), &bytes).unwrap_err();
    assert_eq!(
        e.message,
        "a zip archive of 10002 entries, more than the 10000 a project can hold"
    );
    // Just under the cap is read.
    let bytes = zip_of(&entries[2..]);
    assert!(profile::parse(Path::new("fine.3mf"), &bytes).is_ok());
}

/// A zip whose headers claim a small entry that inflates to far more: the cap holds.
#[test]
fn lying_sizes_are_capped() {
    let mut bytes = zip_of(&[("Metadata/project_settings.config", &vec![b' '; 20 << 20])]);
    let real = (20u32 << 20).to_le_bytes();
    // Every uncompressed-size field (local header and central directory) says 100 bytes.
    let mut at = 0;
    while let Some(p) = bytes[at..].windows(4).position(|w| w == real) {
        let i = at + p;
        bytes[i..i + 4].copy_from_slice(&100u32.to_le_bytes());
        at = i + 4;
    }
    let result = profile::parse(Path::new("lying.3mf"), &bytes);
    let err = result.expect_err("a lying archive is an error");
    assert!(err.message.contains("project_settings.config"), "{err}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Any bytes, under any of the names: a profile or an error, never a panic.
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600), ext in 0usize..5) {
        let name = ["a.json", "a.jsonc", "a.ini", "a.3mf", "a.rot"][ext];
        if let Ok(p) = profile::parse(Path::new(name), &bytes) {
            for f in &p.templates {
                let text = &p.sources[f.source].text;
                let span = f.span_in_source(rotlang::Span::new(0, f.text.len()));
                prop_assert!(span.end <= text.len());
            }
            let _ = p.model(Target::Sparse, None, 20.0);
        }
    }

    /// The project fixture with a few bytes changed: read or refused, never a panic.
    #[test]
    fn damaged_projects_never_panic(edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..6)) {
        let mut bytes = std::fs::read(fixture("project.3mf")).unwrap();
        for (at, b) in edits {
            let i = at % bytes.len();
            bytes[i] = b;
        }
        let _ = profile::parse(Path::new("p.3mf"), &bytes);
    }

    /// JSON-ish text made of the characters that matter: templates map inside the file.
    #[test]
    fn jsonish_text_maps_inside_the_file(parts in proptest::collection::vec(proptest::sample::select(vec![
        "{", "}", "[", "]", ",", ":", "\"", "\\", "\\u00b0", "\\ud835", "//", "/*", "*/", "\n", " ",
        "\"sparse_infill_rotate_template\"", "\"layer_height\"", "0.2", "+30", "°", "𝕏", "true",
    ]), 0..40)) {
        let doc = parts.concat();
        let p = profile::parse(Path::new("x.jsonc"), doc.as_bytes()).unwrap();
        for f in &p.templates {
            let span = f.span_in_source(rotlang::Span::new(0, f.text.len()));
            prop_assert!(doc.get(span.range()).is_some(), "{span:?} in {doc:?}");
        }
        let _ = profile::json::strip_jsonc(&doc);
    }
}

/// Every `profile::` code `rotlang explain` documents: its example, read as a JSON preset,
/// gets a note of that severity (`check` reports notes under these codes).
#[test]
fn explained_profile_examples_report_their_code() {
    let docs: Vec<_> = rotlang::explain::codes()
        .iter()
        .filter(|d| d.code.starts_with("profile::"))
        .collect();
    assert_eq!(docs.len(), 2);
    for doc in docs {
        let p = profile::parse(Path::new("example.json"), doc.example.as_bytes()).unwrap();
        let error = doc.code == "profile::invalid";
        assert_eq!(doc.severity, if error { "error" } else { "warning" });
        assert!(
            p.notes.iter().any(|n| n.error == error),
            "{}: {:?}",
            doc.code,
            p.notes
        );
    }
}

/// Issue 22 item 2: many templates in one file take linear time (one line index per text,
/// not per template; a capped listing). Quadratic, these took hours.
#[test]
fn many_templates_in_one_file_are_read_in_one_pass() {
    let dir = Scratch::new("many");
    let keys = vec![r#""sparse_infill_rotate_template": "0, 90""#; 100_000].join(",");
    let dup = dir.file("dup.json", format!("{{{keys}}}").as_bytes());
    let values = vec![r#""0, 90""#; 100_000].join(", ");
    let array = dir.file(
        "array.json",
        format!("{{\"sparse_infill_rotate_template\": [{values}]}}").as_bytes(),
    );
    let ini = dir.file(
        "many.ini",
        "sparse_infill_rotate_template = X\n"
            .repeat(200_000)
            .as_bytes(),
    );
    let (code, out, _) = rotlang(&["check", "--color", "never", &dup.display().to_string()]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.ends_with("ok: 1 template in 1 file, 99999 warnings (99899 not shown)\n"),
        "{}",
        &out[out.len().saturating_sub(300)..]
    );
    let (code, out, _) = rotlang(&["check", &array.display().to_string()]);
    assert_eq!(code, 0);
    assert!(
        out.ends_with("ok: 100000 templates in 1 file, no problems\n"),
        "{out}"
    );
    // The JSON report goes to a file, read line by line: the test stays small.
    let report = dir.0.join("report.jsonl");
    let status = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["check", "--format", "json", &ini.display().to_string()])
        .stdout(std::fs::File::create(&report).unwrap())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(1));
    // One report per kept template and per duplicate note (past the first 100 listed,
    // a note's report lists no diagnostic and counts it as omitted); exact counts.
    let (mut lines, mut errors, mut warnings, mut listed) = (0, 0, 0, 0);
    for line in std::io::BufRead::lines(std::io::BufReader::new(
        std::fs::File::open(&report).unwrap(),
    )) {
        let r: serde_json::Value = serde_json::from_str(&line.unwrap()).unwrap();
        lines += 1;
        errors += r["errors"].as_u64().unwrap();
        warnings += r["warnings"].as_u64().unwrap();
        listed += r["diagnostics"].as_array().unwrap().len();
    }
    assert_eq!(
        (lines, errors, warnings, listed),
        (200_000, 1, 199_999, 100)
    );
}

/// The fixture project's entries, with `model_settings.config` replaced.
fn project_with_model(model: &[u8]) -> Vec<u8> {
    let bytes = std::fs::read(fixture("project.3mf")).unwrap();
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    let mut entries: Vec<(String, Vec<u8>)> = Vec::new();
    for i in 0..archive.len() {
        let mut f = archive.by_index(i).unwrap();
        let mut content = Vec::new();
        std::io::Read::read_to_end(&mut f, &mut content).unwrap();
        if f.name() == "Metadata/model_settings.config" {
            content = model.to_vec();
        }
        entries.push((f.name().to_owned(), content));
    }
    let refs: Vec<(&str, &[u8])> = entries
        .iter()
        .map(|(n, c)| (n.as_str(), c.as_slice()))
        .collect();
    zip_of(&refs)
}

/// Issue 22 item 4: a project whose model settings were cut after a complete line (the
/// `<object>` and `<config>` never closed) is an error naming the entry and what is lost,
/// not a smaller project.
#[test]
fn a_truncated_project_is_an_error() {
    let dir = Scratch::new("cut");
    let bytes = std::fs::read(fixture("project.3mf")).unwrap();
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    let mut model = String::new();
    std::io::Read::read_to_string(
        &mut archive.by_name("Metadata/model_settings.config").unwrap(),
        &mut model,
    )
    .unwrap();
    let cut = model.find("    <metadata key=\"layer_height\"").unwrap();
    let project = dir.file("cut.3mf", &project_with_model(&model.as_bytes()[..cut]));
    let e = profile::read(&project).unwrap_err();
    assert!(
        e.message
            .contains("Metadata/model_settings.config: truncated")
            && e.message.contains("`<object>` opened at 11:3")
            && e.message.contains("</object>, </config>")
            && e.message.contains("object Lid & hinge"),
        "{e}"
    );
    let (code, out, _) = rotlang(&["check", "--color", "never", &project.display().to_string()]);
    assert_eq!(code, 1);
    assert!(
        out.contains("error: ") && out.contains("truncated"),
        "{out}"
    );
    assert!(!out.contains("ok: "), "{out}");
    // The intact project still reads.
    let whole = dir.file("whole.3mf", &project_with_model(model.as_bytes()));
    assert_eq!(profile::read(&whole).unwrap().templates.len(), 4);
}

/// Issue 22 item 6: a key given twice keeps its last value, as OrcaSlicer's JSON reader
/// (nlohmann::json assigns a repeated key over the one before) and its 3mf reader (each
/// `<metadata>` set in turn) do; the earlier value is a warning, in check and expand alike.
#[test]
fn a_repeated_key_keeps_its_last_value_everywhere() {
    let dir = Scratch::new("dup");
    let json = dir.file(
        "dup.json",
        b"{\n\"sparse_infill_rotate_template\": \"X\",\n\"layer_height\": \"0.1\",\n\"sparse_infill_rotate_template\": \"5, 10\",\n\"layer_height\": \"0.25\"\n}",
    );
    let ini = dir.file(
        "dup.ini",
        b"sparse_infill_rotate_template = X\nsparse_infill_rotate_template = 5, 10\nlayer_height = 0.1\nlayer_height = 0.25\n",
    );
    let xml = br#"<config><object id="1"><metadata key="sparse_infill_rotate_template" value="X"/><metadata key="sparse_infill_rotate_template" value="5, 10"/><metadata key="layer_height" value="0.1"/><metadata key="layer_height" value="0.25"/></object></config>"#;
    let project = dir.file(
        "dup.3mf",
        &zip_of(&[("Metadata/model_settings.config", xml.as_slice())]),
    );
    for file in [&json, &ini, &project] {
        let p = profile::read(file).unwrap();
        let texts: Vec<&str> = p.templates.iter().map(|f| f.text.as_str()).collect();
        assert_eq!(texts, ["5, 10"], "{file:?}");
        let m = p.model(Target::Sparse, p.templates[0].object.as_deref(), 20.0);
        assert_eq!(m.model.layer_height(), 0.25, "{file:?}");
        let notes: Vec<&str> = p.notes.iter().map(|n| n.message.as_str()).collect();
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(
            notes
                .iter()
                .all(|n| n.contains("OrcaSlicer keeps the last value"))
        );
        let path = file.display().to_string();
        let (code, out, _) = rotlang(&["check", "--color", "never", &path]);
        assert_eq!(code, 0, "{out}");
        assert!(
            out.contains("2 warnings") && !out.contains("unknown"),
            "{out}"
        );
        let (code, out, _) = rotlang(&["expand", "--profile", &path, "--format", "csv"]);
        assert_eq!(code, 0);
        assert!(out.lines().nth(2).unwrap().contains(",10"), "{out}");
    }
}

/// Issue 22 item 6: numbers far from 1 are printed in exponent form, control characters of
/// the file are escaped in notes.
#[test]
fn odd_values_are_printed_legibly() {
    let dir = Scratch::new("odd");
    let file = dir.file(
        "odd.json",
        // `0 90`: OrcaSlicer reads it differently, so `check` gives its findings with the notes
        // on the model they were computed on.
        br#"{"layer_height": "1e-320", "inherits": "a\u0000b\u001b[31m", "sparse_infill_rotate_template": "0 90"}"#,
    );
    let path = file.display().to_string();
    let (_, out, err) = rotlang(&["check", "--compat", "orcaslicer", "--color", "never", &path]);
    let (_, _, err2) = rotlang(&["expand", "--profile", &path, "--range", "0..1"]);
    for text in [&out, &err2] {
        assert!(text.contains("the layer height is 1e-320"), "{text}{err}");
        assert!(!text.contains("00000000"), "{text}");
        assert!(text.contains(r"a\u{0}b\u{1b}[31m"), "{text}");
        assert!(!text.contains('\0') && !text.contains('\u{1b}'), "{text}");
    }
}

/// Issue 16 item 4: `check --fix --write` on presets and `.ini` exports changes only the
/// template's value (JSON-escaped in JSON, as read in `.ini`); every other byte stays.
#[test]
fn fix_write_changes_only_the_values() {
    let dir = Scratch::new("fixw");
    let cases: [(&str, &str, &str, &str); 3] = [
        (
            "p.json",
            "\u{feff}{\r\n  \"name\": \"x\",\t\"sparse_infill_rotate_template\": ",
            "\"+30/ 50%,\\t0\"",
            ",\r\n  \"layer_height\" : 0.2 }\r\n",
        ),
        (
            "p.jsonc",
            "// mine\n{\n  /* a */ \"solid_infill_rotate_template\": ",
            "\"+30/ 50%, \\u0030\"",
            ", // b\n  \"layer_height\": \"0.2\",\n}",
        ),
        (
            "p.ini",
            "; exported\nlayer_height = 0.2\nsparse_infill_rotate_template =  ",
            "+30/ 50%, 0",
            "  \r\n[x]\n",
        ),
    ];
    let want = [r#""+30/50%,\t0""#, r#""+30/50%, 0""#, "+30/50%, 0"];
    for ((name, before, value, after), want) in cases.iter().zip(want) {
        let file = dir.file(name, format!("{before}{value}{after}").as_bytes());
        let path = file.display().to_string();
        let (code, out, err) = rotlang(&["check", "--fix", "--write", &path]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(err.contains("1 file rewritten"), "{err}");
        let now = std::fs::read(&file).unwrap();
        assert!(now.starts_with(before.as_bytes()), "{name}");
        assert!(now.ends_with(after.as_bytes()), "{name}");
        let middle = &now[before.len()..now.len() - after.len()];
        assert_eq!(String::from_utf8_lossy(middle), want, "{name}");
        // Clean now: a second run changes nothing.
        let (code, _, err) = rotlang(&["check", "--fix", "--write", &path]);
        assert_eq!(code, 0);
        assert!(err.contains("0 files rewritten"), "{err}");
    }
    // Without --write the fixed file is printed, the file kept.
    let file = dir.file(
        "q.json",
        br#"{"sparse_infill_rotate_template": "+30/ 50%"}"#,
    );
    let (code, out, _) = rotlang(&["check", "--fix", &file.display().to_string()]);
    assert_eq!(
        (code, out.as_str()),
        (0, "{\"sparse_infill_rotate_template\": \"+30/50%\"}\n")
    );
    assert_eq!(
        std::fs::read(&file).unwrap(),
        br#"{"sparse_infill_rotate_template": "+30/ 50%"}"#
    );
    // A project: a clear refusal, the file untouched.
    let project = fixture("project.3mf");
    let (code, _, err) = rotlang(&["check", "--fix", "--write", &project.display().to_string()]);
    assert_eq!(code, 1);
    assert!(
        err.contains("--fix does not rewrite .3mf projects"),
        "{err}"
    );
}

/// Issue 22 item 5: `fmt --write` and `check --fix --write` write through a symbolic link
/// to its target, keep a hard-linked file one file (same inode), keep the mode and the
/// owner, and refuse a read-only file with a clear error (the file untouched).
#[cfg(unix)]
#[test]
fn writes_keep_links_mode_and_owner_and_refuse_read_only_files() {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    let dir = Scratch::new("links");
    let commands: [(&str, &[&str], &str, &str); 2] = [
        ("t.rot", &["fmt", "--write", "-f"], "0,90\n", "0, 90\n"),
        (
            "p.json",
            &["check", "--fix", "--write"],
            r#"{"sparse_infill_rotate_template": "+30/ 50%"}"#,
            r#"{"sparse_infill_rotate_template": "+30/50%"}"#,
        ),
    ];
    for (name, command, old, new) in commands {
        let run = |path: &Path| {
            let mut args = command.to_vec();
            let p = path.display().to_string();
            args.push(&p);
            rotlang(&args)
        };
        // A symbolic link: the target is fixed, the link stays a link.
        let target = dir.file(&format!("target-{name}"), old.as_bytes());
        let link = dir.0.join(format!("link-{name}"));
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let (code, _, err) = run(&link);
        assert_eq!(code, 0, "{err}");
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), new, "{name}");
        // A hard link: both names see the new text (one inode).
        let first = dir.file(&format!("first-{name}"), old.as_bytes());
        let second = dir.0.join(format!("second-{name}"));
        std::fs::hard_link(&first, &second).unwrap();
        let inode = std::fs::metadata(&first).unwrap().ino();
        let (code, _, err) = run(&first);
        assert_eq!(code, 0, "{err}");
        assert_eq!(std::fs::read_to_string(&second).unwrap(), new, "{name}");
        assert_eq!(std::fs::metadata(&first).unwrap().ino(), inode);
        // The mode stays (0640), and the owner (when we may give files away: root).
        let owned = dir.file(&format!("owned-{name}"), old.as_bytes());
        std::fs::set_permissions(&owned, std::fs::Permissions::from_mode(0o640)).unwrap();
        // SAFETY: geteuid has no preconditions.
        let root = unsafe { libc::geteuid() } == 0;
        if root {
            std::os::unix::fs::chown(&owned, Some(65534), Some(65534)).unwrap();
        }
        let (code, _, err) = run(&owned);
        assert_eq!(code, 0, "{err}");
        let meta = std::fs::metadata(&owned).unwrap();
        assert_eq!(meta.mode() & 0o7777, 0o640);
        if root {
            assert_eq!((meta.uid(), meta.gid()), (65534, 65534));
        }
        assert_eq!(std::fs::read_to_string(&owned).unwrap(), new, "{name}");
        // Read-only: refused, named, untouched (even for root, who could write it).
        let locked = dir.file(&format!("locked-{name}"), old.as_bytes());
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o444)).unwrap();
        let (code, _, err) = run(&locked);
        assert_eq!(code, 1, "{err}");
        assert!(err.contains("is read-only: not written"), "{err}");
        assert_eq!(std::fs::read_to_string(&locked).unwrap(), old);
        // No temporary file is left behind.
        let stray: Vec<_> = std::fs::read_dir(&dir.0)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
            .collect();
        assert!(stray.is_empty(), "{stray:?}");
    }
}
