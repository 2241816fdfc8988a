// Polyslice and rotlang's infill side by side on the same five shapes, patterns and
// densities: speed, printed density, largest gap, violations and rotation. Prints a
// markdown table (RESULTS.md is its output).
//
//   ./setup.sh                      # once: Polyslice from its pinned source into vendor/
//   node compare.mjs [--divan FILE] # FILE: the output of `cargo bench --bench infill -- compare`
//
// Without --divan the rotlang times are measured by running that bench (a minute).
// rotlang's paths come from `rotlang preview --format json` (target/release/rotlang, or
// $ROTLANG), layer 40 (no shell), template `45` (Polyslice's grid runs at ±45°).
import { createRequire } from 'node:module';
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { W, measure, parseGcode, polygonRegion } from './measure.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = join(here, '..', '..', '..', '..');
const require = createRequire(import.meta.url);
const Polyslice = require('@jgphilpott/polyslice/src/index.js');
const infill = require('@jgphilpott/polyslice/src/slicer/infill/infill.js');

const Z = 8.1; // layer 40's middle, as rotlang's layer 40
const PATTERNS = ['grid', 'triangles', 'hexagons', 'concentric', 'gyroid', 'spiral', 'lightning'];
const DENSITIES = [10, 20, 40];
// The shapes of rotlang::infill::shapes, in the order of crates/rotlang-geometry/benches/infill.rs's consts.
const regular = (n, r, cw) =>
  Array.from({ length: n }, (_, i) => {
    const a = ((2 * Math.PI * i) / n) * (cw ? -1 : 1);
    return [r * Math.cos(a), r * Math.sin(a)];
  });
const SHAPES = {
  square20: [[[-10, -10], [10, -10], [10, 10], [-10, 10]]],
  circle10: [regular(64, 10, false)],
  holed40: [[[-20, -20], [20, -20], [20, 20], [-20, 20]], regular(64, 10, true)],
  star10: [
    Array.from({ length: 10 }, (_, i) => {
      const r = i % 2 === 0 ? 10 : 4.5;
      const a = (2 * Math.PI * i) / 10 + Math.PI / 2;
      return [r * Math.cos(a), r * Math.sin(a)];
    }),
  ],
  l20: [[[-10, -10], [10, -10], [10, 0], [0, 0], [0, 10], [-10, 10]]],
};
const SHAPE_INDEX = { square20: 0, circle10: 1, holed40: 2, star10: 3, l20: 4 };

const args = process.argv.slice(2);
const divanFile = args.includes('--divan') ? args[args.indexOf('--divan') + 1] : null;
const rotlangBin = process.env.ROTLANG || join(root, 'target', 'release', 'rotlang');
const out = join(here, 'out');
mkdirSync(out, { recursive: true });

// ---------- Polyslice ----------

const slicer = new Polyslice();
slicer.setNozzleDiameter(W);
slicer.setVerbose(false);
const pt = ([x, y]) => ({ x, y });

function runPolyslice(rings, pattern, density) {
  slicer.setInfillDensity(density);
  slicer.setInfillPattern(pattern);
  const boundary = rings[0].map(pt);
  const holes = rings.slice(1).map((r) => r.map(pt));
  const once = () => {
    slicer.gcode = '';
    slicer.cumulativeE = 0;
    infill.generateInfillGCode(slicer, boundary, Z, 0, 0, 25, null, holes, holes);
    return slicer.gcode;
  };
  for (let i = 0; i < 5; i++) once();
  const times = [];
  const start = process.hrtime.bigint();
  while (times.length < 7 || (times.length < 2000 && process.hrtime.bigint() - start < 300_000_000n)) {
    const t0 = process.hrtime.bigint();
    once();
    times.push(Number(process.hrtime.bigint() - t0) / 1e3);
  }
  times.sort((a, b) => a - b);
  return { us: times[times.length >> 1], paths: parseGcode(once()) };
}

// ---------- rotlang ----------

function runRotlang(name, pattern, density) {
  const file = join(out, `${name}.json`);
  writeFileSync(file, JSON.stringify([SHAPES[name].map((r) => [...r, r[0]])]));
  const json = execFileSync(rotlangBin, [
    'preview', '--shape', file, '--pattern', pattern, '--density', String(density),
    '--nozzle', String(W), '--format', 'json', '--layers', '40..41', '--', '45',
  ], { maxBuffer: 1 << 28 });
  return JSON.parse(json).layers[0].polylines;
}

/// rotlang's median time per layer (µs) by shape and `pattern density`, from divan's tree.
function rotlangTimes() {
  const text = divanFile
    ? readFileSync(divanFile, 'utf8')
    : execFileSync('cargo', ['bench', '--bench', 'infill', '--', 'compare'], {
        cwd: root, encoding: 'utf8', maxBuffer: 1 << 26,
      });
  const units = { ns: 1e-3, 'µs': 1, us: 1, ms: 1e3, s: 1e6 };
  const times = {};
  let shape = null;
  for (const line of text.split('\n')) {
    const c = /[├╰]─ (\d+)\s+│/.exec(line);
    if (c) shape = +c[1];
    // Columns: fastest │ slowest │ median │ mean.
    const m = /[├╰]─ (\w+) (\d+)\s+(.*)$/.exec(line);
    if (m && shape !== null) {
      const cols = m[3].split('│').map((s) => s.trim());
      const [v, u] = cols[2].split(/\s+/);
      times[`${shape} ${m[1]} ${m[2]}`] = +v * units[u];
    }
  }
  return times;
}

// ---------- table ----------

const times = rotlangTimes();
if (args.includes("--times")) { console.log(times); process.exit(0); }
const rows = [];
const f = (v, d = 2) => (Number.isFinite(v) ? v.toFixed(d) : '—');
const straight = new Set(['grid', 'triangles', 'hexagons']);
console.log('| shape | pattern | asked | Polyslice µs | rotlang µs | speed-up | density P / r | largest gap mm P / r | outside region mm P / r | in wall band mm P / r | direction° P / r |');
console.log('|---|---|---|---|---|---|---|---|---|---|---|');
for (const name of Object.keys(SHAPES))
  for (const pattern of PATTERNS)
    for (const density of DENSITIES) {
      const p = runPolyslice(SHAPES[name], pattern, density);
      const r = runRotlang(name, pattern, density);
      const region = polygonRegion(SHAPES[name]);
      const mp = measure(region, p.paths), mr = measure(region, r);
      const rt = times[`${SHAPE_INDEX[name]} ${pattern} ${density}`];
      const speed = p.us / rt;
      rows.push({ name, pattern, density, speed });
      const dir = (m) => (straight.has(pattern) ? String(m.rotation) : '—');
      console.log(
        `| ${name} | ${pattern} | ${density}% | ${f(p.us, 1)} | ${f(rt, 2)} | ${f(speed, 1)}× | ` +
          `${f(mp.density * 100, 1)}% / ${f(mr.density * 100, 1)}% | ${f(mp.gap)} / ${f(mr.gap)} | ` +
          `${f(mp.outside)} / ${f(mr.outside)} | ${f(mp.wall)} / ${f(mr.wall)} | ${dir(mp)} / ${dir(mr)} |`,
      );
    }
const slow = rows.filter((r) => !(r.speed >= 10));
console.log(`\n${rows.length - slow.length} of ${rows.length} pairs at ≥ 10×` +
  (slow.length ? `; below: ${slow.map((r) => `${r.name} ${r.pattern} ${r.density}% (${f(r.speed, 1)}×)`).join(', ')}` : '.'));
