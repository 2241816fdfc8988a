// JS `check` on megabyte templates against the native CLI's `check --format json` on the
// same text: `node bench/check.mjs [MEGABYTES]` (after `node build.mjs`; the CLI is
// `../../target/release/rotlang`, or ROTLANG_CLI, built with `cargo build --release`).
// Times are CPU seconds (user + system), the fastest of five runs each, so that other
// work on the machine weighs less than it does on wall-clock times.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { check } from '../rotlang.js';

const size = Math.round(Number(process.argv[2] ?? 1) * 1_000_000);
const cli = process.env.ROTLANG_CLI ?? fileURLToPath(new URL('../../../target/release/rotlang', import.meta.url));
const RUNS = 5;
// Short instructions (the most per megabyte), errors (capped diagnostics), non-ASCII
// text (UTF-16 offsets differ from bytes), one instruction a line.
const KINDS = {
  'valid': '+10L25%, -10l25%, ',
  'errors': '+30X5, +30/50 %, ',
  'unicode': '+30°, α, ',
  'lines': '+30\n',
  'zeros': '0, ',
};

function cpu(f) {
  let best = Infinity;
  let result;
  for (let i = 0; i < RUNS; i++) {
    const t = process.cpuUsage();
    result = f();
    const d = process.cpuUsage(t);
    best = Math.min(best, (d.user + d.system) / 1e6);
  }
  return [best, result];
}

function cliSeconds(file) {
  let best = Infinity;
  for (let i = 0; i < RUNS; i++) {
    const r = spawnSync('/usr/bin/time', ['-f', '%U %S', cli, 'check', '--format', 'json', '--file', file], { encoding: 'utf8', maxBuffer: 1 << 30 });
    const [user, system] = r.stderr.trim().split('\n').at(-1).split(' ').map(Number);
    best = Math.min(best, user + system);
  }
  return best;
}

const haveCli = existsSync(cli) && existsSync('/usr/bin/time');
if (!haveCli) console.log(`no CLI at ${cli} (cargo build --release) or no /usr/bin/time: JS times only`);
const dir = mkdtempSync(join(tmpdir(), 'rotlang-bench-'));
try {
  for (const [kind, unit] of Object.entries(KINDS)) {
    const text = unit.repeat(Math.ceil(size / unit.length)).slice(0, size);
    check(text); // warm-up: the JIT, and wasm memory grown once
    const [js, r] = cpu(() => check(text));
    let line = `${kind.padEnd(8)} ${(text.length / 1e6).toFixed(1)}M UTF-16 units, ${r.instructions.length} instructions, ${r.diagnostics.length} diagnostics: JS check ${js.toFixed(3)} s`;
    if (haveCli) {
      const file = join(dir, `${kind}.rot`);
      writeFileSync(file, text);
      const native = cliSeconds(file);
      line += `, CLI ${native.toFixed(3)} s, ratio ${(js / native).toFixed(2)}`;
    }
    console.log(line);
  }
} finally {
  rmSync(dir, { recursive: true, force: true });
}
