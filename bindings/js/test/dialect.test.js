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

test('compat: OrcaSlicer findings as diagnostics with spans', async () => {
  const { compat } = await import('../rotlang.js');
  const list = compat('0 90');
  assert.ok(list.length > 0);
  assert.ok(list.every((d) => d.code.startsWith('orcaslicer::')), list.map((d) => d.code).join());
  assert.ok(list.some((d) => d.fix), 'a fix keeps both readings');
  assert.deepEqual(compat('+30/50%'), []);
});

test('readProfile: templates and model from JSON, jsonc and ini; broken input is an error', async () => {
  const { readProfile, RotlangError } = await import('../full.js');
  const p = readProfile('pla.json', JSON.stringify({
    layer_height: '0.16', initial_layer_print_height: '0.24', bottom_shell_layers: '5',
    top_shell_layers: '6', sparse_infill_rotate_template: '+10L25%', infill_direction: '45',
  }));
  assert.equal(p.kind, 'json');
  assert.deepEqual(p.templates.map((t) => [t.key, t.target, t.text]), [['sparse_infill_rotate_template', 'sparse', '+10L25%']]);
  assert.equal(p.model.layerHeight, 0.16);
  assert.equal(p.model.firstLayerHeight, 0.24);
  assert.equal(p.model.bottomShells, 5);
  assert.equal(p.model.topShells, 6);
  assert.equal(p.base, 45);
  const ini = readProfile('config.ini', 'layer_height = 0.2\nsolid_infill_rotate_template = 0, 90\n');
  assert.deepEqual(ini.templates.map((t) => [t.target, t.text]), [['solid', '0, 90']]);
  const jsonc = readProfile('p.jsonc', '{ // comment\n "sparse_infill_rotate_template": "0, 90", }');
  assert.equal(jsonc.templates[0].text, '0, 90');
  assert.throws(() => readProfile('x.json', new Uint8Array([0x7b, 0xff, 0xfe])), (e) => e instanceof RotlangError && e.kind === 'profile' && /UTF-8/.test(e.message));
  const broken = readProfile('x.json', 'this is not JSON {');
  assert.equal(broken.templates.length, 0);
  assert.ok(broken.hasErrors || broken.notes.length > 0, JSON.stringify(broken));
});
