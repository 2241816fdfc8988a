//! Peak memory of `rotlang check` on a long template in every kind of file (issue 22
//! item 1): at most 16× the file, as `check -f` keeps. A test binary of its own, so that
//! no other test's memory is in the measure (a child spawned by `vfork` inherits its
//! parent's peak RSS in `ru_maxrss`).
#![cfg(unix)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

fn zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut z = zip::ZipWriter::new(&mut out);
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated);
        for (name, bytes) in entries {
            z.start_file(*name, options).unwrap();
            z.write_all(bytes).unwrap();
        }
        z.finish().unwrap();
    }
    out.into_inner()
}

/// Peak resident memory of `rotlang ARGS` (stdin from `stdin`, if any), from `wait4`.
// Reaped by `wait4` below, which also gives the rusage `Child::wait` does not.
#[allow(clippy::zombie_processes)]
fn peak_rss(args: &[&str], stdin: Option<&Path>) -> u64 {
    use std::process::Stdio;
    let input = match stdin {
        Some(p) => Stdio::from(std::fs::File::open(p).unwrap()),
        None => Stdio::null(),
    };
    let child = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(args)
        .stdin(input)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: an all-zero rusage is valid; wait4 fills it for the child it reaps.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our child, not yet waited for; the pointers are to live locals.
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(reaped, pid);
    usage.ru_maxrss as u64 * 1024
}

/// Issue 22 item 1: a long template costs what `check -f` costs (at most 16× the file),
/// whichever way it is read: a profile, an `.ini`, a `.3mf`, a `.rot` named as a path,
/// stdin. (It cost ~44× in a profile, ~130× with errors: the IR was built for nothing.)
#[test]
fn a_long_template_costs_the_same_in_every_file() {
    let dir = std::env::temp_dir().join(format!("rotlang-memory-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = |name: &str, bytes: &[u8]| -> PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    let unit = "+10L25%, -10l25%, 0, 90, #5, +22.5/50%, X, ";
    let template = unit.repeat((2 << 20) / unit.len());
    let json = format!("{{\"sparse_infill_rotate_template\": \"{template}\"}}");
    let files = [
        file("long.json", json.as_bytes()),
        file(
            "long.jsonc",
            format!("// c\n{{\"sparse_infill_rotate_template\": \"{template}\",}}").as_bytes(),
        ),
        file(
            "long.ini",
            format!("sparse_infill_rotate_template = {template}\n").as_bytes(),
        ),
        file("long.rot", template.as_bytes()),
        file(
            "long.3mf",
            &zip_of(&[("Metadata/project_settings.config", json.as_bytes())]),
        ),
    ];
    for file in &files {
        let len = template.len() as u64;
        let path = file.display().to_string();
        for args in [
            vec!["check", &path],
            vec!["check", "--format", "json", &path],
        ] {
            let peak = peak_rss(&args, None);
            assert!(peak <= 16 * len, "{args:?}: {peak} bytes for {len}");
        }
    }
    let peak = peak_rss(&["check"], Some(&files[3]));
    assert!(peak <= 16 * template.len() as u64, "stdin: {peak}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22 item 1: the OrcaSlicer lint (`--compat orcaslicer`) on a long template, named
/// with `-f` and in a preset, keeps the bound too. It built the whole IR
/// and decoded every OrcaSlicer token up front: 50× the text on this template, 67× on
/// `0/5, 400, …` (short tokens), 137× on `0 0 0 …` (one piece of a million angles).
#[test]
fn the_orcaslicer_lint_costs_at_most_16_times_the_template() {
    let dir = std::env::temp_dir().join(format!("rotlang-memory-compat-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Templates without errors: the lint runs on those only.
    for (name, unit) in [
        ("templates", "+10L25%, -10l25%, 0, 90, #5, +22.5/50%, "),
        ("short", "0/5, 400, "),
        ("spaces", "0 "),
    ] {
        let template = unit.repeat((2 << 20) / unit.len());
        let len = template.len() as u64;
        let rot = dir.join(format!("{name}.rot"));
        std::fs::write(&rot, &template).unwrap();
        let json = dir.join(format!("{name}.json"));
        std::fs::write(
            &json,
            format!("{{\"sparse_infill_rotate_template\": \"{template}\"}}"),
        )
        .unwrap();
        let (rot, json) = (rot.display().to_string(), json.display().to_string());
        for args in [
            vec!["check", "--compat", "orcaslicer", "-f", &rot],
            vec!["check", "--compat", "orcaslicer", &json],
        ] {
            let peak = peak_rss(&args, None);
            assert!(peak <= 16 * len, "{name}: {args:?}: {peak} bytes for {len}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22 item 1: a template full of one-time instructions and dummies (`+1!, 0*0, …`,
/// the memory bench's `dummies`) keeps the bound in `expand -f` and in the OrcaSlicer
/// lint. The evaluator kept a remembered walk (64 bytes) and two `usize` links for every
/// instruction, written whether used or not: 20× and 22× the text.
#[test]
fn one_time_instructions_and_dummies_cost_at_most_16_times_the_template() {
    let dir = std::env::temp_dir().join(format!("rotlang-memory-dummies-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let unit = "+1!, 0*0, ";
    let template = unit.repeat((4 << 20) / unit.len());
    let len = template.len() as u64;
    let rot = dir.join("dummies.rot");
    std::fs::write(&rot, &template).unwrap();
    let rot = rot.display().to_string();
    for args in [
        vec!["expand", "-f", &rot],
        vec!["check", "--compat", "orcaslicer", "-f", &rot],
    ] {
        let peak = peak_rss(&args, None);
        assert!(peak <= 16 * len, "{args:?}: {peak} bytes for {len}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
