// A real part through `rotlang/full` (readMesh + part): the same layers as the CLI's
// `rotlang preview --shape part.stl --format json` for the same mesh and template (one
// answer everywhere), and the sections a cube and a cylinder must have. The Rust runner
// (tests/node.rs) passes the workspace's CLI as ROTLANG_CLI.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { RotlangError, part, partSettings, readMesh } from '../full.js';
import { box, boxTriangles, cylinder, modelSettings, threeMf } from './meshes.js';

const cli = process.env.ROTLANG_CLI;
const skip = !cli && 'ROTLANG_CLI names the rotlang binary (tests/node.rs sets it)';

function viaCli(stl, args) {
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  const file = join(dir, 'cube.stl');
  writeFileSync(file, stl);
  const r = spawnSync(cli, ['preview', ...args, '--shape', file, '--format', 'json'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  return JSON.parse(r.stdout);
}

test('a cube gives the CLI\'s layers, sections and paths', { skip }, () => {
  const stl = box([20, 20, 10]);
  const info = readMesh('cube.stl', stl);
  assert.equal(info.triangles, 12);
  assert.deepEqual([info.min, info.max], [[0, 0, 0], [20, 20, 10]]);
  const js = part('+45, 0M', {});
  assert.equal(js.layers.length, 50);
  const shown = viaCli(stl, ['+45, 0M', '--layers', '0..50']);
  assert.deepEqual(js, shown);
  // Another pattern, density, layer height, walls and a range: still the CLI's answer.
  const js2 = part('0, 90', {
    pattern: 'grid', density: 0.35, walls: 3, from: 5, to: 12,
    model: { height: 10, layerHeight: 0.25, firstLayerHeight: 0.3, topShells: 2 },
  });
  const cli2 = viaCli(stl, ['0, 90', '--pattern', 'grid', '--density', '35', '--walls', '3',
    '--height', '10', '--layer-height', '0.25', '--first-layer-height', '0.3', '--top-shell-layers', '2', '--layers', '5..12']);
  assert.equal(js2.layers.length, 7);
  assert.deepEqual(js2, cli2);
  // The solid template and the shells' depths: the first 2 and last 3 layers solid,
  // turned by it; still the CLI's answer.
  const js3 = part('+45', { solidTemplate: '90, 0', model: { bottomShells: 2, topShells: 3 } });
  const cli3 = viaCli(stl, ['+45', '--solid-template', '90, 0', '--bottom-shell-layers', '2',
    '--top-shell-layers', '3', '--layers', '0..50']);
  assert.deepEqual(js3, cli3);
  assert.equal(js3.solid_template, '90, 0');
  assert.deepEqual(js3.layers.map((l) => l.printed),
    js3.layers.map((l) => (l.index < 2 || l.index >= 47 ? 'solid' : 'sparse')));
  assert.deepEqual(js3.layers[1].areas.map((a) => [a.solid, a.angle]), [[true, 0]]);
  assert.deepEqual(js3.layers[10].areas.map((a) => [a.solid, a.angle]), [[false, 45 * 11]]);
  assert.ok(js3.summary.solid_extrusion_mm > 0 && js3.summary.solid_extrusion_mm < js3.summary.extrusion_mm);
  assert.throws(() => part('0', { solidTemplate: 90 }), (e) => e instanceof RotlangError && e.kind === 'options');
  assert.throws(() => part('0', { solidTemplate: '+' }),
    (e) => e instanceof RotlangError && e.kind === 'template' && /solid template/.test(e.message));
});

test('a cube\'s sections are its square; a cylinder\'s are circles of its radius', () => {
  readMesh('cube.stl', box([20, 20, 10]));
  const cube = part('0', {});
  assert.equal(cube.summary.layers, 50);
  for (const l of cube.layers) {
    const [[outline, ...holes]] = l.section;
    assert.equal(holes.length, 0);
    const xs = outline.map((p) => p[0]);
    const ys = outline.map((p) => p[1]);
    assert.deepEqual([Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)], [0, 20, 0, 20]);
    assert.ok(l.polylines.length > 0, `layer ${l.index} has infill`);
  }
  readMesh('cylinder.stl', cylinder(8, 6, 96));
  const cyl = part('0', { model: { layerHeight: 0.3 } });
  assert.equal(cyl.layers.length, 20);
  for (const l of cyl.layers) {
    assert.equal(l.section.length, 1);
    // On the 96-gon's sides: between its inner radius (a side's middle) and the radius.
    for (const [x, y] of l.section[0][0]) {
      const r = Math.hypot(x, y);
      assert.ok(r > 8 * Math.cos(Math.PI / 96) - 1e-5 && r < 8 + 1e-5, `layer ${l.index}: (${x}, ${y})`);
    }
    assert.ok(l.section[0][0].length > 90);
  }
});

test('a file that is not a mesh is refused, and leaves no mesh behind', () => {
  readMesh('cube.stl', box([5, 5, 5]));
  assert.throws(() => readMesh('broken.stl', new Uint8Array([1, 2, 3])),
    (e) => e instanceof RotlangError && e.kind === 'model' && /broken\.stl/.test(e.message));
  assert.throws(() => part('0'), (e) => e instanceof RotlangError && e.kind === 'options' && /readMesh/.test(e.message));
  assert.throws(() => readMesh('x.3mf', new Uint8Array(10)), (e) => e.kind === 'model');
  readMesh('cube.stl', box([5, 5, 5]));
  assert.throws(() => part('0', { walls: 1.5 }), (e) => e.kind === 'options');
  assert.throws(() => part('0', { walls: 'two' }), (e) => e.kind === 'options');
  assert.throws(() => part('0', { density: 0 }), (e) => e.kind === 'options');
  assert.throws(() => part('+', {}), (e) => e.kind === 'template');
  assert.throws(() => part('0', { model: { layerHeight: 0.004, height: 100 } }), (e) => e.kind === 'limit');
  assert.equal(part('0', {}).layers.length, 25);
});

test('a 3MF project: its objects placed by the build and merged, as the CLI reads them', { skip }, () => {
  const project = threeMf([
    { name: 'left', triangles: boxTriangles([10, 10, 4]), at: [0, 0, 0] },
    { name: 'right', triangles: boxTriangles([10, 10, 4]), at: [30, 5, 0] },
  ]);
  const info = readMesh('plate.3mf', project);
  assert.deepEqual(info.objects, ['left', 'right']);
  assert.equal(info.triangles, 24);
  assert.deepEqual([info.min, info.max], [[0, 0, 0], [40, 15, 4]]);
  const js = part('+45', {});
  assert.equal(js.layers.length, 20);
  // Two square sections on every layer, the second where the build put it.
  for (const l of js.layers) {
    assert.equal(l.section.length, 2, `layer ${l.index}`);
    const xs = l.section.flat(2).map((p) => p[0]);
    assert.deepEqual([Math.min(...xs), Math.max(...xs)], [0, 40]);
  }
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  writeFileSync(join(dir, 'plate.3mf'), project);
  const r = spawnSync(cli, ['preview', '+45', '--shape', join(dir, 'plate.3mf'), '--format', 'json', '--layers', '0..20'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  assert.deepEqual(js, JSON.parse(r.stdout));
});

// A project of two objects, each with its own overrides (model_settings.config) over the
// project's settings: a box with its own template, pattern, density and walls, and a
// taller box with its own layer height, shells and solid template.
function twoObjectProject() {
  const settings = JSON.stringify({
    layer_height: '0.2', initial_layer_print_height: '0.2', sparse_infill_density: '15%',
    sparse_infill_pattern: 'zig-zag', internal_solid_infill_pattern: 'concentric', wall_loops: '2',
    line_width: '0.45', nozzle_diameter: ['0.4'], bottom_shell_layers: '3', top_shell_layers: '4',
    sparse_infill_rotate_template: '0, 90', solid_infill_rotate_template: '+30',
  });
  return threeMf([
    { name: 'Low', triangles: boxTriangles([12, 12, 3]), at: [0, 0, 0] },
    { name: 'Tall', triangles: boxTriangles([8, 10, 5]), at: [30, 0, 0] },
  ], {
    'Metadata/project_settings.config': settings,
    'Metadata/model_settings.config': modelSettings({
      Low: { sparse_infill_rotate_template: '+45', sparse_infill_pattern: 'grid', sparse_infill_density: '40%', wall_loops: '3' },
      Tall: { layer_height: '0.25', initial_layer_print_height: '0.25', sparse_infill_pattern: 'concentric', top_shell_layers: '6', solid_infill_rotate_template: '90, 0' },
    }),
  });
}

// `rotlang preview ARGS --format json` in `dir` (the file named as JS names it), or its
// failure.
function cliIn(dir, args) {
  return spawnSync(cli, ['preview', ...args, '--format', 'json'], { encoding: 'utf8', cwd: dir });
}

test('part({object}) is the CLI\'s --object: that object alone, with its overrides', { skip }, () => {
  const project = twoObjectProject();
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  writeFileSync(join(dir, 'plate.3mf'), project);
  const info = readMesh('plate.3mf', project);
  assert.deepEqual(info.objects, ['Low', 'Tall']);
  assert.equal(info.project, true);
  const answers = {};
  for (const name of info.objects) {
    // The file's template (an empty one given), and one given: both the CLI's answer.
    for (const text of ['', '+10']) {
      const js = part(text, { object: name });
      const r = cliIn(dir, [text, '--shape', 'plate.3mf', '--object', name, '--layers', `0..${js.settings.layers}`]);
      assert.equal(r.status, 0, r.stderr);
      assert.deepEqual(js, JSON.parse(r.stdout), `${name}, template '${text}'`);
      if (text === '') answers[name] = js;
    }
    // The settings alone, without slicing: those the part was filled with.
    const s = partSettings('', { object: name });
    assert.deepEqual([s.template, s.solid_template, s.settings], [answers[name].template, answers[name].solid_template, answers[name].settings]);
  }
  // Each object's own overrides, the rest the project's.
  const { Low, Tall } = answers;
  assert.deepEqual([Low.template, Low.solid_template, Low.settings.pattern, Low.settings.density, Low.settings.walls, Low.settings.layer_height],
    ['+45', '+30', 'grid', 0.4, 3, 0.2]);
  assert.deepEqual([Tall.template, Tall.solid_template, Tall.settings.pattern, Tall.settings.density, Tall.settings.walls, Tall.settings.layer_height, Tall.settings.top_shell_layers],
    ['0, 90', '90, 0', 'concentric', 0.15, 2, 0.25, 6]);
  assert.equal(partSettings('', { object: 'Tall' }).first_layer_height, 0.25);
  // A template with errors: the settings still (the part itself is refused).
  assert.equal(partSettings('+', { object: 'Tall' }).settings.layer_height, 0.25);
  assert.throws(() => part('+', { object: 'Tall' }), (e) => e.kind === 'template');
  // Each object's sections are its own box, where the build put it.
  for (const [answer, x0, x1] of [[Low, 0, 12], [Tall, 30, 38]]) {
    for (const l of answer.layers.filter((l) => l.section.length)) {
      assert.equal(l.section.length, 1);
      const xs = l.section.flat(2).map((p) => p[0]);
      assert.deepEqual([Math.min(...xs), Math.max(...xs)], [x0, x1]);
    }
  }
  // All objects (no object): the project's settings, both boxes; the CLI's answer too.
  const all = part('', {});
  const r = cliIn(dir, ['', '--shape', 'plate.3mf', '--layers', `0..${all.settings.layers}`]);
  assert.equal(r.status, 0, r.stderr);
  assert.deepEqual(all, JSON.parse(r.stdout));
  assert.deepEqual([all.template, all.settings.pattern, all.settings.density], ['0, 90', 'lines', 0.15]);
  assert.equal(all.layers[5].section.length, 2);
  // The options win over the file, as the command line does.
  const given = part('+10', { object: 'Low', density: 0.1, walls: 1, pattern: 'grid', solidTemplate: '0' });
  const r2 = cliIn(dir, ['+10', '--shape', 'plate.3mf', '--object', 'Low', '--density', '10', '--walls', '1',
    '--pattern', 'grid', '--solid-template', '0', '--layers', `0..${given.settings.layers}`]);
  assert.equal(r2.status, 0, r2.stderr);
  assert.deepEqual(given, JSON.parse(r2.stdout));
  assert.deepEqual([given.settings.density, given.settings.walls, given.solid_template], [0.1, 1, '0']);
});

test('an unknown object is refused with the CLI\'s message, naming the objects', { skip }, () => {
  const project = twoObjectProject();
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  writeFileSync(join(dir, 'plate.3mf'), project);
  readMesh('plate.3mf', project);
  const r = cliIn(dir, ['0', '--shape', 'plate.3mf', '--object', 'Middle']);
  assert.notEqual(r.status, 0);
  const cliMessage = r.stderr.trim().replace(/^rotlang: /, '');
  assert.equal(cliMessage, 'plate.3mf has no object "Middle"; its objects: Low, Tall');
  assert.throws(() => part('0', { object: 'Middle' }),
    (e) => e instanceof RotlangError && e.kind === 'options' && e.message === cliMessage);
  assert.throws(() => partSettings('0', { object: 'Middle' }), (e) => e.message === cliMessage);
  assert.throws(() => part('0', { object: 3 }), (e) => e.kind === 'options' && /`object` must be a string/.test(e.message));
  // An STL has no objects to pick.
  readMesh('cube.stl', box([5, 5, 5]));
  assert.throws(() => part('0', { object: 'Low' }), (e) => e.kind === 'options' && /cube\.stl is not one/.test(e.message));
});

test('a solid template given turns the solid layers as the CLI\'s --solid-template, over a project\'s', { skip }, () => {
  const project = twoObjectProject();
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  writeFileSync(join(dir, 'plate.3mf'), project);
  readMesh('plate.3mf', project);
  const js = part('0', { object: 'Tall', solidTemplate: '+15' });
  const r = cliIn(dir, ['0', '--shape', 'plate.3mf', '--object', 'Tall', '--solid-template', '+15', '--layers', `0..${js.settings.layers}`]);
  assert.equal(r.status, 0, r.stderr);
  assert.deepEqual(js, JSON.parse(r.stdout));
  // The bottom layers (3, the project's) turn by +15 a layer, not by the object's `90, 0`.
  assert.deepEqual(js.layers.slice(0, 3).map((l) => l.areas.find((a) => a.solid).angle), [15, 30, 45]);
  // A bad one: the same refusal as the CLI's, with its span.
  assert.throws(() => part('0', { object: 'Tall', solidTemplate: '+15X' }), (e) => e.kind === 'template'
    && /solid template/.test(e.message) && e.diagnostics.some((d) => d.severity === 'error' && d.start === 3));
  const bad = cliIn(dir, ['0', '--shape', 'plate.3mf', '--object', 'Tall', '--solid-template', '+15X']);
  assert.equal(bad.status, 1);
  assert.match(bad.stderr, /--solid-template/);
});

test('noSolidTemplate turns the solid layers with the template, over a project\'s, as the CLI\'s --no-solid-template', { skip }, () => {
  const project = twoObjectProject();
  const dir = mkdtempSync(join(tmpdir(), 'rotlang-part-'));
  writeFileSync(join(dir, 'plate.3mf'), project);
  readMesh('plate.3mf', project);
  // Tall's own solid template is `90, 0`: with it, the bottom layers are not at +10 a layer.
  const own = part('+10', { object: 'Tall' });
  assert.equal(own.solid_template, '90, 0');
  const js = part('+10', { object: 'Tall', noSolidTemplate: true });
  const r = cliIn(dir, ['+10', '--shape', 'plate.3mf', '--object', 'Tall', '--no-solid-template', '--layers', `0..${js.settings.layers}`]);
  assert.equal(r.status, 0, r.stderr);
  assert.deepEqual(js, JSON.parse(r.stdout));
  assert.equal(js.solid_template, null);
  assert.equal(partSettings('+10', { object: 'Tall', noSolidTemplate: true }).solid_template, null);
  // Each solid area turns as its layer does, which the project's template did not.
  const solidAngles = (p) => p.layers.slice(0, 3).map((l) => [l.angle, l.areas.find((a) => a.solid).angle]);
  assert.ok(solidAngles(js).every(([layer, solid]) => layer === solid), JSON.stringify(solidAngles(js)));
  assert.ok(!solidAngles(own).every(([layer, solid]) => layer === solid), JSON.stringify(solidAngles(own)));
  // false is the default (the project's); a solid template with it is a contradiction.
  assert.deepEqual(part('+10', { object: 'Tall', noSolidTemplate: false }), own);
  assert.throws(() => part('+10', { object: 'Tall', solidTemplate: '0', noSolidTemplate: true }),
    (e) => e instanceof RotlangError && e.kind === 'options' && /cannot be given together/.test(e.message));
  assert.throws(() => part('+10', { noSolidTemplate: 'yes' }),
    (e) => e instanceof RotlangError && e.kind === 'options' && /`noSolidTemplate` must be true or false/.test(e.message));
});

// Every pattern, on a cylinder (arcs, a concave-free outline) and with a turning
// template: wasm's paths are the CLI's to the last bit. The geometry's sines, cosines and
// hypotenuses go through one implementation (libm) on both targets; std's differ in the
// last bit between wasm32 and native, which moved gyroid and triangles paths.
test('every pattern draws the CLI\'s paths, bit for bit', { skip }, () => {
  const stl = cylinder(9, 3, 48);
  readMesh('cylinder.stl', stl);
  for (const pattern of ['lines', 'grid', 'triangles', 'hexagons', 'concentric', 'gyroid', 'spiral', 'lightning', 'cubic']) {
    for (const density of [0.15, 0.4]) {
      const js = part('+37, -11/3', { pattern, density });
      const shown = viaCli(stl, ['+37, -11/3', '--pattern', pattern, '--density', String(density * 100),
        '--layers', `0..${js.layers.length}`]);
      assert.deepEqual(js, shown, `${pattern} ${density}`);
    }
  }
});
