// Polyslice and rotlang side by side on a mesh: the speed of slicing alone and of the whole
// job (sections filled, to G-code or paths), and per layer the printed infill density,
// largest gap, infill outside the section or in the wall band, and direction, measured as
// compare.mjs measures the five shapes (measure.mjs). Prints markdown (MESH.md holds it).
//
//   node polyslice-mesh.mjs sections out/torus.stl 0.04  # Polytree's slicing (minutes)
//   node polyslice-mesh.mjs job out/torus.stl 0.2        # Polyslice's whole job (minutes)
//   cargo bench --bench slice -- sections_500 > out/divan-slice.txt
//   node compare-mesh.mjs --mesh torus --divan out/divan-slice.txt
//
// rotlang's whole job is timed here: `rotlang preview 45 --shape out/MESH.stl --format json`
// over every layer (grid 20%, 2 walls, 4 top and bottom shell layers, as Polyslice's job),
// three runs, the median. The quality columns compare the layers that both programs fill
// with sparse infill only (no skin, no solid area) and at least 4 lines wide; a layer's
// region is the mesh's exact section at the layer's middle less the two walls (0.8 mm).
import { execFileSync } from 'node:child_process';
import { readFileSync, existsSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { W, annulusRegion, measure, parseGcode } from './measure.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = join(here, '..', '..', '..', '..');
const out = join(here, 'out');
const args = process.argv.slice(2);
const arg = (name, dflt) => (args.includes(name) ? args[args.indexOf(name) + 1] : dflt);
const meshName = arg('--mesh', 'torus');
const divanFile = arg('--divan', null);
const every = Number(arg('--every', '1'));
const rotlangBin = process.env.ROTLANG || join(root, 'target', 'release', 'rotlang');
const H = 0.2; // the whole job's layer height
const WALLS = 2;

// ---------- the meshes' exact sections (those of crates/rotlang-geometry/examples/write_mesh.rs) ----------

/// [inner radius, outer radius] of the section at height z (inner 0: a disc), or null.
const SECTIONS = {
  // shapes::torus(30, 10, 500, 100): the tube's centre circle at z = 10.
  torus(z) {
    const d = 100 - (z - 10) ** 2;
    return d > 0 ? [30 - Math.sqrt(d), 30 + Math.sqrt(d)] : null;
  },
  // shapes::vase: its lathe profile, linear between the 64 steps of each side.
  vase(z) {
    const outer = (t) => 20 + 10 * Math.max(Math.sin(Math.PI * (t / 80) * 1.5), -0.6) + 6 * (t / 80) ** 6;
    const lerp = (z0, step, f) => {
      const k = Math.min(63, Math.max(0, Math.floor((z - z0) / step)));
      const a = z0 + k * step, b = a + step;
      return f(a) + ((f(b) - f(a)) * (z - a)) / step;
    };
    if (z <= 0 || z >= 80) return null;
    const rOut = lerp(0, 80 / 64, outer);
    if (z < 3) return [0, rOut];
    return [lerp(3, 77 / 64, (t) => outer(t) - 2), rOut];
  },
};

/// The infill region at height z: the section less the walls; null where it is narrower
/// than 4 lines (the vase's 2 mm walls leave a 0.4 mm ring: nothing to measure a fill in).
function regionAt(z) {
  const s = SECTIONS[meshName](z);
  if (!s) return null;
  const inset = WALLS * W;
  const rOut = s[1] - inset;
  const rIn = s[0] > 0 ? s[0] + inset : 0;
  return rOut - rIn >= 4 * W ? annulusRegion(0, 0, rIn, rOut) : null;
}

// ---------- speed ----------

const readJson = (f) => JSON.parse(readFileSync(join(out, f), 'utf8'));
const sections = existsSync(join(out, `polyslice-sections-${meshName}-0.04.json`))
  ? readJson(`polyslice-sections-${meshName}-0.04.json`)
  : null;
const split = existsSync(join(out, `polyslice-split-${meshName}.json`)) ? readJson(`polyslice-split-${meshName}.json`) : null;
const job = readJson(`polyslice-${meshName}-${H}.json`);
const gcode = readFileSync(join(out, `polyslice-${meshName}-${H}.gcode`), 'utf8');

/// rotlang's whole job, timed (median of 3 runs), and every layer's JSON. `preview` fills every
/// layer (its summary); the timed run lists the first 256 (as MESH.md's figures were taken,
/// when that was the most it listed: `--layers all` lists every one now), a taller part's
/// other layers come from more, untimed runs.
function rotlangJob() {
  const run = (from, to) => {
    const file = join(out, `rotlang-${meshName}-${H}-${from}.json`);
    execFileSync(rotlangBin, [
      'preview', '--shape', join(out, `${meshName}.stl`), '--pattern', 'grid', '--density', '20',
      '--nozzle', String(W), '--walls', String(WALLS), '--layer-height', String(H),
      '--top-shell-layers', '4', '--bottom-shell-layers', '4', '--layers', `${from}..${to}`,
      '--format', 'json', '--out', file, '--', '45',
    ], { stdio: ['ignore', 'ignore', 'ignore'] });
    return file;
  };
  const first = Math.min(job.layers, 256);
  const times = [];
  let file;
  for (let k = 0; k < 3; k++) {
    const t0 = process.hrtime.bigint();
    file = run(0, first);
    times.push(Number(process.hrtime.bigint() - t0) / 1e9);
  }
  times.sort((a, b) => a - b);
  const json = JSON.parse(readFileSync(file, 'utf8'));
  for (let from = first; from < job.layers; from += 256)
    json.layers.push(...JSON.parse(readFileSync(run(from, Math.min(job.layers, from + 256)), 'utf8')).layers);
  return { seconds: times[1], listed: first, json };
}

/// Medians (s) of the divan output of `cargo bench --bench slice`, by bench name.
function divanTimes() {
  if (!divanFile) return {};
  const units = { ns: 1e-9, 'µs': 1e-6, us: 1e-6, ms: 1e-3, s: 1 };
  const times = {};
  for (const line of readFileSync(divanFile, 'utf8').split('\n')) {
    const m = /[├╰]─ (\w+)\s+(.*)$/.exec(line);
    if (!m) continue;
    const cols = m[2].split('│').map((s) => s.trim());
    const [v, u] = (cols[2] || '').split(/\s+/);
    if (units[u]) times[m[1]] = +v * units[u];
  }
  return times;
}

// ---------- quality, layer by layer ----------

const f = (v, d = 2) => (Number.isFinite(v) ? v.toFixed(d) : '—');
const r = rotlangJob();
const divan = divanTimes();
const pLayers = new Map(parseGcode(gcode, true).map((l) => [l.layer, l.types]));
const shift = ([x, y]) => [x - job.centerOffsetX, y - job.centerOffsetY];
const rows = [];
let pSkinLayers = 0, rSolidLayers = 0;
for (const layer of r.json.layers) {
  const i = layer.index;
  const z = 0.1 + H * i; // both cut at the layer's middle: Polyslice from z = h/2 up, rotlang likewise
  const types = pLayers.get(i + 1) || {};
  const pSkin = (types.SKIN || []).length > 0;
  const rSolid = layer.printed !== 'sparse';
  pSkinLayers += pSkin;
  rSolidLayers += rSolid;
  const region = regionAt(z);
  if (pSkin || rSolid || !region || !types.FILL || i % every) continue;
  const pPaths = types.FILL.map((p) => p.map(shift));
  const rPaths = layer.areas.filter((a) => a.fill === 'sparse').flatMap((a) => a.polylines);
  rows.push({ i, z, p: measure(region, pPaths), r: measure(region, rPaths) });
}

// ---------- table ----------

const load = execFileSync('uptime', { encoding: 'utf8' }).trim();
console.log(`## ${meshName}: ${job.triangles.toLocaleString('en')} triangles\n`);
console.log(`Load when compare-mesh.mjs ran: \`${load}\`.\n`);
console.log('| what | Polyslice | rotlang | speed-up |');
console.log('|---|---|---|---|');
if (sections) {
  const rs = divan.sections_500;
  console.log(`| slicing alone: ${sections.layers} sections at 0.04 mm | ${f(sections.seconds, 1)} s (Polytree.sliceIntoLayers) | ${rs ? f(rs, 3) + ' s (divan median, `sections_500`)' : '—'} | ${rs ? f(sections.seconds / rs, 0) + '×' : '—'} |`);
}
if (sections && split) {
  const bound = split.build + sections.layers * split.planeTest;
  const rs = divan.sections_500;
  console.log(`| the same, were Polytree's per-layer gathering of triangles free (bound: fromMesh ${f(split.build, 2)} s + ${sections.layers} × ${f(split.planeTest * 1000, 0)} ms plane test; it measured ${f(split.gather, 2)} s a layer) | ≥ ${f(bound, 1)} s | ${rs ? f(rs, 3) + ' s' : '—'} | ${rs ? '≥ ' + f(bound / rs, 0) + '×' : '—'} |`);
}
console.log(`| whole job at ${H} mm: ${job.layers} layers, 2 walls, grid 20% | ${f(job.seconds, 1)} s (\`slice()\` to G-code) | ${f(r.seconds, 2)} s (\`rotlang preview --format json\`, every layer filled, ${r.listed} listed, median of 3) | ${f(job.seconds / r.seconds, 0)}× |`);
if (divan.part_500) console.log(`| rotlang's part bench: 500 layers at 0.04 mm, 2 walls, lines 20%, shells | — | ${f(divan.part_500, 3)} s (divan median, \`part_500\`) | — |`);
console.log();
console.log(`Layers with skin or solid areas (left out of the quality table): Polyslice ${pSkinLayers}, rotlang ${rSolidLayers} of ${r.json.layers.length}.\n`);
const sum = (k, who) => rows.reduce((s, row) => s + row[who][k], 0);
const stat = (k, who, fn) => fn(...rows.map((row) => row[who][k]));
const dirs = (who) => [...new Set(rows.map((row) => row[who].rotation))].sort((a, b) => a - b).join(', ');
console.log(`Over the ${rows.length} layers both fill sparse only, in a region at least 4 lines wide (z ${f(rows[0]?.z, 1)} to ${f(rows.at(-1)?.z, 1)} mm):\n`);
console.log('| measure | Polyslice | rotlang |');
console.log('|---|---|---|');
console.log(`| printed density, mean (min–max) | ${f((sum('density', 'p') / rows.length) * 100, 1)}% (${f(stat('density', 'p', Math.min) * 100, 1)}–${f(stat('density', 'p', Math.max) * 100, 1)}) | ${f((sum('density', 'r') / rows.length) * 100, 1)}% (${f(stat('density', 'r', Math.min) * 100, 1)}–${f(stat('density', 'r', Math.max) * 100, 1)}) |`);
console.log(`| largest gap, worst layer (mm) | ${f(stat('gap', 'p', Math.max))} | ${f(stat('gap', 'r', Math.max))} |`);
console.log(`| infill outside the region or in a hole, all layers (mm) | ${f(sum('outside', 'p'), 1)} | ${f(sum('outside', 'r'), 1)} |`);
console.log(`| infill in the wall band, all layers (mm) | ${f(sum('wall', 'p'), 1)} | ${f(sum('wall', 'r'), 1)} |`);
console.log(`| direction° (most length) | ${dirs('p')} | ${dirs('r')} |`);
console.log('\nSome of those layers:\n');
console.log('| layer | z mm | density P / r | largest gap mm P / r | outside mm P / r | in wall band mm P / r | direction° P / r |');
console.log('|---|---|---|---|---|---|---|');
const step = Math.max(1, Math.floor(rows.length / 8));
for (const row of rows.filter((_, k) => k % step === 0)) {
  const { p, r: q } = row;
  console.log(`| ${row.i} | ${f(row.z, 1)} | ${f(p.density * 100, 1)}% / ${f(q.density * 100, 1)}% | ${f(p.gap)} / ${f(q.gap)} | ${f(p.outside)} / ${f(q.outside)} | ${f(p.wall)} / ${f(q.wall)} | ${p.rotation} / ${q.rotation} |`);
}
