//! What real clients do, over the wire: eglot's completion, one `languageId` for every
//! file, plain-text hovers, dynamic registration of settings, `.jsonc` and `.ini` profiles,
//! `\r` line ends, and how the binary treats its command line. Each test pins a behaviour
//! a newcomer met as a bug (issue 9).

mod common;

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{Lsp, cursor, hover_text, range};
use serde_json::{Value, json};

const ROT: &str = "file:///tmp/clients.rot";

/// The completion items at the `$0` of a fixture opened as `uri`.
fn complete(lsp: &mut Lsp, uri: &str, language: &str, fixture: &str) -> (String, Vec<Value>) {
    let (text, line, col, _) = cursor(fixture);
    lsp.open(uri, language, &text);
    let items = lsp.result(
        "textDocument/completion",
        json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": col}}),
    );
    (text, items.as_array().cloned().unwrap_or_default())
}

/// What eglot 1.9 does with an item, on a one-line text (columns are bytes here: the
/// fixtures are ASCII). `bounds` is the symbol at point; only items whose `filterText`
/// (else the proxy) starts with the text from the symbol's start to the cursor are
/// offered. Choosing one replaces the symbol with the proxy (`insertText`, else the
/// label), then its exit function deletes the proxy, puts the symbol's text back and
/// applies the text edit. `None` when eglot would not offer the item.
fn eglot_choose(text: &str, bounds: (usize, usize), cursor: usize, item: &Value) -> Option<String> {
    let proxy = item["insertText"]
        .as_str()
        .unwrap_or(item["label"].as_str()?)
        .to_string();
    let probe = &text[bounds.0..cursor];
    let filter = item["filterText"].as_str().unwrap_or(&proxy);
    if !filter.starts_with(probe) {
        return None;
    }
    let mut buffer = format!("{}{proxy}{}", &text[..bounds.0], &text[bounds.1..]);
    let point = bounds.0 + proxy.len();
    // Its exit function undoes the insertion: the proxy is deleted and the symbol's
    // original text put back, then the edit is applied.
    buffer.replace_range(point - proxy.len()..point, &text[bounds.0..bounds.1]);
    let edit = &item["textEdit"];
    let (start, end) = (
        edit["range"]["start"]["character"].as_u64()? as usize,
        edit["range"]["end"]["character"].as_u64()? as usize,
    );
    buffer.replace_range(start..end, edit["newText"].as_str()?);
    Some(buffer)
}

fn item<'a>(items: &'a [Value], label: &str) -> &'a Value {
    items
        .iter()
        .find(|i| i["label"] == label)
        .unwrap_or_else(|| panic!("no {label} in {items:#?}"))
}

#[test]
fn completion_replaces_the_instruction_typed_so_far_as_eglot_expects() {
    let mut lsp = Lsp::start();
    let (text, items) = complete(&mut lsp, ROT, "rotlang", "0, +30$0");
    let slash = item(&items, "/");
    assert_eq!(slash["textEdit"]["range"], range(0, 3, 0, 6));
    assert_eq!(slash["textEdit"]["newText"], "+30/");
    assert_eq!(slash["filterText"], "+30/");
    assert_eq!(slash["insertText"], "+30/");
    // rot-mode makes `+30` one symbol: eglot offers every joint and inserts it.
    for joint in ["/", "N", "L", "~", "#"] {
        let chosen = eglot_choose(&text, (3, 6), 6, item(&items, joint));
        assert_eq!(chosen, Some(format!("0, +30{joint}")), "{joint}");
    }
    assert_eq!(
        eglot_choose(&text, (3, 6), 6, item(&items, "*")).as_deref(),
        Some("0, +30*")
    );

    // A unit typed in part is completed, not repeated; so is `*` of `*2`.
    let (text, items) = complete(&mut lsp, ROT, "rotlang", "+30/5c$0");
    assert_eq!(
        eglot_choose(&text, (0, 6), 6, item(&items, "cm")).as_deref(),
        Some("+30/5cm")
    );
    // The unit typed so far is replaced by the item's unit, whichever it is (`m` is not
    // a part of `mm` to complete: it is a unit of its own).
    for (fixture, cases) in [
        (
            "+30/5m$0",
            [("m", "+30/5m"), ("mm", "+30/5mm"), ("cm", "+30/5cm")],
        ),
        (
            "+30/5c$0",
            [("m", "+30/5m"), ("mm", "+30/5mm"), ("cm", "+30/5cm")],
        ),
        (
            "+30/5mm$0",
            [("m", "+30/5m"), ("mm", "+30/5mm"), ("cm", "+30/5cm")],
        ),
    ] {
        let (text, items) = complete(&mut lsp, ROT, "rotlang", fixture);
        let end = text.len();
        for (label, want) in cases {
            let unit = item(&items, label);
            assert_eq!(unit["textEdit"]["newText"], want, "{fixture} {label}");
            assert_eq!(unit["textEdit"]["range"], range(0, 0, 0, end as u64));
            assert!(
                unit["filterText"]
                    .as_str()
                    .unwrap()
                    .starts_with(&text[..end]),
                "{fixture} {label}: {unit:#?}"
            );
            assert_eq!(
                eglot_choose(&text, (0, end), end, unit).as_deref(),
                Some(want),
                "{fixture} {label}"
            );
        }
    }
    let (text, items) = complete(&mut lsp, ROT, "rotlang", "+30*$0, 90");
    assert_eq!(
        eglot_choose(&text, (0, 4), 4, item(&items, "*2")).as_deref(),
        Some("+30*2, 90")
    );

    // The cursor at an instruction's start: what follows it is kept (eglot's symbol
    // covers `30`, and choosing used to delete it); only what can begin an instruction
    // is offered there (`*30` is not an instruction: tests/wire.rs).
    let (text, items) = complete(&mut lsp, ROT, "rotlang", "0, $030");
    let plus = item(&items, "+");
    assert_eq!(plus["textEdit"]["range"], range(0, 3, 0, 5));
    assert_eq!(
        eglot_choose(&text, (3, 5), 3, plus).as_deref(),
        Some("0, +30")
    );
    assert!(items.iter().all(|i| i["label"] != "*"), "{items:#?}");

    // A pasted blob without separators is not copied into every item.
    let blob = format!("+{}$0", "9".repeat(100_000));
    let (_, items) = complete(&mut lsp, ROT, "rotlang", &blob);
    let slash = item(&items, "/");
    assert_eq!(slash["textEdit"]["newText"], "/");
    assert_eq!(slash["textEdit"]["range"], range(0, 100_001, 0, 100_001));

    // In a profile the edit is in document coordinates, its text escaped.
    let uri = "file:///tmp/clients.json";
    let (text, items) = complete(
        &mut lsp,
        uri,
        "json",
        r#"{"sparse_infill_rotate_template": "0, +30/5$0"}"#,
    );
    let start = text.find("+30").unwrap() as u64;
    let inch = item(&items, "\"");
    assert_eq!(inch["textEdit"]["range"], range(0, start, 0, start + 5));
    assert_eq!(inch["textEdit"]["newText"], "+30/5\\\"");
}

#[test]
fn the_file_kind_comes_from_the_extension_and_the_language_id_only_as_fallback() {
    let mut lsp = Lsp::start();
    let profile = r#"{"name": "Fine 0.2", "sparse_infill_rotate_template": "0, +30X5", "layer_height": "0.2"}"#;
    // eglot sends one languageId (here the server's first mode) for every file.
    let diags = lsp.open("file:///tmp/p.json", "rotlang", profile);
    assert_eq!(
        diags.len(),
        1,
        "read as a profile, not a template: {diags:#?}"
    );
    assert_eq!(diags[0]["code"], "rotlang::unknown-sign");
    let diags = lsp.open("file:///tmp/t.ROT", "json", "0, +30X5");
    assert_eq!(diags.len(), 1, "read as a template: {diags:#?}");
    assert_eq!(diags[0]["range"], range(0, 6, 0, 7));

    // `.ini` config exports: `key = value` lines.
    let ini = "# exported\nlayer_height = 0.2\nsparse_infill_rotate_template = 0, +30X5\n";
    let diags = lsp.open("file:///tmp/config.ini", "ini", ini);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let col = ini.lines().nth(2).unwrap().find('X').unwrap() as u64;
    assert_eq!(diags[0]["range"], range(2, col, 2, col + 1));

    // No extension: the language id decides.
    let diags = lsp.open(
        "untitled:Untitled-1",
        "jsonc",
        "// draft\n{\"sparse_infill_rotate_template\": \"+30X\",}",
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert_eq!(diags[0]["code"], "rotlang::unknown-sign");

    // A `.3mf` project is a zip archive: never read as text, whatever the language id.
    let uri = "file:///tmp/project.3mf";
    lsp.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "json", "version": 1,
               "text": "PK\u{3}\u{4}{\"sparse_infill_rotate_template\": \"+30X\"}"}}),
    );
    assert_eq!(hover_text(&mut lsp, uri, 0, 40), "");
    let published = lsp.drain(Duration::from_millis(200));
    assert!(
        !published.iter().any(|m| m["params"]["uri"] == uri),
        "{published:?}"
    );
}

#[test]
fn jsonc_profiles_accept_comments_and_trailing_commas() {
    let mut lsp = Lsp::start();
    let doc = concat!(
        "// Process preset, annotated\n",
        "{\n",
        "  /* the sparse one */ \"sparse_infill_rotate_template\": \"0, +30X5\", // a typo\n",
        "  \"solid_infill_rotate_template\": \"0, 90\",\n",
        "  \"wall_loops\": [\"2\",],\n",
        "}\n"
    );
    let diags = lsp.open("file:///tmp/p.jsonc", "jsonc", doc);
    // The compat lint speaks of OrcaSlicer's reading (here: the default direction it
    // ignores for `0, 90`); the comments are what this test is about.
    let diags: Vec<_> = diags
        .into_iter()
        .filter(|d| !d["code"].as_str().unwrap_or("").starts_with("orcaslicer::"))
        .collect();
    assert_eq!(diags.len(), 1, "comments are no error: {diags:#?}");
    assert_eq!(diags[0]["code"], "rotlang::unknown-sign");
    let col = doc.lines().nth(2).unwrap().find('X').unwrap() as u64;
    assert_eq!(diags[0]["range"], range(2, col, 2, col + 1));
    // Hover and formatting work through the comments.
    let h = hover_text(&mut lsp, "file:///tmp/p.jsonc", 3, 40);
    assert!(h.contains("`90`"), "{h}");

    // The same text as `.json` is not JSON (OrcaSlicer cannot read it): reported once.
    let diags = lsp.open("file:///tmp/p.json", "json", doc);
    let syntax: Vec<_> = diags
        .iter()
        .filter(|d| d["code"] == "rotlang-lsp::json-syntax")
        .collect();
    assert_eq!(syntax.len(), 1, "{diags:#?}");
    assert_eq!(syntax[0]["range"]["start"]["line"], 0);

    // A JSON file that names no template key is not a profile: whatever its syntax
    // (VS Code's settings.json has comments), nothing is reported.
    let settings = "{\n  // my settings\n  \"editor.fontSize\": 14,\n}\n";
    assert!(
        lsp.open("file:///tmp/settings.json", "jsonc", settings)
            .is_empty()
    );
    assert!(
        lsp.open("file:///tmp/broken.json", "json", "{\"a\": [1, 2,")
            .is_empty()
    );
}

fn hover_with(format: Value) -> Value {
    let caps = json!({"textDocument": {"hover": {"contentFormat": format}}});
    let (mut lsp, _) = Lsp::start_with(caps, Value::Null);
    lsp.open(ROT, "rotlang", "0, +22.5/50%");
    lsp.result(
        "textDocument/hover",
        json!({"textDocument": {"uri": ROT}, "position": {"line": 0, "character": 5}}),
    )["contents"]
        .clone()
}

#[test]
fn hover_is_plain_text_when_the_client_asks_for_it() {
    let plain = hover_with(json!(["plaintext"]));
    assert_eq!(plain["kind"], "plaintext");
    let text = plain["value"].as_str().unwrap();
    assert!(text.starts_with("+22.5/50% turns +22.5°"), "{text}");
    assert!(text.contains("\nModel: 100 layers"), "{text}");
    assert!(
        !text.contains('`') && !text.contains("**") && !text.contains("_Model"),
        "{text}"
    );

    let markdown = hover_with(json!(["markdown", "plaintext"]));
    assert_eq!(markdown["kind"], "markdown");
    assert!(
        markdown["value"]
            .as_str()
            .unwrap()
            .starts_with("`+22.5/50%`")
    );
}

/// Wait until the hover at (0, 0) of `ROT` contains `needle` (settings pulled or pushed
/// are applied as they arrive).
fn hover_until(lsp: &mut Lsp, needle: &str) -> String {
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let h = hover_text(lsp, ROT, 0, 0);
        if h.contains(needle) || Instant::now() > deadline {
            return h;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn settings_register_warn_once_and_fall_back_to_defaults() {
    // A client allowing dynamic registration gets `workspace/didChangeConfiguration`
    // registered (vscode-languageclient sends changes only then).
    let caps = json!({"workspace": {"didChangeConfiguration": {"dynamicRegistration": true}}});
    let options = json!({"rotlang": {"layers": 0, "layerHeight": 0.3, "colour": "red"}});
    let (mut lsp, _) = Lsp::start_with(caps, options);
    let request = lsp.wait(|m| m["method"] == "client/registerCapability");
    let registration = &request["params"]["registrations"][0];
    assert_eq!(registration["method"], "workspace/didChangeConfiguration");

    // Invalid initialization options: a warning in the log and one message box.
    let log = lsp.wait(|m| m["method"] == "window/logMessage");
    assert_eq!(log["params"]["type"], 2, "a warning: {log}");
    let message = log["params"]["message"].as_str().unwrap();
    assert!(
        message.contains("layers = 0: a whole number from 1 to 1000000"),
        "{message}"
    );
    assert!(
        message.contains("colour: not a rotlang setting"),
        "{message}"
    );
    let shown = lsp.wait(|m| m["method"] == "window/showMessage");
    assert_eq!(shown["params"]["type"], 2);

    lsp.open(ROT, "rotlang", "0, 90");
    let h = hover_until(&mut lsp, "Model: 100 layers × 0.3 mm");
    assert!(
        h.contains("Model: 100 layers × 0.3 mm"),
        "the rest applies: {h}"
    );

    // A second invalid push: logged, but no second message box.
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {"layers": 20, "topShellLayers": -1}}}),
    );
    let log = lsp.wait(|m| m["method"] == "window/logMessage");
    assert!(
        log["params"]["message"]
            .as_str()
            .unwrap()
            .contains("topShellLayers = -1")
    );
    let h = hover_until(&mut lsp, "Model: 20 layers × 0.2 mm");
    assert!(
        h.contains("Model: 20 layers × 0.2 mm (4 mm tall), shells B = 3, T = 4"),
        "{h}"
    );
    let later = lsp.drain(Duration::from_millis(300));
    assert!(
        !later.iter().any(|m| m["method"] == "window/showMessage"),
        "{later:#?}"
    );

    // Removing a setting restores its default; other tools' sections change nothing.
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {}}}),
    );
    let h = hover_until(&mut lsp, "Model: 100 layers × 0.2 mm");
    assert!(h.contains("Model: 100 layers × 0.2 mm (20 mm tall)"), "{h}");
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"python": {"layers": 3}}}),
    );
    assert!(hover_text(&mut lsp, ROT, 0, 0).contains("Model: 100 layers"));

    // Pulled settings are checked too; the VS Code extension's own keys (`server.path`,
    // `trace.server`) in the same section are not settings of the server, and no error.
    let mut lsp = Lsp::spawn();
    lsp.configuration = json!({"layers": "many", "server": {"path": "rotlang-lsp"},
                               "trace": {"server": "off"}});
    lsp.result(
        "initialize",
        json!({"capabilities": {"workspace": {"configuration": true}}}),
    );
    lsp.notify("initialized", json!({}));
    let log = lsp.wait(|m| m["method"] == "window/logMessage");
    let message = log["params"]["message"].as_str().unwrap();
    assert!(message.contains("layers = \"many\""), "{message}");
    assert!(
        !message.contains("server") && !message.contains("trace"),
        "{message}"
    );

    // Without dynamic registration, nothing is registered.
    let (mut lsp, _) = Lsp::start_with(json!({}), Value::Null);
    lsp.open(ROT, "rotlang", "0");
    let messages = lsp.drain(Duration::from_millis(300));
    assert!(
        !messages
            .iter()
            .any(|m| m["method"] == "client/registerCapability"),
        "{messages:#?}"
    );
}

#[test]
fn formatting_keeps_one_instruction_per_line() {
    let mut lsp = Lsp::start();
    let format = |lsp: &mut Lsp| {
        lsp.result(
            "textDocument/formatting",
            json!({"textDocument": {"uri": ROT}, "options": {"tabSize": 4, "insertSpaces": true}}),
        )
    };
    lsp.open(ROT, "rotlang", "0,90\n+30/50%   \n\n  -10L25%,+10l25%\n");
    let edits = format(&mut lsp);
    assert_eq!(
        edits[0]["newText"], "0, 90\n+30/50%\n-10L25%, +10l25%\n",
        "{edits}"
    );
    // One instruction per line is already formatted.
    lsp.change(ROT, 2, "0\n90\n+30/50%\n");
    assert_eq!(format(&mut lsp), json!([]));
    // The file's own line ends are kept.
    lsp.change(ROT, 3, "0,90\r\n+30\r\n");
    assert_eq!(format(&mut lsp)[0]["newText"], "0, 90\r\n+30\r\n");
}

#[test]
fn lines_end_at_cr_lf_and_crlf() {
    let mut lsp = Lsp::start();
    for (v, text) in [
        "0, 90\r+30X5\r-45",
        "0, 90\n+30X5\n-45",
        "0, 90\r\n+30X5\r\n-45",
    ]
    .iter()
    .enumerate()
    {
        let version = v as i64 + 1;
        let diags = if v == 0 {
            lsp.open(ROT, "rotlang", text)
        } else {
            lsp.change(ROT, version, text);
            lsp.diagnostics(ROT, Some(version))
        };
        assert_eq!(diags.len(), 1, "{text:?}: {diags:#?}");
        assert_eq!(diags[0]["range"], range(1, 3, 1, 4), "{text:?}");
        let h = hover_text(&mut lsp, ROT, 2, 1);
        assert!(h.starts_with("`-45`"), "{text:?}: {h}");
    }
}

#[test]
fn the_message_is_the_message_alone() {
    let mut lsp = Lsp::start();
    let diags = lsp.open(ROT, "rotlang", "0, +30°");
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let d = &diags[0];
    assert_eq!(d["message"], "angles are written without `°`");
    let related = d["relatedInformation"]
        .as_array()
        .expect("related information");
    let at_sign = range(0, 6, 0, 7);
    assert!(
        related
            .iter()
            .any(|r| r["message"] == "a degree sign" && r["location"]["range"] == at_sign),
        "{related:#?}"
    );
    assert!(
        related.iter().any(|r| r["message"]
            .as_str()
            .unwrap()
            .starts_with("help: every angle is in degrees already")),
        "{related:#?}"
    );
    // The long help of an unknown sign stays out of the echo-area line too.
    lsp.change(ROT, 2, "+30X5");
    let d = &lsp.diagnostics(ROT, Some(2))[0];
    assert_eq!(d["message"], "unknown sign `X`");
}

/// Run the binary with arguments and stdin left open (a server would wait on it): it must
/// answer and exit by itself.
fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rotlang-lsp"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start rotlang-lsp");
    let deadline = Instant::now() + Duration::from_secs(10);
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("rotlang-lsp {args:?} did not exit: it started the server");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let (mut out, mut err) = (String::new(), String::new());
    child
        .stdout
        .take()
        .unwrap()
        .read_to_string(&mut out)
        .unwrap();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    (status.code(), out, err)
}

#[test]
fn the_command_line_help_version_and_usage_errors() {
    for flag in ["--help", "-h"] {
        let (code, out, _) = run(&[flag]);
        assert_eq!(code, Some(0));
        assert!(out.starts_with("Usage: rotlang-lsp [--stdio]"), "{out}");
        assert!(out.contains("--version"), "{out}");
    }
    for flag in ["--version", "-V"] {
        let (code, out, _) = run(&[flag]);
        assert_eq!(code, Some(0));
        assert_eq!(out, format!("rotlang-lsp {}\n", env!("CARGO_PKG_VERSION")));
    }
    let (code, out, err) = run(&["--port", "4000"]);
    assert_eq!(code, Some(2), "a usage error");
    assert!(out.is_empty());
    assert!(
        err.starts_with("rotlang-lsp: unexpected argument '--port'"),
        "{err}"
    );
    assert!(err.contains("Usage: rotlang-lsp"), "{err}");

    // `--stdio`, which clients pass, starts the server as usual.
    let mut lsp = Lsp::spawn_with_args(&["--stdio"]);
    let init = lsp.result("initialize", json!({"capabilities": {}}));
    assert_eq!(init["serverInfo"]["name"], "rotlang-lsp");
    assert!(lsp.shutdown().success());
}
