// The bindings' agreement table (bindings/agreement/cases.json): JavaScript gives exactly
// the angles, the error kind and the message that the table (and so the C ABI and
// Python, whose suites run the same table) gives. Option names are the table's snake
// case turned into this API's camelCase, and back in the messages.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { expand, RotlangError } from '../rotlang.js';

const table = JSON.parse(readFileSync(new URL('../../agreement/cases.json', import.meta.url), 'utf8'));
const NUMBERS = { NaN, inf: Infinity, '-inf': -Infinity };
const num = (v) => (typeof v === 'string' && v in NUMBERS ? NUMBERS[v] : v);
const camel = (name) => name.replace(/_(.)/g, (_, c) => c.toUpperCase());
const MODEL_NAMES = ['layers', 'height', 'layer_height', 'first_layer_height', 'bottom_shells', 'top_shells'];

function options(c) {
  const o = {};
  for (const key of ['base', 'seed', 'dialect', 'target']) if (key in c) o[key] = num(c[key]);
  if (c.model) {
    o.model = {};
    for (const key of MODEL_NAMES) if (key in c.model) o.model[camel(key)] = num(c.model[key]);
    if (c.model.heights) o.model.layerHeights = c.model.heights.map(num);
  }
  return o;
}

// `bottomShells` in a message is the table's `bottom_shells`.
const snakeNames = (message) => MODEL_NAMES.reduce((m, n) => m.replaceAll(`\`${camel(n)}\``, `\`${n}\``), message);

const cases = table.cases.filter((c) => !c.only || c.only.includes('js'));

test('the table has the cases every binding runs', () => {
  assert.ok(cases.length >= 30, `${cases.length}`);
});

for (const c of cases) {
  test(`agreement: ${c.name}`, () => {
    const { expect } = c;
    if ('error' in expect) {
      assert.throws(() => expand(c.template, options(c)), (e) => {
        assert.ok(e instanceof RotlangError);
        assert.equal(e.kind, expect.error);
        if (expect.error !== 'template') assert.equal(snakeNames(e.message), expect.js_message ?? expect.message);
        return true;
      });
    } else {
      const angles = [...expand(c.template, options(c)).angles];
      assert.equal(angles.length, expect.count);
      assert.deepEqual(angles.slice(0, expect.head.length), expect.head);
      assert.equal(angles.at(-1), expect.last);
    }
  });
}

// The profile table: readProfile (rotlang/full) shows what Python's read_profile shows.
const profiles = JSON.parse(readFileSync(new URL('../../agreement/profiles.json', import.meta.url), 'utf8'));

for (const c of profiles.cases) {
  test(`profile agreement: ${c.name}`, async () => {
    const { readProfile } = await import('../full.js');
    const content = c.bytes ? new Uint8Array(c.bytes) : c.content;
    const { expect } = c;
    if ('error' in expect) {
      assert.throws(() => readProfile(c.file, content), (e) => e instanceof RotlangError
        && e.kind === expect.error && e.message === expect.message);
      return;
    }
    const p = readProfile(c.file, content);
    const m = p.model;
    assert.deepEqual({
      kind: p.kind,
      templates: p.templates.map((t) => [t.key, t.target, t.text, t.base]),
      model: {
        layers: m.layers, layer_height: m.layerHeight, first_layer_height: m.firstLayerHeight,
        bottom_shells: m.bottomShells, top_shells: m.topShells,
      },
      base: p.base,
      has_errors: p.hasErrors,
    }, expect);
  });
}
