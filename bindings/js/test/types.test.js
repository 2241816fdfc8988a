// The .d.ts declares every export of rotlang.js, and nothing that is not there.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
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

// tsc --noEmit through npm (typescript is a locked devDependency) on test/types/usage.ts:
// a declaration that no longer fits its use fails here.
const npm = process.platform === 'win32' ? 'npm.cmd' : 'npm';
const here = fileURLToPath(new URL('..', import.meta.url));
const run = (args) => spawnSync(npm, args, { cwd: here, encoding: 'utf8' });

test('the TypeScript usage example compiles (npm run typecheck)', () => {
  const r = run(['run', '--silent', 'typecheck']);
  assert.equal(r.status, 0, `tsc failed:\n${r.stdout}${r.stderr}`);
});

test('the type check bites: a misuse of the API is a compile error', () => {
  // A project beside usage.ts's, holding one wrong call; removed afterwards.
  const dir = mkdtempSync(join(here, 'test', 'types', 'tmp-'));
  try {
    writeFileSync(join(dir, 'tsconfig.json'), JSON.stringify({ extends: '../tsconfig.json', files: ['bad.ts'] }));
    writeFileSync(join(dir, 'bad.ts'), "import { expand } from 'rotlang';\nconst a: string = expand('0', { model: { layers: '3' } }).angles;\n");
    const r = run(['exec', '--offline', '--', 'tsc', '--noEmit', '-p', dir]);
    assert.notEqual(r.status, 0, 'tsc accepted a wrong call');
    assert.match(r.stdout, /bad\.ts\(2,\d+\): error TS2322/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
