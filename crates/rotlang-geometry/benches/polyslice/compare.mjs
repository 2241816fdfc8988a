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

const here = dirname(fileURLToPath(import.meta.url));
const root = join(here, '..', '..', '..', '..');
const require = createRequire(import.meta.url);
const Polyslice = require('@jgphilpott/polyslice/src/index.js');
const infill = require('@jgphilpott/polyslice/src/slicer/infill/infill.js');

const W = 0.4;
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

/// The extruding moves of G-code as polylines (a move with E extrudes).
function parseGcode(gcode) {
  const paths = [];
  let pos = null;
  let current = null;
  for (const line of gcode.split('\n')) {
    if (!/^G[01]\s/.test(line)) continue;
    const x = /X(-?[\d.]+)/.exec(line);
    const y = /Y(-?[\d.]+)/.exec(line);
    const next = [x ? +x[1] : pos?.[0], y ? +y[1] : pos?.[1]];
    if (next[0] === undefined) continue;
    if (/\sE-?[\d.]/.test(line) && pos) {
      if (!current) {
        current = [pos];
        paths.push(current);
      }
      current.push(next);
    } else {
      current = null;
    }
    pos = next;
  }
  return paths;
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

// ---------- measures ----------

const ringsOf = (name) => SHAPES[name];

function segDist2(p, a, b) {
  const ex = b[0] - a[0], ey = b[1] - a[1];
  const l2 = ex * ex + ey * ey;
  let t = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0;
  t = Math.max(0, Math.min(1, t));
  const dx = p[0] - a[0] - t * ex, dy = p[1] - a[1] - t * ey;
  return dx * dx + dy * dy;
}
function inside(rings, p) {
  let c = false;
  for (const r of rings)
    for (let i = 0, j = r.length - 1; i < r.length; j = i++) {
      const [ax, ay] = r[j], [bx, by] = r[i];
      if ((ay <= p[1]) !== (by <= p[1]) && ax + ((p[1] - ay) * (bx - ax)) / (by - ay) > p[0]) c = !c;
    }
  return c;
}
function boundaryDist(rings, p) {
  let d = Infinity;
  for (const r of rings) for (let i = 0, j = r.length - 1; i < r.length; j = i++) d = Math.min(d, segDist2(p, r[j], r[i]));
  return Math.sqrt(d);
}

// 1-D squared distance transform (lower envelope of parabolas).
function edt1(f, n) {
  const d = new Float64Array(n), v = new Int32Array(n), z = new Float64Array(n + 1);
  let k = 0;
  v[0] = 0; z[0] = -Infinity; z[1] = Infinity;
  for (let q = 1; q < n; q++) {
    if (f[q] === Infinity) continue;
    if (f[v[k]] === Infinity) { v[k] = q; continue; }
    let s;
    for (;;) {
      s = (f[q] + q * q - (f[v[k]] + v[k] * v[k])) / (2 * q - 2 * v[k]);
      if (s <= z[k] && k > 0) k--; else break;
    }
    if (s <= z[k]) { v[k] = q; continue; }
    k++; v[k] = q; z[k] = s; z[k + 1] = Infinity;
  }
  k = 0;
  for (let q = 0; q < n; q++) {
    while (z[k + 1] < q) k++;
    d[q] = f[v[k]] === Infinity ? Infinity : (q - v[k]) ** 2 + f[v[k]];
  }
  return d;
}

const H = 0.05; // raster cell (mm)
function measure(name, paths) {
  const rings = ringsOf(name);
  const xs = rings.flat().map((p) => p[0]), ys = rings.flat().map((p) => p[1]);
  const x0 = Math.min(...xs) - 1, y0 = Math.min(...ys) - 1;
  const nx = Math.ceil((Math.max(...xs) + 1 - x0) / H), ny = Math.ceil((Math.max(...ys) + 1 - y0) / H);
  const grid = new Float64Array(nx * ny).fill(Infinity);
  const mark = (x, y) => {
    const i = Math.floor((x - x0) / H), j = Math.floor((y - y0) / H);
    if (i >= 0 && j >= 0 && i < nx && j < ny) grid[j * nx + i] = 0;
  };
  const trace = (a, b) => {
    const n = Math.ceil(Math.hypot(b[0] - a[0], b[1] - a[1]) / (H / 2)) + 1;
    for (let k = 0; k <= n; k++) mark(a[0] + ((b[0] - a[0]) * k) / n, a[1] + ((b[1] - a[1]) * k) / n);
  };
  // The walls stand on the region's boundary; the infill's lines are where it printed.
  for (const r of rings) for (let i = 0, j = r.length - 1; i < r.length; j = i++) trace(r[j], r[i]);
  let length = 0, outside = 0, wall = 0;
  const step = 0.02;
  for (const p of paths)
    for (let s = 1; s < p.length; s++) {
      const a = p[s - 1], b = p[s];
      const l = Math.hypot(b[0] - a[0], b[1] - a[1]);
      length += l;
      trace(a, b);
      const n = Math.max(1, Math.ceil(l / step));
      for (let k = 0; k < n; k++) {
        const q = [a[0] + ((b[0] - a[0]) * (k + 0.5)) / n, a[1] + ((b[1] - a[1]) * (k + 0.5)) / n];
        if (!inside(rings, q)) outside += l / n;
        else if (boundaryDist(rings, q) < W / 2 - 0.02) wall += l / n;
      }
    }
  // Exact distance transform: columns then rows.
  const col = new Float64Array(ny);
  for (let i = 0; i < nx; i++) {
    for (let j = 0; j < ny; j++) col[j] = grid[j * nx + i];
    const d = edt1(col, ny);
    for (let j = 0; j < ny; j++) grid[j * nx + i] = d[j];
  }
  let gap = 0, cells = 0;
  for (let j = 0; j < ny; j++) {
    const d = edt1(grid.subarray(j * nx, (j + 1) * nx), nx);
    for (let i = 0; i < nx; i++) {
      const p = [x0 + (i + 0.5) * H, y0 + (j + 0.5) * H];
      if (!inside(rings, p)) continue;
      if (boundaryDist(rings, p) >= W / 2) cells++;
      gap = Math.max(gap, Math.sqrt(d[i]) * H);
    }
  }
  const area = cells * H * H; // the infill area: the region inset by half a nozzle
  return { length, density: (length * W) / area, gap: 2 * gap, outside, wall, rotation: rotation(paths) };
}

/// The direction (degrees mod 180) carrying the most line length.
function rotation(paths) {
  const bins = new Float64Array(180);
  for (const p of paths)
    for (let s = 1; s < p.length; s++) {
      const dx = p[s][0] - p[s - 1][0], dy = p[s][1] - p[s - 1][1];
      const a = ((Math.atan2(dy, dx) * 180) / Math.PI + 360) % 180;
      bins[Math.round(a) % 180] += Math.hypot(dx, dy);
    }
  let best = 0;
  for (let i = 1; i < 180; i++) if (bins[i] > bins[best]) best = i;
  return best;
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
      const mp = measure(name, p.paths), mr = measure(name, r);
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
