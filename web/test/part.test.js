// A part in the playground (issue 20, "See it"): a cube STL opened with the file button
// and a cylinder STL dropped on the page, read back from the three.js scene as drawn
// (each layer's geometry: vertex counts, bounding boxes, points) and from the canvas's
// pixels, and checked against the mesh: the cube's layers are its height over the layer
// height, each a 20 mm square; the cylinder's sections are circles of its radius; the
// slider cuts through the stack.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { artifacts, launch, serve } from './harness.js';
import { box, boxTriangles, cylinder, modelSettings, threeMf } from '../../bindings/js/test/meshes.js';

let server;
let browser;
let base;

before(async () => {
  server = await serve();
  base = `http://127.0.0.1:${server.address().port}/`;
  browser = await launch();
});

after(async () => {
  await browser?.cleanup();
  server?.close();
});

async function open(hash = '') {
  const page = await browser.context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.errors = errors;
  await page.goto(base + hash);
  await page.waitForFunction(() => window.rotlangPlayground?.analysis() && window.rotlangPlayground.idle());
  return page;
}

// Waits until the page shows the part `name` sliced for the page as it is (the page says
// when: rotlangPlayground.idle() counts the part's slicing and drawing), and reads it.
async function shown(page, name) {
  await page.waitForFunction((n) => {
    const p = window.rotlangPlayground;
    const s = p.part();
    return s.name === n && (s.scene || s.error) && p.idle();
  }, name);
  return page.evaluate(() => window.rotlangPlayground.part());
}

async function slide(page, layer) {
  await page.locator('#layer-slider').fill(String(layer));
  await page.waitForFunction((l) => window.rotlangPlayground.idle() && window.rotlangPlayground.part().scene?.current === l, layer);
  return page.evaluate(() => window.rotlangPlayground.part());
}

const near = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} is not ${b} ± ${tol}`);

test('a cube STL from the file button: 50 square layers stacked, the slider cutting through them', async () => {
  const page = await open();
  await page.locator('#mesh').setInputFiles({ name: 'cube.stl', mimeType: 'model/stl', buffer: Buffer.from(box([20, 20, 10])) });
  let p = await shown(page, 'cube.stl');
  assert.equal(p.error, null);
  assert.equal(p.info.triangles, 12);
  const { scene } = p;
  // 10 mm at the form's 0.2 mm layers.
  assert.equal(scene.layers.length, 50);
  assert.equal(p.summary.layers, 50);
  // The model follows the part: the plot and the slider have its layers.
  assert.equal(await page.inputValue('#layers'), '50');
  assert.ok(await page.isDisabled('#layers'), 'the part sets the layer count');
  assert.equal(await page.getAttribute('#layer-slider', 'max'), '49');
  scene.layers.forEach((l, i) => {
    assert.equal(l.index, i);
    near(l.z, 0.1 + 0.2 * i, 1e-5, `layer ${i}'s height`);
    // The square's four sides: eight vertices, its corners at 0 and 20 mm.
    assert.equal(l.outline.vertices, 8, `layer ${i}`);
    [0, 0].forEach((v, k) => near(l.outline.min[k], v, 1e-5, `layer ${i} min`));
    [20, 20].forEach((v, k) => near(l.outline.max[k], v, 1e-5, `layer ${i} max`));
    near(l.outline.min[2], l.z, 1e-5, `layer ${i}'s outline is drawn at its height`);
    near(l.outline.max[2], l.z, 1e-5, `layer ${i}'s outline is drawn at its height`);
    // Infill inside the two 0.4 mm walls: solid on the form's 3 bottom and 4 top shell
    // layers (purple), sparse between them (blue), never both on a cube.
    const solid = i < 3 || i >= 46;
    const [filled, empty] = solid ? [l.solid, l.infill] : [l.infill, l.solid];
    assert.ok(filled.vertices >= 4, `layer ${i} has ${solid ? 'solid' : 'sparse'} infill`);
    assert.equal(empty.vertices, 0, `layer ${i} has no ${solid ? 'sparse' : 'solid'} infill`);
    assert.ok(filled.min[0] >= 0.8 - 1e-4 && filled.max[0] <= 19.2 + 1e-4, `layer ${i}'s infill is inside the walls`);
    assert.notEqual(l.solid.color, l.infill.color, 'solid and sparse infill are told apart');
  });
  // Solid infill is dense: a solid layer has more paths than a sparse one.
  assert.ok(scene.layers[0].solid.vertices > 2 * scene.layers[20].infill.vertices);
  // The top layer from above (the slider starts there): its solid area and paths drawn
  // in their own colour, no sparse paths.
  const top = page.locator('#preview svg.part-layer');
  assert.match(await top.getAttribute('aria-label'), /layer 49 of the part .*: solid lines/);
  assert.ok((await top.locator('path.solid').getAttribute('d')).length > 20);
  assert.ok((await top.locator('path.solid-area').getAttribute('d')).length > 10);
  assert.equal(await top.locator('path.infill').getAttribute('d'), '');
  // Its two wall loops, a line wide, round the infill: the middle lines of the walls,
  // 0.2 and 0.6 mm inside the section (the picture's coordinates are mm).
  const extent = async (cls) => {
    const d = await top.locator(`path.${cls}`).getAttribute('d');
    const rings = d.split('M').filter(Boolean).map((r) => r.replace(/Z/g, '').split('L').map((p) => p.split(',').map(Number)));
    const xs = rings.flat().map((p) => p[0]);
    return { rings: rings.length, min: Math.min(...xs), max: Math.max(...xs), each: rings.map((r) => Math.max(...r.map((p) => p[0])) - Math.min(...r.map((p) => p[0]))) };
  };
  const [section, walls] = [await extent('section'), await extent('walls')];
  assert.equal(walls.rings, 2, 'two wall loops');
  near(walls.min, section.min + 0.2, 0.011, 'the outer wall\'s middle line');
  near(walls.max, section.max - 0.2, 0.011, 'the outer wall\'s middle line');
  walls.each.sort((a, b) => b - a).forEach((w, k) => near(w, 19.6 - 0.8 * k, 0.021, `wall ${k}'s width`));
  assert.equal(await top.locator('path.walls').getAttribute('stroke-width'), '0.4');
  const colours = await top.evaluate((svg) => ['infill', 'solid']
    .map((c) => getComputedStyle(svg.querySelector(`path.${c}`)).stroke));
  assert.notEqual(colours[0], colours[1]);
  // Opened, the whole part shows (the slider at the top layer), and WebGL drew it.
  assert.equal(scene.current, 49);
  assert.ok(scene.layers.every((l) => l.visible));
  assert.ok(scene.drawnPixels > 2000, `${scene.drawnPixels} pixels drawn`);
  await page.locator('#view3d canvas').screenshot({ path: join(artifacts, 'part-cube.png') });
  // The slider cuts through: layers above it are hidden, its own is the highlighted one.
  p = await slide(page, 20);
  assert.deepEqual(p.scene.layers.filter((l) => l.visible).map((l) => l.index), [...Array(21).keys()]);
  assert.deepEqual(p.scene.layers.filter((l) => l.current).map((l) => l.index), [20]);
  assert.ok(p.scene.drawnPixels < scene.drawnPixels, 'fewer layers, fewer pixels');
  // The layer from above is its section and infill.
  const svg = page.locator('#preview svg.part-layer');
  assert.match(await svg.getAttribute('aria-label'), /layer 20 of the part at z 4\.1 mm/);
  assert.ok((await svg.locator('path.infill').getAttribute('d')).length > 20);
  assert.equal(await svg.locator('path.solid').getAttribute('d'), '', 'layer 20 is sparse');
  // The first layer from above is solid.
  await slide(page, 0);
  assert.equal(await page.locator('#preview svg.part-layer path.infill').getAttribute('d'), '');
  assert.ok((await page.locator('#preview svg.part-layer path.solid').getAttribute('d')).length > 20);
  // A new template re-fills the same layers.
  await page.evaluate(() => {
    const v = window.rotlangPlayground.view;
    v.dispatch({ changes: { from: 0, to: v.state.doc.length, insert: '+90' } });
  });
  await page.waitForFunction(() => window.rotlangPlayground.analysedText() === '+90' && window.rotlangPlayground.idle());
  p = await page.evaluate(() => window.rotlangPlayground.part());
  assert.equal(p.scene.layers.length, 50);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('a cylinder STL dropped on the page: circular sections of its radius', async () => {
  const page = await open();
  await page.fill('#layer-height', '0.3');
  const bytes = [...cylinder(8, 6, 96)];
  await page.evaluate((b) => {
    const file = new File([new Uint8Array(b)], 'cylinder.stl', { type: 'model/stl' });
    const data = new DataTransfer();
    data.items.add(file);
    document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
  }, bytes);
  const p = await shown(page, 'cylinder.stl');
  assert.equal(p.error, null);
  const { scene } = p;
  assert.equal(scene.layers.length, 20); // 6 mm at 0.3 mm
  const inner = 8 * Math.cos(Math.PI / 96);
  for (const l of scene.layers) {
    // The 96-gon's sides: 192 vertices, every one between its inner radius and its radius.
    assert.equal(l.outline.vertices, 192, `layer ${l.index}`);
    const pts = l.outline.points;
    for (let k = 0; k < pts.length; k += 3) {
      const r = Math.hypot(pts[k], pts[k + 1]);
      assert.ok(r >= inner - 1e-4 && r <= 8 + 1e-4, `layer ${l.index}: a point at radius ${r}`);
      near(pts[k + 2], l.z, 1e-5, `layer ${l.index}'s height`);
    }
    near(l.outline.min[0], -8, 8 - inner + 1e-4, 'leftmost');
    near(l.outline.max[0], 8, 8 - inner + 1e-4, 'rightmost');
    // The infill inside the two 0.4 mm walls: within 7.2 mm of the axis.
    // Solid on the 3 bottom and 4 top shell layers, sparse between.
    const filled = l.index < 3 || l.index >= 16 ? l.solid : l.infill;
    assert.ok(filled.vertices >= 4, `layer ${l.index} has infill`);
    for (let k = 0; k < 2; k += 1) {
      assert.ok(filled.min[k] >= -7.2 - 1e-4 && filled.max[k] <= 7.2 + 1e-4, `layer ${l.index}'s infill: ${filled.min} to ${filled.max}`);
    }
  }
  assert.ok(scene.drawnPixels > 2000);
  await page.locator('#view3d canvas').screenshot({ path: join(artifacts, 'part-cylinder.png') });
  // A file that is not a mesh is refused with the reason, and the page goes on.
  await page.locator('#mesh').setInputFiles({ name: 'broken.stl', mimeType: 'model/stl', buffer: Buffer.from('not a mesh') });
  await page.waitForFunction(() => /refused: cannot read a mesh from broken\.stl/.test(document.getElementById('part-info').textContent));
  // Back to the outlines: the built-in shapes' preview again.
  await page.click('#mesh-close');
  assert.ok(await page.isEnabled('#layers'));
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().name === null
    && document.querySelector('#preview svg') && !document.querySelector('#preview svg.part-layer'));
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('a 3MF project from the file button: both objects, where its build puts them', async () => {
  const page = await open();
  // An OrcaSlicer project: its settings give the template and the layer height.
  const settings = JSON.stringify({ sparse_infill_rotate_template: '0, +30/1mm', layer_height: '0.25' });
  const project = threeMf([
    { name: 'left', triangles: boxTriangles([10, 10, 4]), at: [0, 0, 0] },
    { name: 'right', triangles: boxTriangles([10, 10, 4]), at: [30, 5, 0] },
  ], { 'Metadata/project_settings.config': settings });
  await page.locator('#mesh').setInputFiles({ name: 'plate.3mf', mimeType: 'model/3mf', buffer: Buffer.from(project) });
  const p = await shown(page, 'plate.3mf');
  await page.waitForFunction(() => window.rotlangPlayground.analysedText() === '0, +30/1mm' && window.rotlangPlayground.idle());
  assert.equal(p.error, null);
  assert.deepEqual(p.info.objects, ['left', 'right']);
  assert.equal(await page.inputValue('#layer-height'), '0.25');
  const q = await page.evaluate(() => window.rotlangPlayground.part());
  // 4 mm at the project's 0.25 mm layers over its first layer (OrcaSlicer's 0.2 mm when
  // the project does not say), filled by its template.
  const first = Number(await page.inputValue('#first-layer') || 0.25);
  const layers = 1 + Math.ceil((4 - first) / 0.25 - 1e-6);
  assert.equal(first, 0.2);
  assert.equal(q.scene.layers.length, layers);
  assert.equal(await page.inputValue('#layers'), String(layers));
  near(q.scene.layers[1].z, 0.2 + 0.125, 1e-5, 'the second layer\'s middle');
  for (const l of q.scene.layers) {
    // The top layer's middle is above the 4 mm part (0.2 + 16 × 0.25 = 4.2): nothing there.
    if (l.z > 4) {
      assert.equal(l.outline.vertices, 0);
      continue;
    }
    // Two squares: sixteen vertices from x 0 to 40, y 0 to 15.
    assert.equal(l.outline.vertices, 16);
    assert.deepEqual([l.outline.min[0], l.outline.min[1], l.outline.max[0], l.outline.max[1]], [0, 0, 40, 15]);
  }
  assert.match(await page.textContent('#part-info'), /plate\.3mf: 24 triangles, 40 × 15 × 4 mm \(2 objects: left, right\)/);
  assert.deepEqual(page.errors, []);
  await page.close();
});

// The drawn outline's x and y extent of every layer that has a section.
function extents(scene) {
  return scene.layers.filter((l) => l.outline.vertices > 0)
    .map((l) => [l.outline.min[0], l.outline.min[1], l.outline.max[0], l.outline.max[1]].map((v) => Number(v.toFixed(4))));
}

// A project of two boxes with their own settings: Low (its own template, pattern, density
// and walls) and Tall (its own layer height and solid template).
function plate() {
  const settings = JSON.stringify({
    layer_height: '0.2', initial_layer_print_height: '0.2', sparse_infill_density: '15%',
    sparse_infill_pattern: 'zig-zag', wall_loops: '2', bottom_shell_layers: '3', top_shell_layers: '4',
    sparse_infill_rotate_template: '0, 90', solid_infill_rotate_template: '+30',
  });
  const project = threeMf([
    { name: 'Low', triangles: boxTriangles([12, 12, 3]), at: [0, 0, 0] },
    { name: 'Tall', triangles: boxTriangles([8, 10, 5]), at: [30, 0, 0] },
  ], {
    'Metadata/project_settings.config': settings,
    'Metadata/model_settings.config': modelSettings({
      Low: { sparse_infill_rotate_template: '+45', sparse_infill_pattern: 'grid', sparse_infill_density: '40%', wall_loops: '3' },
      Tall: { layer_height: '0.25', initial_layer_print_height: '0.25', solid_infill_rotate_template: '90, 0' },
    }),
  });
  return { name: 'plate.3mf', mimeType: 'model/3mf', buffer: Buffer.from(project) };
}

test('a 3MF project\'s object chosen: only its geometry drawn, with its own settings', async () => {
  const page = await open();
  await page.locator('#mesh').setInputFiles(plate());
  let p = await shown(page, 'plate.3mf');
  // All objects at first (what `rotlang preview plate.3mf` slices): both boxes, the
  // project's templates and settings in the editor, the form and the solid template.
  assert.equal(p.error, null);
  assert.ok(await page.isVisible('#object'));
  assert.deepEqual(await page.$$eval('#object option', (o) => o.map((e) => [e.value, e.textContent])),
    [['', 'all objects'], ['Low', 'Low'], ['Tall', 'Tall']]);
  assert.equal(p.object, null);
  assert.equal(await page.inputValue('#solid-template'), '+30');
  assert.equal(p.solidTemplate, '+30');
  assert.equal(p.template, '0, 90');
  const both = (scene) => {
    // Both boxes up to the low one's 3 mm, the tall one alone above.
    const e = extents(scene).map((x) => x.join());
    return e.length === 25 && e.slice(0, 15).every((x) => x === '0,0,38,12') && e.slice(15).every((x) => x === '30,0,38,10');
  };
  assert.ok(both(p.scene), JSON.stringify(extents(p.scene)));
  // The tall box alone: its outline only, at its own 0.25 mm layers, with its own solid template.
  await page.selectOption('#object', 'Tall');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === 'Tall'
    && window.rotlangPlayground.part().summary?.layers === 20);
  p = await page.evaluate(() => window.rotlangPlayground.part());
  assert.equal(p.error, null);
  assert.equal(p.scene.layers.length, 20);
  assert.ok(extents(p.scene).length >= 19);
  assert.ok(extents(p.scene).every((e) => e.join() === '30,0,38,10'), JSON.stringify(extents(p.scene)));
  assert.equal(await page.inputValue('#layer-height'), '0.25');
  assert.equal(await page.inputValue('#solid-template'), '90, 0');
  assert.equal(p.solidTemplate, '90, 0');
  assert.match(await page.textContent('#part-info'), /object Tall alone, with its own settings/);
  // The low box: its own template, pattern, density and walls; the project's solid template.
  await page.selectOption('#object', 'Low');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === 'Low'
    && window.rotlangPlayground.part().summary?.layers === 15);
  p = await page.evaluate(() => window.rotlangPlayground.part());
  assert.ok(extents(p.scene).every((e) => e.join() === '0,0,12,12'), JSON.stringify(extents(p.scene)));
  assert.equal(p.template, '+45');
  assert.equal(await page.evaluate(() => window.rotlangPlayground.analysedText()), '+45');
  assert.deepEqual([await page.inputValue('#pattern'), await page.inputValue('#density'), await page.inputValue('#walls')], ['grid', '40', '3']);
  assert.equal(await page.inputValue('#solid-template'), '+30');
  // Back to all objects: both boxes again.
  await page.selectOption('#object', '');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === null
    && window.rotlangPlayground.part().template === '0, 90');
  p = await page.evaluate(() => window.rotlangPlayground.part());
  assert.ok(both(p.scene), JSON.stringify(extents(p.scene)));
  assert.deepEqual(page.errors, []);
  await page.screenshot({ path: join(artifacts, 'part-object.png'), fullPage: true });
  await page.close();
});

test('a share link carries the part\'s object and solid template, chosen when the part is opened again', async () => {
  const page = await open();
  await page.locator('#mesh').setInputFiles(plate());
  await shown(page, 'plate.3mf');
  await page.selectOption('#object', 'Tall');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === 'Tall');
  await page.fill('#solid-template', '+15');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().solidTemplate === '+15');
  await page.click('#share');
  const link = await page.inputValue('#share-link');
  assert.match(link, /[#&]solid=%2B15(&|$)/);
  assert.match(link, /[#&]object=Tall(&|$)/);
  // A change to either makes the link stale.
  await page.fill('#solid-template', '+16');
  assert.ok(await page.isHidden('#share-link'));
  await page.close();
  // The link holds no mesh: the same project opened on the linked page gets them.
  const again = await open(link.slice(link.indexOf('#')));
  await again.locator('#mesh').setInputFiles(plate());
  await again.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === 'Tall'
    && window.rotlangPlayground.part().solidTemplate === '+15' && window.rotlangPlayground.part().summary?.layers === 20);
  assert.equal(await again.inputValue('#object'), 'Tall');
  assert.equal(await again.inputValue('#solid-template'), '+15');
  // Tall's own settings, as choosing it by hand gives.
  assert.equal(await again.inputValue('#layer-height'), '0.25');
  assert.deepEqual(again.errors, []);
  await again.close();
});

test('"none" leaves out the project\'s solid template: the solid layers turn with the template, as --no-solid-template', async () => {
  const page = await open();
  await page.locator('#mesh').setInputFiles(plate());
  await shown(page, 'plate.3mf');
  await page.selectOption('#object', 'Tall');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().object === 'Tall'
    && window.rotlangPlayground.part().solidTemplate === '90, 0');
  const solidDirections = (q) => q.scene.layers.slice(0, 3).map((l) => l.solid.direction);
  const own = solidDirections(await page.evaluate(() => window.rotlangPlayground.part()));
  assert.equal(await page.isChecked('#no-solid-template'), false);
  await page.check('#no-solid-template');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().solidTemplate === null);
  const p = await page.evaluate(() => window.rotlangPlayground.part());
  assert.equal(p.error, null);
  // Tall's template `0, 90` turns them now, a quarter turn from its solid `90, 0`.
  const none = solidDirections(p);
  assert.deepEqual(none.map((d, i) => (d - own[i] + 360) % 180), [90, 90, 90], `${own} → ${none}`);
  assert.equal(await page.isDisabled('#solid-template'), true);
  assert.equal(await page.inputValue('#solid-template'), '90, 0');
  assert.match(await page.textContent('#solid-message'), /No solid template: .*the project's `90, 0` is not used/);
  // The share link carries it.
  await page.click('#share');
  assert.match(await page.inputValue('#share-link'), /[#&]nosolid=1(&|$)/);
  // Unchecked: the project's again.
  await page.uncheck('#no-solid-template');
  await page.waitForFunction(() => window.rotlangPlayground.idle() && window.rotlangPlayground.part().solidTemplate === '90, 0');
  assert.deepEqual(solidDirections(await page.evaluate(() => window.rotlangPlayground.part())), own);
  assert.equal(await page.isDisabled('#solid-template'), false);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('a solid template typed turns the solid layers; a bad one is shown with its span and the last good view stays', async () => {
  const page = await open();
  await page.locator('#mesh').setInputFiles({ name: 'cube.stl', mimeType: 'model/stl', buffer: Buffer.from(box([20, 20, 10])) });
  let p = await shown(page, 'cube.stl');
  assert.ok(await page.isVisible('#solid-template'));
  assert.match(await page.textContent('#solid-message'), /No solid template/);
  // The three bottom layers are solid: their main direction, read from the scene.
  const solidDirections = (q) => q.scene.layers.slice(0, 3).map((l) => l.solid.direction);
  const typed = async (text) => {
    await page.fill('#solid-template', text);
    await page.waitForFunction((t) => {
      const r = window.rotlangPlayground;
      return r.idle() && document.getElementById('solid-template').value === t;
    }, text);
    return page.evaluate(() => window.rotlangPlayground.part());
  };
  p = await typed('0');
  assert.equal(p.solidTemplate, '0');
  const flat = solidDirections(p);
  assert.equal(new Set(flat).size, 1, `all at the solid template's 0°: ${flat}`);
  p = await typed('+30');
  assert.equal(p.error, null);
  const turned = solidDirections(p);
  // +30° a layer: 30, 60 and 90° from the 0° ones, in the 3D view...
  assert.deepEqual(turned.map((d) => (d - flat[0] + 360) % 180), [30, 60, 90]);
  // ... and in the Layer panel (layer 1: 60°).
  await slide(page, 1);
  assert.match(await page.getAttribute('#preview svg.part-layer', 'aria-label'), /layer 1 .*solid lines at 60°/);
  assert.equal(await page.textContent('#solid-message'), '');
  // A bad one: its error with the column and the span marked, the input marked invalid,
  // and the view as it was (the last good solid template's).
  p = await typed('+30X');
  assert.match(p.error, /solid template has errors/);
  assert.deepEqual(solidDirections(p), turned);
  assert.equal(await page.getAttribute('#solid-template', 'aria-invalid'), 'true');
  assert.ok(await page.$eval('#solid-message', (m) => m.classList.contains('error')));
  assert.match(await page.textContent('#solid-message'), /error at column 4: /);
  assert.equal(await page.textContent('#solid-message mark'), 'X');
  assert.match(await page.getAttribute('#preview svg.part-layer', 'aria-label'), /solid lines at 60°/);
  // Another good one: sliced again by it (-30° a layer).
  p = await typed('-30');
  assert.equal(p.error, null);
  assert.deepEqual(solidDirections(p).map((d) => (d - flat[0] + 360) % 180), [150, 120, 90]);
  assert.equal(await page.getAttribute('#solid-template', 'aria-invalid'), 'false');
  assert.deepEqual(page.errors, []);
  await page.close();
});
