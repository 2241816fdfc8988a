//! A preset's infill direction in both readings (the compat lint of `rotlang::dialect` on a
//! profile's model): moved here from the dialect's tests, which cannot read a preset.

use rotlang::Target;
use rotlang::dialect::compat::{DIFFERS, SPACE_SEPARATED_LIST};

fn preset(json: &str) -> rotlang_profile::profile::Profile {
    rotlang_profile::profile::parse(std::path::Path::new("p.json"), json.as_bytes())
        .expect("a preset")
}

#[test]
fn a_profile_direction_turns_an_empty_template_only_in_both_readings() {
    // Issue 16.3: `0 90` with direction 45 once said "layer 1 to 0°, rotlang to 135°"
    // (the real gap is 90°) and left layer 0 (0° against 45°) unflagged.
    let p = preset(r#"{"sparse_infill_rotate_template": "0 90", "sparse_infill_direction": "45"}"#);
    let pm = p.model(Target::Sparse, None, 20.0);
    assert_eq!(pm.direction.degrees, 45.0);
    assert_eq!(pm.direction.key.as_deref(), Some("sparse_infill_direction"));
    assert_eq!(pm.options("0 90").base, 0.0);
    assert_eq!(pm.options("").base, 45.0);
    let found = pm.compat("0 90", Target::Sparse);
    assert_eq!(
        found.iter().map(|d| d.code).collect::<Vec<_>>(),
        [SPACE_SEPARATED_LIST, DIFFERS]
    );
    assert_eq!(
        found[1].message,
        "OrcaSlicer turns layer 1 to 0°, rotlang to 90°"
    );
    // The same angles as each reading prints on its own with these options.
    let ours: Vec<f64> = rotlang::eval::layers(
        &rotlang::parse("0 90", Target::Sparse).template,
        &pm.model,
        pm.options("0 90"),
    )
    .map(|l| l.angle)
    .take(2)
    .collect();
    assert_eq!(ours, [0.0, 90.0]);
    // An empty template is the direction in both: nothing to report.
    assert!(pm.compat("", Target::Sparse).is_empty());
    // A preset that never sets a direction: OrcaSlicer's default 45° does not turn a
    // template, and its note bears on an empty template only.
    let plain =
        preset(r#"{"sparse_infill_rotate_template": "0, 90"}"#).model(Target::Sparse, None, 20.0);
    assert_eq!(
        (plain.direction.key.clone(), plain.options("0, 90").base),
        (None, 0.0)
    );
    assert!(plain.compat("0, 90", Target::Sparse).is_empty());
    assert!(
        plain
            .notes_for("0, 90")
            .iter()
            .all(|n| !n.contains("direction")),
        "{:?}",
        plain.notes_for("0, 90")
    );
    assert!(
        plain
            .notes_for("")
            .iter()
            .any(|n| n.contains("`sparse_infill_direction` not set"))
    );
}

#[test]
fn the_direction_key_is_named_as_the_file_spells_it() {
    let p = preset(r#"{"sparse_infill_rotate_template": "", "infill_direction": "30"}"#);
    let pm = p.model(Target::Sparse, None, 20.0);
    assert_eq!(pm.direction.key.as_deref(), Some("infill_direction"));
    assert_eq!(pm.options("").base, 30.0);
    let bad = preset(r#"{"solid_infill_direction": "north"}"#).model(Target::Solid, None, 20.0);
    assert_eq!(bad.direction.key, None);
    assert_eq!(
        bad.notes_for("").last().map(String::as_str),
        Some(
            "`solid_infill_direction` = `north` is not a number: OrcaSlicer's default 45° is used"
        )
    );
}
