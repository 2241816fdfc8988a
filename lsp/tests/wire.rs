//! Over the wire: the real `rotlang-lsp` binary, framed JSON-RPC on its stdio, one
//! feature per test. Positions are written out by hand (not computed by server code).

mod common;

use common::{Lsp, col16, cursor, hover_text, range};
use serde_json::{Value, json};

const ROT: &str = "file:///tmp/test.rot";
const JSON: &str = "file:///tmp/profile.json";

fn utf8_client() -> Value {
    json!({"general": {"positionEncodings": ["utf-8", "utf-16"]}})
}

#[test]
fn initialize_announces_capabilities() {
    let (lsp, init) = Lsp::start_with(json!({}), Value::Null);
    let caps = &init["capabilities"];
    assert_eq!(
        caps["positionEncoding"], "utf-16",
        "UTF-16 unless offered otherwise"
    );
    assert_eq!(caps["textDocumentSync"]["change"], 1, "full sync");
    assert_eq!(caps["textDocumentSync"]["openClose"], true);
    assert_eq!(caps["hoverProvider"], true);
    assert_eq!(caps["documentFormattingProvider"], true);
    assert_eq!(caps["inlayHintProvider"], true);
    assert_eq!(caps["documentSymbolProvider"], true);
    assert!(caps["completionProvider"].is_object());
    assert_eq!(
        caps["codeActionProvider"]["codeActionKinds"],
        json!(["quickfix"])
    );
    let legend = &caps["semanticTokensProvider"]["legend"];
    assert_eq!(
        legend["tokenModifiers"],
        json!([
            "angle", "sign", "runtime", "solid", "joint", "flip", "count", "unit"
        ])
    );
    assert_eq!(legend["tokenTypes"][0], "number");
    assert_eq!(init["serverInfo"]["name"], "rotlang-lsp");
    assert!(lsp.shutdown().success());

    let (_lsp, init) = Lsp::start_with(utf8_client(), Value::Null);
    assert_eq!(init["capabilities"]["positionEncoding"], "utf-8");
}

#[test]
fn rot_diagnostics_appear_and_clear() {
    let mut lsp = Lsp::start();
    assert_eq!(
        lsp.open(ROT, "rotlang", "0, 90\n+30/50%"),
        Vec::<Value>::new()
    );

    lsp.change(ROT, 2, "+30X5");
    let diags = lsp.diagnostics(ROT, Some(2));
    assert_eq!(diags.len(), 1, "{diags:?}");
    let d = &diags[0];
    assert_eq!(d["range"], range(0, 3, 0, 4), "the range covers `X`");
    assert_eq!(d["severity"], 1);
    assert_eq!(d["code"], "rotlang::unknown-sign");
    assert_eq!(d["source"], "rotlang");
    assert!(d["message"].as_str().unwrap().contains("unknown sign `X`"));

    lsp.change(ROT, 3, "+30/5");
    assert!(lsp.diagnostics(ROT, Some(3)).is_empty(), "fixed: cleared");

    // Warnings are warnings; secondary labels become related information.
    lsp.change(ROT, 4, "10,,20\n+45/10*2");
    let diags = lsp.diagnostics(ROT, Some(4));
    let warn = diags
        .iter()
        .find(|d| d["code"] == "rotlang::empty-instruction")
        .expect("warning");
    assert_eq!(warn["severity"], 2);
    let moved = diags
        .iter()
        .find(|d| d["code"] == "rotlang::repeat-after-joint")
        .expect("error");
    assert_eq!(moved["range"], range(1, 6, 1, 8));
    let related = moved["relatedInformation"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["message"] == "it goes here")
        .expect("the secondary label");
    assert_eq!(related["location"]["uri"], ROT);
    assert_eq!(related["location"]["range"], range(1, 3, 1, 3));
    assert_eq!(related["message"], "it goes here");

    lsp.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": ROT}}),
    );
    assert!(lsp.diagnostics(ROT, None).is_empty(), "closing clears");
}

#[test]
fn ranged_changes_are_applied_too() {
    // The server asks for full sync, but applies ranged changes if a client sends them.
    let mut lsp = Lsp::start();
    lsp.open(ROT, "rotlang", "0, α+30X");
    lsp.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": ROT, "version": 2},
               "contentChanges": [{"range": range(0, 3, 0, 4), "text": ""},
                                  {"range": range(0, 6, 0, 7), "text": "/5"}]}),
    );
    assert!(lsp.diagnostics(ROT, Some(2)).is_empty());
    let symbols = lsp.result(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": ROT}}),
    );
    assert_eq!(symbols[1]["name"], "+30/5");
}

#[test]
fn json_profile_diagnostics_land_on_the_right_characters() {
    let mut lsp = Lsp::start();
    // `\u002b` is `+`, `\"` an inch sign: the template is `0, +30X5` and `+1/2"`.
    let doc = concat!(
        "{\n",
        "  \"name\": \"+30X5 is not a template here\",\n",
        "  \"sparse_infill_rotate_template\": \"0, \\u002b30X5\",\n",
        "  \"solid_infill_rotate_template\": \"+30M3\",\n",
        "  \"other\": [\"\\ud835\\udd4f\"]\n",
        "}\n"
    );
    let diags = lsp.open(JSON, "json", doc);
    // Profiles also get the OrcaSlicer compat findings, templates with errors too, as
    // `rotlang check` reports them: here OrcaSlicer's reading of the solid sign.
    let mut codes: Vec<_> = diags.iter().map(|d| d["code"].as_str().unwrap()).collect();
    codes.sort();
    assert_eq!(
        codes,
        [
            "orcaslicer::solid-sign",
            "rotlang::solid-sign-in-solid-template",
            "rotlang::unknown-sign"
        ],
        "{diags:#?}"
    );
    let line2 = doc.lines().nth(2).unwrap();
    let x = line2.find('X').unwrap() as u64;
    let sparse = diags
        .iter()
        .find(|d| d["code"] == "rotlang::unknown-sign")
        .expect("X");
    assert_eq!(
        sparse["range"],
        range(2, x, 2, x + 1),
        "after the \\u escape"
    );
    let line3 = doc.lines().nth(3).unwrap();
    let m = line3.find('M').unwrap() as u64;
    let solid = diags
        .iter()
        .find(|d| d["code"] == "rotlang::solid-sign-in-solid-template")
        .expect("solid key is checked with the solid target");
    assert_eq!(solid["range"], range(3, m, 3, m + 1));

    // An escaped character outside the BMP: the range spans the whole escape pair.
    let doc = "{\"sparse_infill_rotate_template\": \"\\ud835\\udd4f, +1\"}";
    lsp.change(JSON, 2, doc);
    let diags = lsp.diagnostics(JSON, Some(2));
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let start = doc.find("\\ud835").unwrap() as u64;
    assert_eq!(diags[0]["range"], range(0, start, 0, start + 12));

    // A good profile has no diagnostics (its directions 0: OrcaSlicer's default 45° would
    // be ignored by OrcaSlicer and added by rotlang, orcaslicer::direction-ignored).
    lsp.change(JSON, 3, r#"{"sparse_infill_rotate_template": "+10L25%, -10l25%", "solid_infill_rotate_template": "0, 90", "sparse_infill_direction": "0", "solid_infill_direction": 0}"#);
    assert!(lsp.diagnostics(JSON, Some(3)).is_empty());
}

#[test]
fn malformed_json_documents_report_once_and_keep_working() {
    let mut lsp = Lsp::start();
    let doc = "{\"sparse_infill_rotate_template\": \"+30X\", \"a\": [1, 2,, }";
    let diags = lsp.open(JSON, "json", doc);
    let json_errors: Vec<_> = diags
        .iter()
        .filter(|d| d["code"] == "rotlang-lsp::json-syntax")
        .collect();
    assert_eq!(json_errors.len(), 1, "{diags:#?}");
    assert!(
        diags.iter().any(|d| d["code"] == "rotlang::unknown-sign"),
        "templates before the error are still checked"
    );
    for (v, text) in [
        "{\"sparse_infill_rotate_template\": \"+30",
        "\"\\",
        "\u{0}\u{1}{[",
        "{\"sparse_infill_rotate_template\": [\"1\", ",
    ]
    .iter()
    .enumerate()
    {
        lsp.change(JSON, v as i64 + 2, text);
        let diags = lsp.diagnostics(JSON, Some(v as i64 + 2));
        assert!(diags.len() <= 2, "{diags:#?}");
    }
    assert!(lsp.alive());
}

#[test]
fn hover_on_an_instruction_describes_it_and_its_layers() {
    let mut lsp = Lsp::start();
    let (text, line, col, _) = cursor("0, +22.5N$050%");
    lsp.open(ROT, "rotlang", &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(h.contains("`+22.5N50%` turns +22.5° along a sine (vertical connection) over the next 50% of the object height"), "{h}");
    assert!(h.contains("Governs"), "{h}");
    assert!(h.contains("Layers: 1: "), "layers it governs, listed: {h}");
    assert!(
        h.contains("Model: 100 layers × 0.2 mm (20 mm tall), shells B = 3, T = 4"),
        "{h}"
    );

    let (text, line, col, _) = cursor("+22.5/5$00%");
    lsp.change(ROT, 2, &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(
        h.contains("Governs 100 of the 100 layers. First: layers 0–49, 0°→22.5° over 50 layers."),
        "{h}"
    );
    assert!(h.contains("Layers: 0: 0.45°, 1: 0.9°, 2: 1.35°"), "{h}");

    let (text, line, col, _) = cursor("B!, +3$00");
    lsp.change(ROT, 3, &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(h.contains("`+30` turns +30° in one layer."), "{h}");
    let (text, line, col, _) = cursor("$0B!, +30");
    lsp.change(ROT, 4, &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(
        h.contains(
            "keeps the current direction over the next 3 layers (B = 3, the bottom shell layer count)"
        ),
        "{h}"
    );
    assert!(h.contains("one-time"), "{h}");
}

#[test]
fn hover_between_instructions_shows_the_sequence() {
    let mut lsp = Lsp::start();
    let (text, line, col, _) = cursor("0,$0 90");
    lsp.open(ROT, "rotlang", &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(
        h.contains("**Template** `0, 90` (sparse infill): 2 instructions."),
        "{h}"
    );
    assert!(h.contains("First 24 layers: 0°, 90°, 0°, 90°"), "{h}");
    assert!(
        h.contains("`▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█▁█` first 48 layers"),
        "sparkline: {h}"
    );
    // Per group of layers, the highest and the lowest angle: `0, 90` is not a line at 45°.
    assert!(
        h.contains(&format!(
            "`{}` highest and\n`{}` lowest angle of each group of about 2 layers, all 100 layers",
            "█".repeat(48),
            "▁".repeat(48)
        )),
        "{h}"
    );
    assert!(
        h.contains("Angles from 0° to 90° over all 100 layers."),
        "{h}"
    );
    assert!(h.contains("Model: 100 layers"), "{h}");
    assert!(!h.contains("In brackets"), "all angles in [0°, 180°): {h}");

    // Angles beyond 180° show the direction of their lines beside them.
    lsp.change(ROT, 2, "0, 270");
    let h = hover_text(&mut lsp, ROT, 0, 2);
    assert!(h.contains("First 24 layers: 0°, 270° (90°), 0°"), "{h}");
    assert!(
        h.contains("In brackets: the direction of the infill lines"),
        "{h}"
    );

    // An empty file says so, with no empty code span.
    lsp.change(ROT, 3, "");
    let h = hover_text(&mut lsp, ROT, 0, 0);
    assert!(
        h.contains("**Template** (empty) (sparse infill): 0 instructions."),
        "{h}"
    );
    assert!(!h.contains("``"), "{h}");
    assert!(h.contains("every layer keeps the base direction"), "{h}");

    // In a JSON profile, outside the template strings there is nothing to say.
    let doc = r#"{"sparse_infill_rotate_template": "0, 90"}"#;
    lsp.open(JSON, "json", doc);
    assert_eq!(hover_text(&mut lsp, JSON, 0, 0), "");
    let h = hover_text(&mut lsp, JSON, 0, 5);
    assert!(
        h.contains("**sparse_infill_rotate_template** `0, 90`"),
        "on the key: {h}"
    );
    let h = hover_text(&mut lsp, JSON, 0, doc.find("90").unwrap() as u32 - 1);
    assert!(
        h.contains("**sparse_infill_rotate_template** `0, 90`"),
        "{h}"
    );
}

#[test]
fn the_model_comes_from_settings() {
    let options = json!({"rotlang": {"layers": 10, "layerHeight": 0.3, "bottomShellLayers": 3, "topShellLayers": 4}});
    let (mut lsp, _) = Lsp::start_with(json!({}), options);
    let (text, line, col, _) = cursor("$0B!, +30");
    lsp.open(ROT, "rotlang", &text);
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(
        h.contains("Model: 10 layers × 0.3 mm (3 mm tall), shells B = 3, T = 4"),
        "{h}"
    );
    assert!(
        h.contains("over the next 3 layers (B = 3, the bottom shell layer count)"),
        "{h}"
    );

    // Without the `rotlang` wrapper, through didChangeConfiguration: the whole section,
    // so `layerHeight`, left out, is back at its default.
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"layers": 40, "firstLayerHeight": 0.3}}),
    );
    let h = hover_text(&mut lsp, ROT, line, col);
    assert!(
        h.contains("Model: 40 layers × 0.2 mm, first layer 0.3 mm (8.1 mm tall)"),
        "{h}"
    );
}

#[test]
fn the_model_can_be_pulled_with_workspace_configuration() {
    let mut lsp = Lsp::spawn();
    lsp.configuration = json!({"layers": 7, "layerHeight": 0.25});
    lsp.result(
        "initialize",
        json!({"capabilities": {"workspace": {"configuration": true}}}),
    );
    lsp.notify("initialized", json!({}));
    let request = lsp.wait(|m| m["method"] == "workspace/configuration");
    assert_eq!(request["params"]["items"][0]["section"], "rotlang");
    lsp.open(ROT, "rotlang", "0, 90");
    // The answer is applied as soon as it arrives; allow the server a moment.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
    loop {
        let h = hover_text(&mut lsp, ROT, 0, 2);
        if h.contains("Model: 7 layers × 0.25 mm") {
            break;
        }
        assert!(std::time::Instant::now() < deadline, "{h}");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    // A push of `null` (the pull model's "something changed") pulls again.
    lsp.configuration = json!({"layers": 9});
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": null}),
    );
    lsp.wait(|m| m["method"] == "workspace/configuration");
}

#[test]
fn other_documents_are_left_alone() {
    let mut lsp = Lsp::start();
    let uri = "file:///tmp/notes.txt";
    lsp.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "plaintext", "version": 1, "text": "+30X"}}),
    );
    assert_eq!(hover_text(&mut lsp, uri, 0, 1), "");
    // A `.rot` file is recognised by its extension whatever the language id.
    let diags = lsp.open("file:///tmp/by-extension.rot", "plaintext", "+30X");
    assert_eq!(diags.len(), 1);
    let published = lsp.drain(std::time::Duration::from_millis(200));
    assert!(
        !published.iter().any(|m| m["params"]["uri"] == uri),
        "{published:?}"
    );
}

/// Decode the delta-encoded semantic tokens into (line, col, len, type, modifiers).
fn decode(
    data: &[Value],
    types: &[&str],
    modifiers: &[&str],
) -> Vec<(u64, u64, u64, String, Vec<String>)> {
    let n: Vec<u64> = data.iter().map(|v| v.as_u64().unwrap()).collect();
    let (mut line, mut col) = (0, 0);
    n.chunks(5)
        .map(|t| {
            line += t[0];
            col = if t[0] == 0 { col + t[1] } else { t[1] };
            let mods = (0..modifiers.len())
                .filter(|i| t[4] & (1 << i) != 0)
                .map(|i| modifiers[i].to_string())
                .collect();
            (line, col, t[2], types[t[3] as usize].to_string(), mods)
        })
        .collect()
}

#[test]
fn semantic_tokens_cover_every_part() {
    let (mut lsp, init) = Lsp::start_with(json!({}), Value::Null);
    let legend = &init["capabilities"]["semanticTokensProvider"]["legend"];
    let types: Vec<&str> = legend["tokenTypes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    let mods: Vec<&str> = legend["tokenModifiers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    lsp.open(ROT, "rotlang", "+30*2/-5mm, 240M3\nB!");
    let r = lsp.result(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": ROT}}),
    );
    let tokens = decode(r["data"].as_array().unwrap(), &types, &mods);
    let t = |l, c, len, ty: &str, m: &str| (l, c, len, ty.to_string(), vec![m.to_string()]);
    assert!(
        tokens.contains(&t(0, 0, 1, "operator", "sign")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(0, 1, 2, "number", "angle")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(0, 3, 2, "keyword", "runtime")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(0, 5, 1, "function", "joint")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(0, 6, 1, "operator", "flip")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(0, 7, 1, "number", "count")),
        "{tokens:?}"
    );
    assert!(tokens.contains(&t(0, 8, 2, "type", "unit")), "{tokens:?}");
    assert!(
        tokens.contains(&t(0, 15, 1, "enumMember", "solid")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(1, 0, 1, "variable", "count")),
        "{tokens:?}"
    );
    assert!(
        tokens.contains(&t(1, 1, 1, "keyword", "runtime")),
        "{tokens:?}"
    );

    // In JSON, tokens land inside the string, across escapes (`\"` is one inch sign).
    let doc = r#"{"sparse_infill_rotate_template": "\u002b1/2\""}"#;
    lsp.open(JSON, "json", doc);
    let r = lsp.result(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": JSON}}),
    );
    let tokens = decode(r["data"].as_array().unwrap(), &types, &mods);
    let start = doc.find("\\u002b").unwrap() as u64;
    assert_eq!(tokens[0], t(0, start, 6, "operator", "sign"), "{tokens:?}");
    assert_eq!(
        tokens.last().unwrap(),
        &t(0, start + 9, 2, "type", "unit"),
        "{tokens:?}"
    );
}

#[test]
fn completion_offers_signs_with_meanings() {
    let mut lsp = Lsp::start();
    let (text, line, col, _) = cursor("+30$0");
    lsp.open(ROT, "rotlang", &text);
    let items = lsp.result(
        "textDocument/completion",
        json!({"textDocument": {"uri": ROT}, "position": {"line": line, "character": col}}),
    );
    let items = items.as_array().expect("a list");
    let find = |label: &str| {
        items
            .iter()
            .find(|i| i["label"] == label)
            .unwrap_or_else(|| panic!("{label} in {items:?}"))
    };
    assert!(
        find("N")["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("sine")
    );
    assert_eq!(find("N")["kind"], 24, "operator");
    assert!(
        find("mm")["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("millimetres")
    );
    assert!(
        find("M")["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("monotonic")
    );
    assert!(
        find("!")["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("once")
    );
    assert!(
        find("*")["documentation"]["value"]
            .as_str()
            .unwrap()
            .contains("dummy")
    );
    assert_eq!(
        find("/")["textEdit"],
        json!({"range": range(0, 0, 0, 3), "newText": "+30/"}),
        "replaces the instruction typed so far"
    );
    // `#` once: the joint fits after `+30`, the standard-layers unit does not.
    assert_eq!(items.len(), 16 + 6 + 5 + 6);
    assert_eq!(items.iter().filter(|i| i["label"] == "#").count(), 1);

    // A solid template gets no solid signs; an inch sign is escaped inside JSON.
    let doc = r#"{"solid_infill_rotate_template": "+30/5"}"#;
    lsp.open(JSON, "json", doc);
    let at = doc.rfind('"').unwrap() as u32;
    let items = lsp.result(
        "textDocument/completion",
        json!({"textDocument": {"uri": JSON}, "position": {"line": 0, "character": at}}),
    );
    let items = items.as_array().expect("a list");
    assert!(!items.iter().any(|i| i["label"] == "M"));
    let inch = items.iter().find(|i| i["label"] == "\"").expect("inch");
    assert_eq!(inch["textEdit"]["newText"], "+30/5\\\"");
    // Outside the template strings: nothing.
    let r = lsp.result(
        "textDocument/completion",
        json!({"textDocument": {"uri": JSON}, "position": {"line": 0, "character": 2}}),
    );
    assert!(r.is_null());
}

#[test]
fn formatting_replaces_the_whole_document_or_nothing() {
    let mut lsp = Lsp::start();
    lsp.open(ROT, "rotlang", "0,90   +30\n");
    let edits = lsp.result(
        "textDocument/formatting",
        json!({"textDocument": {"uri": ROT}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert_eq!(
        edits,
        json!([{"range": range(0, 0, 1, 0), "newText": "0, 90, +30\n"}])
    );

    lsp.change(ROT, 2, "0, 90, +30\n");
    let edits = lsp.result(
        "textDocument/formatting",
        json!({"textDocument": {"uri": ROT}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert_eq!(edits, json!([]), "already formatted");

    lsp.change(ROT, 3, "0,90 +30X");
    let edits = lsp.result(
        "textDocument/formatting",
        json!({"textDocument": {"uri": ROT}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert!(edits.is_null(), "no edits when the template has errors");

    let doc = "{\"sparse_infill_rotate_template\": \"0,90\", \"x\": \"\\u00b0\"}";
    lsp.open(JSON, "json", doc);
    let edits = lsp.result(
        "textDocument/formatting",
        json!({"textDocument": {"uri": JSON}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert_eq!(
        edits[0]["newText"],
        "{\"sparse_infill_rotate_template\": \"0, 90\", \"x\": \"\\u00b0\"}"
    );
}

/// Where OrcaSlicer's reading matters (profiles by default; `.rot` with `compat` on),
/// formatting leaves a template alone when OrcaSlicer would read the canonical form
/// differently: `0,,90` is 0°, 0°, 90° for it, `0, 90` is not.
#[test]
fn formatting_keeps_what_orcaslicer_reads() {
    let mut lsp = Lsp::start();
    let format = |lsp: &mut Lsp, uri: &str| {
        lsp.result(
            "textDocument/formatting",
            json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true}}),
        )
    };
    let doc = "{\"sparse_infill_rotate_template\": \"0,,90\", \"solid_infill_rotate_template\": \"+30,90\"}";
    lsp.open(JSON, "json", doc);
    let edits = format(&mut lsp, JSON);
    assert_eq!(
        edits[0]["newText"],
        "{\"sparse_infill_rotate_template\": \"0,,90\", \"solid_infill_rotate_template\": \"+30, 90\"}"
    );
    let ini = "file:///tmp/wire-fmt.ini";
    lsp.open(ini, "ini", "sparse_infill_rotate_template = 0,,90\n");
    assert_eq!(
        format(&mut lsp, ini),
        json!([]),
        "nothing OrcaSlicer reads alike"
    );
    // A `.rot` file is rotlang's unless compat is asked for.
    lsp.open(ROT, "rotlang", "0,,90\n");
    assert_eq!(format(&mut lsp, ROT)[0]["newText"], "0, 90\n");
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {"compat": "orcaslicer"}}}),
    );
    assert_eq!(format(&mut lsp, ROT), json!([]));
    // Off: profiles are formatted as rotlang reads them.
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {"compat": "off"}}}),
    );
    assert_eq!(
        format(&mut lsp, ini)[0]["newText"],
        "sparse_infill_rotate_template = 0, 90\n"
    );
}

#[test]
fn inlay_hints_show_the_resolved_turn() {
    let mut lsp = Lsp::start();
    let text = "+22.5/50%, 30\n10*";
    lsp.open(ROT, "rotlang", text);
    let hints = lsp.result(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": ROT}, "range": range(0, 0, 2, 0)}),
    );
    let hints = hints.as_array().expect("hints");
    let labels: Vec<(&Value, &str)> = hints
        .iter()
        .map(|h| (&h["position"], h["label"].as_str().unwrap()))
        .collect();
    assert_eq!(labels.len(), 2, "no hint for the dummy: {labels:?}");
    assert_eq!(
        labels[0],
        (
            &json!({"line": 0, "character": 9}),
            "0°→22.5° over 50 layers"
        )
    );
    assert_eq!(labels[1].1, "30° for 1 layer");

    // Each layer after the shells is a new range of `+30`: the hint shows one, not all.
    lsp.change(ROT, 2, "B!, +30");
    let hints = lsp.result(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": ROT}, "range": range(0, 0, 0, 7)}),
    );
    let labels: Vec<&str> = hints
        .as_array()
        .unwrap()
        .iter()
        .map(|h| h["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["0° for 3 layers", "0°→30° over 1 layer"]);

    // A flipped range starts at its end angle.
    lsp.change(ROT, 3, "+30/-10#");
    let hints = lsp.result(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": ROT}, "range": range(0, 0, 0, 8)}),
    );
    assert_eq!(hints[0]["label"], "27°→0° over 10 layers");

    // A step is not a ramp: every layer of the range has the turned angle.
    lsp.change(ROT, 4, "+15#10");
    let hints = lsp.result(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": ROT}, "range": range(0, 0, 0, 6)}),
    );
    assert_eq!(hints[0]["label"], "15° for 10 layers (a step from 0°)");
}

#[test]
fn code_actions_apply_the_safe_fix() {
    let mut lsp = Lsp::start();
    let diags = lsp.open(ROT, "rotlang", "+30/5cn");
    assert_eq!(diags[0]["range"], range(0, 5, 0, 7));
    let actions = lsp.result(
        "textDocument/codeAction",
        json!({"textDocument": {"uri": ROT}, "range": range(0, 5, 0, 5), "context": {"diagnostics": diags}}),
    );
    let action = &actions[0];
    assert_eq!(action["title"], "write `cm`");
    assert_eq!(action["kind"], "quickfix");
    assert_eq!(action["diagnostics"][0]["code"], "rotlang::unknown-unit");
    assert_eq!(
        action["edit"]["changes"][ROT],
        json!([{"range": range(0, 5, 0, 7), "newText": "cm"}])
    );

    // An unfixable error offers nothing.
    lsp.change(ROT, 2, "+30X5");
    lsp.diagnostics(ROT, Some(2));
    let actions = lsp.result("textDocument/codeAction", json!({"textDocument": {"uri": ROT}, "range": range(0, 0, 0, 5), "context": {"diagnostics": []}}));
    assert_eq!(actions, json!([]));
}

#[test]
fn document_symbols_are_the_instructions() {
    let mut lsp = Lsp::start();
    lsp.open(ROT, "rotlang", "0, +30/5\nB!");
    let symbols = lsp.result(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": ROT}}),
    );
    let names: Vec<&str> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["0", "+30/5", "B!"]);
    assert_eq!(symbols[1]["range"], range(0, 3, 0, 8));
    assert!(
        symbols[1]["detail"]
            .as_str()
            .unwrap()
            .contains("turns +30°")
    );

    let doc = r#"{"sparse_infill_rotate_template": "0, 90"}"#;
    lsp.open(JSON, "json", doc);
    let symbols = lsp.result(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": JSON}}),
    );
    assert_eq!(symbols[0]["name"], "sparse_infill_rotate_template");
    assert_eq!(symbols[0]["children"].as_array().unwrap().len(), 2);
}

#[test]
fn utf16_and_utf8_positions_with_wide_characters() {
    // `°` is 2 bytes / 1 UTF-16 unit, `α` 2 / 1, `𝕏` 4 / 2.
    let text = "°, 𝕏, +30X +5\nα";
    let x = text.find('X').unwrap();
    for (caps, x_col, degree, blackboard, alpha) in [
        (json!({}), col16(text, x), 1, (3, 5), (0, 1)),
        (utf8_client(), x as u64, 2, (4, 8), (0, 2)),
    ] {
        let (mut lsp, _) = Lsp::start_with(caps, Value::Null);
        let diags = lsp.open(ROT, "rotlang", text);
        let find = |code: &str| {
            diags
                .iter()
                .filter(|d| d["code"] == code)
                .map(|d| d["range"].clone())
                .collect::<Vec<_>>()
        };
        assert_eq!(
            find("rotlang::unknown-sign"),
            [range(0, x_col, 0, x_col + 1)]
        );
        assert_eq!(find("rotlang::degree-sign"), [range(0, 0, 0, degree)]);
        let unexpected = find("rotlang::unexpected-character");
        assert!(
            unexpected.contains(&range(0, blackboard.0, 0, blackboard.1)),
            "{unexpected:?}"
        );
        assert!(
            unexpected.contains(&range(1, alpha.0, 1, alpha.1)),
            "{unexpected:?}"
        );
        // Hover on the `5` of `+5`, at the encoding's column.
        let h = hover_text(&mut lsp, ROT, 0, x_col as u32 + 3);
        assert!(h.contains("`+5` turns +5°"), "{h}");
    }
    // The same in a JSON profile with an escaped degree sign: `\u00b0` is one character.
    let doc = "{\"sparse_infill_rotate_template\": \"\\u00b0, α+1\"}";
    let (mut lsp, _) = Lsp::start_with(json!({}), Value::Null);
    let diags = lsp.open(JSON, "json", doc);
    let deg = doc.find("\\u00b0").unwrap() as u64;
    let d = diags
        .iter()
        .find(|d| d["code"] == "rotlang::degree-sign")
        .expect("degree sign");
    assert_eq!(d["range"], range(0, deg, 0, deg + 6));
    let a = col16(doc, doc.find('α').unwrap());
    let d = diags
        .iter()
        .find(|d| d["code"] == "rotlang::unexpected-character")
        .expect("alpha");
    assert_eq!(d["range"], range(0, a, 0, a + 1));
}

/// One reading of a preset (issue 16 item 3, issue 17): a preset that sets a direction and
/// has a non-empty template is read as OrcaSlicer reads it (the template's angles alone,
/// on the preset's own layer heights), and the hover, the inlay hints and the compat
/// diagnostic agree with the library on every layer they name.
#[test]
fn a_preset_reads_the_same_in_hover_inlay_hints_and_diagnostics() {
    use rotlang::eval::Options;
    use rotlang::explain::deg_and_lines;
    let mut lsp = Lsp::start();
    let uri = "file:///tmp/preset.json";
    let doc = "{\n  \"layer_height\": \"0.12\",\n  \"sparse_infill_direction\": \"45\",\n  \"sparse_infill_rotate_template\": \"0 90\"\n}\n";
    let diags = lsp.open(uri, "json", doc);
    // The library's reading: the preset's model; no direction added to a non-empty template.
    let profile =
        rotlang_profile::profile::parse(std::path::Path::new("preset.json"), doc.as_bytes())
            .unwrap();
    let pm = profile.model(
        rotlang::Target::Sparse,
        None,
        rotlang_profile::profile::DEFAULT_OBJECT_HEIGHT,
    );
    let template = rotlang::parse("0 90", rotlang::Target::Sparse).template;
    let angles: Vec<f64> = rotlang::eval::layers(&template, &pm.model, Options::default())
        .map(|l| l.angle)
        .collect();
    assert_eq!(angles.len(), 166, "0.2 mm, then 0.12 mm layers to 20 mm");

    // The hover on the key: the first 24 layers, and the model's layer count.
    let h = hover_text(&mut lsp, uri, 3, 5);
    let first: Vec<String> = angles[..24].iter().map(|&a| deg_and_lines(a)).collect();
    assert!(
        h.contains(&format!("First 24 layers: {}, …", first.join(", "))),
        "{h}"
    );
    assert!(h.contains("over all 166 layers"), "{h}");

    // The inlay hint of each instruction: the angle of the first layer it governs.
    let hints = lsp.result(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": uri}, "range": range(0, 0, 5, 0)}),
    );
    let labels: Vec<&str> = hints
        .as_array()
        .unwrap()
        .iter()
        .map(|h| h["label"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            format!("{} for 1 layer", rotlang::explain::deg(angles[0])),
            format!("{} for 1 layer", rotlang::explain::deg(angles[1])),
        ]
    );

    // The compat diagnostic: rotlang's angle of the layer it names is the library's, and
    // the hover on the same characters lists that layer with that angle.
    let differs = diags
        .iter()
        .find(|d| d["code"] == "orcaslicer::differs")
        .expect("OrcaSlicer reads `0 90` as `0`");
    let message = differs["message"].as_str().unwrap();
    let layer: usize = message
        .split("layer ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .expect(message);
    let start = &differs["range"]["start"];
    let h = hover_text(
        &mut lsp,
        uri,
        start["line"].as_u64().unwrap() as u32,
        start["character"].as_u64().unwrap() as u32,
    );
    assert!(
        h.contains(&format!("{layer}: {}", deg_and_lines(angles[layer]))),
        "layer {layer} in the hover: {h}"
    );
    let ours: f64 = message
        .rsplit("rotlang to ")
        .next()
        .and_then(|s| s.trim_end_matches('°').parse().ok())
        .expect(message);
    assert_eq!(
        ours, angles[layer],
        "the diagnostic's angle is the hover's (needs the library's one reading of a \
         profile, issue 16 item 3): {message}"
    );
}

/// At the start of an instruction only what can begin one is offered (issue 17): at
/// `0, ⎀+30` nothing that would make `/+30` or `*+30`; at `0, ⎀` the angle's signs, and no
/// runtime mark or unit, which cannot begin an instruction.
#[test]
fn completion_at_the_start_of_an_instruction_offers_what_can_begin_one() {
    let mut lsp = Lsp::start();
    let labels = |lsp: &mut Lsp, fixture: &str| -> Vec<(String, String)> {
        let (text, line, col, _) = cursor(fixture);
        lsp.open(ROT, "rotlang", &text);
        let items = lsp.result(
            "textDocument/completion",
            json!({"textDocument": {"uri": ROT}, "position": {"line": line, "character": col}}),
        );
        items
            .as_array()
            .expect("a list")
            .iter()
            .map(|i| {
                let edit = i["textEdit"]["newText"].as_str().unwrap_or("").to_owned();
                (i["label"].as_str().unwrap().to_owned(), edit)
            })
            .collect()
    };
    let before_turn = labels(&mut lsp, "0, $0+30");
    for (label, new_text) in &before_turn {
        let parse = rotlang::parse(new_text, rotlang::Target::Sparse);
        assert!(
            parse
                .diagnostics
                .iter()
                .all(|d| d.code == "rotlang::incomplete"),
            "`{label}` makes `{new_text}`: {:?}",
            parse.diagnostics.iter().map(|d| d.code).collect::<Vec<_>>()
        );
    }
    assert!(
        !before_turn
            .iter()
            .any(|(l, _)| ["/", "*", "*2", "!", "N"].contains(&l.as_str()))
    );

    let empty = labels(&mut lsp, "0, $0");
    let offered: Vec<&str> = empty.iter().map(|(l, _)| l.as_str()).collect();
    assert!(
        offered.contains(&"+") && offered.contains(&"-"),
        "{offered:?}"
    );
    for never in ["*", "*2", "!", "*!", "mm", "cm"] {
        assert!(!offered.contains(&never), "`{never}` offered: {offered:?}");
    }
    // Within an instruction the signs are offered as before.
    let within = labels(&mut lsp, "0, +30$0");
    let offered: Vec<&str> = within.iter().map(|(l, _)| l.as_str()).collect();
    for sign in ["/", "N", "*", "!"] {
        assert!(offered.contains(&sign), "`{sign}` missing: {offered:?}");
    }
    assert!(!offered.contains(&"+"), "{offered:?}");
}
