// The OrcaSlicer dialect through the JS API: the corpus's `orcaslicer` angles and findings
// on every case, and OrcaSlicer's own angles on the 6,300 texts of dialect-text.jsonl.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { compare, expand } from '../rotlang.js';
import { jsonl, models, sameDirection } from './corpus.js';

// Checks one case; returns a failure message or null.
function run(template, model, o, rotlangDegrees) {
  const r = expand(template, { model, dialect: 'orcaslicer' });
  if (!r.angles.every(Number.isFinite)) return 'an angle is not finite';
  const codes = r.findings.map((f) => f.code).sort();
  const expected = o.status === 'same' ? rotlangDegrees : o.degrees;
  const want = { same: [], differs: [], ok: [], nan: ['orcaslicer::nan'], hangs: ['orcaslicer::hangs'], undefined: ['orcaslicer::undefined'] }[o.status];
  const got = o.status === 'undefined' ? codes.filter((c) => c !== 'orcaslicer::nan') : codes;
  if (JSON.stringify(got) !== JSON.stringify(want)) return `findings ${codes} for status ${o.status}`;
  if (o.status === 'hangs' && r.findings.find((f) => f.code === 'orcaslicer::hangs').firstLayer !== o.layer) {
    return `hang reported at ${r.findings[0].firstLayer}, expected ${o.layer}`;
  }
  if (expected) {
    if (expected.length !== r.angles.length) return `${r.angles.length} layers, expected ${expected.length}`;
    let nulls = 0;
    for (let i = 0; i < expected.length; i++) {
      if (expected[i] === null) { nulls++; continue; }
      if (!sameDirection(r.angles[i], expected[i])) return `layer ${i}: ${r.angles[i]} != ${expected[i]}`;
    }
    const nan = r.findings.find((f) => f.code === 'orcaslicer::nan');
    if (nulls && nan?.layers !== nulls) return `${nulls} NaN layers, reported ${nan?.layers}`;
  }
  return null;
}

test('cases.jsonl: OrcaSlicer angles and findings', () => {
  const failures = [];
  const cases = jsonl('cases.jsonl');
  for (const c of cases) {
    const f = run(c.template, models[c.model], c.orcaslicer, c.degrees);
    if (f) failures.push(`${JSON.stringify(c.template)} on ${c.model}: ${f}`);
  }
  assert.deepEqual(failures.slice(0, 10), [], `${failures.length} of ${cases.length} fail`);
});

test('dialect-text.jsonl: OrcaSlicer angles on any text', () => {
  const failures = [];
  const cases = jsonl('dialect-text.jsonl');
  assert.ok(cases.length > 6000);
  for (const c of cases) {
    const m = c.model;
    const model = { layers: m.layers, layerHeight: m.layer_height, firstLayerHeight: m.first_layer_height, bottomShells: m.bottom_shell_layers, topShells: m.top_shell_layers };
    const f = run(c.template, model, c.orcaslicer, null);
    if (f) failures.push(`${JSON.stringify(c.template)}: ${f}`);
  }
  assert.deepEqual(failures.slice(0, 10), [], `${failures.length} of ${cases.length} fail`);
});

test('compare: where OrcaSlicer parts from rotlang', () => {
  assert.equal(compare('+30/50%').firstDifference, null);
  const spaces = compare('0 90'); // OrcaSlicer reads a space-separated list as its first number
  assert.equal(spaces.firstDifference.layer, 1);
  assert.equal(spaces.firstDifference.rotlang, 90);
  assert.equal(spaces.firstDifference.orcaslicer, 0);
  assert.equal(compare('0, 90S').solidLayersLost, 50);
  const hang = compare('10!, 5*');
  assert.equal(hang.findings[0].code, 'orcaslicer::hangs');
  assert.equal(compare('+30X5').rotlangErrors, true);
});

test('the OrcaSlicer dialect reads text that rotlang rejects, and names its instructions', () => {
  const r = expand('+30X5', { dialect: 'orcaslicer', model: { layers: 3 } });
  assert.equal(r.dialect, 'orcaslicer');
  assert.equal(r.angles.length, 3);
  for (const i of r.instructionIndex) assert.ok(i < r.instructions.length);
  assert.throws(() => expand('0', { dialect: 'prusa' }), (e) => e.kind === 'options' && /unknown dialect/.test(e.message));
});
