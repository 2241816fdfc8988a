// The conformance corpus through the JS API: every exact case's angles and fills, and the
// random cases' bounds and seeds.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { expand, FILLS } from '../rotlang.js';
import { jsonl, models, sameDirection, within } from './corpus.js';

test('exact cases: every layer angle and fill', () => {
  const cases = jsonl('cases.jsonl');
  assert.ok(cases.length >= 1000, `only ${cases.length} cases read`);
  const failures = [];
  for (const c of cases) {
    const model = models[c.model];
    const got = expand(c.template, { model });
    assert.equal(got.angles.length, c.degrees.length, `${c.template} on ${c.model}: layer count`);
    for (let i = 0; i < c.degrees.length; i++) {
      if (!sameDirection(got.angles[i], c.degrees[i])) {
        failures.push(`${JSON.stringify(c.template)} on ${c.model} layer ${i}: ${got.angles[i]} != ${c.degrees[i]}`);
        break;
      }
      const fill = c.fills ? c.fills[i] : 'sparse';
      if (FILLS[got.fills[i]] !== fill) {
        failures.push(`${JSON.stringify(c.template)} on ${c.model} layer ${i}: fill ${FILLS[got.fills[i]]} != ${fill}`);
        break;
      }
    }
  }
  assert.deepEqual(failures.slice(0, 10), [], `${failures.length} of ${cases.length} cases fail`);
});

test('random cases: bounds, same seed same angles, another seed changes a layer', () => {
  const cases = jsonl('cases-random.jsonl');
  assert.ok(cases.length > 0);
  let changed = 0;
  let random = 0;
  for (const c of cases) {
    const model = models[c.model];
    const a = expand(c.template, { model, seed: 7 });
    const b = expand(c.template, { model, seed: 7 });
    assert.deepEqual(a.angles, b.angles, `${c.template}: same seed, same angles`);
    for (let i = 0; i < c.min_degrees.length; i++) {
      assert.ok(within(a.angles[i], c.min_degrees[i], c.max_degrees[i]),
        `${c.template} on ${c.model} layer ${i}: ${a.angles[i]} outside [${c.min_degrees[i]}, ${c.max_degrees[i]}]`);
    }
    if (c.min_degrees.some((m, i) => m < c.max_degrees[i])) {
      random++;
      const other = expand(c.template, { model, seed: 8 });
      if (other.angles.some((x, i) => x !== a.angles[i])) changed++;
    }
  }
  assert.ok(random > 0);
  assert.equal(changed, random, 'every case with a random layer changes with the seed');
});

test('a layer range equals the same slice of the whole', () => {
  const model = models.adaptive;
  const whole = expand('+10L25%, -10l25%, #14, +15R', { model });
  const part = expand('+10L25%, -10l25%, #14, +15R', { model, from: 40, to: 77 });
  assert.equal(part.from, 40);
  assert.equal(part.to, 77);
  assert.deepEqual(part.angles, whole.angles.slice(40, 77));
  assert.deepEqual(part.fills, whole.fills.slice(40, 77));
});
