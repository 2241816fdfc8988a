//! End to end with a real editor: headless Neovim (Debian's 0.7.2) talks to the built
//! `rotlang-lsp` through `vim.lsp.start_client`. `tests/nvim/run.sh` installs Neovim
//! when it is missing and we are root (CI), and `tests/nvim/e2e.lua` drives the editor.

use std::path::Path;
use std::process::{Command, Stdio};

use serde_json::Value;

#[test]
fn neovim_shows_the_diagnostic_clears_it_and_hovers() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/nvim");
    let out = std::env::temp_dir().join(format!("rotlang-nvim-{}.json", std::process::id()));
    let _ = std::fs::remove_file(&out);
    let status = Command::new("bash")
        .arg(dir.join("run.sh"))
        .arg(env!("CARGO_BIN_EXE_rotlang-lsp"))
        .arg(&out)
        .stdin(Stdio::null())
        .status()
        .expect("run tests/nvim/run.sh");
    if status.code() == Some(77) {
        // CI runs as root and installs Neovim; there, a skip would hide a broken set-up.
        assert!(
            std::env::var_os("CI").is_none(),
            "Neovim could not be installed in CI (see the message above)"
        );
        eprintln!("SKIPPED: Neovim is not available (see the message above)");
        return;
    }
    assert!(status.success(), "run.sh failed: {status}");
    let text = std::fs::read_to_string(&out).expect("e2e.lua wrote its result");
    let _ = std::fs::remove_file(&out);
    let r: Value = serde_json::from_str(&text).expect("result JSON");
    assert_eq!(r["ok"], true, "{r:#}");
    assert_eq!(r["got_diagnostic"], true, "{r:#}");
    let d = &r["diagnostic"];
    assert!(
        d["message"]
            .as_str()
            .unwrap_or("")
            .contains("unknown sign `X`"),
        "{r:#}"
    );
    // `0, +30X5`: the X is at byte (and UTF-16) column 6.
    assert_eq!(
        (d["lnum"].as_i64(), d["col"].as_i64(), d["end_col"].as_i64()),
        (Some(0), Some(6), Some(7)),
        "{r:#}"
    );
    assert_eq!(d["severity"], 1, "an error");
    assert_eq!(
        r["cleared"], true,
        "fixing the text clears the diagnostic: {r:#}"
    );
    let hover = r["hover"].as_str().unwrap_or("");
    assert!(
        hover.contains("`+22.5/50%` turns +22.5° linearly over the next 50% of the object height"),
        "{hover}"
    );
    assert!(
        hover.contains("First: layers 6–55, 30°→52.5° over 50 layers."),
        "{hover}"
    );
    assert!(hover.contains("Layers: 6: 30.45°, 7: 30.9°"), "{hover}");
    assert!(hover.contains("Model: 100 layers × 0.2 mm"), "{hover}");

    // Completion through Neovim's own omnifunc helpers: with the documented 'iskeyword'
    // the keyword before the cursor is `+30`, where the server's edits start, and the
    // joints survive Neovim's prefix filter.
    assert_eq!(r["completion_start"], 3, "{r:#}");
    assert_eq!(r["completion_edit_start"], 3, "{r:#}");
    let words: Vec<&str> = r["completion_words"]
        .as_array()
        .expect("completion words")
        .iter()
        .filter_map(Value::as_str)
        .collect();
    for word in ["+30/", "+30N", "+30L", "+30#"] {
        assert!(words.contains(&word), "{word} in {words:?}");
    }
}

/// The README's own Neovim 0.7 set-up, extracted from `lsp/README.md` and run as the
/// whole `init.lua`: a `.rot` file, a JSON preset, a `.jsonc` one and an `.ini` export
/// each get the server and their diagnostic (the snippet covered `rotlang` and `json`).
#[test]
fn neovim_runs_the_readme_snippet_for_every_kind_of_file() {
    let lsp = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(lsp.join("README.md")).expect("lsp/README.md");
    let section = readme
        .split("### Neovim 0.7")
        .nth(1)
        .expect("a Neovim 0.7 section");
    let lua_block = |text: &str| -> String {
        let start = text.find("```lua\n").expect("a lua block") + "```lua\n".len();
        let end = start + text[start..].find("```").expect("the block ends");
        text[start..end].to_string()
    };
    // The `iskeyword` snippet every version uses, then the 0.7 one.
    let keyword = lua_block(readme.split("## Neovim").nth(1).expect("## Neovim"));
    let init = format!("{keyword}\n{}", lua_block(section));
    assert!(init.contains("vim.lsp.start_client"), "{init}");
    let base = std::env::temp_dir().join(format!("rotlang-nvim-readme-{}", std::process::id()));
    let (script, out) = (base.with_extension("lua"), base.with_extension("json"));
    std::fs::write(&script, &init).expect("write the snippet");
    let _ = std::fs::remove_file(&out);
    let status = Command::new("bash")
        .arg(lsp.join("tests/nvim/run.sh"))
        .arg(env!("CARGO_BIN_EXE_rotlang-lsp"))
        .arg(&out)
        .arg(&script)
        .stdin(Stdio::null())
        .status()
        .expect("run tests/nvim/run.sh");
    let _ = std::fs::remove_file(&script);
    if status.code() == Some(77) {
        assert!(
            std::env::var_os("CI").is_none(),
            "Neovim could not be installed in CI (see the message above)"
        );
        eprintln!("SKIPPED: Neovim is not available (see the message above)");
        return;
    }
    assert!(status.success(), "run.sh failed: {status}");
    let text = std::fs::read_to_string(&out).expect("readme.lua wrote its result");
    let _ = std::fs::remove_file(&out);
    let r: Value = serde_json::from_str(&text).expect("result JSON");
    assert_eq!(r["ok"], true, "{r:#}");
    for (name, filetype, line, prefix) in [
        ("bad.rot", "rotlang", 0, "0, +30"),
        (
            "preset.json",
            "json",
            1,
            "  \"sparse_infill_rotate_template\": \"0, +30",
        ),
        (
            "preset.jsonc",
            "jsonc",
            2,
            "  \"sparse_infill_rotate_template\": \"0, +30",
        ),
        (
            "export.ini",
            "dosini",
            1,
            "sparse_infill_rotate_template = 0, +30",
        ),
    ] {
        let f = &r["files"][name];
        assert_eq!(f["filetype"], filetype, "{name}: {r:#}");
        assert_eq!(
            f["client"], "rotlang",
            "{name}: the server is attached: {r:#}"
        );
        assert_eq!(f["diagnosed"], true, "{name}: {r:#}");
        assert_eq!(
            (f["lnum"].as_i64(), f["col"].as_i64()),
            (Some(line), Some(prefix.len() as i64)),
            "{name}: the error at the X: {r:#}"
        );
        assert!(
            f["message"]
                .as_str()
                .unwrap_or("")
                .contains("unknown sign `X`"),
            "{name}: {r:#}"
        );
    }
}
