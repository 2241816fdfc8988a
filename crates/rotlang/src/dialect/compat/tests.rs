//! Each finding of the compat lint on the smallest template that shows it.

use super::*;

fn lint(text: &str) -> Vec<Diagnostic> {
    compat(text, Target::Sparse, &Model::cube20(), Options::default())
}

fn codes(text: &str) -> Vec<&'static str> {
    lint(text).iter().map(|d| d.code).collect()
}

fn find(text: &str, code: &str) -> Diagnostic {
    lint(text)
        .into_iter()
        .find(|d| d.code == code)
        .unwrap_or_else(|| panic!("{text:?}: no {code} in {:?}", codes(text)))
}

fn fixed(text: &str, code: &str) -> Option<String> {
    find(text, code).fix.map(|f| {
        format!(
            "{}{}{}",
            &text[..f.span.start],
            f.replacement,
            &text[f.span.end..]
        )
    })
}

#[test]
fn agreeing_templates_are_clean() {
    for text in [
        "0, 90",
        "+10L25%, -10l25%",
        "5, 10!, +20",
        "",
        "+30/5",
        "B!, +30",
    ] {
        assert_eq!(codes(text), Vec::<&str>::new(), "{text:?}");
    }
}

#[test]
fn space_separated_list() {
    let d = find("0 90", SPACE_SEPARATED_LIST);
    assert_eq!(
        d.message,
        "OrcaSlicer reads only `0` here: in a plain list it separates angles at commas, not spaces"
    );
    assert_eq!(d.primary_span(), Span::new(1, 2));
    assert_eq!(
        fixed("0 90", SPACE_SEPARATED_LIST).as_deref(),
        Some("0, 90")
    );
    assert_eq!(
        fixed("0, 45 90  135", SPACE_SEPARATED_LIST).as_deref(),
        Some("0, 45, 90, 135")
    );
    assert!(codes("0 90").contains(&DIFFERS));
    // In the metalanguage reading spaces separate like commas.
    assert_eq!(codes("+10 +20"), Vec::<&str>::new());
}

#[test]
fn differs_names_both_angles_on_the_instruction() {
    let model = Model::uniform(20, 0.2, Some(0.3)).unwrap();
    let all = compat("+45/10#", Target::Sparse, &model, Options::default());
    let d = all.iter().find(|d| d.code == DIFFERS).unwrap();
    assert_eq!(
        d.message,
        "OrcaSlicer turns layer 9 to 47.25°, rotlang to 45°"
    );
    assert_eq!(d.primary_span(), Span::new(0, 7));
    assert_eq!(d.severity, crate::Severity::Warning);
    let d = find("0 90", DIFFERS);
    assert_eq!(d.message, "OrcaSlicer turns layer 1 to 0°, rotlang to 90°");
    assert_eq!(d.primary_span(), Span::new(2, 4));
    // Solid layers lost at equal angles.
    let d = find("#3, 0M", DIFFERS);
    assert_eq!(
        d.message,
        "OrcaSlicer makes layer 3 sparse infill, rotlang a monotonic solid layer"
    );
}

#[test]
fn hangs_nan_and_crashes_are_errors() {
    let d = find("10!, 5*", HANGS);
    assert!(d.is_error());
    assert!(d.message.contains("layer 1"), "{}", d.message);
    let model = Model::uniform(100, 0.2, Some(0.3)).unwrap();
    let all = compat("+22.5$50%", Target::Sparse, &model, Options::default());
    let nan = all.iter().find(|d| d.code == NAN).unwrap();
    assert!(nan.is_error());
    assert_eq!(nan.primary_span(), Span::new(0, 9));
    let d = find("0, +30/1e10", UNDEFINED);
    assert!(d.is_error());
    assert_eq!(d.primary_span(), Span::new(3, 11));
}

#[test]
fn fractions() {
    let d = find("1:4", FRACTION);
    assert_eq!(
        d.message,
        "OrcaSlicer has no `α:β` angles: it reads `1:4` as 1°"
    );
    assert_eq!(fixed("1:4", FRACTION).as_deref(), Some("25%"));
    assert_eq!(fixed("0, +1:8", FRACTION).as_deref(), Some("0, +12.5%"));
    // 1/3 of 360° has no short percentage: no fix.
    assert_eq!(fixed("1:3", FRACTION), None);
    assert_eq!(fixed("+10/1:4", FRACTION).as_deref(), Some("+10/25%"));
}

#[test]
fn solid_signs_shells_after_joint_random() {
    assert!(codes("+30M3").contains(&SOLID_SIGN));
    assert!(find("+30M3", SOLID_SIGN).fix.is_none());
    let d = find("+10/B", SHELLS_AFTER_JOINT);
    assert_eq!(d.primary_span(), Span::new(4, 5));
    assert!(codes("+10/-T").contains(&SHELLS_AFTER_JOINT));
    assert!(!codes("+10B").contains(&SHELLS_AFTER_JOINT));
    assert!(codes("+10~5").contains(&RANDOM));
    assert!(codes("+10^5").contains(&RANDOM));
}

#[test]
fn text_after_bang() {
    let d = find("+7!B", TEXT_AFTER_BANG);
    assert_eq!(d.message, "OrcaSlicer ignores `B` after the `!`");
    assert_eq!(fixed("+7!B", TEXT_AFTER_BANG).as_deref(), Some("+7B!"));
    assert_eq!(
        fixed("-175!q-27%", TEXT_AFTER_BANG).as_deref(),
        Some("-175q-27%!")
    );
    // `+75!` would be another angle: no fix.
    assert_eq!(fixed("+7!5", TEXT_AFTER_BANG), None);
    assert!(!codes("+7B!").contains(&TEXT_AFTER_BANG));
}

#[test]
fn empty_instructions() {
    assert_eq!(fixed("10,,20", EMPTY_INSTRUCTION).as_deref(), Some("10,20"));
    assert_eq!(
        fixed(", 10, 20", EMPTY_INSTRUCTION).as_deref(),
        Some(" 10, 20")
    );
    assert_eq!(
        fixed("0, 90, ", EMPTY_INSTRUCTION).as_deref(),
        Some("0, 90")
    );
    // A trailing comma is dropped by OrcaSlicer too.
    assert!(!codes("0, 90,").contains(&EMPTY_INSTRUCTION));
    // Metalanguage: only a leading separator makes an empty token.
    assert_eq!(fixed(", +10", EMPTY_INSTRUCTION).as_deref(), Some("+10"));
    assert!(!codes("+10,,+20").contains(&EMPTY_INSTRUCTION));
}

#[test]
fn plain_list_ignores_bang_and_shells() {
    let all = lint("10!, 20B");
    let spans: Vec<Span> = all
        .iter()
        .filter(|d| d.code == IGNORED_IN_LIST)
        .map(Diagnostic::primary_span)
        .collect();
    assert_eq!(spans, [Span::new(2, 3), Span::new(7, 8)]);
    assert!(codes("+10!, 20").iter().all(|c| *c != IGNORED_IN_LIST));
}

#[test]
fn every_fix_keeps_rotlang_meaning() {
    for text in ["0 90", "1:4", "+7!B", "10,,20", ", +10", "0, 90, "] {
        for d in lint(text) {
            if let Some(f) = d.fix {
                let after = format!(
                    "{}{}{}",
                    &text[..f.span.start],
                    f.replacement,
                    &text[f.span.end..]
                );
                assert!(
                    rules::keeps_meaning(text, &after, Target::Sparse),
                    "{text:?} -> {after:?}"
                );
                assert!(
                    !codes(&after).contains(&d.code) || d.code == EMPTY_INSTRUCTION,
                    "{text:?} -> {after:?} still has {}",
                    d.code
                );
            }
        }
    }
}

#[test]
fn orcaslicer_change_detects_rewrites_it_reads_differently() {
    assert!(orcaslicer_change("10,,20", "10, 20").is_some());
    assert!(orcaslicer_change("0 90", "0, 90").is_some());
    assert!(orcaslicer_change("  +10L25%", "+10L25%").is_some());
    assert_eq!(orcaslicer_change("0 90  +30/50%", "0, 90, +30/50%"), None);
    assert_eq!(orcaslicer_change("B!\n240M3\n#25", "B!, 240M3, #25"), None);
}

#[test]
fn solid_layer_messages_read_well() {
    // `S` once said "rotlang a solid solid layer".
    assert_eq!(
        find("0S, 90", DIFFERS).message,
        "OrcaSlicer makes layer 0 sparse infill, rotlang a solid layer"
    );
    assert_eq!(
        find("0M, 90", DIFFERS).message,
        "OrcaSlicer makes layer 0 sparse infill, rotlang a monotonic solid layer"
    );
}

fn lint_on(text: &str, target: Target, base: f64) -> Vec<Diagnostic> {
    compat(text, target, &Model::cube20(), Options { base, seed: 0 })
}

#[test]
fn an_explicit_base_turns_both_readings_alike() {
    // `--base` (an embedder's base) is added to every angle in both readings.
    assert!(lint_on("0, 90", Target::Sparse, 45.0).is_empty());
    let d = lint_on("0, 1:4", Target::Sparse, 45.0)
        .into_iter()
        .find(|d| d.code == DIFFERS)
        .expect("differs");
    assert_eq!(
        d.message,
        "OrcaSlicer turns layer 1 to 46°, rotlang to 135°"
    );
    // Retired: the two readings never part on the direction.
    assert!(!CODES.iter().any(|c| c.ends_with("::direction-ignored")));
}

#[test]
fn orcaslicer_options_in_a_profile_keep_the_direction_for_empty_text_only() {
    let with = Options {
        base: 45.0,
        seed: 7,
    };
    let (empty, set) = (
        orcaslicer::profile_options("", with),
        orcaslicer::profile_options("0, 90", with),
    );
    assert_eq!((empty.base, empty.seed), (45.0, 7));
    assert_eq!((set.base, set.seed), (0.0, 7));
}

#[test]
fn a_solid_template_is_not_said_to_become_sparse() {
    // Issue 17: the lint said OrcaSlicer "fills these layers as sparse infill" of a solid
    // template, whose layers are solid whatever the sign.
    let solid = compat("+15R", Target::Solid, &Model::cube20(), Options::default());
    let d = solid
        .iter()
        .find(|d| d.code == SOLID_SIGN)
        .expect("solid-sign");
    assert!(
        d.message.ends_with("with its own solid pattern"),
        "{}",
        d.message
    );
    assert!(!format!("{d:?}").contains("sparse"), "{d:?}");
    let sparse = compat("+15R", Target::Sparse, &Model::cube20(), Options::default());
    let d = sparse
        .iter()
        .find(|d| d.code == SOLID_SIGN)
        .expect("solid-sign");
    assert!(d.message.ends_with("as sparse infill"), "{}", d.message);
}
