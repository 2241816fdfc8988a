// Builds rotlang.wasm and rotlang-full.wasm: cargo with the `wasm` profile (opt-level "z", LTO, strip), then
// wasm-opt -Oz from the `binaryen` npm package (a devDependency: `npm ci` here first; left
// out with a warning when missing), then copies the module beside rotlang.js. Honours
// CARGO_TARGET_DIR (tests share the workspace's target/). The optimised module is cached
// by the hash of cargo's output, so a second build with nothing changed costs nothing.
// `--deny-warnings` (the Node test passes it): fail when cargo warns (cargo replays a
// fresh crate's warnings, so a cached build still reports them). The sizes in README.md
// and ../../web/README.md (between `<!-- sizes -->` markers) are rewritten from the
// modules built, so the documentation cannot go stale.
import { execFileSync, spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { copyFileSync, existsSync, readFileSync, renameSync, statSync, writeFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
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
// rotlang-full.wasm (feature `full`, `rotlang/full`: profile reading, previews and meshes for the playground).
// Cargo keeps both builds; only the final copy differs.
const outDir = join(targetDir, 'wasm32-unknown-unknown', 'wasm');
// binaryen from this package's devDependencies, or from the caller's (the playground's).
const wasmOpt = [here, process.cwd()]
  .map((d) => join(d, 'node_modules', 'binaryen', 'bin', 'wasm-opt'))
  .find(existsSync);
if (!wasmOpt) {
  console.error('build.mjs: binaryen is not installed (npm ci in bindings/js or web): the modules are not run through wasm-opt');
}

const denyWarnings = process.argv.includes('--deny-warnings');
const warnings = [];

function build(features, name) {
  const cargo = spawnSync('cargo', [
    'build', '--profile', 'wasm', '--target', 'wasm32-unknown-unknown', '-p', 'rotlang-wasm',
    ...(features ? ['--features', features] : []),
  ], {
    cwd: root,
    stdio: ['ignore', 'inherit', 'pipe'],
    encoding: 'utf8',
    env: { ...process.env, CARGO_TARGET_DIR: targetDir },
  });
  process.stderr.write(cargo.stderr ?? '');
  if (cargo.status !== 0) throw new Error(`cargo build (${name}) failed: ${cargo.error?.message ?? `exit ${cargo.status}`}`);
  for (const m of (cargo.stderr ?? '').matchAll(/^warning: (?!`).*$/gm)) warnings.push(`${name}: ${m[0]}`);
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
  const size = statSync(out).size;
  console.error(`${name}: ${size} bytes (cargo: ${statSync(built).size})`);
  return { size, cargo: statSync(built).size, gzip: gzipSync(readFileSync(out), { level: 9 }).length, optimised: source !== built };
}

const core = build(null, 'rotlang.wasm');
const full = build('full', 'rotlang-full.wasm');
if (warnings.length) {
  console.error(`build.mjs: cargo warned:\n${warnings.join('\n')}`);
  if (denyWarnings) process.exit(1);
}

// The documented sizes, from this build (only when wasm-opt ran: those are the shipped sizes).
const kb = (n) => `${Math.round(n / 1024)} KB`;
const bytes = (n) => n.toLocaleString('en');
const SIZES = {
  [join(here, 'README.md')]: `\`rotlang.wasm\` is ${kb(core.size)} (${bytes(core.size)} bytes, ${kb(core.gzip)} gzipped)
with everything above, under the 320 KB budget: the \`wasm\` cargo profile (opt-level "z",
LTO, one codegen unit, strip, panic=abort) gives ${kb(core.cargo)}, and \`wasm-opt -Oz\` from the
\`binaryen\` npm package takes off another ${Math.round((1 - core.size / core.cargo) * 100)}%. \`rotlang-full.wasm\` is
${kb(full.size)} (${bytes(full.size)} bytes, ${kb(full.gzip)} gzipped): profile reading, the infill
preview, the chart and meshes (the STL, OBJ and 3MF readers with 3MF's zip, deflate and XML,
and the slicer: about 180 KB of it) are what does not fit in the budget.`,
  [join(root, 'web', 'README.md')]: `${kb(full.size)}, ${kb(full.gzip)} gzipped`,
};
if (core.optimised && full.optimised) {
  for (const [file, text] of Object.entries(SIZES)) {
    if (!existsSync(file)) continue;
    const old = readFileSync(file, 'utf8');
    const updated = old.replace(/(<!-- sizes -->)[^]*?(<!-- \/sizes -->)/, (_, a, b) => `${a}${text}${b}`);
    if (updated !== old) writeFileSync(file, updated);
  }
}
