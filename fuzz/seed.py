#!/usr/bin/env python3
"""Writes the seed corpus of every fuzz target into fuzz/corpus/<target>/.

Sources: corpus/ (valid, warn, invalid templates), the conformance templates
(../shared/conformance/cases*.jsonl when present), the reproducers of issue 7, and a few
hand-written JSON profiles and LSP sessions. Run from the repository root:

    python3 fuzz/seed.py

then let each target run, and minimise before committing (see fuzz/README.md).
"""
import hashlib
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "fuzz" / "corpus"


def templates():
    found = set()
    for path in sorted((ROOT / "corpus").glob("*/*.rot")):
        found.add(path.read_text(encoding="utf-8", errors="replace").rstrip("\n"))
    for name in ("cases.jsonl", "cases-random.jsonl"):
        path = ROOT.parent / "shared" / "conformance" / name
        if path.exists():
            for line in path.read_text(encoding="utf-8").splitlines():
                found.add(json.loads(line)["template"])
    found |= {
        "0,," * 100 + "X",
        "0,," * 100 + "S",
        "0/5 " * 100 + "+5*2*",
        "+10L99999999",
        "+10L1e9, -5/100%, 30*1000000000",
        '"0, 90"',
        "+30/1,5mm",
        "+30 /50%",
        "\ufeff+30°, 𝕏, α, ℕ",
    }
    return sorted(found)


def write(target, data):
    d = OUT / target
    d.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8")
    (d / hashlib.sha1(data).hexdigest()).write_bytes(data)


def frame(message):
    body = json.dumps(message).encode("utf-8")
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def session(uri, language, text, extra=()):
    msgs = [
        {"jsonrpc": "2.0", "id": 1, "method": "initialize",
         "params": {"processId": None, "rootUri": None, "capabilities": {}}},
        {"jsonrpc": "2.0", "method": "initialized", "params": {}},
        {"jsonrpc": "2.0", "method": "textDocument/didOpen",
         "params": {"textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}}},
    ]
    doc = {"textDocument": {"uri": uri}}
    pos = {"line": 0, "character": 2}
    requests = [
        ("textDocument/hover", {**doc, "position": pos}),
        ("textDocument/completion", {**doc, "position": pos}),
        ("textDocument/formatting", {**doc, "options": {"tabSize": 4, "insertSpaces": True}}),
        ("textDocument/semanticTokens/full", doc),
        ("textDocument/inlayHint", {**doc, "range": {"start": {"line": 0, "character": 0},
                                                    "end": {"line": 9, "character": 0}}}),
        ("textDocument/codeAction", {**doc, "range": {"start": pos, "end": pos},
                                     "context": {"diagnostics": []}}),
        ("textDocument/documentSymbol", doc),
    ]
    for i, (method, params) in enumerate(requests):
        msgs.append({"jsonrpc": "2.0", "id": 10 + i, "method": method, "params": params})
    msgs.extend(extra)
    msgs.append({"jsonrpc": "2.0", "id": 99, "method": "shutdown"})
    msgs.append({"jsonrpc": "2.0", "method": "exit"})
    return b"".join(frame(m) for m in msgs)


def main():
    ts = templates()
    for t in ts:
        write("parse", t)
        write("fmt", t)
    # eval: 4 header bytes (model, sizes, options), then the template.
    headers = [b"\x00\x00\x00\x00", b"\x01\x05\x03\x10", b"\x02\x20\x07\x30",
               b"\x03\x00\x00\x00", b"\x04\x11\x27\x05", b"\x81\x02\x02\x40"]
    for i, t in enumerate(ts):
        write("eval", headers[i % len(headers)] + t.encode("utf-8"))
    # lsp_json: profiles with templates, escapes, arrays, nesting, broken JSON.
    keys = ["sparse_infill_rotate_template", "solid_infill_rotate_template"]
    for i, t in enumerate(ts[:120]):
        key = keys[i % 2]
        write("lsp_json", json.dumps({"name": "p", key: t}))
        write("lsp_json", json.dumps({"x": {key: [t, "0"]}}, ensure_ascii=True))
    write("lsp_json", '{"sparse_infill_rotate_template": "+30\\u00b0, \\"a\\", \\ud835\\udd4f"}')
    write("lsp_json", '{"sparse_infill_rotate_template": "abc')
    write("lsp_json", '{"solid_infill_rotate_template" : ["0", "90"], "a": [1, {"b": null}]}')
    # lsp_framing: whole sessions, and malformed frames.
    write("lsp_framing", session("file:///a.rot", "rotlang", "+10L25%, -10l25%\n0 90 +30X"))
    write("lsp_framing", session("file:///a.rot", "rotlang", "0,," * 100 + "X"))
    write("lsp_framing", session(
        "file:///p.json", "json",
        '{"sparse_infill_rotate_template": "+30\\u00b0, #5", "solid_infill_rotate_template": "S"}',
        [{"jsonrpc": "2.0", "method": "textDocument/didChange",
          "params": {"textDocument": {"uri": "file:///p.json", "version": 2},
                     "contentChanges": [{"range": {"start": {"line": 0, "character": 3},
                                                   "end": {"line": 0, "character": 5}},
                                         "text": "x"}]}},
         {"jsonrpc": "2.0", "method": "workspace/didChangeConfiguration",
          "params": {"settings": {"rotlang": {"layers": 7, "layerHeight": 0.3}}}},
         {"jsonrpc": "2.0", "method": "textDocument/didClose",
          "params": {"textDocument": {"uri": "file:///p.json"}}}]))
    write("lsp_framing", b"Content-Length: 5\r\n\r\n{nope" + b"Content-Length: x\r\n\r\n"
          + b"content-length: 2\r\n\r\n{}" + frame({"jsonrpc": "2.0", "id": 3, "method": "$/x"}))
    for seed in lsp_sync_seeds():
        write("lsp_framing", seed)


def lsp_sync_seeds():
    """Issue 22: an oversized Content-Length before real messages (the stream resyncs on
    the next header), edits that cannot be applied (negative, reversed, past the end: the
    document goes out of sync until a full text), and a request cancelled while it waits."""
    uri = "file:///s.rot"
    change = lambda v, changes: {"jsonrpc": "2.0", "method": "textDocument/didChange",
                                 "params": {"textDocument": {"uri": uri, "version": v},
                                            "contentChanges": changes}}
    rng = lambda l0, c0, l1, c1: {"start": {"line": l0, "character": c0},
                                  "end": {"line": l1, "character": c1}}
    yield (b"Content-Length: 1000000000000\r\n\r\n{\"id\": 5}"
           + session(uri, "rotlang", "+30/50%, 90"))
    yield session(uri, "rotlang", "+30/50%, 90", [
        change(2, [{"range": rng(0, -1, 0, 2), "text": "X"}]),
        change(3, [{"range": rng(0, 4, 0, 1), "text": "X"}]),
        change(4, [{"range": rng(7, 0, 7, 1), "text": "X"}]),
        {"jsonrpc": "2.0", "id": 50, "method": "textDocument/hover",
         "params": {"textDocument": {"uri": uri}, "position": {"line": 0, "character": 1}}},
        change(5, [{"range": rng(0, 0, 0, 0), "text": "0, "}]),
        change(6, [{"text": "+30X"}, {"range": rng(0, 4, 1, 0), "text": ", 5"}]),
        {"jsonrpc": "2.0", "id": 51, "method": "textDocument/hover",
         "params": {"textDocument": {"uri": uri}, "position": {"line": 0, "character": 1}}},
        {"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": 51}},
    ])


if __name__ == "__main__":
    main()
