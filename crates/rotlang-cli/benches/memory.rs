//! Peak memory of the CLI on large templates: `cargo bench --bench memory`.
//!
//! Runs the `rotlang` binary (built in the bench profile) on generated templates of 1, 4
//! and 16 MiB (16 MiB is the most the CLI reads) with `check`, `expand` and `fmt`, and
//! reads each child's peak resident set size from `wait4`'s rusage. Target: at most 16×
//! the text. Prints one line per run and exits 1 when a run is over the target.
//!
//! Every way `check` reads a template is measured (issue 22 item 1): `--file`, the file
//! named as a path, stdin, and the template as the value of a JSON preset, a jsonc preset,
//! an `.ini` line and a `.3mf` project's settings (a 16 MiB template is more than a 3mf
//! entry may inflate to: that run measures the refusal).
//!
//! `check` runs the OrcaSlicer lint by default on inputs of every size; `check --compat
//! none -f` measures rotlang's reading alone. The other ways of reading a template are measured
//! where they are built: the language server (`rotlang-lsp` beside `rotlang`: `cargo build
//! --release -p rotlang-lsp` first, or `ROTLANG_LSP`) opening the `.rot` and the `.json`;
//! JavaScript's `readProfile` on both (after `node bindings/js/build.mjs`); Python's
//! `check` on the template (`ROTLANG_PYTHON`, a Python with the package installed; it has
//! no profile reader). A way that is not built is named with the reason, not measured.
//!
//! Last, a part's every layer listed as JSON (`preview --layers all`), which is written a
//! layer at a time: at most 32 MB for a 100k-triangle, 400-layer vase.
//!
//! `ROTLANG_MEMORY_SIZES=1,4` picks sizes (MiB); `ROTLANG_MEMORY_KINDS=templates,minimal`
//! picks inputs; `ROTLANG_MEMORY_RUNS=lsp,compat` the runs whose label contains one of
//! the words.

use std::path::PathBuf;
use std::process::{Command, Stdio};

#[path = "memory/bindings.rs"]
mod bindings;
#[path = "memory/lsp.rs"]
mod lsp;

const MIB: usize = 1 << 20;
/// Peak RSS over text size, at most.
const TARGET_RATIO: f64 = 16.0;

/// The inputs: a repeated unit, cut to the size.
const KINDS: [(&str, &str); 6] = [
    // What a pasted profile or template looks like, at scale.
    ("templates", "+10L25%, -10l25%, 0, 90, #5, +22.5/50%, "),
    // Legal, a warning each (capped): the IR without the diagnostics.
    ("warnings", "0/5, 400, "),
    // An error each (capped).
    ("errors", "X, +30/5/5, "),
    // The shortest instructions there are: the most instructions per byte.
    ("minimal", "0 "),
    // One-time instructions and dummies: the evaluator keeps links and walks per
    // instruction for these (what `expand` and the OrcaSlicer lint cost most on).
    ("dummies", "+1!, 0*0, "),
    // Some of everything, as a pasted log file would be.
    (
        "log",
        "2024-01-01 12:00:00 INFO slicing layer 12 of 300 (+30/5mm), ",
    ),
];

#[cfg(unix)]
/// The peak RSS of `cmd` (stdin from `stdin`) and its exit code (-1 when killed by a signal).
fn peak_rss_bytes(cmd: &mut Command, stdin: Option<&std::path::Path>) -> Option<(u64, i32)> {
    let input = match stdin {
        Some(path) => Stdio::from(std::fs::File::open(path).ok()?),
        None => Stdio::null(),
    };
    let child = cmd
        .stdin(input)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: an all-zero rusage is valid; wait4 fills it for the child it reaps.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our child, not yet waited for; the pointers are to live locals.
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -1
    };
    (reaped == pid).then_some((usage.ru_maxrss as u64 * 1024, code))
}

#[cfg(not(unix))]
fn peak_rss_bytes(_: &mut Command, _: Option<&std::path::Path>) -> Option<(u64, i32)> {
    None
}

/// Writes `unit` repeated to exactly `len` bytes, a block at a time: the bench itself must
/// stay small, since a spawned child's peak RSS counts the memory it shares with its
/// parent before `exec`.
fn write_input(path: &std::path::Path, unit: &str, len: usize) {
    use std::io::Write;
    let block = unit.repeat(65_536 / unit.len() + 1);
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).expect("create the input"));
    let mut left = len;
    while left > 0 {
        let n = left.min(block.len());
        file.write_all(&block.as_bytes()[..n])
            .expect("write the input");
        left -= n;
    }
    file.flush().expect("write the input");
}

/// `prefix`, then `unit` repeated to `len` bytes, then `suffix`, written to `path`.
fn write_wrapped(path: &std::path::Path, prefix: &str, unit: &str, len: usize, suffix: &str) {
    use std::io::Write;
    let body = path.with_extension("body");
    write_input(&body, unit, len);
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).expect("create the input"));
    out.write_all(prefix.as_bytes()).expect("write the input");
    std::io::copy(&mut std::fs::File::open(&body).expect("the body"), &mut out)
        .expect("write the input");
    out.write_all(suffix.as_bytes()).expect("write the input");
    out.flush().expect("write the input");
    let _ = std::fs::remove_file(body);
}

/// A `.3mf` project whose `project_settings.config` holds the template, streamed into the
/// archive a block at a time.
fn write_project(path: &std::path::Path, unit: &str, len: usize) {
    use std::io::Write;
    let file = std::fs::File::create(path).expect("create the input");
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("Metadata/project_settings.config", options)
        .expect("write the input");
    zip.write_all(b"{\"sparse_infill_rotate_template\": \"")
        .expect("write the input");
    let block = unit.repeat(65_536 / unit.len() + 1);
    let mut left = len;
    while left > 0 {
        let n = left.min(block.len());
        zip.write_all(&block.as_bytes()[..n])
            .expect("write the input");
        left -= n;
    }
    zip.write_all(b"\"}").expect("write the input");
    zip.finish().expect("write the input");
}

/// The profile files of a template: name, and how `check` is run on it.
fn profile_runs(
    dir: &std::path::Path,
    name: &str,
    mib: usize,
    unit: &str,
) -> Vec<(String, PathBuf)> {
    let len = mib * MIB;
    let mut runs = Vec::new();
    let json = dir.join(format!("{name}-{mib}.json"));
    write_wrapped(
        &json,
        "{\"sparse_infill_rotate_template\": \"",
        unit,
        len,
        "\"}",
    );
    runs.push(("check .json".to_owned(), json));
    let jsonc = dir.join(format!("{name}-{mib}.jsonc"));
    write_wrapped(
        &jsonc,
        "// a preset\n{\"sparse_infill_rotate_template\": \"",
        unit,
        len,
        "\",}",
    );
    runs.push(("check .jsonc".to_owned(), jsonc));
    let ini = dir.join(format!("{name}-{mib}.ini"));
    write_wrapped(&ini, "sparse_infill_rotate_template = ", unit, len, "\n");
    runs.push(("check .ini".to_owned(), ini));
    {
        let project = dir.join(format!("{name}-{mib}.3mf"));
        write_project(&project, unit, len);
        runs.push(("check .3mf".to_owned(), project));
    }
    runs
}

fn list(var: &str) -> Option<Vec<String>> {
    let v = std::env::var(var).ok()?;
    Some(v.split(',').map(|s| s.trim().to_owned()).collect())
}

fn main() {
    // This binary run again as the language server's client (one measure), if it is.
    lsp::client();
    // `cargo bench` passes `--bench`; a filter argument is ignored.
    let sizes: Vec<usize> = list("ROTLANG_MEMORY_SIZES")
        .map(|l| l.iter().filter_map(|s| s.parse().ok()).collect())
        .unwrap_or_else(|| vec![1, 4, 16]);
    let kinds: Vec<(&str, &str)> = match list("ROTLANG_MEMORY_KINDS") {
        Some(names) => KINDS
            .into_iter()
            .filter(|(n, _)| names.iter().any(|m| m == n))
            .collect(),
        None => KINDS.to_vec(),
    };
    let dir = std::env::temp_dir().join(format!("rotlang-memory-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temp dir");
    let binary = env!("CARGO_BIN_EXE_rotlang");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let server = lsp::binary(std::path::Path::new(binary));
    let wanted = list("ROTLANG_MEMORY_RUNS");
    let wanted = |label: &str| {
        wanted
            .as_ref()
            .is_none_or(|words| words.iter().any(|w| label.contains(w.as_str())))
    };
    let mut over = 0;
    println!(
        "{:<10} {:>5} {:<28} {:>10} {:>7}",
        "input", "MiB", "command", "peak RSS", "ratio"
    );
    for (name, unit) in &kinds {
        for &mib in &sizes {
            let len = mib * MIB;
            let path: PathBuf = dir.join(format!("{name}-{mib}.rot"));
            write_input(&path, unit, len);
            let mut runs: Vec<(String, Command, Option<&std::path::Path>)> = Vec::new();
            for command in ["check", "expand", "fmt"] {
                let mut cmd = Command::new(binary);
                cmd.arg(command).arg("--file").arg(&path);
                runs.push((format!("{command} -f"), cmd, None));
            }
            let mut cmd = Command::new(binary);
            cmd.arg("check").arg(&path);
            runs.push(("check .rot".to_owned(), cmd, None));
            let mut cmd = Command::new(binary);
            cmd.arg("check");
            runs.push(("check stdin".to_owned(), cmd, Some(&path)));
            let mut cmd = Command::new(binary);
            cmd.args(["check", "--compat", "none", "--file"]).arg(&path);
            runs.push(("check --compat none -f".to_owned(), cmd, None));
            let profiles = profile_runs(&dir, name, mib, unit);
            for (label, file) in &profiles {
                let mut cmd = Command::new(binary);
                cmd.arg("check").arg(file);
                runs.push((label.clone(), cmd, None));
            }
            let json = &profiles[0].1;
            let mut report = |command: &str, peak: Result<u64, String>| {
                let peak = match peak {
                    Ok(peak) => peak,
                    Err(why) => {
                        return println!("{name:<10} {mib:>5} {command:<28} (not measured: {why})");
                    }
                };
                let ratio = peak as f64 / len as f64;
                let flag = if ratio > TARGET_RATIO {
                    over += 1;
                    "  OVER"
                } else {
                    ""
                };
                println!(
                    "{name:<10} {mib:>5} {command:<28} {:>7.1} MB {ratio:>6.1}x{flag}",
                    peak as f64 / 1e6
                );
            };
            for (command, mut cmd, stdin) in runs {
                if wanted(&command) {
                    // `check` exits 1 on errors (the `errors` input has them): a signal is
                    // what fails the run (an allocation refused, the OOM killer).
                    let peak = match peak_rss_bytes(&mut cmd, stdin) {
                        Some((peak, code)) if code >= 0 => Ok(peak),
                        Some(_) => Err("killed by a signal".to_owned()),
                        None => Err("not on this platform".to_owned()),
                    };
                    report(&command, peak);
                }
            }
            // The language server, on the template as a document and in a preset.
            for (command, file, uri, language) in [
                ("lsp .rot", &path, "file:///big.rot", "rotlang"),
                ("lsp .json", json, "file:///big.json", "json"),
            ] {
                if wanted(command) {
                    let peak = match &server {
                        Some(server) => lsp::measure(server, uri, language, file),
                        None => Err(
                            "rotlang-lsp not built (cargo build --release -p rotlang-lsp)".into(),
                        ),
                    };
                    report(command, peak);
                }
            }
            // The bindings, each running on a script of its language.
            for (command, way) in [
                ("node readProfile .rot", bindings::js(root, &path)),
                ("node readProfile .json", bindings::js(root, json)),
                ("python check", bindings::python(root, &path)),
            ] {
                if wanted(command) {
                    let peak = way.and_then(|mut cmd| match peak_rss_bytes(&mut cmd, None) {
                        Some((peak, 0)) => Ok(peak),
                        Some((_, code)) => Err(format!("the script failed ({code})")),
                        None => Err("not on this platform".into()),
                    });
                    report(command, peak);
                }
            }
            let _ = std::fs::remove_file(&path);
            for (_, file) in profiles {
                let _ = std::fs::remove_file(file);
            }
        }
    }
    if wanted("preview") {
        over += part_preview(binary, &dir);
    }
    let _ = std::fs::remove_dir(&dir);
    if over > 0 {
        eprintln!("{over} runs above their target");
        std::process::exit(1);
    }
}

/// A part's every layer as JSON (`preview --layers all --format json`), written a layer
/// at a time: the vase of `benches/slice.rs`'s family (100k triangles, 80 mm: 400
/// layers, about 26 MB of JSON) in at most [`PART_TARGET_MB`]. Listing 256 layers of it
/// as one document took 124 MB. Returns 1 when over the target.
fn part_preview(binary: &str, dir: &std::path::Path) -> usize {
    let stl = dir.join("vase.stl");
    std::fs::write(
        &stl,
        rotlang_geometry::mesh::shapes::vase(384).to_binary_stl(),
    )
    .expect("the mesh written");
    let mut cmd = Command::new(binary);
    cmd.args([
        "preview", "+30", "--layers", "all", "--format", "json", "--shape",
    ])
    .arg(&stl)
    .args(["--out", "/dev/null"]);
    let label = "preview vase --layers all json";
    let over = match peak_rss_bytes(&mut cmd, None) {
        Some((peak, 0)) => {
            let mb = peak as f64 / 1e6;
            let flag = mb > PART_TARGET_MB;
            println!(
                "{:<10} {:>5} {label:<28} {mb:>7.1} MB (target {PART_TARGET_MB} MB){}",
                "part",
                "-",
                if flag { "  OVER" } else { "" }
            );
            usize::from(flag)
        }
        other => {
            println!("part  {label}: not measured ({other:?})");
            0
        }
    };
    let _ = std::fs::remove_file(&stl);
    over
}

/// Peak RSS of a part's every layer listed, at most (MB).
const PART_TARGET_MB: f64 = 32.0;
