//! The VS Code extension declares every setting the server reads (so VS Code shows them),
//! with the server's defaults and ranges, and nothing the server would reject: the two
//! cannot drift apart.

use rotlang_lsp::settings::{KEYS, ModelSettings};
use serde_json::{Map, Value};

/// The extension's own settings: read by the client, ignored by the server.
const CLIENT_KEYS: [&str; 2] = ["server.path", "trace.server"];

fn declared() -> Map<String, Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../editors/vscode/package.json"
    );
    let text = std::fs::read_to_string(path).expect("editors/vscode/package.json");
    let manifest: Value = serde_json::from_str(&text).expect("package.json is JSON");
    manifest["contributes"]["configuration"]["properties"]
        .as_object()
        .expect("contributes.configuration.properties")
        .iter()
        .map(|(k, v)| {
            let key = k.strip_prefix("rotlang.").unwrap_or_else(|| {
                panic!("{k}: every setting of the extension is under `rotlang.`")
            });
            (key.to_owned(), v.clone())
        })
        .collect()
}

#[test]
fn package_json_declares_exactly_the_server_settings() {
    let declared = declared();
    let mut server: Vec<&str> = KEYS.to_vec();
    server.extend(CLIENT_KEYS);
    server.sort_unstable();
    let mut in_manifest: Vec<&str> = declared.keys().map(String::as_str).collect();
    in_manifest.sort_unstable();
    assert_eq!(
        in_manifest, server,
        "package.json's rotlang.* settings against settings::KEYS and the client's own"
    );
    // `rotlang.trace.server` is the standard client trace setting (vscode-languageclient
    // reads `<id>.trace.server` for the client id `rotlang`).
    assert_eq!(
        declared["trace.server"]["enum"],
        serde_json::json!(["off", "messages", "verbose"])
    );
}

/// The declared defaults, sent as VS Code sends the section (dotted keys nested), are
/// accepted by the server as they are and are its own defaults.
#[test]
fn package_json_defaults_are_the_server_defaults() {
    let mut section = Map::new();
    for (key, spec) in declared() {
        let default = spec
            .get("default")
            .unwrap_or_else(|| panic!("rotlang.{key} has a default"))
            .clone();
        match key.split_once('.') {
            Some((outer, inner)) => {
                let entry = section
                    .entry(outer.to_owned())
                    .or_insert_with(|| Value::Object(Map::new()));
                entry
                    .as_object_mut()
                    .unwrap()
                    .insert(inner.to_owned(), default);
            }
            None => {
                section.insert(key, default);
            }
        }
    }
    // Changed first: the defaults must come from the section, not be left over.
    let mut settings = ModelSettings {
        layers: 7,
        ..ModelSettings::default()
    };
    let rejected = settings.replace(&Value::Object(section));
    assert!(rejected.is_empty(), "{rejected:?}");
    assert_eq!(settings, ModelSettings::default());
    // The declared ranges are the server's: one past either end is rejected.
    for (key, spec) in declared() {
        for (bound, step) in [("minimum", -1.0), ("maximum", 1.0)] {
            let Some(edge) = spec.get(bound).and_then(Value::as_f64) else {
                continue;
            };
            let step = if spec["type"] == "integer" {
                step
            } else {
                step * edge.abs().max(1.0) * 1e-3
            };
            let mut s = ModelSettings::default();
            let inside = s.replace(&serde_json::json!({ key.as_str(): edge }));
            assert!(inside.is_empty(), "rotlang.{key} = {edge}: {inside:?}");
            let outside = s.replace(&serde_json::json!({ key.as_str(): edge + step }));
            assert_eq!(outside.len(), 1, "rotlang.{key} = {}", edge + step);
        }
    }
}

/// The extension's README documents every setting the extension declares (it listed 6 of
/// 9), and says how to install the `.vsix`.
#[test]
fn the_extension_readme_lists_every_setting() {
    let readme = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../editors/vscode/README.md"
    ))
    .expect("editors/vscode/README.md");
    let rows: Vec<&str> = readme
        .lines()
        .filter_map(|l| l.strip_prefix("| `rotlang."))
        .filter_map(|l| l.split('`').next())
        .collect();
    let mut declared: Vec<String> = declared().keys().cloned().collect();
    declared.sort();
    let mut listed: Vec<String> = rows.iter().map(|s| s.to_string()).collect();
    listed.sort();
    assert_eq!(listed, declared, "the README's settings table");
    assert!(readme.contains("code --install-extension target/rotlang.vsix"));
}
