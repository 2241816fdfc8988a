//! The OrcaSlicer dialect (SEMANTICS.md section 10) against OrcaSlicer's own angles: every
//! case of `cases.jsonl` (its `orcaslicer` field) and of `dialect-text.jsonl` (OrcaSlicer's
//! function run on valid and invalid text).
//!
//! Angles compare modulo 360 within 1e-4°, relatively within 1e-9 above 1e9 (conformance
//! README). Findings must match the status exactly: NaN findings on exactly the `null`
//! layers, a hang at `orcaslicer.layer`, undefined behaviour where OrcaSlicer crashes, and
//! nothing else. `ROTLANG_CONFORMANCE=DIR` runs another corpus of the same kind (the
//! counts per status are then only printed, not compared with this corpus's).

use std::collections::{BTreeMap, HashMap};

use rotlang::dialect::{Finding, HANGS, NAN, UNDEFINED, orcaslicer};
use rotlang::eval::{Model, Options};
use serde::Deserialize;
use serde_json::Value;

const DEFAULT_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/conformance/");
const TOLERANCE: f64 = 1e-4;

fn dir() -> (String, bool) {
    match std::env::var("ROTLANG_CONFORMANCE") {
        Ok(d) if !d.is_empty() => (format!("{}/", d.trim_end_matches('/')), false),
        _ => (DEFAULT_DIR.to_owned(), true),
    }
}

fn read(name: &str) -> String {
    let path = format!("{}{name}", dir().0);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {path}: {e}"))
}

#[derive(Deserialize)]
struct NamedModel {
    layer_heights: Vec<f64>,
    layer_height: f64,
    bottom_shell_layers: u32,
    top_shell_layers: u32,
}

#[derive(Deserialize)]
struct InlineModel {
    layers: usize,
    layer_height: f64,
    first_layer_height: f64,
    bottom_shell_layers: u32,
    top_shell_layers: u32,
}

#[derive(Deserialize)]
struct Orca {
    status: String,
    #[serde(default)]
    degrees: Option<Vec<Option<f64>>>,
    #[serde(default)]
    layer: Option<usize>,
}

#[derive(Deserialize)]
struct Case {
    template: String,
    model: Value,
    #[serde(default)]
    degrees: Vec<f64>,
    orcaslicer: Orca,
}

fn named_models() -> HashMap<String, Model> {
    let specs: HashMap<String, NamedModel> =
        serde_json::from_str(&read("models.json")).expect("models.json");
    specs
        .into_iter()
        .map(|(name, s)| {
            let model = Model::from_heights(s.layer_heights, s.layer_height)
                .unwrap_or_else(|e| panic!("model {name}: {e}"))
                .with_shells(s.bottom_shell_layers, s.top_shell_layers);
            (name, model)
        })
        .collect()
}

fn cases(name: &str) -> Vec<Case> {
    read(name)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .enumerate()
        .map(|(i, l)| serde_json::from_str(l).unwrap_or_else(|e| panic!("{name}:{}: {e}", i + 1)))
        .collect()
}

fn same_angle(got: f64, expected: f64) -> bool {
    if expected.abs() > 1e9 {
        return (got - expected).abs() <= 1e-9 * expected.abs();
    }
    let diff = (got - expected).rem_euclid(360.0);
    diff <= TOLERANCE || diff >= 360.0 - TOLERANCE
}

/// Runs the dialect on one case and compares angles and findings. `expected` has `None`
/// for the layers OrcaSlicer computes as NaN (those must be reported as NaN layers).
fn check(
    text: &str,
    model: &Model,
    expected: Option<&[Option<f64>]>,
    codes: &[&str],
    hang_layer: Option<usize>,
) -> Result<(), String> {
    let mut stream = orcaslicer::layers(text, model, Options::default());
    let mut nan_seen = 0;
    let mut index = 0;
    while let Some(layer) = stream.next() {
        if layer.index != index {
            return Err(format!("layer {index} yielded as {}", layer.index));
        }
        if !layer.angle.is_finite() || !(std::f64::consts::PI * layer.angle / 180.0).is_finite() {
            return Err(format!(
                "layer {index}: angle {} is not finite",
                layer.angle
            ));
        }
        let nan_now = stream
            .findings()
            .iter()
            .find(|f| f.code == NAN)
            .map_or(0, |f| f.layers);
        let reported_nan = nan_now > nan_seen;
        nan_seen = nan_now;
        if let Some(expected) = expected {
            match expected.get(index) {
                None => {
                    return Err(format!(
                        "layer {index} beyond the expected {}",
                        expected.len()
                    ));
                }
                Some(None) if !reported_nan => {
                    return Err(format!(
                        "layer {index}: OrcaSlicer's angle is NaN, not reported"
                    ));
                }
                Some(Some(e)) if reported_nan => {
                    return Err(format!("layer {index}: reported NaN, OrcaSlicer gives {e}"));
                }
                Some(Some(e)) if !same_angle(layer.angle, *e) => {
                    return Err(format!("layer {index}: expected {e}, got {}", layer.angle));
                }
                _ => {}
            }
        }
        index += 1;
    }
    if index != model.len() {
        return Err(format!("{index} layers, model has {}", model.len()));
    }
    if let Some(expected) = expected
        && expected.len() != index
    {
        return Err(format!("{index} layers, expected {}", expected.len()));
    }
    let findings: &[Finding] = stream.findings();
    let mut got: Vec<&str> = findings.iter().map(|f| f.code).collect();
    // Where OrcaSlicer crashes, the corpus has no angles: layers below the crash may be
    // NaN layers too (and then are reported), which the test cannot check layer by layer.
    if expected.is_none() {
        got.retain(|&c| c != NAN);
    }
    got.sort();
    let mut want = codes.to_vec();
    want.sort();
    if got != want {
        return Err(format!("findings {findings:?}, expected codes {want:?}"));
    }
    if let Some(layer) = hang_layer {
        let hang = findings.iter().find(|f| f.code == HANGS);
        if hang.map(|f| f.first_layer) != Some(layer) {
            return Err(format!(
                "hang reported as {hang:?}, expected at layer {layer}"
            ));
        }
    }
    Ok(())
}

fn run(case: &Case, model: &Model) -> Result<(), String> {
    let o = &case.orcaslicer;
    let theirs = || {
        o.degrees
            .as_deref()
            .ok_or_else(|| format!("status {} without orcaslicer.degrees", o.status))
    };
    match o.status.as_str() {
        "same" => {
            let degrees: Vec<Option<f64>> = case.degrees.iter().copied().map(Some).collect();
            check(&case.template, model, Some(&degrees), &[], None)
        }
        "differs" | "ok" => {
            let d = theirs()?;
            if d.iter().any(Option::is_none) {
                return Err("null angle in a case without NaN".into());
            }
            check(&case.template, model, Some(d), &[], None)
        }
        "nan" => check(&case.template, model, Some(theirs()?), &[NAN], None),
        "hangs" => {
            let layer = o.layer.ok_or("hangs without orcaslicer.layer")?;
            check(
                &case.template,
                model,
                Some(theirs()?),
                &[HANGS],
                Some(layer),
            )
        }
        "undefined" => check(&case.template, model, None, &[UNDEFINED], None),
        other => Err(format!("unknown status {other}")),
    }
}

/// Runs every case; returns the number of cases per status. Fails listing every failure.
fn run_all(
    file: &str,
    model_of: impl Fn(&Value) -> Result<Model, String>,
) -> BTreeMap<String, usize> {
    let cases = cases(file);
    let mut counts = BTreeMap::new();
    let mut failures = Vec::new();
    for case in &cases {
        *counts.entry(case.orcaslicer.status.clone()).or_insert(0) += 1;
        let result = model_of(&case.model).and_then(|model| run(case, &model));
        if let Err(e) = result {
            failures.push(format!(
                "{:?} on {} ({}): {e}",
                case.template, case.model, case.orcaslicer.status
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases in {file} fail:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    eprintln!("{file}: all {} cases pass: {counts:?}", cases.len());
    counts
}

fn counts(pairs: &[(&str, usize)]) -> BTreeMap<String, usize> {
    pairs.iter().map(|&(s, n)| (s.to_owned(), n)).collect()
}

#[test]
fn corpus_cases() {
    let models = named_models();
    let got = run_all("cases.jsonl", |m| {
        let name = m.as_str().ok_or("model is not a name")?;
        models
            .get(name)
            .cloned()
            .ok_or_else(|| format!("unknown model {name}"))
    });
    if dir().1 {
        let want = counts(&[("same", 1081), ("differs", 451), ("nan", 28), ("hangs", 12)]);
        assert_eq!(got, want, "cases per status in cases.jsonl");
    }
}

#[test]
fn dialect_text_cases() {
    let got = run_all("dialect-text.jsonl", |m| {
        let m: InlineModel = serde_json::from_value(m.clone()).map_err(|e| e.to_string())?;
        Model::uniform(m.layers, m.layer_height, Some(m.first_layer_height))
            .map(|model| model.with_shells(m.bottom_shell_layers, m.top_shell_layers))
            .map_err(|e| e.to_string())
    });
    if dir().1 {
        let want = counts(&[("ok", 5357), ("nan", 838), ("undefined", 81), ("hangs", 24)]);
        assert_eq!(got, want, "cases per status in dialect-text.jsonl");
    }
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    /// Text made mostly of the characters OrcaSlicer gives a meaning to, with numbers at
    /// the 32-bit and 64-bit edges, plus any character at all.
    fn text() -> impl Strategy<Value = String> {
        let piece = prop_oneof![
            8 => proptest::sample::select(vec![
                "+", "-", "%", "*", "!", "@", "'", "\"", "c", "m", "mm", "/", "N", "n", "Z", "z",
                "$", "L", "l", "U", "u", "Q", "q", "|", "#", "B", "T", "D", "S", "M", "R", ",", " ",
                "\t", "\n", ":", ".", "e", "x", "p", "0x", "inf", "nan", "0", "1", "5", "9", "45",
                "22.5", "1e308", "1e-320", "2147483647", "2147483648", "4294967296",
                "-2147483648", "99999999999999999999", "08", "0x7fffffff", "°", "𝕏",
            ])
            .prop_map(str::to_owned),
            1 => any::<char>().prop_map(String::from),
        ];
        proptest::collection::vec(piece, 0..24).prop_map(|v| v.concat())
    }

    fn model() -> impl Strategy<Value = Model> {
        (1usize..160, 0.05f64..0.6, 0.05f64..0.6, 0u32..6, 0u32..6).prop_map(
            |(n, h, first, b, t)| {
                Model::uniform(n, h, Some(first))
                    .expect("valid heights")
                    .with_shells(b, t)
            },
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

        /// Any text: every layer comes out, finite in degrees and in radians; findings have
        /// known codes and name layers of the model; a hang or undefined behaviour halts.
        #[test]
        fn any_text_terminates_finite(text in text(), model in model(), base in -720.0f64..720.0) {
            let mut stream = orcaslicer::layers(&text, &model, Options { base, seed: 1 });
            let mut count = 0;
            for layer in stream.by_ref() {
                prop_assert_eq!(layer.index, count);
                prop_assert!(layer.angle.is_finite());
                prop_assert!((std::f64::consts::PI * layer.angle / 180.0).is_finite());
                if let Some(span) = layer.instruction {
                    prop_assert!(text.get(span.range()).is_some());
                }
                count += 1;
            }
            prop_assert_eq!(count, model.len());
            let findings = stream.findings();
            prop_assert!(findings.iter().filter(|f| f.code != NAN).count() <= 1);
            for f in findings {
                prop_assert!([HANGS, UNDEFINED, NAN].contains(&f.code));
                prop_assert!(f.first_layer < model.len() && f.layers >= 1);
                prop_assert!(f.first_layer + f.layers <= model.len());
            }
        }
    }
}

/// `rotlang expand --dialect orcaslicer`: OrcaSlicer's angles for any text, findings on
/// stderr, exit 0; the grammar's errors do not stop it.
#[test]
fn cli_expand_dialect() {
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(args)
            .output()
            .expect("run rotlang");
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (code, out, err) = run(&[
        "expand",
        "--dialect",
        "orcaslicer",
        "0 90",
        "--layers",
        "2",
        "--format",
        "csv",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        out,
        "index,bottom,top,angle,fill,start,end,instruction\n0,0,0.2,0,sparse,0,4,0 90\n1,0.2,0.4,0,sparse,0,4,0 90\n"
    );
    let (code, out, _) = run(&["expand", "0 90", "--layers", "2", "--format", "csv"]);
    assert_eq!(code, Some(0));
    assert!(out.contains("\n1,0.2,0.4,90,"), "{out}");
    let (code, out, err) = run(&[
        "expand",
        "--dialect",
        "orcaslicer",
        "10!, 5*",
        "--layers",
        "3",
        "--format",
        "csv",
    ]);
    assert_eq!(code, Some(0));
    assert!(out.ends_with("2,0.4,0.6,10,sparse,,,\n"), "{out}");
    assert!(
        err.contains("warning[orcaslicer::hangs]") && err.contains("layer 1"),
        "{err}"
    );
    // Text the grammar rejects still has OrcaSlicer's meaning.
    let (code, out, err) = run(&[
        "expand",
        "--dialect",
        "orcaslicer",
        "+10qq?",
        "--layers",
        "1",
        "--format",
        "csv",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("\n0,0,0.2,"), "{out}");
    let (code, _, err) = run(&["expand", "--dialect", "klipper", "0"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("expected `rotlang` or `orcaslicer`"), "{err}");
}

/// The compat lint on every corpus case, on the case's model: every case OrcaSlicer reads
/// differently (`differs`, `nan`, `hangs`) is flagged by a finding on the model; a `same`
/// case gets only rule-based findings (counted here, so that a change shows).
#[test]
fn compat_flags_every_case_orcaslicer_reads_differently() {
    use rotlang::Target;
    use rotlang::dialect::compat::{self, CODES, DIFFERS, RULES};
    let models = named_models();
    let mut rule_findings: BTreeMap<&str, usize> = BTreeMap::new();
    let mut same_with_rules = 0;
    let mut failures = Vec::new();
    for case in cases("cases.jsonl") {
        let model = &models[case.model.as_str().expect("model name")];
        let diagnostics = compat::compat(&case.template, Target::Sparse, model, Options::default());
        let codes: Vec<&str> = diagnostics.iter().map(|d| d.code).collect();
        let status = case.orcaslicer.status.as_str();
        let wanted = match status {
            "differs" => Some(DIFFERS),
            "nan" => Some(NAN),
            "hangs" => Some(HANGS),
            _ => None,
        };
        let on_model: Vec<&str> = codes
            .iter()
            .copied()
            .filter(|c| !RULES.contains(c))
            .collect();
        let ok = match wanted {
            Some(code) => on_model.contains(&code),
            None => on_model.is_empty(),
        };
        if !ok || codes.iter().any(|c| !CODES.contains(c)) {
            failures.push(format!(
                "{:?} on {} ({status}): {codes:?}",
                case.template, case.model
            ));
        }
        for d in &diagnostics {
            let severity_ok =
                matches!(d.code, c if [HANGS, NAN, UNDEFINED].contains(&c)) == d.is_error();
            if !severity_ok || d.labels.is_empty() {
                failures.push(format!("{:?}: bad diagnostic {d:?}", case.template));
            }
        }
        if status == "same" && !codes.is_empty() {
            same_with_rules += 1;
            for c in codes {
                *rule_findings.entry(c).or_insert(0) += 1;
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // A line the notes can quote as it is.
    let per_code: Vec<String> = rule_findings
        .iter()
        .map(|(code, n)| format!("{n} {code}"))
        .collect();
    eprintln!(
        "{same_with_rules} `same` cases get rule-based findings ({} findings: {})",
        rule_findings.values().sum::<usize>(),
        per_code.join(", ")
    );
    if dir().1 {
        let want: BTreeMap<&str, usize> = [
            ("orcaslicer::ignored-in-list", 28),
            ("orcaslicer::text-after-bang", 20),
        ]
        .into();
        assert_eq!(
            (same_with_rules, rule_findings),
            (40, want),
            "`same` cases with rule-based findings, and the findings per code"
        );
    }
}

/// `rotlang fmt` leaves a template alone when OrcaSlicer would read the canonical form
/// differently (`10,,20` is 10, 0, 20 for it), unless `--force`; `--write` keeps the file.
#[test]
fn cli_fmt_keeps_orcaslicer_meaning() {
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(args)
            .output()
            .expect("run rotlang");
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (code, out, err) = run(&["fmt", "10,,20", "+10 +20"]);
    assert_eq!(code, Some(1));
    assert_eq!(out, "10,,20\n+10, +20\n");
    assert!(
        err.contains("would change what OrcaSlicer does") && err.contains("--force"),
        "{err}"
    );
    let (code, out, _) = run(&["fmt", "--force", "10,,20"]);
    assert_eq!((code, out.as_str()), (Some(0), "10, 20\n"));
    let dir = std::env::temp_dir().join(format!("rotlang-dialect-fmt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("a.rot");
    std::fs::write(&path, "0 90\n").unwrap();
    let (code, out, _) = run(&["fmt", "--write", "--file", path.to_str().unwrap()]);
    assert_eq!((code, out.as_str()), (Some(1), ""));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "0 90\n");
    let (code, _, _) = run(&[
        "fmt",
        "--write",
        "--force",
        "--file",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "0, 90\n");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every `orcaslicer::` code `rotlang explain` documents: its example gets that code from
/// the compat lint on the 20 mm cube, at the documented severity.
#[test]
fn explained_compat_examples_report_their_code() {
    use rotlang::Target;
    let docs: Vec<_> = rotlang::explain::codes()
        .iter()
        .filter(|d| d.code.starts_with("orcaslicer::"))
        .collect();
    assert_eq!(docs.len(), rotlang::dialect::compat::CODES.len());
    for doc in docs {
        let base = 0.0;
        let found = rotlang::dialect::compat(
            doc.example,
            Target::Sparse,
            &Model::cube20(),
            Options { base, seed: 0 },
        );
        let d = found
            .iter()
            .find(|d| d.code == doc.code)
            .unwrap_or_else(|| {
                panic!(
                    "{} example {:?}: {:?}",
                    doc.code,
                    doc.example,
                    found.iter().map(|d| d.code).collect::<Vec<_>>()
                )
            });
        assert_eq!(d.severity.as_str(), doc.severity, "{}", doc.code);
    }
}

/// Every help text of a `rotlang::` diagnostic that says what OrcaSlicer does with the
/// characters its fix removes is checked against the dialect: OrcaSlicer's angles on the
/// cube with and without them (issue 16.4: the trailing `0 , 90 ,` was said to be read
/// as 0, where OrcaSlicer gives 0, 90, 0, 90).
#[test]
fn help_texts_about_orcaslicer_agree_with_the_dialect() {
    use rotlang::Target;
    let mut texts: Vec<String> = [
        "0 , 90 ,",
        "0, 90,",
        "0, 90,,",
        "10,,20",
        ", +10",
        "+10, , +20",
        "0 ,, 90",
        ",",
        "0,\n90,\n",
        "+30, 0,,",
    ]
    .map(str::to_owned)
    .to_vec();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../corpus");
    for dir in ["valid", "warn", "invalid"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap().flatten() {
            if entry.path().extension().is_some_and(|e| e == "rot")
                && let Ok(text) = std::fs::read_to_string(entry.path())
            {
                texts.push(text);
            }
        }
    }
    let model = Model::cube20();
    // In a profile whose direction is 45°: an empty template is 45°, anything else not.
    let angles = |t: &str| -> Vec<u64> {
        let options = orcaslicer::profile_options(
            t,
            Options {
                base: 45.0,
                seed: 0,
            },
        );
        orcaslicer::layers(t, &model, options)
            .map(|l| (l.angle * 1e6).round().to_bits())
            .collect()
    };
    let mut checked = 0;
    for text in &texts {
        for d in rotlang::parse(text, Target::Sparse).diagnostics {
            let Some(help) = d.help.as_deref().filter(|h| h.contains("OrcaSlicer")) else {
                continue;
            };
            let Some(fix) = &d.fix else { continue };
            let fixed = format!(
                "{}{}{}",
                &text[..fix.span.start],
                fix.replacement,
                &text[fix.span.end..]
            );
            let same = angles(text) == angles(&fixed);
            let says_same =
                help.contains("so does OrcaSlicer") || help.contains("as OrcaSlicer does");
            let says_differs = help.contains("OrcaSlicer reads this empty instruction");
            assert!(
                says_same || says_differs,
                "a help about OrcaSlicer this test does not know: {help:?}"
            );
            assert_eq!(same, says_same, "{text:?}: {help}");
            checked += 1;
        }
    }
    assert!(checked >= 8, "{checked} helps checked");
}
