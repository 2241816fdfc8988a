// Builds rotlang.wasm: cargo with the `wasm` profile (opt-level "z", LTO, strip), then
// copies the module beside rotlang.js. Honours CARGO_TARGET_DIR (tests share the
// workspace's target/). Usage: node build.mjs [--features infill]
import { execFileSync } from 'node:child_process';
import { copyFileSync, renameSync, statSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../..');
const targetDir = process.env.CARGO_TARGET_DIR
  ? resolve(root, process.env.CARGO_TARGET_DIR)
  : join(root, 'target');
const args = [
  'build', '--profile', 'wasm', '--target', 'wasm32-unknown-unknown', '-p', 'rotlang-wasm',
  ...process.argv.slice(2),
];
execFileSync('cargo', args, {
  cwd: root,
  stdio: ['ignore', 'inherit', 'inherit'],
  env: { ...process.env, CARGO_TARGET_DIR: targetDir },
});
const built = join(targetDir, 'wasm32-unknown-unknown', 'wasm', 'rotlang_wasm.wasm');
const out = join(here, 'rotlang.wasm');
// Copy then rename: tests that build at the same time never read half a file.
const tmp = `${out}.${process.pid}.tmp`;
copyFileSync(built, tmp);
renameSync(tmp, out);
console.error(`rotlang.wasm: ${statSync(out).size} bytes`);
