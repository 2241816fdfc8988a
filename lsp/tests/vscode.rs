//! The VS Code extension (`editors/vscode`): installs its locked npm dependencies through
//! `scripts/ensure npm-ci`, tests its TextMate grammar with vscode-textmate and
//! vscode-oniguruma (the engine VS Code uses) against the built server's semantic tokens
//! on every corpus template, tests its client glue with VS Code and the language client
//! replaced by fakes, and packages it (the client bundled by esbuild) with `@vscode/vsce`
//! into `target/rotlang.vsix`, so the repository's test command builds the extension.
//! `vscode_extension_end_to_end_in_code_server` installs that package into code-server
//! (VS Code in a browser, from npm, locked in `editors/vscode/e2e`) and drives it through
//! Debian's Chromium.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

fn target() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target"))
}

/// Skip (exit-77 semantics): allowed only outside CI.
fn skip(why: &str) {
    assert!(
        std::env::var_os("CI").is_none(),
        "the VS Code extension test cannot run in CI: {why}"
    );
    eprintln!("SKIPPED: {why}");
}

/// `scripts/ensure ARGS` with extra environment; `Err` (a skip) when it cannot install.
fn ensure(args: &[&str], env: &[(&str, &Path)]) -> Result<(), String> {
    let status = Command::new(root().join("scripts/ensure"))
        .args(args)
        .envs(env.iter().map(|(k, v)| (*k, *v)))
        .stdin(Stdio::null())
        .status()
        .expect("run scripts/ensure");
    if status.code() == Some(77) {
        return Err(format!(
            "scripts/ensure {args:?} could not install (see above)"
        ));
    }
    assert!(status.success(), "scripts/ensure {args:?} failed: {status}");
    Ok(())
}

/// Node.js 20 or newer (Debian's, installed when missing), or why not.
fn node_20() -> Result<(), String> {
    if Command::new("node").arg("--version").output().is_err() {
        ensure(&["apt", "nodejs", "npm"], &[])?;
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
        // @vscode/vsce 3 and code-server 4.99 need Node.js 20.
        return Err(format!(
            "Node.js 20 or newer is needed, found {:?}",
            version.trim()
        ));
    }
    Ok(())
}

/// Packages the extension into `out` (`vscode:prepublish` bundles the client into
/// `dist/`; both tests package, one at a time).
fn package(out: &Path) {
    static PACKAGING: Mutex<()> = Mutex::new(());
    let _one = PACKAGING.lock().unwrap_or_else(|e| e.into_inner());
    let ext = root().join("editors/vscode");
    let _ = std::fs::remove_file(out);
    let output = Command::new(ext.join("node_modules/.bin/vsce"))
        .args([
            "package",
            "--no-dependencies",
            "--allow-missing-repository",
            "--out",
        ])
        .arg(out)
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
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(!said.contains("WARNING"), "vsce warns:\n{said}");
}

/// The names of the members of a zip archive, from its central directory.
fn zip_members(bytes: &[u8]) -> Vec<String> {
    let mut names = Vec::new();
    let mut i = 0;
    while i + 46 <= bytes.len() {
        if bytes[i..i + 4] == [0x50, 0x4b, 0x01, 0x02] {
            let n = u16::from_le_bytes([bytes[i + 28], bytes[i + 29]]) as usize;
            let extra = u16::from_le_bytes([bytes[i + 30], bytes[i + 31]]) as usize;
            let comment = u16::from_le_bytes([bytes[i + 32], bytes[i + 33]]) as usize;
            if let Some(name) = bytes.get(i + 46..i + 46 + n) {
                names.push(String::from_utf8_lossy(name).into_owned());
            }
            i += 46 + n + extra + comment;
        } else {
            i += 1;
        }
    }
    names
}

#[test]
fn vscode_extension_grammar_matches_the_parser_and_packages() {
    let root = root();
    let ext = root.join("editors/vscode");
    if let Err(why) = node_20().and_then(|()| ensure(&["npm-ci", &ext.to_string_lossy()], &[])) {
        return skip(&why);
    }

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
    assert!(report.contains("# pass 8"), "{report}");

    // Package. The target directory is where the build puts everything else.
    let target = target();
    std::fs::create_dir_all(&target).expect("target directory");
    let vsix = target.join("rotlang.vsix");
    package(&vsix);
    let bytes = std::fs::read(&vsix).expect("the .vsix was written");
    assert!(bytes.starts_with(b"PK"), "a zip archive");
    // What VS Code loads and nothing else: the manifest, the bundled client (which holds
    // the language client library), the grammar, the README and the licence.
    let mut members = zip_members(&bytes);
    members.sort();
    assert_eq!(
        members,
        [
            "[Content_Types].xml",
            "extension.vsixmanifest",
            "extension/LICENSE.txt",
            "extension/dist/extension.js",
            "extension/language-configuration.json",
            "extension/package.json",
            "extension/readme.md",
            "extension/syntaxes/rotlang.tmLanguage.json",
        ]
    );
    let has = |name: &str| bytes.windows(name.len()).any(|w| w == name.as_bytes());
    assert!(!has(".gitignore"));
    eprintln!("packaged {}", vsix.display());
}

/// The extension for real, in code-server driven by Chromium (`editors/vscode/e2e`). The
/// install (code-server 4.99.4, the last for Node 20, from npm with its native modules
/// built by node-gyp against Debian's Node headers) is locked and done once; a run takes
/// about half a minute.
#[test]
fn vscode_extension_end_to_end_in_code_server() {
    let root = root();
    let ext = root.join("editors/vscode");
    let e2e = ext.join("e2e");
    let work = target().join("vscode-e2e");
    // @vscode/ripgrep's install script downloads rg from GitHub unless its cache holds
    // the archive: Debian's ripgrep fills it. Native modules build against Debian's Node
    // headers (kerberos needs libkrb5-dev).
    let tmp = work.join("tmp");
    let prepared = node_20()
        .and_then(|()| ensure(&["npm-ci", &ext.to_string_lossy()], &[]))
        .and_then(|()| {
            ensure(
                &[
                    "apt",
                    "chromium",
                    "libkrb5-dev",
                    "ripgrep",
                    "make",
                    "g++",
                    "python3",
                ],
                &[],
            )
        })
        .and_then(|()| ripgrep_cache(&tmp))
        .and_then(|()| {
            ensure(
                &["npm-ci", &e2e.to_string_lossy()],
                &[
                    ("TMPDIR", &tmp),
                    ("npm_config_nodedir", Path::new("/usr")),
                    ("npm_config_yes", Path::new("true")),
                    // code-server's install script refuses root without it.
                    ("npm_config_unsafe_perm", Path::new("true")),
                ],
            )
        });
    if let Err(why) = prepared {
        return skip(&why);
    }
    let vsix = work.join("rotlang.vsix");
    std::fs::create_dir_all(&work).expect("target/vscode-e2e");
    package(&vsix);
    let run = work.join("run");
    let output = Command::new("node")
        .args(["--test", "--test-concurrency=1", "e2e.test.js"])
        .current_dir(&e2e)
        .env("ROTLANG_LSP", env!("CARGO_BIN_EXE_rotlang-lsp"))
        .env("ROTLANG_VSIX", &vsix)
        .env("ROTLANG_E2E_DIR", &run)
        .stdin(Stdio::null())
        .output()
        .expect("run node --test e2e.test.js");
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success() && report.contains("# pass 3") && report.contains("# fail 0"),
        "code-server end-to-end tests failed (screenshots in {}):\n{report}\n{}",
        run.join("screenshots").display(),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(run.join("screenshots/rot.png").is_file());
}

/// Fills @vscode/ripgrep's download cache in `tmp` with Debian's `rg`, as the archive its
/// install script would download (`ripgrep-<version>-<target>.tar.gz` holding `rg`).
fn ripgrep_cache(tmp: &Path) -> Result<(), String> {
    // The versions code-server 4.99.4 locks (lib/vscode/npm-shrinkwrap.json): package
    // 1.15.11 downloads ripgrep v13.0.0-10.
    let target = match std::env::consts::ARCH {
        "x86_64" => "x86_64-unknown-linux-musl",
        "aarch64" => "aarch64-unknown-linux-musl",
        other => return Err(format!("no ripgrep build is known for {other}")),
    };
    let cache = tmp.join("vscode-ripgrep-cache-1.15.11");
    let archive = cache.join(format!("ripgrep-v13.0.0-10-{target}.tar.gz"));
    if archive.is_file() {
        return Ok(());
    }
    let rg = Path::new("/usr/bin/rg");
    if !rg.is_file() {
        return Err("Debian's ripgrep is not installed".into());
    }
    let staging = tmp.join("rg-staging");
    std::fs::create_dir_all(&staging).expect("ripgrep staging folder");
    std::fs::create_dir_all(&cache).expect("ripgrep cache folder");
    std::fs::copy(rg, staging.join("rg")).expect("copy rg");
    let status = Command::new("tar")
        .arg("czf")
        .arg(&archive)
        .arg("-C")
        .arg(&staging)
        .arg("rg")
        .status()
        .expect("run tar");
    assert!(status.success(), "tar failed: {status}");
    Ok(())
}
