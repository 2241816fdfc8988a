//! The language server's peak memory on a large document: the server (`rotlang-lsp`,
//! beside the `rotlang` binary, or `ROTLANG_LSP`) opens it, publishes its diagnostics
//! and is shut down; its peak resident set comes from `wait4`, as for the CLI.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use serde_json::{Value, json};

/// How long one answer may take before the run is given up (a 16 MiB document on a loaded
/// machine takes tens of seconds; a hang must not hold the bench forever).
const PATIENCE: Duration = Duration::from_secs(600);

/// The server: `ROTLANG_LSP`, else `rotlang-lsp` beside `cli` (`cargo build --release -p
/// rotlang-lsp` puts it there).
pub fn binary(cli: &Path) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("ROTLANG_LSP") {
        return Some(p.into());
    }
    let p = cli.with_file_name("rotlang-lsp");
    p.exists().then_some(p)
}

fn send(to: &mut ChildStdin, message: &Value) -> std::io::Result<()> {
    let body = message.to_string();
    write!(to, "Content-Length: {}\r\n\r\n", body.len())?;
    to.write_all(body.as_bytes())?;
    to.flush()
}

/// The server's messages, one by one, from a thread of their own (the server may write
/// while the document is still being sent).
fn messages(from: impl Read + Send + 'static) -> Receiver<Value> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        let mut reader = BufReader::new(from);
        loop {
            let mut length = None;
            loop {
                let mut line = String::new();
                if reader.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                let line = line.trim_end();
                if line.is_empty() {
                    break;
                }
                if let Some(v) = line.strip_prefix("Content-Length:") {
                    length = v.trim().parse::<usize>().ok();
                }
            }
            let mut body = vec![0; length.unwrap_or(0)];
            if reader.read_exact(&mut body).is_err() {
                return;
            }
            if let Ok(v) = serde_json::from_slice(&body)
                && tx.send(v).is_err()
            {
                return;
            }
        }
    });
    rx
}

fn wait_for(rx: &Receiver<Value>, what: &str, pred: impl Fn(&Value) -> bool) -> Result<(), String> {
    loop {
        match rx.recv_timeout(PATIENCE) {
            Ok(m) if pred(&m) => return Ok(()),
            Ok(_) => {}
            Err(e) => return Err(format!("no {what} ({e})")),
        }
    }
}

/// The variable that makes the bench binary the client of one measure (see [`measure`]).
const CLIENT: &str = "ROTLANG_MEMORY_LSP_CLIENT";

/// Peak RSS of the server that opens `file` as the document `uri` in `language`
/// (`rotlang` or `json`), analyses it and shuts down. The client is this binary run again
/// (see [`client`]): the document and its message are megabytes, and a child spawned by
/// the bench shares its memory until `exec`, so its peak RSS counts the bench's own peak:
/// held here, they would inflate every later measure.
pub fn measure(server: &Path, uri: &str, language: &str, file: &Path) -> Result<u64, String> {
    let me = std::env::current_exe().map_err(|e| e.to_string())?;
    let spec = [
        server.display().to_string(),
        uri.to_owned(),
        language.to_owned(),
        file.display().to_string(),
    ];
    let out = Command::new(me)
        .env(CLIENT, spec.join("\n"))
        .stdin(Stdio::null())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| e.to_string())?;
    let said = String::from_utf8_lossy(&out.stdout);
    match said.trim().strip_prefix("peak ") {
        Some(n) => n.parse().map_err(|_| format!("the client said {said:?}")),
        None => Err(said.trim().to_owned()),
    }
}

/// In the client run (the variable set): measures, prints `peak BYTES` or the reason, and
/// exits.
pub fn client() {
    let Ok(spec) = std::env::var(CLIENT) else {
        return;
    };
    let parts: Vec<&str> = spec.split('\n').collect();
    let [server, uri, language, file] = parts[..] else {
        println!("a malformed {CLIENT}");
        std::process::exit(0);
    };
    match peak(Path::new(server), uri, language, Path::new(file)) {
        Ok(n) => println!("peak {n}"),
        Err(why) => println!("{why}"),
    }
    std::process::exit(0);
}

/// The measure itself: the server is spawned first, while this process is small.
#[cfg(unix)]
fn peak(server: &Path, uri: &str, language: &str, file: &Path) -> Result<u64, String> {
    let mut child = Command::new(server)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| format!("{}: {e}", server.display()))?;
    let pid = child.id() as libc::pid_t;
    let mut stdin = child.stdin.take().expect("piped");
    let rx = messages(child.stdout.take().expect("piped"));
    let talk = |stdin: &mut ChildStdin| -> Result<(), String> {
        let io = |e: std::io::Error| e.to_string();
        let text = std::fs::read_to_string(file).map_err(io)?;
        // The default limit (4 MiB) would refuse the document: raised to the transport's.
        send(
            stdin,
            &json!({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
                "processId": null, "rootUri": null, "capabilities": {},
                "initializationOptions": {"rotlang": {"maxDocumentBytes": 48 << 20}}}}),
        )
        .map_err(io)?;
        wait_for(&rx, "initialize answer", |m| m["id"] == 1)?;
        send(
            stdin,
            &json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}),
        )
        .map_err(io)?;
        send(
            stdin,
            &json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
                "textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}}}),
        )
        .map_err(io)?;
        wait_for(&rx, "diagnostics", |m| {
            m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri
        })?;
        send(
            stdin,
            &json!({"jsonrpc": "2.0", "id": 2, "method": "shutdown"}),
        )
        .map_err(io)?;
        wait_for(&rx, "shutdown answer", |m| m["id"] == 2)?;
        send(stdin, &json!({"jsonrpc": "2.0", "method": "exit"})).map_err(io)
    };
    let talked = talk(&mut stdin);
    drop(stdin);
    if talked.is_err() {
        let _ = child.kill();
    }
    let mut status = 0;
    // SAFETY: an all-zero rusage is valid; wait4 fills it for the child it reaps.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our child, not yet waited for; the pointers are to live locals.
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    talked?;
    if reaped != pid {
        return Err("the server was not reaped".into());
    }
    Ok(usage.ru_maxrss as u64 * 1024)
}

#[cfg(not(unix))]
fn peak(_: &Path, _: &str, _: &str, _: &Path) -> Result<u64, String> {
    Err("not measured on this platform".into())
}
