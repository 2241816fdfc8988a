//! Golden runs of the built `rotlang` binary: stdout, stderr and the exit code of each run
//! are snapshotted together (`tests/snapshots/cli__*.snap`).
//!
//! Runs have no terminal (pipes) and `NO_COLOR=1`, so reports are plain text.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
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
    assert_eq!(
        angles,
        [
            "5.0000", "10.0000", "30.0000", "5.0000", "25.0000", "5.0000", "25.0000"
        ]
    );
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
