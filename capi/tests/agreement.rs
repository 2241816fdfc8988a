//! The bindings' agreement table (`bindings/agreement/cases.json`): every case is what
//! `rotlang::api` gives (the table cannot drift from the core), and the C ABI gives
//! exactly the same (`tests/c/agreement.c`, compiled with gcc). The JavaScript
//! (`bindings/js/test/agreement.test.js`) and Python (`bindings/python/tests/
//! test_agreement.py`) suites assert the same table, so one input gets one answer, one
//! error kind and one message in all three.

mod common;

use std::io::Write;
use std::process::{Command, Stdio};

use common::*;
use rotlang::api::{self, ApiError, ModelSpec, Style};
use rotlang::dialect::{Dialect, orcaslicer};
use rotlang::eval::{self, limits, limits::Given};
use serde_json::Value;

fn cases() -> Vec<Value> {
    let path = root().join("bindings/agreement/cases.json");
    let text = std::fs::read_to_string(&path).expect("bindings/agreement/cases.json");
    let table: Value = serde_json::from_str(&text).expect("the table is JSON");
    table["cases"].as_array().expect("cases").clone()
}

/// A number of the table: a JSON number, or "NaN", "inf", "-inf".
fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => Some(s.parse().expect("NaN, inf or -inf")),
        _ => None,
    }
}

fn int(v: &Value) -> Option<Given> {
    v.as_i64()
        .map(|i| Given::Int(i.into()))
        .or_else(|| v.as_u64().map(|i| Given::Int(i.into())))
}

/// What a binding answered: every angle, or an error's kind and message.
#[derive(Debug, PartialEq)]
enum Outcome {
    Angles(Vec<f64>),
    Error(String, String),
}

impl From<ApiError> for Outcome {
    fn from(e: ApiError) -> Outcome {
        Outcome::Error(e.kind.as_str().to_string(), e.message)
    }
}

/// The case as the core reads it, in the order the Python binding reads its arguments.
fn core(case: &Value) -> Outcome {
    let run = || -> Result<Vec<f64>, Outcome> {
        let options = api::options(number(&case["base"]), int(&case["seed"]), limits::MAX_SEED)?;
        let target = api::target(case["target"].as_str().unwrap_or("sparse"))?;
        let dialect = api::dialect(case["dialect"].as_str().unwrap_or("rotlang"))?;
        let m = &case["model"];
        let heights: Option<Vec<f64>> = m["heights"]
            .as_array()
            .map(|a| a.iter().map(|h| number(h).expect("a height")).collect());
        let spec = ModelSpec {
            heights: heights.map(Into::into),
            layers: int(&m["layers"]),
            height: number(&m["height"]),
            layer_height: number(&m["layer_height"]),
            first_layer_height: number(&m["first_layer_height"]),
            bottom_shells: int(&m["bottom_shells"]),
            top_shells: int(&m["top_shells"]),
        };
        let model = spec.build(Style::Snake)?;
        let text = case["template"].as_str().expect("template");
        Ok(match dialect {
            Dialect::OrcaSlicer => orcaslicer::layers(text, &model, options)
                .map(|l| l.angle)
                .collect(),
            Dialect::Rotlang => {
                let parse = rotlang::parse(text, target);
                if parse.has_errors() {
                    return Err(Outcome::Error("template".into(), String::new()));
                }
                eval::layers(&parse.template, &model, options)
                    .map(|l| l.angle)
                    .collect()
            }
        })
    };
    run().map_or_else(|e| e, Outcome::Angles)
}

/// Whether `outcome` is the case's `expect` (for `binding`: a `BINDING_message` replaces
/// the message where the bindings' ranges differ by design).
fn meets(case: &Value, outcome: &Outcome, binding: &str) -> bool {
    let expect = &case["expect"];
    match outcome {
        Outcome::Angles(angles) => {
            let head: Vec<f64> = expect["head"]
                .as_array()
                .map(|h| h.iter().filter_map(Value::as_f64).collect())
                .unwrap_or_default();
            expect["count"].as_u64() == Some(angles.len() as u64)
                && angles.len() >= head.len()
                && angles.iter().zip(&head).all(|(a, h)| same(*a, *h))
                && angles
                    .last()
                    .zip(expect["last"].as_f64())
                    .is_some_and(|(a, l)| same(*a, l))
        }
        Outcome::Error(kind, message) => {
            let wanted = expect[format!("{binding}_message")]
                .as_str()
                .or(expect["message"].as_str());
            expect["error"].as_str() == Some(kind.as_str())
                && (kind == "template" || wanted == Some(message.as_str()))
        }
    }
}

/// The same double, or its neighbour: serde_json's float parsing (without its
/// `float_roundtrip` feature) may miss the last bit of a 17-digit number. The bindings'
/// answers are compared with each other exactly (`assert_eq!` on the outcomes), and by
/// the JavaScript and Python tests with their own exact parsers.
fn same(a: f64, b: f64) -> bool {
    a == b || a.to_bits().abs_diff(b.to_bits()) == 1
}

fn in_c(case: &Value) -> bool {
    case["only"]
        .as_array()
        .is_none_or(|only| only.iter().any(|b| b == "c"))
}

#[test]
fn the_table_is_what_the_core_gives() {
    let cases = cases();
    assert!(cases.len() >= 30, "{}", cases.len());
    let mut wrong = Vec::new();
    for case in &cases {
        let outcome = core(case);
        if !meets(case, &outcome, "python") {
            wrong.push(format!("{}: the core gives {outcome:?}", case["name"]));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // Both kinds of answer and both kinds of refusal are in the table.
    let kinds = |k: &str| cases.iter().filter(|c| c["expect"]["error"] == k).count();
    assert!(
        kinds("options") >= 5 && kinds("model") >= 10,
        "too few refusals"
    );
    assert!(
        cases
            .iter()
            .filter(|c| c["expect"]["count"].is_u64())
            .count()
            >= 10
    );
}

/// The case as a line of `tests/c/agreement.c`'s input.
fn c_line(case: &Value) -> String {
    let names = |field: &str, names: &[&str]| -> usize {
        let name = case[field].as_str().unwrap_or(names[0]);
        names
            .iter()
            .position(|n| *n == name)
            .expect("a C row names a known value")
    };
    let m = &case["model"];
    let f = |v: &Value, default: f64| format!("{:?}", number(v).unwrap_or(default));
    let u = |v: &Value, default: u64| v.as_u64().unwrap_or(default).to_string();
    let heights: Vec<String> = m["heights"]
        .as_array()
        .map(|a| a.iter().map(|h| f(h, 0.0)).collect())
        .unwrap_or_default();
    let kind = match (m["heights"].is_array(), m["layers"].is_u64()) {
        (true, _) => 2,
        (false, true) => 1,
        _ => 0,
    };
    assert!(m.is_null() || kind != 0, "C has no model by height: {case}");
    let mut fields = vec![
        names("dialect", &api::DIALECTS).to_string(),
        names("target", &api::TARGETS).to_string(),
        kind.to_string(),
        u(&m["layers"], 0),
        f(&m["layer_height"], 0.2),
        f(&m["first_layer_height"], 0.0),
        u(&m["bottom_shells"], 3),
        u(&m["top_shells"], 4),
        f(&case["base"], 0.0),
        u(&case["seed"], 0),
        heights.len().to_string(),
    ];
    fields.extend(heights);
    fields.push(case["template"].as_str().expect("template").to_string());
    fields.join(" ")
}

/// One line of `agreement.c`'s output as an outcome (the status as the error's kind).
fn c_outcome(line: &str) -> Outcome {
    if let Some(angles) = line.strip_prefix("ok") {
        return Outcome::Angles(
            angles
                .split_whitespace()
                .map(|a| a.parse().expect("an angle"))
                .collect(),
        );
    }
    let rest = line.strip_prefix("err ").expect("ok or err");
    let (status, message) = rest.split_once(' ').unwrap_or((rest, ""));
    let kind = match status {
        "4" => "options",
        "5" => "model",
        "6" => "template",
        other => panic!("status {other}: {message}"),
    };
    Outcome::Error(kind.into(), message.into())
}

#[test]
fn the_c_abi_gives_the_table() {
    if !ensure(&["apt", "gcc"]) {
        return;
    }
    let dir = scratch("agreement");
    let exe = dir.join("agreement");
    check(
        Command::new("gcc")
            .args([
                "-std=c11",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-pedantic",
                "-O1",
            ])
            .arg("-I")
            .arg(root().join("include"))
            .arg(root().join("capi/tests/c/agreement.c"))
            .arg(lib_dir().join("librotlang_capi.a"))
            .args(["-lpthread", "-ldl", "-lm", "-o"])
            .arg(&exe),
    );
    let cases: Vec<Value> = cases().into_iter().filter(in_c).collect();
    assert!(cases.len() >= 25, "{}", cases.len());
    let input: String = cases.iter().map(|c| c_line(c) + "\n").collect();
    let mut child = Command::new(&exe)
        .env_remove("LD_LIBRARY_PATH")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run agreement");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("write the cases");
    let out = child.wait_with_output().expect("agreement's output");
    assert!(out.status.success());
    let out = String::from_utf8(out.stdout).expect("UTF-8");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), cases.len(), "{out}");
    let mut wrong = Vec::new();
    for (case, line) in cases.iter().zip(lines) {
        let outcome = c_outcome(line);
        if !meets(case, &outcome, "c") {
            wrong.push(format!("{}: C gives {outcome:?}", case["name"]));
        }
        // The same as the core, angle for angle (not only the table's head and last).
        assert_eq!(
            outcome_without_template_message(outcome),
            outcome_without_template_message(core(case)),
            "{}",
            case["name"]
        );
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // And under valgrind: no invalid access or leak on any case, refused ones included
    // (the handles freed, the last-error buffer sized).
    if ensure(&["apt", "valgrind"]) {
        let cases_file = dir.join("cases.txt");
        std::fs::write(&cases_file, &input).expect("write the cases");
        let checked = valgrind(&exe, &[cases_file.to_str().expect("UTF-8 path")]);
        assert!(checked.status.success());
        assert_eq!(String::from_utf8_lossy(&checked.stdout), out);
    }
}

/// A template error's message is each binding's own: compared by kind only.
fn outcome_without_template_message(o: Outcome) -> Outcome {
    match o {
        Outcome::Error(kind, _) if kind == "template" => Outcome::Error(kind, String::new()),
        other => other,
    }
}

/// The profile table (`bindings/agreement/profiles.json`) as the core reads it, in the
/// table's form (the JavaScript and Python suites compare theirs with the same form).
fn core_profile(case: &Value) -> Value {
    let bytes: Vec<u8> = match case["bytes"].as_array() {
        Some(b) => b
            .iter()
            .map(|v| v.as_u64().expect("a byte") as u8)
            .collect(),
        None => case["content"]
            .as_str()
            .expect("content")
            .as_bytes()
            .to_vec(),
    };
    match rotlang_profile::api::profile(case["file"].as_str().expect("file"), &bytes) {
        Err(e) => serde_json::json!({ "error": e.kind.as_str(), "message": e.message }),
        Ok(p) => serde_json::json!({
            "kind": p.kind,
            "templates": p.templates.iter().map(|t| serde_json::json!([
                t.key, api::TARGETS[usize::from(t.target == rotlang::Target::Solid)], t.text, t.base
            ])).collect::<Vec<_>>(),
            "model": {
                "layers": p.model.len(),
                "layer_height": p.model.layer_height(),
                "first_layer_height": p.first_layer_height,
                "bottom_shells": p.model.bottom_shells(),
                "top_shells": p.model.top_shells(),
            },
            "base": p.base,
            "has_errors": p.has_errors,
        }),
    }
}

#[test]
fn the_profile_table_is_what_the_core_gives() {
    let path = root().join("bindings/agreement/profiles.json");
    let table: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("profiles.json")).expect("JSON");
    let cases = table["cases"].as_array().expect("cases");
    assert!(cases.len() >= 5);
    for case in cases {
        let core = core_profile(case);
        assert!(
            same_json(&core, &case["expect"]),
            "{}: the core gives {core}",
            case["name"]
        );
    }
}

/// Equal JSON, numbers compared as doubles (the table's 0 is the core's 0.0).
fn same_json(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => x.as_f64() == y.as_f64(),
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same_json(x, y))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| same_json(v, w)))
        }
        _ => a == b,
    }
}
