// The .d.ts declares every export of rotlang.js, and nothing that is not there.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as rotlang from '../rotlang.js';

test('rotlang.d.ts and rotlang.js export the same names', () => {
  const dts = readFileSync(new URL('../rotlang.d.ts', import.meta.url), 'utf8');
  const declared = new Set([...dts.matchAll(/^export (?:declare )?(?:function|const|class) (\w+)/gm)].map((m) => m[1]));
  assert.deepEqual([...declared].sort(), Object.keys(rotlang).sort());
});

test('full.d.ts declares what full.js adds to rotlang.js', async () => {
  const full = await import('../full.js');
  const core = Object.keys(rotlang);
  const dts = readFileSync(new URL('../full.d.ts', import.meta.url), 'utf8');
  const declared = [...dts.matchAll(/^export (?:declare )?(?:function|const|class) (\w+)/gm)].map((m) => m[1]);
  assert.deepEqual([...core, ...declared].sort(), Object.keys(full).sort());
});
