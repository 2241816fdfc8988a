//! A guard in front of tower-lsp-server's framing.
//!
//! tower-lsp-server stops reading for good after one undecodable message (its framed
//! reader ends the stream after an error), so a single malformed JSON-RPC message would
//! end the session. This layer reads the frames itself, forwards only messages tower can
//! decode, and answers the rest with a JSON-RPC error; it also bounds message size.

use std::io;

use serde::Deserialize;
use serde_json::{Value, json};
use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader};
use tokio::sync::mpsc;
use tower_lsp_server::jsonrpc::{Request, Response};
use tower_lsp_server::ls_types::DidChangeTextDocumentParams;

/// Larger messages are refused: no real document comes close, and the limit bounds memory.
pub const MAX_MESSAGE: usize = 64 << 20;

/// A `didChange` the framing guard could not read, forwarded under this name
/// (`crate::server` handles it).
pub const INVALID_CHANGE: &str = "rotlang-lsp/invalidChange";
/// Header lines longer than this are garbage, not headers.
const MAX_HEADER_LINE: u64 = 8 << 10;

/// One framed message, or the reason a frame could not be read.
enum Frame {
    Body(Vec<u8>),
    /// The frame was skipped (no length, too long); answer with this error.
    Refused(&'static str),
    Eof,
}

/// What the next read starts with.
enum Carry {
    /// Reading the next header.
    Nothing,
    /// A refused message is to be skipped: input is discarded up to the next header
    /// (`skip_to_header`). Done at the next read, so the refusal is answered first.
    Skip,
    /// A header line already read while skipping.
    Line(Vec<u8>),
}

/// A framed stream: the reader, and where the next read starts.
struct Framed<R> {
    reader: BufReader<R>,
    carry: Carry,
}

impl<R: AsyncRead + Unpin> Framed<R> {
    fn new(input: R) -> Self {
        Framed {
            reader: BufReader::new(input),
            carry: Carry::Nothing,
        }
    }

    async fn read_frame(&mut self) -> io::Result<Frame> {
        read_frame(&mut self.reader, &mut self.carry).await
    }
}

/// Read the next frame. Never fails on bad input: bad headers or sizes become `Refused`.
async fn read_frame<R: AsyncRead + Unpin>(
    reader: &mut BufReader<R>,
    carry: &mut Carry,
) -> io::Result<Frame> {
    if let Carry::Skip = carry {
        *carry = match skip_to_header(reader).await? {
            Some(line) => Carry::Line(line),
            None => return Ok(Frame::Eof),
        };
    }
    let mut length: Option<usize> = None;
    let mut bad_length = false;
    let mut saw_header = false;
    loop {
        let line = match std::mem::replace(carry, Carry::Nothing) {
            Carry::Line(line) => line,
            _ => {
                let mut line = Vec::new();
                let n = (&mut *reader)
                    .take(MAX_HEADER_LINE)
                    .read_until(b'\n', &mut line)
                    .await?;
                if n == 0 {
                    return Ok(Frame::Eof);
                }
                line
            }
        };
        let text = String::from_utf8_lossy(&line);
        let text = text.trim();
        if text.is_empty() {
            if saw_header {
                break;
            }
            continue; // stray blank lines between messages
        }
        saw_header = true;
        // Found anywhere in the line, so that after a body shorter or longer than its
        // declared length the next header is still recognised and the stream resyncs.
        if let Some(at) = text.to_ascii_lowercase().find("content-length:") {
            match text[at + "content-length:".len()..].trim().parse::<usize>() {
                Ok(n) => {
                    length = Some(n);
                    bad_length = false;
                }
                Err(_) => bad_length = true,
            }
        }
    }
    let Some(length) = length.filter(|_| !bad_length) else {
        return Ok(Frame::Refused("missing or invalid Content-Length header"));
    };
    if length > MAX_MESSAGE {
        // Not read past its declared length: a wrong length (a client's bug, or a garbled
        // header) would swallow every later message while the server looks alive. Skip to
        // the next header instead; a real message this large is skipped all the same.
        *carry = Carry::Skip;
        return Ok(Frame::Refused("message too large"));
    }
    let mut body = vec![0; length];
    reader.read_exact(&mut body).await?;
    Ok(Frame::Body(body))
}

/// Discard input up to the next `Content-Length` header (case-insensitive, anywhere),
/// and return that header's line, read to its end, for the next frame; `None` at the end of
/// input. Memory stays bounded: the reader's buffer and one header line.
async fn skip_to_header<R: AsyncRead + Unpin>(
    reader: &mut BufReader<R>,
) -> io::Result<Option<Vec<u8>>> {
    const HEADER: &[u8] = b"content-length:";
    // How much of HEADER the input discarded so far ends with (a header may be split
    // between two reads).
    let mut matched = 0;
    loop {
        let buffer = reader.fill_buf().await?;
        if buffer.is_empty() {
            return Ok(None);
        }
        let mut consumed = buffer.len();
        for (i, &b) in buffer.iter().enumerate() {
            if b.eq_ignore_ascii_case(&HEADER[matched]) {
                matched += 1;
            } else {
                matched = usize::from(b.eq_ignore_ascii_case(&HEADER[0]));
            }
            if matched == HEADER.len() {
                consumed = i + 1;
                break;
            }
        }
        reader.consume(consumed);
        if matched == HEADER.len() {
            let mut line = HEADER.to_vec();
            (&mut *reader)
                .take(MAX_HEADER_LINE)
                .read_until(b'\n', &mut line)
                .await?;
            return Ok(Some(line));
        }
    }
}

fn frame(body: &[u8]) -> Vec<u8> {
    let mut out = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    out.extend_from_slice(body);
    out
}

fn error_frame(id: Value, code: i64, message: &str) -> Vec<u8> {
    let body = json!({"jsonrpc": "2.0", "id": id, "error": {"code": code, "message": message}});
    frame(body.to_string().as_bytes())
}

/// What tower-lsp-server would make of this body (its message type is private, but it is
/// exactly "a response or a request"): `Some(Some(request))`, `Some(None)` for a response,
/// `None` when it cannot decode it. A request is read first: most messages are requests or
/// notifications, and each is parsed once.
fn decode(body: &[u8]) -> Option<Option<Request>> {
    match serde_json::from_slice::<Request>(body) {
        Ok(request) => Some(Some(request)),
        Err(_) => serde_json::from_slice::<Response>(body).ok().map(|_| None),
    }
}

#[cfg(test)]
fn decodable(body: &[u8]) -> bool {
    decode(body).is_some()
}

/// `$/` requests (with an id) must be answered with Method not found, but
/// tower-lsp-server drops them silently, leaving the client waiting: the answer.
fn dollar_request(request: &Request) -> Option<Vec<u8>> {
    if !request.method().starts_with("$/") {
        return None;
    }
    let id = serde_json::to_value(request.id()?).ok()?;
    Some(error_frame(id, -32601, "Method not found"))
}

/// A `textDocument/didChange` whose parameters the server cannot read (a negative
/// position, a missing field) would be dropped without a word by tower-lsp-server, and the
/// document would silently part from the editor's. It is forwarded instead as the
/// notification `rotlang-lsp/invalidChange` with the document and the reason, so the
/// server marks the document out of sync (see `crate::sync`).
fn unreadable_change(request: &Request) -> Option<Vec<u8>> {
    if request.method() != "textDocument/didChange" {
        return None;
    }
    let params = request.params().unwrap_or(&Value::Null);
    let reason = DidChangeTextDocumentParams::deserialize(params).err()?;
    let uri = params.pointer("/textDocument/uri").cloned();
    let message = json!({
        "jsonrpc": "2.0",
        "method": INVALID_CHANGE,
        "params": {"uri": uri, "reason": format!("an edit the server cannot read: {reason}")},
    });
    Some(message.to_string().into_bytes())
}

/// The error for a body tower cannot decode: Invalid Request when it is JSON (with its id,
/// if it has one), Parse error otherwise.
fn rejection(body: &[u8]) -> Vec<u8> {
    match serde_json::from_slice::<Value>(body) {
        Ok(value) => {
            let id = value
                .get("id")
                .filter(|id| id.is_string() || id.is_number())
                .cloned()
                .unwrap_or(Value::Null);
            error_frame(id, -32600, "Invalid request")
        }
        Err(_) => error_frame(Value::Null, -32700, "Parse error"),
    }
}

/// Copy client messages to the server, answering the undecodable ones directly.
async fn filter_input<R, W>(
    input: R,
    mut to_server: W,
    replies: mpsc::Sender<Vec<u8>>,
) -> io::Result<()>
where
    R: AsyncRead + Unpin,
    W: AsyncWrite + Unpin,
{
    let mut reader = Framed::new(input);
    loop {
        match reader.read_frame().await? {
            Frame::Eof => return Ok(()),
            Frame::Refused(why) => {
                eprintln!("rotlang-lsp: skipped a message: {why}");
                let _ = replies.send(error_frame(Value::Null, -32700, why)).await;
            }
            Frame::Body(body) => {
                let Some(request) = decode(&body) else {
                    eprintln!("rotlang-lsp: skipped an undecodable message");
                    let _ = replies.send(rejection(&body)).await;
                    continue;
                };
                if let Some(reply) = request.as_ref().and_then(dollar_request) {
                    let _ = replies.send(reply).await;
                    continue;
                }
                let body = request.as_ref().and_then(unreadable_change).unwrap_or(body);
                to_server.write_all(&frame(&body)).await?;
                to_server.flush().await?;
            }
        }
    }
}

/// Copy the server's frames, whole, into the output queue; `None` marks the end.
async fn pump_output<R: AsyncRead + Unpin>(from_server: R, out: mpsc::Sender<Option<Vec<u8>>>) {
    let mut reader = Framed::new(from_server);
    while let Ok(Frame::Body(body)) = reader.read_frame().await {
        if out.send(Some(frame(&body))).await.is_err() {
            return;
        }
    }
    let _ = out.send(None).await;
}

/// Serve a language server over `input`/`output` with the guard in between. Returns when
/// the server has finished (after `exit`, or at the end of input) and every reply is out.
pub async fn serve<I, O, F, Fut>(input: I, mut output: O, run: F)
where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin,
    F: FnOnce(tokio::io::DuplexStream, tokio::io::DuplexStream) -> Fut,
    Fut: std::future::Future<Output = ()>,
{
    let (client_side, server_in) = tokio::io::duplex(1 << 16);
    let (server_out, output_side) = tokio::io::duplex(1 << 16);
    let (out_tx, mut out_rx) = mpsc::channel::<Option<Vec<u8>>>(64);
    let (reply_tx, mut reply_rx) = mpsc::channel::<Vec<u8>>(64);

    tokio::spawn(async move {
        if let Err(e) = filter_input(input, client_side, reply_tx).await {
            eprintln!("rotlang-lsp: input closed: {e}");
        }
    });
    let errors_out = out_tx.clone();
    tokio::spawn(async move {
        while let Some(reply) = reply_rx.recv().await {
            if errors_out.send(Some(reply)).await.is_err() {
                return;
            }
        }
    });
    tokio::spawn(pump_output(output_side, out_tx));

    let writer = async {
        while let Some(Some(bytes)) = out_rx.recv().await {
            if output.write_all(&bytes).await.is_err() || output.flush().await.is_err() {
                return;
            }
        }
    };
    join(run(server_in, server_out), writer).await;
}

/// Drives two futures to completion on this task. (tokio's `join!` sits behind its
/// `macros` feature, which would bring in tokio-macros and a second major version of syn.)
async fn join(a: impl std::future::Future<Output = ()>, b: impl std::future::Future<Output = ()>) {
    let (mut a, mut b) = (std::pin::pin!(a), std::pin::pin!(b));
    let (mut a_done, mut b_done) = (false, false);
    std::future::poll_fn(|cx| {
        if !a_done {
            a_done = a.as_mut().poll(cx).is_ready();
        }
        if !b_done {
            b_done = b.as_mut().poll(cx).is_ready();
        }
        if a_done && b_done {
            std::task::Poll::Ready(())
        } else {
            std::task::Poll::Pending
        }
    })
    .await
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tells_good_from_bad_messages() {
        assert!(decodable(
            br#"{"jsonrpc":"2.0","id":1,"method":"shutdown"}"#
        ));
        assert!(decodable(
            br#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#
        ));
        assert!(!decodable(br#"{"jsonrpc":"1.0","id":1,"method":"x"}"#));
        assert!(!decodable(br#"{"foo":1}"#));
        assert!(!decodable(b"{nope"));
        assert!(!decodable(&[0xff, 0xfe]));
        let request = |body: &[u8]| serde_json::from_slice::<Request>(body).unwrap();
        assert!(dollar_request(&request(br#"{"jsonrpc":"2.0","id":3,"method":"$/x"}"#)).is_some());
        assert!(
            dollar_request(&request(
                br#"{"jsonrpc":"2.0","method":"$/cancelRequest","params":{"id":1}}"#
            ))
            .is_none()
        );
        // A didChange with a negative position becomes the server's own notification.
        let bad = request(
            br#"{"jsonrpc":"2.0","method":"textDocument/didChange","params":{"textDocument":{"uri":"file:///a.rot","version":2},"contentChanges":[{"range":{"start":{"line":0,"character":-1},"end":{"line":0,"character":0}},"text":"x"}]}}"#,
        );
        let forwarded: Value = serde_json::from_slice(&unreadable_change(&bad).unwrap()).unwrap();
        assert_eq!(forwarded["method"], INVALID_CHANGE);
        assert_eq!(forwarded["params"]["uri"], "file:///a.rot");
        let good = request(
            br#"{"jsonrpc":"2.0","method":"textDocument/didChange","params":{"textDocument":{"uri":"file:///a.rot","version":2},"contentChanges":[{"text":"x"}]}}"#,
        );
        assert!(unreadable_change(&good).is_none());
        let r = String::from_utf8(rejection(br#"{"id":7,"x":1}"#)).unwrap();
        assert!(r.contains(r#""id":7"#) && r.contains("-32600"), "{r}");
    }
}
