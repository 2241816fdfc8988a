// Hostile input: JS exceptions carrying the reason, never a crash, and the module keeps
// working afterwards.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { check, expand, format, RotlangError } from '../rotlang.js';

const isError = (kind) => (e) => e instanceof RotlangError && e.kind === kind && e.message.length > 0;

test('a 1 MB template checks, formats and expands', () => {
  const big = '+10L25%, -10l25%, '.repeat(1 << 16);
  assert.ok(big.length > 1_000_000);
  const r = check(big);
  assert.equal(r.hasErrors, false);
  assert.equal(format(big).length, big.length - 2);
  const e = expand(big, { model: { layers: 1000 } });
  assert.equal(e.angles.length, 1000);
  assert.ok(e.angles.every(Number.isFinite));
});

test('a 1 MB template full of errors: capped diagnostics, then an exception from expand', () => {
  const bad = '+30X5, '.repeat(150_000);
  const r = check(bad);
  assert.equal(r.hasErrors, true);
  assert.ok(r.diagnostics.length <= 101);
  assert.ok(r.omitted > 0);
  assert.throws(() => expand(bad), isError('template'));
});

test('bad models throw model errors', () => {
  const bad = [
    { layers: -1 }, { layers: 0 }, { layers: 1.5 }, { layers: 1e12 }, { layers: NaN },
    { layers: 10, layerHeight: 0 }, { layers: 10, layerHeight: -0.2 }, { layers: 10, layerHeight: Infinity },
    { layers: 10, firstLayerHeight: 1e9 }, { height: -5 }, { layerHeights: [] },
    { layerHeights: [0.2, NaN] }, { layerHeights: [0.2, -1] }, { layerHeights: 'abc' },
    { layers: '10' }, { layers: 10, bottomShells: -1 }, { layers: 10, unknown: 1 }, 'cube',
  ];
  for (const model of bad) {
    assert.throws(() => expand('0, 90', { model }), isError('model'), JSON.stringify(model));
  }
});

test('bad options and arguments throw option errors', () => {
  assert.throws(() => check(42), isError('options'));
  assert.throws(() => check(null), isError('options'));
  assert.throws(() => check('0', { target: 'floor' }), isError('options'));
  assert.throws(() => check('0', 'x'), isError('options'));
  assert.throws(() => expand('0', { base: NaN }), isError('options'));
  assert.throws(() => expand('0', { seed: -1 }), isError('options'));
  assert.throws(() => expand('0', { from: 50, to: 10 }), isError('options'));
  assert.throws(() => expand('0', { colour: 'red' }), isError('options'));
});

test('a base beyond ±1e9 and a seed beyond 2^53 are refused in both dialects, as C and Python refuse them', () => {
  for (const dialect of ['rotlang', 'orcaslicer']) {
    for (const base of [2e300, -2e300, 1e9 + 1]) {
      assert.throws(() => expand('0, 90', { base, dialect }), (e) => isError('options')(e)
        && e.message.startsWith('`base` must be a finite number of degrees within ±1000000000, not '), `${dialect} ${base}`);
    }
    assert.deepEqual([...expand('0, 90', { base: -1e9, dialect, model: { layers: 2 } }).angles], [-1e9, -1e9 + 90]);
    assert.throws(() => expand('0', { seed: 2 ** 53, dialect }),
      (e) => isError('options')(e) && e.message === '`seed` must be a whole number from 0 to 9007199254740991, not 9007199254740992');
  }
  assert.throws(() => expand('0', { model: { layers: 10, topShells: 2 ** 40 } }),
    (e) => isError('model')(e) && e.message === '`topShells` must be a whole number from 0 to 4294967295, not 1099511627776');
});

test('a hundred million layers is refused at once, a range of them works', () => {
  assert.throws(() => expand('+1', { model: { layers: 1e8 } }), isError('limit'));
  const r = expand('+1', { model: { layers: 1e7 + 3 }, from: 1e7 });
  assert.deepEqual([...r.angles], [1e7 + 1, 1e7 + 2, 1e7 + 3]);
});

test('lone surrogates and control characters are data, not crashes', () => {
  for (const text of ['\ud800', '+30\udfff', '\u0000\u0001, 90', '𝕏'.repeat(1000), '"', '*'.repeat(100_000)]) {
    const r = check(text);
    assert.ok(Array.isArray(r.diagnostics));
    for (const d of r.diagnostics) assert.ok(d.endUtf16 <= text.length);
  }
  assert.equal(check('0, 90').hasErrors, false, 'still working afterwards');
});
