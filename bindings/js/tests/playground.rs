//! The playground (`web/`) in a real browser: `npm ci` and `npm run build` (the wasm, then
//! Vite) as a user would, then `web/test/*.test.js` drives Debian's Chromium through
//! playwright-core against `web/dist` served on 127.0.0.1. Screenshots are kept in
//! `target/playground/`.

mod common;

use common::*;

#[test]
fn playground_works_in_chromium() {
    let web = root().join("web");
    if !ensure(&["rust-target", "wasm32-unknown-unknown"])
        || !ensure(&["npm-ci", &web.to_string_lossy()])
        || !ensure(&["apt", "chromium"])
    {
        return;
    }
    let vite = web.join("node_modules/vite/bin/vite.js");
    node(&web, &["../bindings/js/build.mjs"], &[]);
    node(
        &web,
        &[&vite.to_string_lossy(), "build", "--logLevel", "warn"],
        &[],
    );
    assert!(web.join("dist/index.html").is_file());
    let artifacts = target_dir().join("playground");
    let files = test_files(&web.join("test"));
    assert!(!files.is_empty());
    let mut args = vec!["--test", "--test-concurrency=1"];
    args.extend(files.iter().map(String::as_str));
    let stdout = node(&web, &args, &[("ROTLANG_ARTIFACTS", &artifacts)]);
    assert!(stdout.contains("# fail 0"), "no test failed");
    assert!(artifacts.join("playground.png").is_file());
}
