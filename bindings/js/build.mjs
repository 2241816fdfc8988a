// Builds rotlang.wasm and rotlang-full.wasm: cargo with the `wasm` profile (opt-level "z", LTO, strip), then
// wasm-opt -Oz from the `binaryen` npm package (a devDependency: `npm ci` here first; left
// out with a warning when missing), then copies the module beside rotlang.js. Honours
// CARGO_TARGET_DIR (tests share the workspace's target/). The optimised module is cached
// by the hash of cargo's output, so a second build with nothing changed costs nothing.
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { copyFileSync, existsSync, readFileSync, renameSync, statSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../..');
const targetDir = process.env.CARGO_TARGET_DIR
  ? resolve(root, process.env.CARGO_TARGET_DIR)
  : join(root, 'target');
// The wasm target (rustup's), added when missing, as scripts/ensure does for the tests.
try {
  const installed = execFileSync('rustup', ['target', 'list', '--installed'], { encoding: 'utf8' });
  if (!installed.split('\n').includes('wasm32-unknown-unknown')) {
    console.error('build.mjs: rustup target add wasm32-unknown-unknown');
    execFileSync('rustup', ['target', 'add', 'wasm32-unknown-unknown'], { stdio: 'inherit' });
  }
} catch (e) {
  if (e.code !== 'ENOENT') throw e; // no rustup: let cargo say what is missing
}
// Two modules from one crate: rotlang.wasm (the package's core, `rotlang`) and
// rotlang-full.wasm (feature `full`, `rotlang/full`: profile reading for the playground).
// Cargo keeps both builds; only the final copy differs.
const outDir = join(targetDir, 'wasm32-unknown-unknown', 'wasm');
// binaryen from this package's devDependencies, or from the caller's (the playground's).
const wasmOpt = [here, process.cwd()]
  .map((d) => join(d, 'node_modules', 'binaryen', 'bin', 'wasm-opt'))
  .find(existsSync);
if (!wasmOpt) {
  console.error('build.mjs: binaryen is not installed (npm ci in bindings/js or web): the modules are not run through wasm-opt');
}

function build(features, name) {
  execFileSync('cargo', [
    'build', '--profile', 'wasm', '--target', 'wasm32-unknown-unknown', '-p', 'rotlang-wasm',
    ...(features ? ['--features', features] : []),
  ], {
    cwd: root,
    stdio: ['ignore', 'inherit', 'inherit'],
    env: { ...process.env, CARGO_TARGET_DIR: targetDir },
  });
  const built = join(outDir, 'rotlang_wasm.wasm');
  const hash = createHash('sha256').update(readFileSync(built)).digest('hex').slice(0, 16);
  const optimised = join(outDir, `rotlang_wasm.opt-${hash}.wasm`);
  let source = built;
  if (existsSync(optimised)) {
    source = optimised;
  } else if (wasmOpt) {
    const tmp = `${optimised}.${process.pid}.tmp`;
    // The features rustc enables by default for wasm32-unknown-unknown.
    execFileSync(process.execPath, [
      wasmOpt, '-Oz', '--strip-debug', '--strip-producers',
      '--enable-bulk-memory', '--enable-sign-ext', '--enable-mutable-globals',
      '--enable-nontrapping-float-to-int', '--enable-multivalue', '--enable-reference-types',
      built, '-o', tmp,
    ], { stdio: ['ignore', 'inherit', 'inherit'] });
    renameSync(tmp, optimised);
    source = optimised;
  }
  const out = join(here, name);
  // Copy then rename: tests that build at the same time never read half a file.
  const tmp = `${out}.${process.pid}.tmp`;
  copyFileSync(source, tmp);
  renameSync(tmp, out);
  console.error(`${name}: ${statSync(out).size} bytes (cargo: ${statSync(built).size})`);
}

build(null, 'rotlang.wasm');
build('full', 'rotlang-full.wasm');
