//! Golden runs of the built `rotlang` binary: stdout, stderr and the exit code of each run
//! are snapshotted together (`tests/snapshots/cli__*.snap`).
//!
//! Runs have no terminal (pipes) and `NO_COLOR=1`, so reports are plain text.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Runs `rotlang ARGS` from the repository root, with `stdin` piped in (empty when `None`).
fn run(args: &[&str], stdin: Option<&str>) -> (String, i32) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rotlang"));
    cmd.args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .env("COLUMNS", "100")
        .env_remove("CLICOLOR_FORCE")
        .env_remove("RUST_BACKTRACE")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("the rotlang binary runs");
    {
        let mut input = child.stdin.take().unwrap();
        if let Some(text) = stdin {
            input.write_all(text.as_bytes()).unwrap();
        }
    }
    let out = child.wait_with_output().unwrap();
    let code = out
        .status
        .code()
        .expect("rotlang exits, it is not killed by a signal");
    let shown_args: Vec<String> = args.iter().map(|a| shell_quote(a)).collect();
    let mut golden = format!("$ rotlang {}\n", shown_args.join(" "));
    if let Some(text) = stdin {
        golden.push_str(&format!("stdin: {text:?}\n"));
    }
    golden.push_str(&format!(
        "exit: {code}\n----- stdout -----\n{}----- stderr -----\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ));
    (golden, code)
}

fn shell_quote(arg: &str) -> String {
    if !arg.is_empty()
        && arg
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_./=:".contains(&b))
    {
        arg.to_owned()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    }
}

/// Snapshots a run and checks its exit code.
macro_rules! golden {
    ($name:literal, $code:expr, $args:expr) => {
        golden!($name, $code, $args, None)
    };
    ($name:literal, $code:expr, $args:expr, $stdin:expr) => {{
        let (golden, code) = run(&$args, $stdin);
        insta::assert_snapshot!($name, golden);
        assert_eq!(code, $code, "exit code of {golden}");
    }};
}

/// A fresh directory under the system temp dir, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> TempDir {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos();
        let dir =
            std::env::temp_dir().join(format!("rotlang-cli-{tag}-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn file(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A run on files in a temp dir, with the dir shown as `[TMP]` so the snapshot is stable.
fn run_in(dir: &TempDir, args: &[&str]) -> (String, i32) {
    let (golden, code) = run(args, None);
    (golden.replace(&dir.0.display().to_string(), "[TMP]"), code)
}

// ── check ───────────────────────────────────────────────────────────────────────────────

#[test]
fn check_ok() {
    golden!(
        "check_ok",
        0,
        ["check", "+10L25%, -10l25%, -10L25%, +10l25%"]
    );
}

#[test]
fn check_warnings_exit_0() {
    golden!("check_warnings", 0, ["check", "400, 10,,20"]);
}

#[test]
fn check_deny_warnings_exit_1() {
    golden!(
        "check_deny_warnings",
        1,
        ["check", "--deny-warnings", "400"]
    );
}

#[test]
fn check_errors() {
    golden!("check_errors", 1, ["check", "+30X5, +45/10*2, 1:0"]);
}

#[test]
fn check_several_inputs() {
    golden!(
        "check_several",
        1,
        ["check", "0, 90", "+30X5", "400", "+30°"]
    );
}

#[test]
fn check_files() {
    golden!(
        "check_files",
        1,
        [
            "check",
            "--file",
            "corpus/valid/doc-bottom-240-monotonic3-25.rot",
            "-f",
            "corpus/invalid/two-joints-adjacent.rot",
            "+30/50%"
        ]
    );
}

#[test]
fn check_file_with_newlines() {
    let dir = TempDir::new("newlines");
    let path = dir.file("profile.rot", "0\n+30/5cn\n\n+10L25%\n");
    let (golden, code) = run_in(&dir, &["check", "--file", path.to_str().unwrap()]);
    insta::assert_snapshot!("check_file_with_newlines", golden);
    assert_eq!(code, 1);
}

#[test]
fn check_stdin() {
    golden!("check_stdin", 1, ["check"], Some("+30/50 %\n"));
}

#[test]
fn check_stdin_clean() {
    golden!("check_stdin_clean", 0, ["check"], Some("B!, +30\n"));
}

#[test]
fn check_json() {
    golden!("check_json", 1, ["check", "--format", "json", "+30/50 %"]);
}

#[test]
fn check_json_several_and_non_ascii() {
    // Offsets are bytes, columns characters: `α` is 2 bytes, `𝕏` 4.
    golden!(
        "check_json_several",
        1,
        ["check", "--format", "json", "0, 90", "α, +30°", "𝕏 400"]
    );
}

#[test]
fn check_json_lines_parse() {
    let (golden, code) = run(&["check", "--format", "json", "0", "+30X5", "10,,20"], None);
    assert_eq!(code, 1);
    let stdout = golden.split("----- stdout -----\n").nth(1).unwrap();
    let stdout = stdout.split("----- stderr -----").next().unwrap();
    let lines: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3, "one object per input");
    for line in &lines {
        let input = line["input"].as_str().unwrap();
        for d in line["diagnostics"].as_array().unwrap() {
            let (start, end) = (
                d["start"].as_u64().unwrap() as usize,
                d["end"].as_u64().unwrap() as usize,
            );
            assert!(start <= end && end <= input.len(), "{d}");
            assert!(["error", "warning"].contains(&d["severity"].as_str().unwrap()));
            for key in ["code", "message", "line", "column", "help"] {
                assert!(d.get(key).is_some(), "missing {key} in {d}");
            }
        }
    }
}

#[test]
fn check_negative_template_after_dashdash() {
    golden!("check_dashdash", 0, ["check", "--", "-30", "-10/5"]);
}

#[test]
fn check_negative_template_without_dashdash_is_a_usage_error() {
    golden!("check_negative_without_dashdash", 2, ["check", "-30/5"]);
}

#[test]
fn check_target_solid() {
    golden!(
        "check_target_solid",
        1,
        ["check", "--target", "solid", "#14, +15R", "+30/50%"]
    );
}

#[test]
fn check_target_sparse_allows_solid_signs() {
    golden!(
        "check_target_sparse",
        0,
        ["check", "--target", "sparse", "#14, +15R"]
    );
}

#[test]
fn check_usage_error_bad_option_value() {
    golden!(
        "check_usage_bad_format",
        2,
        ["check", "--format", "yaml", "0"]
    );
}

#[test]
fn check_usage_error_missing_file() {
    golden!(
        "check_usage_missing_file",
        2,
        ["check", "--file", "corpus/no-such-file.rot"]
    );
}

#[test]
fn usage_error_unknown_command() {
    golden!("usage_unknown_command", 2, ["frobnicate"]);
}

#[test]
fn check_help() {
    golden!("check_help", 0, ["check", "--help"]);
}

// ── fmt ─────────────────────────────────────────────────────────────────────────────────

#[test]
fn fmt_help() {
    golden!("fmt_help", 0, ["fmt", "--help"]);
}

#[test]
fn fmt_prints_canonical_form() {
    golden!(
        "fmt_print",
        0,
        [
            "fmt",
            "--force",
            "0 90  +30/50%",
            "  +10L25%,-10l25%\n\n#5 ,",
            "10,,20"
        ]
    );
}

#[test]
fn fmt_negative_template_after_dashdash() {
    golden!("fmt_dashdash", 0, ["fmt", "--", "-30 ,  +10"]);
}

#[test]
fn fmt_stdin() {
    golden!("fmt_stdin", 0, ["fmt"], Some("B!\n240M3\n#25\n"));
}

#[test]
fn fmt_check_canonical_exit_0() {
    golden!(
        "fmt_check_canonical",
        0,
        ["fmt", "--check", "0, 90, +30/50%"]
    );
}

#[test]
fn fmt_check_not_canonical_exit_1() {
    golden!(
        "fmt_check_not_canonical",
        1,
        ["fmt", "--check", "0, 90, +30/50%", "0 90"]
    );
}

#[test]
fn fmt_check_files() {
    let dir = TempDir::new("check");
    let good = dir.file("good.rot", "0, 90\n");
    let bad = dir.file("bad.rot", "0 ,90\n");
    let (golden, code) = run_in(&dir, &["fmt", "--check", "--file", good.to_str().unwrap()]);
    insta::assert_snapshot!("fmt_check_file_canonical", golden);
    assert_eq!(code, 0);
    let (golden, code) = run_in(
        &dir,
        &[
            "fmt",
            "--check",
            "-f",
            good.to_str().unwrap(),
            "-f",
            bad.to_str().unwrap(),
        ],
    );
    insta::assert_snapshot!("fmt_check_file_not_canonical", golden);
    assert_eq!(code, 1);
    assert_eq!(
        std::fs::read_to_string(&bad).unwrap(),
        "0 ,90\n",
        "--check never writes"
    );
}

#[test]
fn fmt_write_rewrites_the_file() {
    let dir = TempDir::new("write");
    let path = dir.file("a.rot", "0 90  +30/50%\n+10L25%,-10l25%\n");
    let (golden, code) = run_in(&dir, &["fmt", "--write", "--file", path.to_str().unwrap()]);
    insta::assert_snapshot!("fmt_write", golden);
    assert_eq!(code, 0);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "0, 90, +30/50%, +10L25%, -10l25%\n"
    );
    // Formatting the result again changes nothing.
    let (_, code) = run_in(&dir, &["fmt", "--check", "--file", path.to_str().unwrap()]);
    assert_eq!(code, 0);
}

#[test]
fn fmt_write_with_errors_writes_nothing() {
    let dir = TempDir::new("write-errors");
    let text = "0 90 +30X5\n";
    let path = dir.file("bad.rot", text);
    let (golden, code) = run_in(&dir, &["fmt", "--write", "--file", path.to_str().unwrap()]);
    insta::assert_snapshot!("fmt_write_errors", golden);
    assert_eq!(code, 1);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        text,
        "a template with errors is left alone"
    );
}

#[test]
fn fmt_errors_exit_1() {
    golden!("fmt_errors", 1, ["fmt", "0 90", "+30/5/"]);
}

#[test]
fn fmt_check_conflicts_with_write() {
    golden!(
        "fmt_usage_check_and_write",
        2,
        ["fmt", "--check", "--write", "0"]
    );
}

#[test]
fn check_empty_stdin_is_the_empty_template() {
    golden!("check_stdin_empty", 0, ["check"], Some(""));
}

#[test]
fn check_json_from_stdin() {
    golden!(
        "check_json_stdin",
        1,
        ["check", "--format", "json"],
        Some("+30°\n+10+20\n")
    );
}

#[test]
fn no_colour_without_a_terminal_even_without_no_color() {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["check", "+30X5, 400"])
        .env_remove("NO_COLOR")
        .env_remove("CLICOLOR_FORCE")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(!out.stdout.contains(&0x1b), "escape codes in piped output");
    assert!(!out.stderr.contains(&0x1b), "escape codes in piped output");
}

#[test]
fn colour_when_asked() {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["check", "--color", "always", "+30X5"])
        .env_remove("NO_COLOR")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(
        out.stdout.contains(&0x1b),
        "--color always colours piped output"
    );
}

// ── expand ──────────────────────────────────────────────────────────────────────────────

#[test]
fn expand_default_cube_table() {
    let (golden, code) = run(&["expand", "5, 10!, +20"], None);
    assert_eq!(code, 0);
    // 100 layers of the documentation's cube, after a header line.
    let stdout = golden.split("----- stdout -----\n").nth(1).unwrap();
    let rows: Vec<&str> = stdout
        .lines()
        .take_while(|l| !l.starts_with("-----"))
        .collect();
    assert_eq!(rows.len(), 101, "{golden}");
    let angles: Vec<&str> = rows[1..8]
        .iter()
        .map(|r| r.split_whitespace().nth(3).unwrap())
        .collect();
    // The documented sequence: 5, 10, 30, 5, 25, 5, 25.
    assert_eq!(angles, ["5", "10", "30", "5", "25", "5", "25"]);
}

#[test]
fn expand_uniform_model_csv() {
    golden!(
        "expand_uniform_csv",
        0,
        [
            "expand",
            "+10L25%, -10l25%",
            "--layers",
            "8",
            "--layer-height",
            "0.25",
            "--first-layer-height",
            "0.3",
            "--format",
            "csv",
            "--wrap",
            "360"
        ]
    );
}

#[test]
fn expand_height_json_with_solid_layers() {
    golden!(
        "expand_height_json",
        0,
        [
            "expand",
            "#2, +15R",
            "--height",
            "1.2",
            "--layer-height",
            "0.2",
            "--format",
            "json"
        ]
    );
}

#[test]
fn expand_model_file_and_stdin_template() {
    let dir = TempDir::new("expand");
    let model = dir.file(
        "model.json",
        r#"{"layer_heights": [0.3, 0.2, 0.2, 0.2], "layer_height": 0.2, "bottom_shell_layers": 2, "top_shell_layers": 1}"#,
    );
    let (golden, code) = run(
        &[
            "expand",
            "--model",
            model.to_str().unwrap(),
            "--format",
            "csv",
        ],
        Some("B!, +30\n"),
    );
    let golden = golden.replace(&dir.0.display().to_string(), "[TMP]");
    insta::assert_snapshot!("expand_model_file_stdin", golden);
    assert_eq!(code, 0);
}

#[test]
fn expand_negative_template_after_double_dash() {
    golden!(
        "expand_negative",
        0,
        [
            "expand",
            "--layers",
            "3",
            "--layer-height",
            "0.2",
            "--",
            "-50%Z1cm"
        ]
    );
}

#[test]
fn expand_errors_and_bad_models() {
    golden!("expand_template_error", 1, ["expand", "+30X5, 10,,20"]);
    golden!(
        "expand_warning_proceeds",
        0,
        ["expand", "400", "--layers", "2", "--layer-height", "0.2"]
    );
    golden!(
        "expand_no_layers",
        2,
        ["expand", "0", "--layers", "0", "--layer-height", "0.2"]
    );
    golden!(
        "expand_bad_height",
        2,
        ["expand", "0", "--layers", "3", "--layer-height", "-0.2"]
    );
}

// ── issue 9: the CLI as a newcomer meets it ──────────────────────────────────────────────

/// The stdout of a golden run.
fn stdout_of(golden: &str) -> &str {
    let out = golden.split("----- stdout -----\n").nth(1).unwrap();
    out.split("----- stderr -----").next().unwrap()
}

#[test]
fn space_after_a_joint_warns_with_a_fix() {
    golden!(
        "space_after_joint",
        0,
        ["check", "+30/ 50%", "+30# 10", "+10L 25%, -10l 25%"]
    );
    // The count cannot stand alone: the message names the space, not a missing joint.
    golden!("space_after_joint_error", 1, ["check", "+30/ 5cm"]);
}

#[test]
fn dash_is_stdin() {
    golden!(
        "stdin_dash_check",
        0,
        ["check", "0, 90", "-"],
        Some("+30/50%")
    );
    golden!(
        "stdin_dash_fmt_file",
        0,
        ["fmt", "--file", "-"],
        Some("0,90\n")
    );
    golden!(
        "stdin_dash_expand",
        0,
        ["expand", "-", "--layers", "2", "--format", "csv"],
        Some("+45")
    );
    golden!(
        "stdin_dash_twice",
        2,
        ["check", "-", "--file", "-"],
        Some("0")
    );
}

#[test]
fn numbers_have_no_float_noise() {
    golden!(
        "numbers_wrapped_csv",
        0,
        [
            "expand",
            "+10L25%, -10l25%, -90, +0.1, -0.1",
            "--layers",
            "12",
            "--layer-height",
            "0.1",
            "--wrap",
            "180",
            "--format",
            "csv"
        ]
    );
    // On many layers and every wrap: no exponent, no negative zero, no 180/360 after
    // wrapping, heights to the micrometre, angles to 1e-9.
    for wrap in ["none", "360", "180"] {
        let (golden, code) = run(
            &[
                "expand",
                "+10L25%, -10l25%, -30N7, +1:3/3, 0.1, -45$5, +360/2",
                "--layers",
                "3000",
                "--layer-height",
                "0.1",
                "--first-layer-height",
                "0.3",
                "--wrap",
                wrap,
                "--format",
                "csv",
            ],
            None,
        );
        assert_eq!(code, 0);
        for line in stdout_of(&golden).lines().skip(1) {
            let f: Vec<&str> = line.split(',').collect();
            for (i, v) in f[1..4].iter().enumerate() {
                assert!(!v.contains(['e', 'E']) && *v != "-0", "{line}");
                let decimals = v.split('.').nth(1).map_or(0, str::len);
                assert!(decimals <= if i < 2 { 6 } else { 9 }, "{line}");
                assert!(!v.ends_with('0') || !v.contains('.'), "{line}");
            }
            let angle: f64 = f[3].parse().unwrap();
            match wrap {
                "360" => assert!((0.0..360.0).contains(&angle), "{line}"),
                "180" => assert!((0.0..180.0).contains(&angle), "{line}"),
                _ => {}
            }
        }
    }
}

#[test]
fn negative_option_values_say_the_range() {
    golden!("negative_layers", 2, ["expand", "0", "--layers", "-5"]);
    golden!("negative_seed", 2, ["expand", "0", "--seed", "-1"]);
    golden!(
        "negative_shells",
        2,
        ["expand", "0", "--bottom-shell-layers", "-1"]
    );
    golden!("negative_template_first", 2, ["check", "-50%Z1cm"]);
}

#[test]
fn unquoted_templates_get_a_note() {
    golden!("pieces_check", 0, ["check", "0,", "90"]);
    golden!("pieces_unit", 1, ["check", "+30/50", "%"]);
    golden!("pieces_fmt", 0, ["fmt", "0,", "90"]);
}

#[test]
fn long_lines_report_the_files_column() {
    let template = format!("{}+30X5", "0, ".repeat(200));
    let (golden, code) = run(&["check", &template], None);
    assert_eq!(code, 1);
    // The `X` is at byte 603, column 604 of line 1.
    assert!(golden.contains("┌─ <template>:1:604\n"), "{golden}");
    assert!(
        golden.contains("\n1 │ "),
        "the file's line number: {golden}"
    );
    let (golden, _) = run(&["check", &format!("0,\n{template}")], None);
    assert!(golden.contains("┌─ <template>:2:604\n"), "{golden}");
    assert!(golden.contains("\n2 │ "), "{golden}");
}

#[test]
fn model_files_with_defaults_maps_and_named_fields() {
    let dir = TempDir::new("models");
    dir.file(
        "one.json",
        r#"{"layer_heights": [0.3, 0.2, 0.2], "layer_height": 0.2}"#,
    );
    dir.file(
        "map.json",
        r#"{"tall": {"layer_heights": [0.2, 0.2], "layer_height": 0.2, "bottom_shell_layers": 1},
            "short": {"layer_heights": [0.3], "layer_height": 0.2}}"#,
    );
    dir.file(
        "bad.json",
        r#"{"layer_heights": [0.2, "x"], "layer_height": 0.2}"#,
    );
    dir.file(
        "shells.json",
        r#"{"layer_heights": [0.2], "layer_height": 0.2, "top_shell_layers": -1}"#,
    );
    let path = |name: &str| dir.0.join(name).display().to_string();
    for (name, code, model) in [
        ("model_default_shells", 0, path("one.json")),
        ("model_map_named", 0, format!("{}:tall", path("map.json"))),
        ("model_map_without_name", 2, path("map.json")),
        (
            "model_map_unknown_name",
            2,
            format!("{}:wide", path("map.json")),
        ),
        ("model_field_named", 2, path("bad.json")),
        ("model_shells_named", 2, path("shells.json")),
    ] {
        let (golden, got) = run_in(
            &dir,
            &["expand", "B, +1", "--model", &model, "--format", "json"],
        );
        // JSON is long: the model echo and the exit code are what is pinned.
        let shown = match golden.find("\"model\":") {
            Some(at) => format!(
                "{}…{}",
                &golden[..golden.find("----- stdout -----").unwrap() + 19],
                &golden[at..golden[at..].find('}').map_or(golden.len(), |e| at + e + 1)]
            ),
            None => golden.clone(),
        };
        insta::assert_snapshot!(name, shown);
        assert_eq!(got, code, "{golden}");
    }
}

#[test]
fn consistency() {
    golden!("degree_word_help", 1, ["check", "45deg", "+30°/5"]);
    golden!("second_repeat_count", 1, ["check", "+30*3*2"]);
    golden!("comma_alone", 0, ["check", ","]);
    golden!("trailing_commas", 0, ["check", "0, 90,", "0, 90,,"]);
    golden!(
        "solid_target_labels_solid",
        0,
        ["expand", "+30", "--target", "solid", "--layers", "2"]
    );
    golden!(
        "table_wide_index",
        0,
        ["expand", "+1", "--layers", "100001", "--range", "99998.."]
    );
    golden!(
        "expand_json_errors",
        1,
        ["expand", "+30X5", "--format", "json"]
    );
    golden!("expand_help", 0, ["expand", "--help"]);
    let dir = TempDir::new("bom");
    let bom = dir.file("bom.rot", "\u{feff}0, 90\n");
    let (golden, code) = run_in(&dir, &["check", "--file", bom.to_str().unwrap()]);
    insta::assert_snapshot!("byte_order_mark_skipped", golden);
    assert_eq!(code, 0);
}

#[test]
fn check_fix_prints_writes_and_refuses() {
    golden!(
        "check_fix",
        0,
        ["check", "--fix", "--force", "\"+30°, 10,,20\"", "+30 /50%"]
    );
    golden!(
        "check_fix_refuses_errors",
        1,
        ["check", "--fix", "45deg, +30X5"]
    );
    let dir = TempDir::new("fix");
    let file = dir.file("a.rot", "+30°\n10,,20\n");
    let (golden, code) = run_in(
        &dir,
        &[
            "check",
            "--fix",
            "--force",
            "--write",
            "--file",
            file.to_str().unwrap(),
        ],
    );
    insta::assert_snapshot!("check_fix_write", golden);
    assert_eq!(code, 0);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "+30\n10, 20\n");
    let bad = dir.file("b.rot", "+30°, +30X5\n");
    let (_, code) = run_in(
        &dir,
        &["check", "--fix", "--write", "--file", bad.to_str().unwrap()],
    );
    assert_eq!(code, 1);
    assert_eq!(
        std::fs::read_to_string(&bad).unwrap(),
        "+30°, +30X5\n",
        "a file that keeps errors is not written"
    );
    golden!("check_write_needs_fix", 2, ["check", "--write", "0"]);
}

#[test]
fn explain_codes_and_templates() {
    golden!(
        "explain_code",
        0,
        ["explain", "rotlang::space-splits-instruction"]
    );
    golden!("explain_code_short", 0, ["explain", "degree-sign"]);
    golden!(
        "explain_unknown_code",
        2,
        ["explain", "rotlang::no-such-code"]
    );
    golden!("explain_list", 0, ["explain", "--list"]);
    golden!("explain_template", 0, ["explain", "+10L25%, -10l25%"]);
    golden!(
        "explain_template_model",
        0,
        ["explain", "B!, +30, +15#5", "--layers", "20"]
    );
    golden!("explain_template_errors", 1, ["explain", "+30X5, 90"]);
    golden!("explain_stdin", 0, ["explain", "-"], Some("0, 90"));
}

#[test]
fn expand_range() {
    golden!(
        "expand_range",
        0,
        ["expand", "+10", "--range", "5..8", "--format", "csv"]
    );
    golden!(
        "expand_range_inclusive_single",
        0,
        ["expand", "+10", "--range", "99"]
    );
    golden!(
        "expand_range_outside",
        2,
        ["expand", "+10", "--range", "95..101"]
    );
}

#[test]
fn completions_man_and_version() {
    for shell in ["bash", "zsh", "fish", "powershell"] {
        let (golden, code) = run(&["completions", shell], None);
        assert_eq!(code, 0, "{golden}");
        let out = stdout_of(&golden);
        for word in ["check", "fmt", "expand", "explain", "deny-warnings", "wrap"] {
            assert!(out.contains(word), "{shell} completes {word}");
        }
    }
    let (golden, code) = run(&["man"], None);
    assert_eq!(code, 0);
    let page = stdout_of(&golden);
    assert!(
        page.starts_with(".ie") || page.contains(".TH rotlang 1"),
        "{page}"
    );
    assert!(page.contains("explain"), "{page}");
    let (golden, code) = run(&["man", "expand"], None);
    assert_eq!(code, 0);
    assert!(
        stdout_of(&golden).contains(".TH rotlang-expand 1"),
        "{golden}"
    );
    assert!(stdout_of(&golden).contains("\\-\\-range"), "{golden}");
    golden!("man_unknown", 2, ["man", "nope"]);
    for command in ["check", "fmt", "expand", "explain", "completions", "man"] {
        let (golden, code) = run(&[command, "--version"], None);
        assert_eq!(code, 0, "{golden}");
        assert!(
            stdout_of(&golden).contains(env!("CARGO_PKG_VERSION")),
            "{golden}"
        );
    }
}

#[test]
fn invisible_characters_get_a_caret_and_keep_columns() {
    // After a zero-width character, columns still count the file's characters.
    let (golden, code) = run(&["check", "0, \u{feff}90, +30X5"], None);
    assert_eq!(code, 1);
    assert!(golden.contains("<template>:1:4\n"), "{golden}");
    assert!(
        golden.contains("<template>:1:12\n"),
        "the X is character 12: {golden}"
    );
    assert!(golden.contains("0, ???90, +30X5"), "{golden}");
}

#[test]
fn pieces_of_one_template_in_single_template_commands() {
    // The second piece is not a template that begins with `-`: the quoting note.
    golden!("pieces_expand", 2, ["expand", "0,", "90"]);
    golden!("pieces_explain", 2, ["explain", "0,", "90"]);
    golden!("pieces_expand_unit", 2, ["expand", "+30/50", "%"]);
}

#[test]
fn option_values_beginning_with_a_dash_say_what_is_allowed() {
    golden!("negative_range", 2, ["expand", "0", "--range", "-5..3"]);
    golden!("negative_wrap", 2, ["expand", "0", "--wrap", "-1"]);
    golden!("negative_format", 2, ["check", "--format", "-1", "0"]);
    golden!("negative_columns", 2, ["preview", "0", "--columns", "-1"]);
    golden!("negative_plot_seed", 2, ["plot", "0", "--seed", "-1"]);
    golden!("negative_plot_layers", 2, ["plot", "0", "--layers", "-5"]);
    golden!(
        "negative_preview_layers",
        2,
        ["preview", "0", "--layers", "-1..3"]
    );
    // A flag before a negative template still takes the template.
    golden!(
        "flag_then_negative_template",
        0,
        ["check", "--deny-warnings", "-30"]
    );
}

#[test]
fn degree_help_names_the_angle() {
    for (template, says) in [
        ("45 deg", "write `45`, not `45 deg`"),
        ("45deg", "write `45`, not `45deg`"),
        ("45°", "write `45`, not `45°`"),
        ("+45 degrees", "write `+45`, not `+45 degrees`"),
        ("0, deg", "remove `deg`"),
    ] {
        let (golden, code) = run(&["check", template], None);
        assert_eq!(code, 1, "{golden}");
        assert!(golden.contains(says), "{template}: {golden}");
        assert!(!golden.contains("write ``"), "{golden}");
    }
}

#[test]
fn byte_order_mark_and_lone_cr_keep_editor_positions() {
    let dir = TempDir::new("bom-cr");
    let bom = dir.file("f.rot", "\u{feff}0, +30X5");
    let (golden, code) = run_in(&dir, &["check", "--file", bom.to_str().unwrap()]);
    insta::assert_snapshot!("bom_error_column", golden);
    assert_eq!(code, 1);
    assert!(
        golden.contains("f.rot:1:7\n") && !golden.contains('?'),
        "{golden}"
    );
    let (golden, _) = run_in(
        &dir,
        &["check", "--format", "json", "--file", bom.to_str().unwrap()],
    );
    let value: serde_json::Value = serde_json::from_str(stdout_of(&golden)).unwrap();
    let d = &value["diagnostics"][0];
    // Columns as editors count them; offsets stay the file's bytes.
    assert_eq!(
        (d["line"].as_u64(), d["column"].as_u64()),
        (Some(1), Some(7))
    );
    assert_eq!(d["start"], 9);
    let cr = dir.file("cr.rot", "0, 90\r+30X5");
    let (golden, code) = run_in(&dir, &["check", "--file", cr.to_str().unwrap()]);
    insta::assert_snapshot!("lone_cr_is_a_line_end", golden);
    assert_eq!(code, 1);
    assert!(
        golden.contains("cr.rot:2:4\n") && !golden.contains('\r'),
        "{golden}"
    );
    // Profiles too: a byte-order mark and CR-only line ends.
    let ini = dir.file(
        "p.ini",
        "\u{feff}layer_height = 0.2\rsparse_infill_rotate_template = 0, +30X5\r",
    );
    let (golden, code) = run_in(&dir, &["check", ini.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(golden.contains("p.ini:2:39\n"), "{golden}");
    let json = dir.file(
        "p.json",
        "\u{feff}{\"sparse_infill_rotate_template\": \"0, +30X5\"}",
    );
    let (golden, _) = run_in(&dir, &["check", "--format", "json", json.to_str().unwrap()]);
    let value: serde_json::Value =
        serde_json::from_str(stdout_of(&golden).lines().next().unwrap()).unwrap();
    assert_eq!(value["diagnostics"][0]["column"], 42, "{golden}");
}

#[test]
fn heights_are_micrometres() {
    golden!(
        "heights_micrometres",
        0,
        [
            "expand", "+1", "--layers", "1000000", "--range", "999999..", "--format", "csv"
        ]
    );
}

#[test]
fn expand_json_errors_are_checks_object() {
    for template in ["+30X5", "+30X5, 10,,20"] {
        let (expand, code) = run(&["expand", "--format", "json", template], None);
        assert_eq!(code, 1);
        let (check, _) = run(&["check", "--format", "json", template], None);
        assert_eq!(stdout_of(&expand), stdout_of(&check), "{expand}");
    }
}

#[test]
fn expand_orcaslicer_json_has_the_findings() {
    let (golden, code) = run(
        &[
            "expand",
            "--dialect",
            "orcaslicer",
            "+10$50%%",
            "--layers",
            "3",
            "--format",
            "json",
        ],
        None,
    );
    assert_eq!(code, 0);
    let value: serde_json::Value =
        serde_json::from_str(stdout_of(&golden)).expect("one JSON object");
    let d = &value["diagnostics"][0];
    assert_eq!(d["code"], "orcaslicer::nan", "{golden}");
    assert_eq!(d["first_layer"], 2);
    assert_eq!(value["layers"].as_array().map(Vec::len), Some(3));
    // Without findings the list is there, empty.
    let (golden, _) = run(
        &[
            "expand",
            "--dialect",
            "orcaslicer",
            "0, 90",
            "--layers",
            "2",
            "--format",
            "json",
        ],
        None,
    );
    let value: serde_json::Value =
        serde_json::from_str(stdout_of(&golden)).expect("one JSON object");
    assert_eq!(value["diagnostics"], serde_json::json!([]));
}

#[test]
fn fmt_leaves_a_space_after_a_joint_with_the_warning() {
    golden!("fmt_space_after_joint", 1, ["fmt", "+30/ 50%"]);
    golden!(
        "fmt_space_after_joint_check",
        1,
        ["fmt", "--check", "+30/ 50%"]
    );
    golden!(
        "fmt_space_after_joint_force",
        0,
        ["fmt", "--force", "+30/ 50%"]
    );
    let dir = TempDir::new("fmt-space");
    let file = dir.file("a.rot", "+10L 25%, -10l 25%\n");
    let (_, code) = run_in(&dir, &["fmt", "--write", "--file", file.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        "+10L 25%, -10l 25%\n"
    );
    // `check --fix` applies the warning's own fix.
    let (golden, code) = run(&["check", "--fix", "+30/ 50%"], None);
    assert_eq!((stdout_of(&golden), code), ("+30/50%\n", 0));
}

#[test]
fn trailing_comma_warns_with_a_fix() {
    golden!("trailing_comma_fix", 0, ["check", "--fix", "0, 90,"]);
    let (golden, _) = run(&["check", "--format", "json", "0, 90,"], None);
    let value: serde_json::Value = serde_json::from_str(stdout_of(&golden)).unwrap();
    assert_eq!(
        value["diagnostics"][0]["code"],
        "rotlang::empty-instruction"
    );
    assert_eq!(value["diagnostics"][0]["fix"]["replacement"], "");
}

#[test]
fn second_repeat_count_help_matches_the_fix() {
    let (golden, _) = run(&["check", "+30*3*2"], None);
    assert!(
        golden.contains("remove `*2` to run the instruction 3 times (the fix)"),
        "{golden}"
    );
    assert!(golden.contains("the product `*6`"), "{golden}");
    let (golden, code) = run(&["check", "--fix", "+30*3*2"], None);
    assert_eq!((stdout_of(&golden), code), ("+30*3\n", 0));
}

#[test]
fn check_fix_with_compat_and_the_orcaslicer_guard() {
    golden!(
        "fix_compat",
        0,
        ["check", "--compat", "orcaslicer", "--fix", "0 90"]
    );
    // Issue 16.4: a fix is applied when afterwards OrcaSlicer reads the template as rotlang
    // does (these were all left unchanged, "pass --force").
    golden!(
        "fix_readings_meet",
        0,
        [
            "check",
            "--fix",
            "0; 90",
            "b!, +30",
            "+30/50 %",
            "+45/10 layers",
            "10,,20"
        ]
    );
    let (golden, _) = run(
        &["check", "--fix", "0; 90", "b!, +30", "+30/50 %", "10,,20"],
        None,
    );
    assert_eq!(
        stdout_of(&golden),
        "0, 90\nB!, +30\n+30/50%\n10,20\n",
        "{golden}"
    );
    // An OrcaSlicer error that no fix removes leaves the template as it is (exit 1).
    let (golden, code) = run(&["check", "--fix", "10!, 5*"], None);
    assert_eq!((stdout_of(&golden), code), ("10!, 5*\n", 1), "{golden}");
    assert!(golden.contains("error[orcaslicer::hangs]"), "{golden}");
    golden!(
        "fix_orcaslicer_force",
        0,
        ["check", "--fix", "--force", "10,,20"]
    );
    // One line per input, in order; the refused ones named on stderr.
    golden!(
        "fix_several_attributable",
        1,
        ["check", "--fix", "+30X5", "10,,20", "+30°"]
    );
}

#[test]
fn a_file_named_as_the_template() {
    golden!(
        "expand_profile_named_as_template",
        0,
        [
            "expand",
            "tests/fixtures/profiles/export.ini",
            "--layers",
            "3"
        ]
    );
    golden!(
        "fmt_profile_named_as_template",
        2,
        ["fmt", "tests/fixtures/profiles/export.ini"]
    );
    let dir = TempDir::new("fmt-named");
    let file = dir.file("a.rot", "0,  90\n");
    let (golden, code) = run_in(&dir, &["fmt", file.to_str().unwrap()]);
    insta::assert_snapshot!("fmt_file_named_as_template", golden);
    assert_eq!(code, 0);
    let (_, code) = run_in(&dir, &["fmt", "--write", file.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "0, 90\n");
}

/// Issue 16.4: `check` tells an OrcaSlicer user what OrcaSlicer does, by default: a hang is
/// an error, a difference a warning; `--compat none` turns the lint off.
#[test]
fn check_lints_for_orcaslicer_by_default() {
    golden!("check_default_hang", 1, ["check", "10!, 5*"]);
    let (golden, code) = run(&["check", "0 90", "1:4"], None);
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("warning[orcaslicer::space-separated-list]")
            && golden.contains("warning[orcaslicer::fraction]"),
        "{golden}"
    );
    for args in [
        &["check", "--compat", "none", "10!, 5*", "0 90", "1:4"][..],
        &["check", "--compat", "none", "--format", "json", "10!, 5*"][..],
    ] {
        let (golden, code) = run(args, None);
        assert_eq!(code, 0, "{golden}");
        assert!(!golden.contains("orcaslicer::"), "{golden}");
    }
    // A folder of presets too.
    let (golden, code) = run(&["check", "tests/fixtures/profiles/orca/process"], None);
    assert_eq!(code, 0, "{golden}");
    assert!(golden.contains("warning[orcaslicer::"), "{golden}");
    let (golden, _) = run(&["check", "--format", "json", "10!, 5*"], None);
    assert!(golden.contains(r#""code":"orcaslicer::hangs""#), "{golden}");
}

/// The OrcaSlicer lint runs on a template of any size, as the language server's does: a
/// 200 KiB template ending in `0 90` (OrcaSlicer reads `0`) gets the warning from stdin, a
/// `.rot` file and a preset alike (it used to be skipped above 64 KiB, with a note).
#[test]
fn check_lints_a_long_template_as_the_editor_does() {
    let long = format!("{}0 90", "15, ".repeat(50_000));
    let dir = TempDir::new("long-lint");
    let rot = dir.file("long.rot", &long);
    let preset = dir.file(
        "long.json",
        &format!(r#"{{"sparse_infill_rotate_template": "{long}"}}"#),
    );
    for args in [
        vec!["check", "--format", "json", "-f", "-"],
        vec!["check", "--format", "json", rot.to_str().unwrap()],
        vec!["check", "--format", "json", preset.to_str().unwrap()],
    ] {
        let stdin = (args.last() == Some(&"-")).then_some(long.as_str());
        let (out, code) = run(&args, stdin);
        assert_eq!(code, 0, "{args:?}: {out}");
        assert!(
            out.contains(r#""code":"orcaslicer::space-separated-list""#),
            "{args:?}: {out}"
        );
        assert!(!out.contains("lint is skipped"), "{args:?}: {out}");
    }
}

/// Issue 16.4: the command `fmt` suggests for a profile is one a shell runs.
#[test]
fn fmt_quotes_the_path_it_suggests() {
    let dir = TempDir::new("fmt-quote");
    let file = dir.file(
        "0.20mm Rotating Gyroid.json",
        r#"{"sparse_infill_rotate_template": "0, 90"}"#,
    );
    let (golden, code) = run_in(&dir, &["fmt", file.to_str().unwrap()]);
    assert_eq!(code, 2, "{golden}");
    assert!(
        golden.contains("`rotlang check '[TMP]/0.20mm Rotating Gyroid.json'` checks"),
        "{golden}"
    );
}

/// Issue 16.5: one path rule for every command; a missing path is "no such file" first; `/`
/// alone is a template; a broken profile is an error in every command that reads it.
#[test]
fn one_path_rule_for_every_command() {
    for command in ["check", "fmt", "expand", "plot", "preview", "explain"] {
        let (golden, code) = run(&[command, "nosuch.json"], None);
        assert!(
            golden.contains("nosuch.json: no such file or folder"),
            "{command}: {golden}"
        );
        assert!(!golden.contains("unknown sign"), "{command}: {golden}");
        assert_ne!(code, 0, "{command}: {golden}");
        let (golden, _) = run(&[command, "process/0.20mm Rotating Gyroid.json"], None);
        assert!(
            golden.contains("no such file") && !golden.contains("unknown sign"),
            "{command}: {golden}"
        );
    }
    // `/` alone is a template (the filesystem is not scanned).
    let (golden, code) = run(&["check", "--compat", "none", "/"], None);
    assert_eq!(code, 0, "{golden}");
    assert!(golden.contains("ok: 1 template, no problems"), "{golden}");
    // A file named where the template goes is read, by every command.
    let preset = "tests/fixtures/profiles/export.ini";
    for args in [
        &["expand", preset, "--layers", "2"][..],
        &["plot", preset][..],
        &["preview", preset, "--layers", "0..1", "--format", "json"][..],
        &["explain", preset][..],
    ] {
        let (golden, code) = run(args, None);
        assert_eq!(code, 0, "{golden}");
        assert!(golden.contains("5, 10!, +20"), "{golden}");
    }
}

#[test]
fn a_broken_profile_fails_every_command_alike() {
    let dir = TempDir::new("broken");
    let broken = dir.file(
        "broken.json",
        r#"{"layer_height": "0.2" "sparse_infill_rotate_template": "0, 90"}"#,
    );
    let path = broken.to_str().unwrap();
    let (golden, code) = run_in(&dir, &["expand", "--profile", path]);
    insta::assert_snapshot!("expand_broken_profile", golden);
    assert_eq!(code, 1);
    for args in [
        &["check", path][..],
        &["expand", path][..],
        &["plot", "--profile", path][..],
        &["preview", "--profile", path][..],
        &["explain", "--profile", path][..],
    ] {
        let (golden, code) = run(args, None);
        assert_eq!(code, 1, "{golden}");
        assert!(golden.contains("error[profile::invalid]: "), "{golden}");
        assert!(
            !golden.contains("\n    0   "),
            "no layers printed: {golden}"
        );
    }
}

/// Issue 16.5: `plot`, `preview` and `explain` take `--profile`; a project lists its objects
/// and takes `--object`.
#[test]
fn profiles_and_objects_in_every_command() {
    let project = "tests/fixtures/profiles/project.3mf";
    let (golden, code) = run(&["expand", "--profile", project, "--layers", "1"], None);
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("objects Lid & hinge / part Hinge, Lid & hinge (--object NAME"),
        "{golden}"
    );
    let (golden, code) = run(
        &[
            "expand",
            "--profile",
            project,
            "--object",
            "Lid & hinge",
            "--layers",
            "2",
            "--format",
            "csv",
        ],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("(object Lid & hinge) `0, 1:4` (125 layers of 0.16 mm"),
        "{golden}"
    );
    let (golden, code) = run(&["plot", "--profile", project, "--object", "Nope"], None);
    assert_eq!(code, 2, "{golden}");
    assert!(
        golden.contains("no object `Nope`; its objects: "),
        "{golden}"
    );
    let (golden, code) = run(
        &["explain", "--profile", project, "--object", "Lid & hinge"],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("`0, 1:4`") && golden.contains("125 layers"),
        "{golden}"
    );
    let (golden, code) = run(
        &["plot", "--profile", "tests/fixtures/profiles/export.ini"],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("<svg") && golden.contains("84 layers of 0.24 mm"),
        "{golden}"
    );
}

/// Issue 17: `explain` of a template with errors shows them; a word near a code names it.
#[test]
fn explain_errors_and_near_codes() {
    let (golden, code) = run(&["explain", "+30X5"], None);
    assert_eq!(code, 1, "{golden}");
    assert!(golden.contains("The template has errors:"), "{golden}");
    assert!(golden.contains("unknown sign `X`"), "{golden}");
    assert!(!golden.contains("The template is empty"), "{golden}");
    let (golden, code) = run(&["explain", "hangs"], None);
    assert_eq!(code, 2, "{golden}");
    assert!(
        golden.contains("no diagnostic code `hangs`; did you mean `orcaslicer::hangs`?"),
        "{golden}"
    );
    let (golden, code) = run(&["explain", "nosuchcode"], None);
    assert_eq!(code, 1, "{golden}");
    assert!(
        golden.contains("The template has errors:")
            && golden.contains("Nor is `nosuchcode` a diagnostic code"),
        "{golden}"
    );
}

/// Issue 17: every command that writes stdout ends quietly when its reader has gone
/// (`rotlang completions bash | head -1` panicked with a backtrace, exit 101).
#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    let commands: [&[&str]; 9] = [
        &["check", "+30X5", "0 90"],
        &["fmt", "0 90"],
        &["expand", "+30", "--layers", "5000"],
        &["plot", "+30"],
        &["preview", "+30", "--layers", "0..2"],
        &["explain", "+10L25%, -10l25%"],
        &["explain", "--list"],
        &["completions", "bash"],
        &["man"],
    ];
    for args in commands {
        // The reading end is closed before the command starts: its first write fails.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(args)
            .current_dir(root())
            .env_remove("RUST_BACKTRACE")
            .stdin(Stdio::null())
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !stderr.contains("panicked") && !stderr.contains("cannot write output"),
            "{args:?}: {stderr}"
        );
        assert_eq!(out.status.code(), Some(0), "{args:?}: {stderr}");
    }
}

/// Issue 17: `man --dir` writes every page rotlang(1) refers to, each with the version; the
/// NAME line does not repeat the name.
#[test]
fn man_dir_writes_every_page() {
    let dir = TempDir::new("man");
    let (golden, code) = run_in(&dir, &["man", "--dir", dir.0.to_str().unwrap()]);
    assert_eq!(code, 0, "{golden}");
    let root = std::fs::read_to_string(dir.0.join("rotlang.1")).unwrap();
    assert!(
        root.contains("rotlang \\- check, format and expand infill rotation templates"),
        "{root}"
    );
    let version = env!("CARGO_PKG_VERSION");
    for command in [
        "check",
        "fmt",
        "expand",
        "plot",
        "preview",
        "explain",
        "completions",
        "man",
    ] {
        let name = format!("rotlang-{command}");
        let roff = name.replace('-', "\\-");
        assert!(
            root.contains(&format!("{roff}(1)")),
            "rotlang(1) refers to {name}(1)"
        );
        let page = std::fs::read_to_string(dir.0.join(format!("{name}.1")))
            .unwrap_or_else(|e| panic!("{name}.1: {e}"));
        assert!(page.contains(&format!("\"{name} {version}\"")), "{page}");
    }
}

/// Issue 17: `º` (U+00BA) and `˚` (U+02DA), typed for `°`, get the degree-sign diagnostic
/// and its fix.
#[test]
fn look_alike_degree_signs() {
    for sign in ["º", "˚"] {
        let template = format!("+30{sign}, 90");
        let (golden, code) = run(&["check", "--compat", "none", &template], None);
        assert_eq!(code, 1, "{golden}");
        assert!(golden.contains("error[rotlang::degree-sign]"), "{golden}");
        assert!(
            golden.contains(&format!("fix: remove the `{sign}`")),
            "{golden}"
        );
        let (golden, code) = run(&["check", "--fix", &template], None);
        assert_eq!((stdout_of(&golden), code), ("+30, 90\n", 0), "{golden}");
    }
}

/// Issue 17: lengths on the command line take the language's units; a template where the
/// command goes gets the command to run; profile reports in JSON carry `omitted` and the
/// notes.
#[test]
fn cli_polish() {
    let (golden, code) = run(
        &[
            "expand",
            "+30",
            "--layers",
            "2",
            "--layer-height",
            "0.2mm",
            "--format",
            "csv",
        ],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    assert!(golden.contains("\n1,0.2,0.4,60,"), "{golden}");
    let (golden, code) = run(
        &[
            "expand",
            "+30",
            "--height",
            "1cm",
            "--layer-height",
            "0.5mm",
        ],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    assert!(golden.contains("   19         9.5          10"), "{golden}");
    let (golden, code) = run(
        &["plot", "+30", "--height", "2cm", "--layer-height", "0.2mm"],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    let (golden, code) = run(&["+30"], None);
    assert_eq!(code, 2, "{golden}");
    assert!(
        golden.contains("tip: to check a template or a file, run: rotlang check +30"),
        "{golden}"
    );
    let (golden, code) = run(
        &[
            "check",
            "--format",
            "json",
            "tests/fixtures/profiles/user-overrides.jsonc",
        ],
        None,
    );
    assert_eq!(code, 0, "{golden}");
    let lines: Vec<serde_json::Value> = stdout_of(&golden)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert!(
        lines
            .iter()
            .filter(|l| l.get("input").is_some())
            .all(|l| l["omitted"] == 0),
        "{golden}"
    );
    assert!(
        lines.iter().any(|l| l["note"]
            .as_str()
            .is_some_and(|n| n.contains("OrcaSlicer's default 3 is used"))),
        "{golden}"
    );
}

/// Issue 16.5: `plot --dialect orcaslicer` draws OrcaSlicer's angles for any text, as
/// `expand --dialect` prints them; where the readings agree the pictures are the same.
#[test]
fn plot_in_the_orcaslicer_dialect() {
    let svg = |args: &[&str]| {
        let (golden, code) = run(args, None);
        assert_eq!(code, 0, "{golden}");
        golden
    };
    for text in ["0, 90", "+10L25%, -10l25%", "B!, +30"] {
        assert_eq!(
            stdout_of(&svg(&["plot", "--dialect", "orcaslicer", text])),
            stdout_of(&svg(&["plot", text])),
            "{text}"
        );
    }
    assert_ne!(
        stdout_of(&svg(&["plot", "--dialect", "orcaslicer", "0 90"])),
        stdout_of(&svg(&["plot", "0 90"]))
    );
    let golden = svg(&[
        "plot",
        "--dialect",
        "orcaslicer",
        "10!, 5*",
        "--layers",
        "5",
    ]);
    assert!(golden.contains("warning[orcaslicer::hangs]"), "{golden}");
    // Text rotlang rejects is drawn as OrcaSlicer reads it.
    let golden = svg(&["plot", "--dialect", "orcaslicer", "+30X5"]);
    assert!(golden.contains("<svg"), "{golden}");
}

/// Issue 16.5: `explain --dialect orcaslicer` says how OrcaSlicer reads the template.
#[test]
fn explain_in_the_orcaslicer_dialect() {
    let (golden, code) = run(&["explain", "--dialect", "orcaslicer", "0 90"], None);
    assert_eq!(code, 0, "{golden}");
    assert!(
        golden.contains("In OrcaSlicer (`--dialect orcaslicer`): layers from 0 at 0°, 0°, 0°"),
        "{golden}"
    );
    assert!(
        golden.contains("OrcaSlicer turns layer 1 to 0°, rotlang to 90° [orcaslicer::differs]"),
        "{golden}"
    );
    let (golden, _) = run(
        &[
            "explain",
            "--dialect",
            "orcaslicer",
            "0, 90",
            "--layers",
            "4",
        ],
        None,
    );
    assert!(
        golden.contains("at 0°, 90°, 0°, 90°.\nIt reads the template as rotlang does"),
        "{golden}"
    );
    let (golden, _) = run(&["explain", "0 90"], None);
    assert!(!golden.contains("In OrcaSlicer"), "{golden}");
}

/// Issue 16.3: the retired `orcaslicer::direction-ignored` is explained as retired.
#[test]
fn the_retired_direction_code_is_explained() {
    let code = ["orcaslicer::", "direction-ignored"].concat();
    let (golden, status) = run(&["explain", &code], None);
    assert_eq!(status, 0, "{golden}");
    assert!(
        golden.contains("(retired)") && golden.contains("empty template only"),
        "{golden}"
    );
}

// ── preview of a part (issue 20) ───────────────────────────────────────────────────────

#[path = "support/project.rs"]
mod project;

/// `rotlang preview ARGS` in `dir`: stdout as JSON (with `--format json`), and stderr.
fn preview_json(dir: &Path, args: &[&str]) -> (serde_json::Value, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .arg("preview")
        .args(args)
        .args(["--format", "json"])
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "{args:?}: {stderr}");
    (serde_json::from_slice(&out.stdout).unwrap(), stderr)
}

/// Every layer of a part, listed: `--layers all --format json` streams each layer as it
/// is filled (a part taller than the 256 panels a picture holds), the same text to stdout
/// and to `--out`, the same layers as a range asked for; a picture of them all is refused
/// with the way to list them.
#[test]
fn preview_json_lists_every_layer_of_a_tall_part() {
    let dir = TempDir::new("part-all-layers");
    let stl = dir.0.join("tall.stl");
    // 60 mm at 0.2 mm: 300 layers.
    std::fs::write(
        &stl,
        rotlang_geometry::mesh::shapes::cuboid([8.0, 8.0, 60.0]).to_binary_stl(),
    )
    .unwrap();
    let (all, _) = preview_json(&dir.0, &["+15", "--shape", "tall.stl", "--layers", "all"]);
    let layers = all["layers"].as_array().unwrap();
    assert_eq!(layers.len(), 300);
    assert_eq!(all["summary"]["layers"], 300);
    let indices: Vec<u64> = layers
        .iter()
        .map(|l| l["index"].as_u64().unwrap())
        .collect();
    assert_eq!(indices, (0..300).collect::<Vec<u64>>());
    let (some, _) = preview_json(
        &dir.0,
        &["+15", "--shape", "tall.stl", "--layers", "280..=299"],
    );
    assert_eq!(some["layers"].as_array().unwrap()[..], layers[280..]);
    assert_eq!(some["summary"], all["summary"]);
    // To a file: the same bytes, and nothing left beside it.
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .args(["preview", "+15", "--shape", "tall.stl", "--layers", "all"])
            .args(extra)
            .current_dir(&dir.0)
            .output()
            .unwrap()
    };
    let stdout = run(&["--format", "json"]);
    assert!(
        run(&["--format", "json", "--out", "all.json"])
            .status
            .success()
    );
    assert_eq!(
        std::fs::read(dir.0.join("all.json")).unwrap(),
        stdout.stdout
    );
    let names: Vec<String> = std::fs::read_dir(&dir.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    let svg = run(&[]);
    assert_eq!(svg.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&svg.stderr).trim(),
        "rotlang: --layers 0..300 is 300 layers; a picture shows at most 256 (--format json lists any number)"
    );
}

/// Issue 20: top and bottom shells are areas. A 30 × 10 mm block with a 10 mm tower on its
/// left end: the block's top beside the tower is solid on its last 4 layers (turned by
/// --solid-template), the rest of those layers and the tower above stay sparse; the JSON
/// says which areas are solid, the SVG and the summary too.
#[test]
fn preview_of_a_part_makes_its_top_surfaces_solid() {
    let dir = TempDir::new("part-shells");
    let stl = dir.0.join("step.stl");
    std::fs::write(
        &stl,
        rotlang_geometry::mesh::shapes::step([30.0, 10.0, 10.0], [10.0, 10.0, 10.0])
            .to_binary_stl(),
    )
    .unwrap();
    let (v, stderr) = preview_json(
        &dir.0,
        &[
            "0",
            "--shape",
            "step.stl",
            "--solid-template",
            "90",
            "--layers",
            "44..54",
        ],
    );
    assert!(stderr.contains("m solid)"), "{stderr}");
    assert_eq!(v["solid_template"], "90");
    let layers = v["layers"].as_array().unwrap();
    assert_eq!(layers.len(), 10);
    for l in layers {
        let i = l["index"].as_u64().unwrap();
        let areas = l["areas"].as_array().unwrap();
        if (46..=49).contains(&i) {
            assert_eq!(l["printed"], "sparse+solid", "layer {i}");
            assert_eq!(areas.len(), 2, "layer {i}");
            let (sparse, solid) = (&areas[0], &areas[1]);
            assert_eq!(
                (&sparse["solid"], &solid["solid"]),
                (&false.into(), &true.into())
            );
            assert_eq!(
                (&sparse["angle"], &solid["angle"]),
                (&0.0.into(), &90.0.into())
            );
            assert_eq!(solid["density"], 1.0);
            // The solid area is the block's top right of the tower, less the walls.
            let area = solid["area_mm2"].as_f64().unwrap();
            assert!((area - 19.2 * 8.4).abs() < 1e-6, "layer {i}: {area}");
            for ring in solid["region"].as_array().unwrap() {
                for p in ring[0].as_array().unwrap() {
                    assert!(p[0].as_f64().unwrap() >= 10.0 - 1e-9, "layer {i}: {p}");
                }
            }
            assert!(!solid["polylines"].as_array().unwrap().is_empty());
        } else {
            assert_eq!(l["printed"], "sparse", "layer {i}");
            assert_eq!(areas.len(), 1, "layer {i}");
            assert_eq!(areas[0]["solid"], false);
        }
    }
    let summary = &v["summary"];
    let (all, solid) = (
        summary["extrusion_mm"].as_f64().unwrap(),
        summary["solid_extrusion_mm"].as_f64().unwrap(),
    );
    assert!(solid > 0.0 && solid < all, "{solid} of {all}");
    let svg = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["preview", "0", "--shape", "step.stl", "--layers", "47"])
        .current_dir(&dir.0)
        .output()
        .unwrap();
    let svg = String::from_utf8(svg.stdout).unwrap();
    assert!(svg.contains("lines 20% + solid 68% (lines 0°)"), "{svg}");
}

/// Issue 20: `rotlang preview project.3mf --object NAME` fills the object with the
/// project's settings and the object's own overrides (model_settings.config), each unless
/// the command line says otherwise.
#[test]
fn preview_of_a_project_takes_each_objects_settings() {
    let dir = TempDir::new("part-project");
    let (cube, tube) = (
        rotlang_geometry::mesh::shapes::cuboid([20.0, 20.0, 6.0]),
        rotlang_geometry::mesh::shapes::tube(8.0, 4.0, 6.0, 48),
    );
    let bytes = project::project(
        &[
            project::Object {
                name: "Box",
                mesh: &cube,
                at: [50.0, 0.0],
                overrides: &[
                    ("sparse_infill_density", "40%"),
                    ("sparse_infill_pattern", "gyroid"),
                    ("wall_loops", "3"),
                    ("sparse_infill_rotate_template", "+45"),
                ],
            },
            project::Object {
                name: "Tube",
                mesh: &tube,
                at: [0.0, 0.0],
                overrides: &[
                    ("sparse_infill_pattern", "grid"),
                    ("layer_height", "0.25"),
                    ("initial_layer_print_height", "0.25"),
                    ("top_shell_layers", "6"),
                ],
            },
        ],
        r#"{"layer_height": "0.2", "initial_layer_print_height": "0.2",
            "sparse_infill_density": "15%", "sparse_infill_pattern": "zig-zag",
            "internal_solid_infill_pattern": "concentric", "wall_loops": "2",
            "line_width": "0.45", "nozzle_diameter": ["0.4"],
            "bottom_shell_layers": "3", "top_shell_layers": "4",
            "sparse_infill_rotate_template": "0, 90",
            "solid_infill_rotate_template": "+30"}"#,
    );
    std::fs::write(dir.0.join("project.3mf"), bytes).unwrap();
    let settings = |v: &serde_json::Value| {
        let s = &v["settings"];
        (
            s["pattern"].as_str().unwrap().to_owned(),
            s["density"].as_f64().unwrap(),
            s["walls"].as_u64().unwrap(),
            s["line_width"].as_f64().unwrap(),
            s["layer_height"].as_f64().unwrap(),
            s["top_shell_layers"].as_u64().unwrap(),
        )
    };
    // The box: its own template, pattern, density and walls; the project's line width,
    // layers and shells, and solid template.
    let (v, stderr) = preview_json(
        &dir.0,
        &["project.3mf", "--object", "Box", "--layers", "10"],
    );
    assert_eq!(
        settings(&v),
        ("gyroid".into(), 0.4, 3, 0.45, 0.2, 4),
        "{stderr}"
    );
    assert_eq!(
        (&v["template"], &v["solid_template"]),
        (&"+45".into(), &"+30".into())
    );
    assert_eq!(v["settings"]["solid_pattern"], "concentric");
    let layer = &v["layers"][0];
    assert_eq!(layer["angle"], 45.0 * 11.0);
    assert_eq!(layer["pattern"], "gyroid");
    // Three walls of 0.45 mm inside the 20 mm box.
    let area = layer["areas"][0]["area_mm2"].as_f64().unwrap();
    assert!((area - 17.3 * 17.3).abs() < 1e-6, "{area}");
    assert!(
        stderr.contains(
            "project.3mf with object Box's overrides: sparse_infill_rotate_template `+45`"
        ),
        "{stderr}"
    );
    // Its top layers are solid, turned by the project's solid template (+30 a layer).
    let (v, _) = preview_json(
        &dir.0,
        &["project.3mf", "--object", "Box", "--layers", "29"],
    );
    let top = &v["layers"][0];
    assert_eq!(top["printed"], "solid");
    assert_eq!(top["areas"][0]["angle"], 30.0 * 30.0);
    assert_eq!(top["areas"][0]["pattern"], "concentric");
    // --no-solid-template: the same layer's solid area turned by the sparse template
    // (+45 a layer), and stderr says the project's solid template was left out.
    let (v, stderr) = preview_json(
        &dir.0,
        &[
            "project.3mf",
            "--object",
            "Box",
            "--no-solid-template",
            "--layers",
            "29",
        ],
    );
    let top = &v["layers"][0];
    assert_eq!(top["printed"], "solid");
    assert_eq!(top["areas"][0]["angle"], 45.0 * 30.0);
    assert_eq!(v["solid_template"], serde_json::Value::Null);
    assert!(
        stderr.contains("solid_infill_rotate_template `+30` not used (--no-solid-template)"),
        "{stderr}"
    );
    // The tube: the project's template, density and walls; its own pattern, layers, shells.
    let (v, _) = preview_json(
        &dir.0,
        &["project.3mf", "--object", "Tube", "--layers", "5"],
    );
    assert_eq!(settings(&v), ("grid".into(), 0.15, 2, 0.45, 0.25, 6));
    assert_eq!(v["template"], "0, 90");
    assert_eq!(v["settings"]["layers"], 24);
    assert_eq!(v["layers"][0]["angle"], 90.0);
    // The command line wins over the file.
    let (v, _) = preview_json(
        &dir.0,
        &[
            "+10",
            "--shape",
            "project.3mf",
            "--object",
            "Box",
            "--density",
            "10",
            "--walls",
            "1",
            "--layer-height",
            "0.3",
            "--layers",
            "3",
        ],
    );
    assert_eq!(settings(&v), ("gyroid".into(), 0.1, 1, 0.45, 0.3, 4));
    assert_eq!(v["template"], "+10");
    assert_eq!(v["layers"][0]["angle"], 40.0);
}

/// A preset given by --profile fills a mesh as a project does (its pattern in OrcaSlicer's
/// name, density, walls, line width, layers, shells and template); `--object` on an STL
/// without a project is a usage error.
#[test]
fn preview_of_a_part_takes_a_presets_settings() {
    let dir = TempDir::new("part-preset");
    std::fs::write(
        dir.0.join("cube.stl"),
        rotlang_geometry::mesh::shapes::cuboid([20.0, 20.0, 4.0]).to_binary_stl(),
    )
    .unwrap();
    std::fs::write(
        dir.0.join("preset.json"),
        r#"{"sparse_infill_pattern": "honeycomb", "sparse_infill_density": "30%",
            "wall_loops": "1", "sparse_infill_line_width": "125%", "nozzle_diameter": ["0.4"],
            "layer_height": "0.1", "initial_layer_print_height": "0.1",
            "top_shell_layers": "2", "sparse_infill_rotate_template": "+15"}"#,
    )
    .unwrap();
    let (v, _) = preview_json(
        &dir.0,
        &[
            "--profile",
            "preset.json",
            "--shape",
            "cube.stl",
            "--layers",
            "5",
        ],
    );
    let s = &v["settings"];
    assert_eq!(
        (&s["pattern"], &s["density"], &s["walls"], &s["line_width"]),
        (&"hexagons".into(), &0.3.into(), &1.into(), &0.5.into())
    );
    assert_eq!(
        (&s["layers"], &s["top_shell_layers"]),
        (&40.into(), &2.into())
    );
    assert_eq!(v["template"], "+15");
    assert_eq!(v["layers"][0]["angle"], 90.0);
    // One wall of 0.5 mm: 19 × 19 mm to fill.
    let area = v["layers"][0]["areas"][0]["area_mm2"].as_f64().unwrap();
    assert!((area - 19.0 * 19.0).abs() < 1e-6, "{area}");
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["preview", "0", "--shape", "cube.stl", "--object", "Box"])
        .current_dir(&dir.0)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--object picks an object of a 3MF"));
}

/// A project's unusable values are notes and the options' defaults are used; a template
/// of the project with errors is reported and the preview stops (exit 1), as with
/// --profile.
#[test]
fn preview_of_a_project_with_bad_values() {
    let dir = TempDir::new("part-bad-project");
    let cube = rotlang_geometry::mesh::shapes::cuboid([10.0, 10.0, 2.0]);
    let objects = [project::Object {
        name: "Cube",
        mesh: &cube,
        at: [0.0, 0.0],
        overrides: &[
            ("wall_loops", "lots"),
            ("sparse_infill_pattern", "hilbertcurve"),
        ],
    }];
    std::fs::write(
        dir.0.join("bad.3mf"),
        project::project(
            &objects,
            r#"{"sparse_infill_density": "0%", "line_width": "-1"}"#,
        ),
    )
    .unwrap();
    let (v, stderr) = preview_json(&dir.0, &["bad.3mf", "--object", "Cube", "--layers", "4"]);
    let s = &v["settings"];
    assert_eq!(
        (&s["pattern"], &s["density"], &s["walls"], &s["line_width"]),
        (&"lines".into(), &0.2.into(), &2.into(), &0.4.into())
    );
    for key in [
        "`wall_loops` = `lots`",
        "`sparse_infill_pattern` = `hilbertcurve`",
        "`sparse_infill_density` = `0%`",
        "`line_width` = `-1`",
    ] {
        assert!(stderr.contains(key), "{key}: {stderr}");
    }
    std::fs::write(
        dir.0.join("errors.3mf"),
        project::project(&objects, r#"{"sparse_infill_rotate_template": "+30X5"}"#),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(["preview", "errors.3mf", "--object", "Cube"])
        .current_dir(&dir.0)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("unknown sign `X`"), "{stderr}");
}

/// A mesh gives the model's height: `--layer-height` (and `--first-layer-height`) alone
/// slice it in those layers, not refused for want of `--height`.
#[test]
fn preview_of_a_part_takes_its_height_from_the_mesh() {
    let dir = TempDir::new("part-height");
    std::fs::write(
        dir.0.join("part.stl"),
        rotlang_geometry::mesh::shapes::cuboid([20.0, 20.0, 10.0]).to_binary_stl(),
    )
    .unwrap();
    let (v, _) = preview_json(
        &dir.0,
        &["0", "--shape", "part.stl", "--layer-height", "0.25"],
    );
    assert_eq!(v["settings"]["layers"], 40);
    assert_eq!(v["settings"]["layer_height"], 0.25);
    assert_eq!(v["summary"]["layers"], 40);
    let (v, _) = preview_json(
        &dir.0,
        &[
            "0",
            "--shape",
            "part.stl",
            "--layer-height",
            "0.25",
            "--first-layer-height",
            "0.5",
        ],
    );
    assert_eq!(v["summary"]["layers"], 39);
    assert_eq!(v["layers"][0]["top"], 0.5);
}
