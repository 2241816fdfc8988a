use super::*;

fn graph(edges: &[(&str, &str)]) -> Graph {
    let mut g = Graph::new();
    for (a, b) in edges {
        g.entry(a.to_string()).or_default().insert(b.to_string());
    }
    g
}

#[test]
fn a_cycle_is_found_and_a_chain_is_not() {
    let chain = graph(&[("a", "b"), ("b", "c"), ("a", "c")]);
    assert!(cycles(&chain).is_empty());
    let looped = graph(&[
        ("a", "b"),
        ("b", "c"),
        ("c", "a"),
        ("c", "d"),
        ("d", "e"),
        ("e", "d"),
    ]);
    assert_eq!(
        cycles(&looped),
        [vec!["a", "b", "c"], vec!["d", "e"]]
            .map(|c| c.into_iter().map(String::from).collect::<Vec<_>>())
    );
    // A file naming itself is not a cycle.
    assert!(cycles(&graph(&[("a", "a")])).is_empty());
}

#[test]
fn a_long_chain_does_not_overflow_the_stack() {
    let names: Vec<String> = (0..100_000).map(|i| format!("n{i}")).collect();
    let mut g = Graph::new();
    for w in names.windows(2) {
        g.entry(w[0].clone()).or_default().insert(w[1].clone());
    }
    assert!(cycles(&g).is_empty());
    g.entry(names[99_999].clone())
        .or_default()
        .insert(names[0].clone());
    assert_eq!(cycles(&g)[0].len(), 100_000);
}

/// A crate written to a scratch folder: (path under src/, text).
fn scratch(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rotlang-cycles-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

fn crate_cycles(name: &str, files: &[(&str, &str)]) -> Vec<Vec<String>> {
    let dir = scratch(name, files);
    let found = cycles(&crate_graph(&dir).unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
    found
}

#[test]
fn modules_that_use_each_other_are_a_cycle() {
    // As `lint` ↔ `syntax` once were: each names an item of the other.
    let found = crate_cycles(
        "pair",
        &[
            ("lib.rs", "mod lint;\nmod syntax;\n"),
            ("lint.rs", "use crate::syntax::Sink;\npub fn lint() {}\n"),
            (
                "syntax/mod.rs",
                "pub struct Sink;\nfn parse() { crate::lint::lint() }\n",
            ),
        ],
    );
    assert_eq!(
        found,
        [vec!["lint.rs".to_string(), "syntax/mod.rs".to_string()]]
    );
}

#[test]
fn a_cycle_through_a_re_export_is_found() {
    // As `infill` curves ↔ region: `super::Region` is re-exported from region.rs.
    let found = crate_cycles(
        "reexport",
        &[
            ("lib.rs", "pub mod infill;\n"),
            (
                "infill/mod.rs",
                "mod curves;\nmod region;\npub use region::Region;\npub struct Error;\n",
            ),
            (
                "infill/curves.rs",
                "use super::Region;\npub(crate) fn spiral(r: &Region) {}\n",
            ),
            (
                "infill/region.rs",
                "use super::{Error, curves};\npub struct Region;\nfn fill() { curves::spiral(&Region) }\n",
            ),
        ],
    );
    assert_eq!(
        found,
        [vec![
            "infill/curves.rs".to_string(),
            "infill/region.rs".to_string()
        ]]
    );
}

#[test]
fn a_facade_and_inline_tests_are_not_cycles() {
    let found = crate_cycles(
        "facade",
        &[
            (
                "lib.rs",
                "//! Docs naming crate::a::A in a comment.\nmod a;\nmod b;\npub use a::A;\npub use b::B;\n\
                 const S: &str = \"crate::b::B\";\n#[cfg(test)]\nmod tests {\n    use super::*;\n    use crate::b::B;\n}\n",
            ),
            ("a.rs", "pub struct A;\nuse crate::B;\n"),
            ("b.rs", "pub struct B;\nfn f() -> char { '{' }\n"),
        ],
    );
    assert!(found.is_empty(), "{found:?}");
}

#[test]
fn a_missing_module_file_is_an_error() {
    let dir = scratch("missing", &[("lib.rs", "mod gone;\n")]);
    let err = crate_graph(&dir).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(err.contains("mod gone"), "{err}");
}

#[test]
fn strings_comments_and_raw_strings_are_skipped() {
    let toks = tokenize("a /* b /* c */ d */ e // f\n r#\"g\"h\"# 'i' '\\n' 'j x \"k\\\"l\" m");
    let words: Vec<_> = toks
        .iter()
        .filter_map(|t| match t {
            Tok::Ident(w) => Some(w.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(words, ["a", "e", "x", "m"]);
}

#[test]
fn a_glob_re_export_leads_to_the_module_that_has_the_name() {
    // `pub use ir::*` at the root: `crate::Template` is ir.rs's, not lib.rs's; a glob of
    // another crate (`use other::*`) is outside, no edge.
    let files = [
        (
            "lib.rs",
            "use other::*;\nmod ir;\nmod syntax;\npub use ir::*;\npub fn parse() { syntax::run() }\n",
        ),
        ("ir.rs", "pub struct Template;\n"),
        (
            "syntax/mod.rs",
            "use crate::Template;\nuse crate::Outside;\npub fn run() {}\n",
        ),
    ];
    let dir = scratch("glob", &files);
    let graph = crate_graph(&dir).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        graph["syntax/mod.rs"].iter().collect::<Vec<_>>(),
        ["ir.rs"],
        "{graph:?}"
    );
    assert!(cycles(&graph).is_empty());
}

#[test]
fn path_attributes_are_followed_as_rustc_reads_them() {
    let files = [
        (
            "lib.rs",
            "#[path = \"other/thing.rs\"]\nmod thing;\nmod a;\nmod outer {\n    #[path = \"deep.rs\"]\n    mod d;\n}\n",
        ),
        // From a non-mod-rs file, relative to its folder; stacked attributes.
        (
            "a.rs",
            "pub struct A;\nfn f() { crate::thing::g() }\n#[cfg(test)]\n#[path = \"a_tests.rs\"]\nmod tests;\n",
        ),
        ("a_tests.rs", "use crate::outer::D;\n"),
        // A #[path] file's children are its siblings; `..` climbs back to src/.
        (
            "other/thing.rs",
            "mod inner;\n#[path = \"../up.rs\"]\nmod up;\nuse crate::a::A;\npub fn g() {}\n",
        ),
        ("other/inner.rs", "pub struct I;\n"),
        ("up.rs", "use crate::thing::inner::I;\n"),
        // Inside an inline module: relative to that module's folder.
        ("outer/deep.rs", "pub struct D;\n"),
    ];
    let dir = scratch("path", &files);
    let graph = crate_graph(&dir).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let read: Vec<&str> = graph.keys().map(String::as_str).collect();
    assert_eq!(
        read,
        [
            "a.rs",
            "a_tests.rs",
            "lib.rs",
            "other/inner.rs",
            "other/thing.rs",
            "outer/deep.rs",
            "up.rs"
        ],
        "{graph:?}"
    );
    assert_eq!(
        graph["up.rs"].iter().collect::<Vec<_>>(),
        ["other/inner.rs"]
    );
    assert_eq!(graph["a_tests.rs"].iter().collect::<Vec<_>>(), ["lib.rs"]);
    assert_eq!(
        cycles(&graph),
        [vec!["a.rs".to_string(), "other/thing.rs".to_string()]]
    );
}

#[test]
fn a_path_attribute_without_its_file_or_on_an_inline_module_is_an_error() {
    let dir = scratch(
        "path-missing",
        &[("lib.rs", "#[path = \"elsewhere/x.rs\"]\nmod x;\n")],
    );
    let err = crate_graph(&dir).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        err.contains("elsewhere/x.rs") && err.contains("mod x"),
        "{err}"
    );
    let dir = scratch(
        "path-inline",
        &[("lib.rs", "#[path = \"d\"]\nmod m {\n    mod n;\n}\n")],
    );
    let err = crate_graph(&dir).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(err.contains("inline `mod m`"), "{err}");
}

#[test]
fn string_literals_are_tokens_of_their_own() {
    let toks = tokenize("#[path = \"a/b.rs\"] r#\"c\"d\"# b\"e\"");
    let strings: Vec<_> = toks
        .iter()
        .filter_map(|t| match t {
            Tok::Str(s) => Some(s.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(strings, ["a/b.rs", "c\"d", "e"]);
}
