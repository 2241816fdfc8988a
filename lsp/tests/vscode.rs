//! The VS Code extension (`editors/vscode`): installs its locked npm dependencies through
//! `scripts/ensure npm-ci`, tests its TextMate grammar with vscode-textmate and
//! vscode-oniguruma (the engine VS Code uses) against the built server's semantic tokens
//! on every corpus template, tests its client glue with VS Code and the language client
//! replaced by fakes (no VS Code runs here), and packages it with `@vscode/vsce` into
//! `target/rotlang.vsix`, so the repository's test command builds the extension.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

/// Skip (exit-77 semantics): allowed only outside CI.
fn skip(why: &str) {
    assert!(
        std::env::var_os("CI").is_none(),
        "the VS Code extension test cannot run in CI: {why}"
    );
    eprintln!("SKIPPED: {why}");
}

#[test]
fn vscode_extension_grammar_matches_the_parser_and_packages() {
    let root = root();
    let ext = root.join("editors/vscode");
    if Command::new("node").arg("--version").output().is_err() {
        // Debian's packages, through the shared locked installer.
        let status = Command::new(root.join("scripts/ensure"))
            .args(["apt", "nodejs", "npm"])
            .stdin(Stdio::null())
            .status()
            .expect("run scripts/ensure");
        if !status.success() {
            return skip("Node.js is not installed and could not be (see above)");
        }
    }
    let version = Command::new("node")
        .arg("--version")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let major: u32 = version
        .trim()
        .trim_start_matches('v')
        .split('.')
        .next()
        .and_then(|m| m.parse().ok())
        .unwrap_or(0);
    if major < 20 {
        // @vscode/vsce 3 needs Node.js 20.
        return skip(&format!(
            "Node.js 20 or newer is needed, found {:?}",
            version.trim()
        ));
    }
    let status = Command::new(root.join("scripts/ensure"))
        .arg("npm-ci")
        .arg(&ext)
        .stdin(Stdio::null())
        .status()
        .expect("run scripts/ensure");
    if status.code() == Some(77) {
        return skip("npm dependencies could not be installed (see above)");
    }
    assert!(status.success(), "scripts/ensure npm-ci failed: {status}");

    let output = Command::new("node")
        .args(["--test", "test/grammar.test.js", "test/extension.test.js"])
        .current_dir(&ext)
        .env("ROTLANG_LSP", env!("CARGO_BIN_EXE_rotlang-lsp"))
        .env("ROTLANG_CORPUS", root.join("corpus"))
        .stdin(Stdio::null())
        .output()
        .expect("run node --test");
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "grammar tests failed:\n{report}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(report.contains("# pass 5"), "{report}");

    // Package. The target directory is where the build puts everything else.
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    std::fs::create_dir_all(&target).expect("target directory");
    let vsix = target.join("rotlang.vsix");
    let _ = std::fs::remove_file(&vsix);
    let vsce = ext.join("node_modules/.bin/vsce");
    let output = Command::new(&vsce)
        .args([
            "package",
            "--allow-missing-repository",
            "--skip-license",
            "--out",
        ])
        .arg(&vsix)
        .current_dir(&ext)
        .stdin(Stdio::null())
        .output()
        .expect("run vsce");
    assert!(
        output.status.success(),
        "vsce package failed:\n{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    let bytes = std::fs::read(&vsix).expect("the .vsix was written");
    assert!(bytes.starts_with(b"PK"), "a zip archive");
    // Zip archives keep member names uncompressed: the manifest, the grammar, the client
    // and the language client library it needs at run time are all inside.
    let has = |name: &str| bytes.windows(name.len()).any(|w| w == name.as_bytes());
    for name in [
        "extension/package.json",
        "extension/extension.js",
        "extension/syntaxes/rotlang.tmLanguage.json",
        "extension/language-configuration.json",
        "extension/node_modules/vscode-languageclient/package.json",
    ] {
        assert!(has(name), "{name} in the .vsix");
    }
    assert!(
        !has("extension/node_modules/vscode-textmate/"),
        "development dependencies stay out of the .vsix"
    );
    eprintln!("packaged {}", vsix.display());
}
