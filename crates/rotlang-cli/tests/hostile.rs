//! Hostile input: megabyte templates, NUL bytes, characters outside ASCII and outside the
//! BMP, absurd numbers. Whatever the input: no panic, at most 101 diagnostics (100 and one
//! "N more not shown"), every span within the text and on char boundaries, and a report
//! whose size does not grow with the input. No timing here (benches/ measures speed).
//!
//! A megabyte of short instructions (`+1, ` × 262 144) takes seconds to parse in a debug
//! build, so those inputs are parsed once (sparse target) and each has its own test to
//! run in parallel; single-instruction megabytes are fast and get both targets.

use rotlang::{Parse, Span, Target};
use rotlang_cli::cli::{Input, render_human};

const MB: usize = 1 << 20;
/// `MAX_DIAGNOSTICS` (100) plus the one that counts the rest.
const CAP: usize = 101;

fn span_ok(text: &str, s: Span) -> bool {
    s.start <= s.end
        && s.end <= text.len()
        && text.is_char_boundary(s.start)
        && text.is_char_boundary(s.end)
}

/// Parses for both targets and checks the invariants; returns the sparse parse.
fn survive(name: &str, text: &str) -> Parse {
    survive_for(name, text, &[Target::Sparse, Target::Solid])
}

/// Parses once, for the sparse target: for inputs with many instructions.
fn survive_once(name: &str, text: &str) -> Parse {
    survive_for(name, text, &[Target::Sparse])
}

fn survive_for(name: &str, text: &str, targets: &[Target]) -> Parse {
    let mut sparse = None;
    for &target in targets {
        let parse = rotlang::parse(text, target);
        assert!(
            parse.diagnostics.len() <= CAP,
            "{name}: {} diagnostics",
            parse.diagnostics.len()
        );
        for d in &parse.diagnostics {
            for s in d
                .labels
                .iter()
                .map(|l| l.span)
                .chain(d.fix.iter().map(|f| f.span))
            {
                assert!(
                    span_ok(text, s),
                    "{name}: {} has span {s:?} (text is {} bytes)",
                    d.code,
                    text.len()
                );
            }
        }
        for ins in &parse.template.instructions {
            assert!(
                span_ok(text, ins.span),
                "{name}: instruction span {:?}",
                ins.span
            );
        }
        sparse.get_or_insert(parse);
    }
    sparse.unwrap()
}

/// Like `survive`, and the template must have an error with a non-empty primary span.
fn rejected(name: &str, text: &str) -> Parse {
    has_error(name, survive(name, text))
}

fn rejected_once(name: &str, text: &str) -> Parse {
    has_error(name, survive_once(name, text))
}

fn has_error(name: &str, parse: Parse) -> Parse {
    let first = parse.diagnostics.iter().find(|d| d.is_error());
    let first = first.unwrap_or_else(|| panic!("{name}: no error"));
    assert!(
        !first.primary_span().is_empty(),
        "{name}: empty primary span for {}",
        first.code
    );
    parse
}

fn codes(parse: &Parse) -> Vec<&'static str> {
    let mut c: Vec<_> = parse.diagnostics.iter().map(|d| d.code).collect();
    c.dedup();
    c
}

/// `s` repeated to at least `len` bytes.
fn repeat_to(s: &str, len: usize) -> String {
    s.repeat(len.div_ceil(s.len()))
}

/// Deterministic pseudo-random bytes (no dependency; the same every run).
fn noise(len: usize, mut seed: u64) -> Vec<u8> {
    (0..len)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 56) as u8
        })
        .collect()
}

// ── one megabyte ────────────────────────────────────────────────────────────────────────

#[test]
fn megabyte_of_valid_instructions() {
    let text = repeat_to("+1, ", MB);
    let parse = survive_once("+1, ×1M", &text);
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
    assert_eq!(parse.template.instructions.len(), text.len() / 4);
    let formatted = rotlang::format::canonical(&text, &parse.template);
    assert_eq!(
        formatted.len(),
        text.len() - 2,
        "only the trailing `, ` goes"
    );
}

#[test]
fn megabyte_of_mixed_valid_instructions() {
    let text = repeat_to("+10L25%, -10l25%\n#14 +15R\tB!, 240M3, +30/1cm, ST, ", MB);
    let parse = survive_once("doc mix ×1M", &text);
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
}

#[test]
fn megabyte_of_random_bytes() {
    let text = String::from_utf8_lossy(&noise(MB, 1)).into_owned();
    survive_once("noise", &text);
}

#[test]
fn megabyte_of_language_characters_in_random_order() {
    let alphabet = b"0123456789.+-*!:%/NnZz$LlUuQq~^|#DSOMRBTmc'\"e ,";
    let text: String = noise(MB, 7)
        .iter()
        .map(|b| alphabet[*b as usize % alphabet.len()] as char)
        .collect();
    survive_once("soup", &text);
}

#[test]
fn one_megabyte_number() {
    let digits = "9".repeat(MB);
    let parse = rejected("1 MB angle", &digits);
    assert!(
        codes(&parse)
            .iter()
            .any(|c| c.starts_with("rotlang::number")),
        "{:?}",
        codes(&parse)
    );
    rejected("1 MB count", &format!("+30/{digits}"));
    rejected("1 MB repeat", &format!("+30*{digits}"));
    rejected("1 MB length", &format!("+30/{digits}mm"));
    rejected("1 MB fraction", &format!("{digits}:{digits}"));
    // A long fraction part is an ordinary number.
    let parse = survive("0.999…", &format!("0.{digits}"));
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
}

#[test]
fn megabyte_of_one_letter() {
    // (`!` and `*` are in `megabyte_of_repeated_marks`.)
    for c in [
        "X", "B", "M", "m", "e", "/", "#", "%", "-", "+", ".", ":", "'",
    ] {
        survive(c, &c.repeat(MB));
    }
    rejected("X×1M", &"X".repeat(MB));
}

#[test]
fn megabyte_of_separators() {
    for sep in [",", " ", "\n", "\r\n", ", ", "\t,"] {
        let parse = survive_once(sep, &repeat_to(sep, MB));
        assert!(!parse.has_errors(), "{sep:?}: {:?}", codes(&parse));
        assert!(parse.template.instructions.is_empty());
    }
}

#[test]
fn megabyte_of_errors_is_capped() {
    let parse = rejected_once("X, ×1M", &repeat_to("X, ", MB));
    assert_eq!(parse.diagnostics.len(), CAP);
    assert_eq!(
        parse.diagnostics.last().unwrap().code,
        "rotlang::too-many-diagnostics"
    );
}

#[test]
fn megabyte_of_warnings_is_capped() {
    let parse = survive_once("400, ×1M", &repeat_to("400, ", MB));
    assert_eq!(parse.diagnostics.len(), CAP, "warnings are capped too");
    assert!(!parse.has_errors());
}

#[test]
fn megabyte_single_instructions() {
    rejected("+30/5/5/5…", &format!("+30{}", repeat_to("/5", MB)));
}

#[test]
fn megabyte_of_repeated_marks() {
    // One instruction with a million `!` (or `*`): a million duplicate-mark warnings, capped.
    let parse = survive_once("+30!!!…", &format!("+30{}", "!".repeat(MB)));
    assert_eq!(parse.diagnostics.len(), CAP);
    survive_once("+30***…", &format!("+30{}", "*".repeat(MB)));
    rejected("+30*2*2*2…", &format!("+30{}", repeat_to("*2", MB)));
    rejected("+30/5mmmm…", &format!("+30/5{}", "m".repeat(MB)));
    rejected("-----…30", &format!("{}30", "-".repeat(MB)));
}

/// The terminal report shows a window of a long line, not the whole line under each
/// diagnostic.
fn report_stays_small(name: &str, text: &str) {
    let parse = survive_once(name, text);
    let input = Input {
        name: name.into(),
        text: text.to_owned(),
        path: None,
    };
    let report = render_human(&[(&input, &parse.diagnostics)], false);
    assert!(
        report.len() < 256 * 1024,
        "{name}: a {} byte report",
        report.len()
    );
}

#[test]
fn megabyte_report_of_many_errors_stays_small() {
    report_stays_small("X, ×1M", &repeat_to("X, ", MB));
}

#[test]
fn megabyte_report_of_noise_stays_small() {
    report_stays_small("noise", &String::from_utf8_lossy(&noise(MB, 9)));
}

#[test]
fn megabyte_report_of_one_long_span_stays_small() {
    report_stays_small("1 MB number", &"9".repeat(MB));
}

// ── characters ──────────────────────────────────────────────────────────────────────────

#[test]
fn nul_bytes() {
    rejected("NUL", "\0");
    rejected("+30 NUL", "+30\0, 90");
    rejected("NUL in unit", "+30/5m\0m");
    rejected("NUL×1M", &"\0".repeat(MB));
}

#[test]
fn megabyte_of_nul_instructions() {
    rejected_once("NUL, ×1M", &repeat_to("\0, ", MB));
}

#[test]
fn characters_outside_ascii() {
    for c in [
        "°", "ℕ", "α", "𝕏", "\u{feff}", "\u{200b}", "\u{fffd}", "é", "\u{301}", "🙂",
    ] {
        if c == "\u{feff}" {
            // A byte-order mark at the start of a file is skipped (editors write one);
            // anywhere else it is an error.
            assert!(!survive(c, c).has_errors());
            assert!(!survive(c, &format!("{c}, +10")).has_errors());
            rejected("+10, {c}", &format!("+10, {c}"));
        } else {
            rejected(c, c);
            rejected(&format!("{c}, +10"), &format!("{c}, +10"));
        }
        rejected(&format!("+30{c}"), &format!("+30{c}"));
        rejected(&format!("+30/{c}5"), &format!("+30/{c}5"));
        rejected(&format!("+10/5{c}%"), &format!("+10/5{c}%"));
        rejected(&format!("{c}×1M"), &c.repeat(MB / c.len()));
        rejected(
            &format!("+30/{c}×1M"),
            &format!("+30/{}", c.repeat(MB / c.len())),
        );
    }
    let parse = rejected("mixed", "+30°, ℕ, α1, 𝕏 +10/5𝕏");
    let first = parse.diagnostics[0].primary_span();
    assert_eq!(&"+30°, ℕ, α1, 𝕏 +10/5𝕏"[first.range()], "°");
}

#[test]
fn megabyte_of_two_byte_instructions() {
    rejected_once("α, ×1M", &repeat_to("α, ", MB));
}

#[test]
fn megabyte_of_astral_instructions() {
    rejected_once("𝕏1, ×1M", &repeat_to("𝕏1, ", MB));
}

#[test]
fn characters_that_look_like_the_language() {
    // Full-width digits and signs, the Unicode minus, superscripts: errors, not angles.
    for t in ["３０", "＋30", "+30/−5", "+³⁰", "+30⁄5", "٣٠"] {
        rejected(t, t);
    }
}

// ── numbers ─────────────────────────────────────────────────────────────────────────────

#[test]
fn huge_numbers_and_counts() {
    let big = "9".repeat(400);
    let zeros = "0".repeat(400);
    for t in [
        "1e999".to_owned(),
        "+1e999".to_owned(),
        "+30/1e999".to_owned(),
        "+30/1e999mm".to_owned(),
        "1e999%".to_owned(),
        "1:1e999".to_owned(),
        "1e999:1".to_owned(),
        big.clone(),
        format!("+{big}"),
        format!("+30/{big}"),
        format!("+30*{big}"),
        format!("+30/{big}:{big}"),
        format!("{big}:{big}"),
        format!("1:{zeros}"),
        format!("+30/1:{zeros}"),
        "+30*1000000001".to_owned(),
        "+30/1000000001".to_owned(),
        "+1/1e10".to_owned(),
        "+30*99999999999999999999999".to_owned(),
        "+inf".to_owned(),
        "+30/NaN".to_owned(),
    ] {
        rejected(&t, &t);
    }
    // At the limit: accepted, whatever the evaluator makes of it.
    for t in [
        "+30*1000000000",
        "+1/1e9",
        "*1000000000",
        "+30/1000000000mm",
        &format!("0.{zeros}1"),
    ] {
        let parse = survive(t, t);
        assert!(!parse.has_errors(), "{t}: {:?}", codes(&parse));
    }
}

/// Hostile profiles, presets and projects (issue 22, "what held"): each is an error for
/// the file or a profile whose spans stay in its text, never a panic, a hang or an
/// unbounded allocation. The archive cases that need a zip writer are in
/// `tests/profiles.rs` too (bombs, 10,001 entries, lying sizes, truncated archives).
mod profiles {
    use std::io::Write;
    use std::path::{Path, PathBuf};

    use rotlang::Target;
    use rotlang_profile::profile::{self, Profile};

    /// Parsed, and every template and note span inside its source.
    fn read(name: &str, bytes: &[u8]) -> Result<Profile, String> {
        let p = profile::parse(Path::new(name), bytes).map_err(|e| e.message)?;
        for f in &p.templates {
            let text = &p.sources[f.source].text;
            let span = f.span_in_source(rotlang::Span::new(0, f.text.len()));
            assert!(text.get(span.range()).is_some(), "{name}: {span:?}");
        }
        for n in &p.notes {
            assert!(
                p.sources[n.source].text.get(n.span.range()).is_some(),
                "{name}"
            );
        }
        let m = p.model(Target::Sparse, None, 20.0);
        assert!(
            !m.model.is_empty() && m.direction.degrees.is_finite(),
            "{name}"
        );
        Ok(p)
    }

    /// A zip of `entries`; `encrypted` marks every entry encrypted (the flag bit in the
    /// local and central headers: what a reader goes by).
    fn zip_of(entries: &[(&str, &[u8])], encrypted: bool) -> Vec<u8> {
        let mut out = std::io::Cursor::new(Vec::new());
        {
            let mut z = zip::ZipWriter::new(&mut out);
            let options = zip::write::SimpleFileOptions::default()
                .compression_method(zip::CompressionMethod::Stored);
            for (name, bytes) in entries {
                z.start_file(*name, options).unwrap();
                z.write_all(bytes).unwrap();
            }
            z.finish().unwrap();
        }
        let mut bytes = out.into_inner();
        if encrypted {
            for (sig, flags) in [(b"PK\x03\x04", 6), (b"PK\x01\x02", 8)] {
                let at = bytes.windows(4).position(|w| w == sig).unwrap();
                bytes[at + flags] |= 1;
            }
        }
        bytes
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("rotlang-hostile-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn json_a_million_deep_and_a_million_keys() {
        let deep = format!(
            "{{\"a\": {}{}, \"sparse_infill_rotate_template\": \"0, 90\"}}",
            "[".repeat(1_000_000),
            "]".repeat(1_000_000)
        );
        let p = read("deep.json", deep.as_bytes()).unwrap();
        // Valid JSON, read without recursion (no stack overflow): the template after it
        // is the preset's.
        assert_eq!(p.templates.len(), 1);
        let keys: String = (0..1_000_000).map(|i| format!("\"k{i}\": {i}, ")).collect();
        let many = format!("{{{keys}\"layer_height\": \"0.1\"}}");
        let p = read("keys.json", many.as_bytes()).unwrap();
        assert_eq!(p.settings.values["layer_height"].value, "0.1");
    }

    #[test]
    fn files_over_the_limit_are_refused_unread() {
        let dir = scratch("big");
        let huge = dir.join("line.json");
        std::fs::File::create(&huge)
            .unwrap()
            .set_len(100 << 20)
            .unwrap();
        let e = profile::read(&huge).unwrap_err();
        assert!(e.message.contains("larger than 64 MiB"), "{e}");
        // An endless device is read only to the limit.
        let e = profile::read(Path::new("/dev/zero")).unwrap_err();
        assert!(e.message.contains("larger than 64 MiB"), "{e}");
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn bad_text_and_bad_numbers() {
        assert!(read("latin1.json", b"{\"layer_height\": \"\xb0\"}").is_err());
        let p = read(
            "nul.json",
            b"{\"sparse_infill_rotate_template\": \"0\x00, \\u0000, \\ud800, \\udfff\\ud800x\"}",
        )
        .unwrap();
        assert_eq!(p.templates[0].text, "0\0, \0, \u{fffd}, \u{fffd}\u{fffd}x");
        for value in ["1e99999", "-1e99999", "NaN", "1e-320", "0", "-0.2"] {
            let doc = format!(
                "{{\"layer_height\": \"{value}\", \"initial_layer_print_height\": {value}, \"sparse_infill_direction\": \"{value}\", \"sparse_infill_rotate_template\": \"0\"}}"
            );
            let p = read("n.json", doc.as_bytes()).unwrap();
            let m = p.model(Target::Sparse, None, 20.0);
            assert!(m.model.layer_height().is_finite() && m.model.layer_height() > 0.0);
            assert!(!m.notes.is_empty(), "{value}");
        }
    }

    #[test]
    fn inherits_cycles_and_paths_outside_the_folder() {
        let dir = scratch("inherits");
        let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
        write(
            "a.json",
            r#"{"inherits": "b", "sparse_infill_rotate_template": "0"}"#,
        );
        write("b.json", r#"{"inherits": "a", "layer_height": "0.1"}"#);
        write("self.json", r#"{"inherits": "self"}"#);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        write("secret.json", r#"{"layer_height": "0.3"}"#);
        write(
            "sub/out.json",
            r#"{"inherits": "../secret", "sparse_infill_rotate_template": "0"}"#,
        );
        let a = profile::read(&dir.join("a.json")).unwrap();
        assert_eq!(a.settings.values["layer_height"].value, "0.1");
        assert!(profile::read(&dir.join("self.json")).is_ok());
        let out = profile::read(&dir.join("sub/out.json")).unwrap();
        assert!(!out.settings.values.contains_key("layer_height"));
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn encrypted_entries_and_zips_in_zips() {
        let settings = br#"{"sparse_infill_rotate_template": "0"}"#;
        let locked = zip_of(
            &[("Metadata/project_settings.config", settings.as_slice())],
            true,
        );
        let e = read("locked.3mf", &locked).unwrap_err();
        assert!(e.contains("Metadata/project_settings.config"), "{e}");
        let inner = zip_of(
            &[("Metadata/project_settings.config", settings.as_slice())],
            false,
        );
        let nested = zip_of(
            &[("Metadata/project_settings.config", inner.as_slice())],
            false,
        );
        let e = read("nested.3mf", &nested).unwrap_err();
        assert!(e.contains("not UTF-8"), "{e}");
        // A project inside a project is one entry among others, not opened.
        let outer = zip_of(
            &[
                ("inner.3mf", inner.as_slice()),
                ("Metadata/project_settings.config", b"{}".as_slice()),
            ],
            false,
        );
        assert!(read("outer.3mf", &outer).unwrap().templates.is_empty());
    }

    fn model(xml: &str) -> Result<Profile, String> {
        read(
            "m.3mf",
            &zip_of(&[("Metadata/model_settings.config", xml.as_bytes())], false),
        )
    }

    #[test]
    fn entities_are_never_expanded() {
        let mut laughs =
            String::from("<?xml version=\"1.0\"?><!DOCTYPE config [<!ENTITY lol \"lol\">");
        for i in 1..10 {
            let prev = if i == 1 {
                "lol".to_owned()
            } else {
                format!("lol{}", i - 1)
            };
            laughs.push_str(&format!(
                "<!ENTITY lol{i} \"{}\">",
                format!("&{prev};").repeat(10)
            ));
        }
        laughs.push_str(
            "<!ENTITY xxe SYSTEM \"file:///etc/passwd\">]><config><object id=\"1\">\
             <metadata key=\"sparse_infill_rotate_template\" value=\"&lol9;&xxe;\"/>\
             </object></config>",
        );
        // An entity the reader does not know stays as written: no expansion, no file read.
        match model(&laughs) {
            Ok(p) => assert_eq!(p.templates[0].text, "&lol9;&xxe;"),
            Err(e) => assert!(e.contains("XML"), "{e}"),
        }
    }

    #[test]
    fn a_million_nested_elements() {
        let n = 1_000_000;
        let closed = format!("<config>{}{}</config>", "<a>".repeat(n), "</a>".repeat(n));
        assert!(model(&closed).unwrap().templates.is_empty());
        let open = format!("<config>{}", "<a>".repeat(n));
        let e = model(&open).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
    }

    /// A folder with a symbolic link to itself and a FIFO named like a preset: read, not
    /// followed round the loop, the FIFO never opened (it would block).
    #[cfg(unix)]
    #[test]
    fn symlink_loops_and_fifos_in_folders() {
        let dir = scratch("folder");
        std::os::unix::fs::symlink(&dir, dir.join("loop")).unwrap();
        std::os::unix::fs::symlink(dir.join("nowhere"), dir.join("dangling.json")).unwrap();
        let fifo = std::ffi::CString::new(dir.join("fifo.json").to_str().unwrap()).unwrap();
        // SAFETY: a valid C string; mkfifo only creates the node.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
        std::os::unix::fs::symlink(dir.join("fifo.json"), dir.join("to-fifo.json")).unwrap();
        std::fs::write(
            dir.join("p.json"),
            r#"{"sparse_infill_rotate_template": "0"}"#,
        )
        .unwrap();
        let (files, errors) = profile::files_under(&dir);
        assert_eq!(files, [dir.join("p.json")]);
        assert!(errors.is_empty(), "{errors:?}");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_rotlang"))
            .arg("check")
            .arg(&dir)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0));
        let _ = std::fs::remove_dir_all(dir);
    }
}
