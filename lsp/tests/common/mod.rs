//! A tiny LSP client for the tests: spawns the real `rotlang-lsp` binary and speaks
//! Content-Length framed JSON-RPC over its stdio. Every wait has a timeout, so a hung
//! server fails the test instead of blocking CI.

#![allow(dead_code)] // each test binary uses a different subset

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

pub const TIMEOUT: Duration = Duration::from_secs(20);

pub struct Lsp {
    child: Child,
    stdin: ChildStdin,
    rx: Receiver<Value>,
    next_id: i64,
    /// Messages read while waiting for something else.
    backlog: VecDeque<Value>,
    /// The answer to the server's `workspace/configuration` requests (one per item).
    pub configuration: Value,
}

impl Lsp {
    /// Spawn the server without initializing it.
    pub fn spawn() -> Lsp {
        Lsp::spawn_with_args(&[])
    }

    /// Spawn with command-line arguments (as clients pass `--stdio`).
    pub fn spawn_with_args(args: &[&str]) -> Lsp {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rotlang-lsp"))
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start rotlang-lsp");
        let stdin = child.stdin.take().expect("stdin");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            while let Some(body) = read_frame(&mut reader) {
                match serde_json::from_slice::<Value>(&body) {
                    Ok(v) => {
                        if tx.send(v).is_err() {
                            return;
                        }
                    }
                    Err(e) => panic!("server sent invalid JSON: {e}"),
                }
            }
        });
        Lsp {
            child,
            stdin,
            rx,
            next_id: 1,
            backlog: VecDeque::new(),
            configuration: Value::Null,
        }
    }

    /// Spawn and initialize with these client capabilities and initialization options.
    /// Returns the server and its `InitializeResult`.
    pub fn start_with(capabilities: Value, options: Value) -> (Lsp, Value) {
        let mut lsp = Lsp::spawn();
        let result = lsp.result(
            "initialize",
            json!({"processId": null, "rootUri": null, "capabilities": capabilities,
                   "initializationOptions": options}),
        );
        lsp.notify("initialized", json!({}));
        (lsp, result)
    }

    pub fn start() -> Lsp {
        Lsp::start_with(json!({}), Value::Null).0
    }

    pub fn send_raw(&mut self, bytes: &[u8]) {
        self.stdin.write_all(bytes).expect("write to server");
        self.stdin.flush().expect("flush");
    }

    pub fn send(&mut self, message: &Value) {
        let body = message.to_string();
        let frame = format!("Content-Length: {}\r\n\r\n{body}", body.len());
        self.send_raw(frame.as_bytes());
    }

    pub fn notify(&mut self, method: &str, params: Value) {
        self.send(&json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Send a request; return the whole response object.
    pub fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        self.wait(|m| m.get("id") == Some(&json!(id)) && m.get("method").is_none())
    }

    /// Send a request; return its result, failing the test on an error response.
    pub fn result(&mut self, method: &str, params: Value) -> Value {
        let response = self.request(method, params);
        assert!(
            response.get("error").is_none(),
            "{method} failed: {response}"
        );
        response["result"].clone()
    }

    /// The next message matching `pred` (from the backlog first), within the timeout.
    /// Requests from the server are answered: `workspace/configuration` with
    /// `self.configuration`, anything else with null.
    pub fn wait(&mut self, pred: impl Fn(&Value) -> bool) -> Value {
        if let Some(i) = self.backlog.iter().position(&pred) {
            return self.backlog.remove(i).expect("backlog entry");
        }
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.rx.recv_timeout(left) {
                Ok(m) => {
                    if m.get("method").is_some() && m.get("id").is_some() {
                        let result = if m["method"] == "workspace/configuration" {
                            json!([self.configuration])
                        } else {
                            Value::Null
                        };
                        self.send(&json!({"jsonrpc": "2.0", "id": m["id"], "result": result}));
                    }
                    if pred(&m) {
                        return m;
                    }
                    self.backlog.push_back(m);
                }
                Err(RecvTimeoutError::Timeout) => panic!("timed out waiting for a message"),
                Err(RecvTimeoutError::Disconnected) => panic!("the server closed its output"),
            }
        }
    }

    /// Forget messages already read but not yet asked for.
    pub fn clear_backlog(&mut self) {
        self.backlog.clear();
    }

    /// Messages that arrive within `d`, without waiting for anything in particular.
    pub fn drain(&mut self, d: Duration) -> Vec<Value> {
        let deadline = Instant::now() + d;
        let mut out: Vec<Value> = self.backlog.drain(..).collect();
        while let Ok(m) = self
            .rx
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
        {
            out.push(m);
        }
        out
    }

    /// The next `publishDiagnostics` for `uri` (optionally for one version).
    pub fn diagnostics(&mut self, uri: &str, version: Option<i64>) -> Vec<Value> {
        let m = self.wait(|m| {
            m["method"] == "textDocument/publishDiagnostics"
                && m["params"]["uri"] == uri
                && version.is_none_or(|v| m["params"]["version"] == v)
        });
        m["params"]["diagnostics"]
            .as_array()
            .cloned()
            .unwrap_or_default()
    }

    pub fn open(&mut self, uri: &str, language: &str, text: &str) -> Vec<Value> {
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}}),
        );
        self.diagnostics(uri, Some(1))
    }

    pub fn change(&mut self, uri: &str, version: i64, text: &str) {
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri, "version": version},
                   "contentChanges": [{"text": text}]}),
        );
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Whether the process is still running.
    pub fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }

    /// `shutdown` + `exit`, and the exit status within the timeout.
    pub fn shutdown(mut self) -> std::process::ExitStatus {
        let _ = self.result("shutdown", Value::Null);
        self.notify("exit", Value::Null);
        let deadline = Instant::now() + TIMEOUT;
        loop {
            if let Ok(Some(status)) = self.child.try_wait() {
                return status;
            }
            assert!(Instant::now() < deadline, "server did not exit");
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Lsp {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn read_frame(reader: &mut impl BufRead) -> Option<Vec<u8>> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim();
        if line.is_empty() {
            break;
        }
        if let Some(v) = line.strip_prefix("Content-Length:") {
            length = v.trim().parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).ok()?;
    Some(body)
}

/// A fixture with the cursor marked `$0`: the text without the marker, and the marker's
/// line and column in UTF-16 code units and in UTF-8 bytes.
pub fn cursor(fixture: &str) -> (String, u32, u32, u32) {
    let at = fixture.find("$0").expect("fixture has a $0 cursor");
    let text = fixture.replacen("$0", "", 1);
    let before = &text[..at];
    let line = before.matches('\n').count() as u32;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col16 = before[line_start..].encode_utf16().count() as u32;
    let col8 = (before.len() - line_start) as u32;
    (text, line, col16, col8)
}

/// The UTF-16 column of the byte offset `at` in a one-line text.
pub fn col16(text: &str, at: usize) -> u64 {
    text[..at].encode_utf16().count() as u64
}

pub fn range(l0: u64, c0: u64, l1: u64, c1: u64) -> Value {
    json!({"start": {"line": l0, "character": c0}, "end": {"line": l1, "character": c1}})
}

/// Hover Markdown at a position ("" when the server answers null).
pub fn hover_text(lsp: &mut Lsp, uri: &str, line: u32, character: u32) -> String {
    let r = lsp.result(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}),
    );
    r["contents"]["value"].as_str().unwrap_or("").to_string()
}
