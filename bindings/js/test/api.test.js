// The API's shape: diagnostics with byte and UTF-16 spans, format, expand's typed arrays.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { check, expand, format, version, FILLS, RotlangError } from '../rotlang.js';

test('version is the crate version', () => {
  assert.match(version(), /^\d+\.\d+\.\d+/);
});

test('check: unknown sign X in +30X5, with its span and message', () => {
  const r = check('+30X5');
  assert.equal(r.hasErrors, true);
  const d = r.diagnostics.find((d) => d.code === 'rotlang::unknown-sign');
  assert.ok(d, JSON.stringify(r.diagnostics));
  assert.equal(d.severity, 'error');
  assert.equal('+30X5'.slice(d.startUtf16, d.endUtf16), 'X');
  assert.match(d.message, /X/);
  assert.deepEqual([d.line, d.column], [1, 4]);
});

test('check: each instruction with its byte and UTF-16 span and its text, after a 𝕏 too', () => {
  assert.deepEqual(check('𝕏, +10, -5').instructions, [
    { start: 6, end: 9, startUtf16: 4, endUtf16: 7, text: '+10' },
    { start: 11, end: 13, startUtf16: 9, endUtf16: 11, text: '-5' },
  ]);
  const big = '+10L25%, α, '.repeat(50_000);
  const r = check(big);
  assert.equal(r.instructions.length, 50_000);
  assert.deepEqual(r.instructions.at(-1), {
    start: 49_999 * 13, end: 49_999 * 13 + 7, startUtf16: 49_999 * 12, endUtf16: 49_999 * 12 + 7, text: '+10L25%',
  });
  assert.deepEqual(check('').instructions, []);
});

test('check: the space before % has a fix that gives +30/50%', () => {
  const text = '+30/50 %';
  const d = check(text).diagnostics.find((d) => d.fix);
  assert.ok(d);
  const f = d.fix;
  assert.equal(text.slice(0, f.startUtf16) + f.replacement + text.slice(f.endUtf16), '+30/50%');
  assert.equal(check('+30/50%').diagnostics.length, 0);
});

test('check: UTF-16 offsets differ from bytes after ° α and 𝕏', () => {
  const text = '+30°, α𝕏, 𝕏X';
  const r = check(text);
  assert.ok(r.diagnostics.length > 0);
  const bytes = Buffer.from(text);
  for (const d of r.diagnostics) {
    // Both offset kinds name the same text.
    assert.equal(text.slice(d.startUtf16, d.endUtf16), bytes.subarray(d.start, d.end).toString());
    for (const l of d.labels) {
      assert.equal(text.slice(l.startUtf16, l.endUtf16), bytes.subarray(l.start, l.end).toString());
    }
  }
  assert.ok(r.diagnostics.some((d) => d.start !== d.startUtf16));
});

test('check: solid target rejects solid signs', () => {
  assert.equal(check('+30S').hasErrors, false);
  const r = check('+30S', { target: 'solid' });
  assert.ok(r.diagnostics.some((d) => d.code === 'rotlang::solid-sign-in-solid-template'));
});

test('format: canonical separators; errors throw with diagnostics', () => {
  assert.equal(format('  +10L25%,-10l25%\n\n#5 ,'), '+10L25%, -10l25%, #5');
  assert.throws(() => format('+30X5'), (e) => e instanceof RotlangError && e.kind === 'template'
    && e.diagnostics.some((d) => d.code === 'rotlang::unknown-sign'));
});

test('expand: typed arrays, fills, instruction of each layer', () => {
  const r = expand('5, 10!, +20', { model: { layers: 7, layerHeight: 0.2 } });
  assert.ok(r.angles instanceof Float64Array);
  assert.ok(r.fills instanceof Uint8Array);
  assert.deepEqual([...r.angles], [5, 10, 30, 5, 25, 5, 25]);
  assert.deepEqual([...r.instructionIndex].map((i) => r.instructions[i].text), ['5', '10!', '+20', '5', '+20', '5', '+20']);
  const solid = expand('0, 90S', { model: { layers: 4 } });
  assert.deepEqual([...solid.fills].map((f) => FILLS[f]), ['sparse', 'solid', 'sparse', 'solid']);
});

test('expand: list heights as array or Float64Array, base and seed', () => {
  const a = expand('+90', { model: { layerHeights: [0.3, 0.2, 0.2], layerHeight: 0.2 }, base: 45 });
  assert.deepEqual([...a.angles], [135, 225, 315]);
  const b = expand('+90', { model: { layerHeights: new Float64Array([0.3, 0.2, 0.2]) }, base: 45 });
  assert.deepEqual(b.angles, a.angles);
  assert.equal(a.model.layers, 3);
});

test('explain: the template in words with layer ranges; codes explained', async () => {
  const { explain, explainCode } = await import('../rotlang.js');
  const text = explain('+10L25%, -10l25%', { model: { layers: 100 } });
  assert.match(text, /layers 0–24/);
  const doc = explainCode('rotlang::unknown-sign');
  assert.equal(doc.code, 'rotlang::unknown-sign');
  assert.ok(doc.fix.length > 0 && doc.example.length > 0);
  assert.equal(explainCode('rotlang::no-such-code'), null);
  const r = expand('0, +30/50%');
  assert.equal(r.words.length, 2);
  assert.match(r.words[1], /30/);
});
