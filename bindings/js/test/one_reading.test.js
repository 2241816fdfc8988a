// One reading of a profile everywhere (issue 16 item 3): the same preset through the JS
// package, the CLI (`rotlang expand --profile`) and the language server (hover and inlay
// hints) gives the same angles, and the profile's direction turns none of them (OrcaSlicer
// uses it only for an empty template). The Rust runner (tests/node.rs) passes the
// workspace's built binaries as ROTLANG_CLI and ROTLANG_LSP.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { expand } from '../rotlang.js';
import { readProfile } from '../full.js';

const cli = process.env.ROTLANG_CLI;
const lsp = process.env.ROTLANG_LSP;
const skip = !(cli && lsp) && 'ROTLANG_CLI and ROTLANG_LSP name the binaries (tests/node.rs sets them)';

const PRESET = `{
  "layer_height": "0.12",
  "initial_layer_print_height": "0.24",
  "sparse_infill_direction": "45",
  "sparse_infill_rotate_template": "0, +30/5mm, 90"
}
`;

// A minimal LSP client over stdio: framed JSON-RPC, answers matched by id.
function client(bin) {
  const child = spawn(bin, [], { stdio: ['pipe', 'pipe', 'inherit'] });
  let buf = Buffer.alloc(0);
  const waiting = new Map();
  const published = [];
  child.stdout.on('data', (chunk) => {
    buf = Buffer.concat([buf, chunk]);
    for (;;) {
      const end = buf.indexOf('\r\n\r\n');
      if (end < 0) return;
      const len = Number(/Content-Length: (\d+)/i.exec(buf.subarray(0, end).toString())[1]);
      if (buf.length < end + 4 + len) return;
      const msg = JSON.parse(buf.subarray(end + 4, end + 4 + len).toString());
      buf = buf.subarray(end + 4 + len);
      if (msg.id !== undefined && waiting.has(msg.id)) {
        waiting.get(msg.id)(msg);
        waiting.delete(msg.id);
      } else if (msg.method === 'textDocument/publishDiagnostics') {
        published.push(msg.params);
      }
    }
  });
  const send = (m) => {
    const body = JSON.stringify({ jsonrpc: '2.0', ...m });
    child.stdin.write(`Content-Length: ${Buffer.byteLength(body)}\r\n\r\n${body}`);
  };
  let next = 1;
  return {
    request: (method, params) =>
      new Promise((resolve) => {
        const id = next++;
        waiting.set(id, resolve);
        send({ id, method, params });
      }),
    notify: (method, params) => send({ method, params }),
    published,
    close: () => child.kill(),
  };
}

test('a preset reads the same in the JS package, the CLI and the language server', { skip }, async () => {
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-one-reading-'));
  const path = join(dir, 'preset.json');
  writeFileSync(path, PRESET);

  // JS: the profile's model and the template's own base.
  const p = readProfile('preset.json', PRESET);
  const t = p.templates[0];
  assert.equal(p.base, 45, 'the profile sets a direction');
  assert.equal(t.base, 0, 'it does not turn a non-empty template');
  const js = expand(t.text, { model: p.model, base: t.base }).angles;

  // The CLI.
  const run = spawnSync(cli, ['expand', '--profile', path, '--format', 'json'], { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr);
  const out = JSON.parse(run.stdout);
  const fromCli = out.layers.map((l) => l.angle);
  assert.equal(fromCli.length, js.length, 'one model');
  for (let i = 0; i < js.length; i++) {
    assert.ok(Math.abs(fromCli[i] - js[i]) < 1e-9, `layer ${i}: CLI ${fromCli[i]}°, JS ${js[i]}°`);
  }
  assert.deepEqual(fromCli.slice(0, 3), [0, 0.72, 1.44], 'no direction added, 0.12 mm layers');

  // The language server: the hover on the key lists the first layers' angles, and each
  // instruction's inlay hint is the angle of the first layer it governs.
  const c = client(lsp);
  try {
    await c.request('initialize', { processId: null, rootUri: null, capabilities: {} });
    c.notify('initialized', {});
    const uri = pathToFileURL(path).href;
    c.notify('textDocument/didOpen', { textDocument: { uri, languageId: 'json', version: 1, text: PRESET } });
    const hover = await c.request('textDocument/hover', { textDocument: { uri }, position: { line: 4, character: 5 } });
    const text = JSON.stringify(hover.result.contents);
    const listed = /First (\d+) layers: ([^…]*)…/.exec(text);
    assert.ok(listed, text);
    const angles = [...listed[2].matchAll(/(-?[\d.]+)°(?: \([^)]*\))?/g)].map((m) => Number(m[1]));
    assert.equal(angles.length, Number(listed[1]), text);
    angles.forEach((a, i) => assert.ok(Math.abs(a - js[i]) < 0.006, `hover layer ${i}: ${a}°, JS ${js[i]}°`));
    assert.match(text, new RegExp(`over all ${js.length} layers`));

    const hints = await c.request('textDocument/inlayHint', {
      textDocument: { uri },
      range: { start: { line: 0, character: 0 }, end: { line: 6, character: 0 } },
    });
    // Each instruction's first run in the CLI's layers: its angles and length.
    const runs = [];
    out.layers.forEach((l, i) => {
      const prev = out.layers[i - 1];
      if (i === 0 || l.instruction.start !== prev.instruction.start) runs.push({ start: l.instruction.start, angles: [] });
      runs[runs.length - 1].angles.push(l.angle);
    });
    const firstRuns = runs.filter((r, i) => runs.findIndex((q) => q.start === r.start) === i);
    assert.equal(hints.result.length, firstRuns.length, JSON.stringify(hints.result));
    hints.result.forEach((h, i) => {
      const run = firstRuns[i].angles;
      const near = (a, b) => Math.abs(a - b) < 0.006;
      // `0° for 1 layer`, or a turn: `0°→30° over 42 layers` (ending on the run's last layer).
      const turn = /^(-?[\d.]+)°→(-?[\d.]+)° over (\d+) layers?/.exec(h.label);
      const hold = /^(-?[\d.]+)° for (\d+) layers?/.exec(h.label);
      assert.ok(turn || hold, h.label);
      if (turn) {
        assert.ok(near(Number(turn[2]), run[run.length - 1]) && Number(turn[3]) === run.length, `${h.label}: CLI ${run}`);
      } else {
        assert.ok(near(Number(hold[1]), run[0]) && Number(hold[2]) === run.length, `${h.label}: CLI ${run}`);
      }
    });
  } finally {
    await c.request('shutdown', null).catch(() => {});
    c.close();
  }
});
