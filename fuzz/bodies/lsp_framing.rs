//! Fuzz target `lsp_framing`: any bytes as the client's side of a session with the real
//! server behind its framing guard (`rotlang_lsp::transport::serve`). The server must
//! neither panic nor hang, and everything it writes must be well-framed JSON.
//!
//! The seed corpus holds whole sessions (initialize, open, change, hover, formatting,
//! ...), so mutations reach the handlers as well as the framing.

use std::io;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};

/// A writer that keeps what the server writes.
#[derive(Clone, Default)]
struct Captured(Arc<Mutex<Vec<u8>>>);

impl AsyncWrite for Captured {
    fn poll_write(
        self: Pin<&mut Self>,
        _: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        self.0.lock().expect("not poisoned").extend_from_slice(buf);
        Poll::Ready(Ok(buf.len()))
    }
    fn poll_flush(self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<io::Result<()>> {
        Poll::Ready(Ok(()))
    }
    fn poll_shutdown(self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<io::Result<()>> {
        Poll::Ready(Ok(()))
    }
}

/// The client's bytes, one message at a time (cut before each `Content-Length`), with a
/// few turns of the (single-threaded) runtime between messages and before the end of
/// input: as a client waits for answers, and since the end of input (or `exit`) cancels
/// what is pending. No timers, so runs are deterministic.
struct Client {
    data: Vec<u8>,
    at: usize,
    turns: u32,
}

/// Turns of the runtime given to the server after each message.
const TURNS: u32 = 64;

impl AsyncRead for Client {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let this = &mut *self;
        if this.turns > 0 {
            this.turns -= 1;
            cx.waker().wake_by_ref();
            return Poll::Pending;
        }
        if this.at < this.data.len() {
            let rest = &this.data[this.at..];
            let next = rest
                .windows(15)
                .skip(1)
                .position(|w| w.eq_ignore_ascii_case(b"Content-Length:"))
                .map_or(rest.len(), |i| i + 1);
            let n = buf.remaining().min(next);
            buf.put_slice(&rest[..n]);
            this.at += n;
            this.turns = TURNS;
            return Poll::Ready(Ok(()));
        }
        Poll::Ready(Ok(()))
    }
}

pub fn run(data: &[u8]) {
    check_frames(&session(data));
}

/// What the server writes when a client sends `data` and closes its side.
pub fn session(data: &[u8]) -> Vec<u8> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .build()
        .expect("a runtime");
    let output = Captured::default();
    let input = Client {
        data: data.to_vec(),
        at: 0,
        turns: 0,
    };
    runtime.block_on(rotlang_lsp::server::serve(input, output.clone()));
    output.0.lock().expect("not poisoned").clone()
}

/// Every frame the server wrote is `Content-Length: n\r\n\r\n` and n bytes of JSON.
fn check_frames(mut bytes: &[u8]) {
    while !bytes.is_empty() {
        let end = bytes
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("a header ends with a blank line");
        let header = std::str::from_utf8(&bytes[..end]).expect("an ASCII header");
        let length: usize = header
            .strip_prefix("Content-Length: ")
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("a bad header {header:?}"));
        let body = &bytes[end + 4..end + 4 + length];
        let value: serde_json::Value = serde_json::from_slice(body).expect("a JSON body");
        assert_eq!(value["jsonrpc"], "2.0", "{value}");
        bytes = &bytes[end + 4 + length..];
    }
}
