//! The bindings' readers, measured by running their language on a script: JavaScript's
//! `readProfile` (bindings/js, after `node build.mjs` there) and Python's `check` (the
//! package has no profile reader: a template is its only input), when the package is
//! installed in `ROTLANG_PYTHON` (a Python executable; the test suite's venv is
//! `target/python-venv`). Each returns the command to measure, or why it cannot run.

use std::path::Path;
use std::process::Command;

/// Reads the file named by argv[1] with `readProfile` (bytes, as a file input gives them)
/// and touches every template read.
const JS: &str = "
const { readFileSync } = await import('node:fs');
const { basename } = await import('node:path');
const { readProfile } = await import(process.env.ROTLANG_FULL_JS);
const file = process.argv[1];
const profile = readProfile(basename(file), readFileSync(file));
let n = 0;
for (const t of profile.templates) n += t.text.length;
if (n === 0) throw new Error('no template read');
";

/// `node` on the script above for `file`.
pub fn js(root: &Path, file: &Path) -> Result<Command, String> {
    let full = root.join("bindings/js/full.js");
    if !root.join("bindings/js/rotlang-full.wasm").exists() {
        return Err("bindings/js/rotlang-full.wasm not built (node bindings/js/build.mjs)".into());
    }
    let mut cmd = Command::new("node");
    cmd.args(["--input-type=module", "-e", JS])
        .arg(file)
        .env("ROTLANG_FULL_JS", format!("file://{}", full.display()));
    Ok(cmd)
}

/// `python` on `rotlang.check` of the template in `file`.
pub fn python(root: &Path, file: &Path) -> Result<Command, String> {
    let python = std::env::var_os("ROTLANG_PYTHON")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| root.join("target/python-venv/bin/python"));
    let installed = Command::new(&python)
        .args(["-c", "import rotlang"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !installed {
        return Err(format!(
            "no rotlang package in {} (ROTLANG_PYTHON names a Python that has it)",
            python.display()
        ));
    }
    let mut cmd = Command::new(python);
    cmd.args([
        "-c",
        "import sys, rotlang; rotlang.check(open(sys.argv[1], encoding='utf-8').read(), 'sparse')",
    ])
    .arg(file);
    Ok(cmd)
}
