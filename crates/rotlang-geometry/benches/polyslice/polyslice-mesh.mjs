// Runs Polyslice on a mesh (binary STL) and records how long it took, for compare-mesh.mjs.
// Each run is long (Polytree's slicing rescans every triangle per layer), so it is its own
// step and its output is kept in out/:
//
//   node polyslice-mesh.mjs sections out/torus.stl 0.04   # Polytree.sliceIntoLayers alone
//   node polyslice-mesh.mjs job out/torus.stl 0.2         # Polyslice's slice() to G-code
//
// `sections`: Polytree.sliceIntoLayers(mesh, h, h/2, top), the call Polyslice's slice makes
// (out/polyslice-sections-NAME-H.json: seconds, layers, segments per layer).
// `split`: where sliceIntoLayers' time goes: building the polytree (Polytree.fromMesh), one
// polytree.getTriangles() (it gathers the triangles anew for every layer), and a layer's
// plane test over them: sliceIntoLayers of 25 layers on the built polytree with its
// getTriangles answering a list gathered once (a harness-side substitution, to bound what
// the slicing would cost were the gathering free; Polytree's code is not changed).
// `job`: Polyslice's slice() at layer height h, nozzle 0.4, 2 walls (0.8 mm), 4 top and bottom
// skin layers (0.8 mm), grid infill at 20%, no adhesion or support, verbose (its `; TYPE:`
// marks say which moves are infill) (out/polyslice-NAME-H.gcode and .json: seconds, offsets).
import { createRequire } from 'node:module';
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const require = createRequire(import.meta.url);
const THREE = require('three');
const { STLLoader } = await import('three/examples/jsm/loaders/STLLoader.js');

const [what, file, h = '0.2'] = process.argv.slice(2);
if (!['sections', 'split', 'job'].includes(what) || !file) {
  console.error('usage: node polyslice-mesh.mjs sections|split|job MESH.stl [LAYER_HEIGHT]');
  process.exit(2);
}
const layerHeight = Number(h);
const name = basename(file, '.stl');
const out = join(here, 'out');
mkdirSync(out, { recursive: true });

// Wall-clock time is what the tables compare; the process's CPU time (user + system) is
// kept beside it, as the machine is shared.
const cpuSeconds = (c0) => {
  const c = process.cpuUsage(c0);
  return (c.user + c.system) / 1e6;
};
const bytes = readFileSync(file);
const geometry = new STLLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
const mesh = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial());
const box = new THREE.Box3().setFromObject(mesh);
const triangles = geometry.attributes.position.count / 3;

if (what === 'sections') {
  const Polytree = require('@jgphilpott/polytree');
  const t0 = process.hrtime.bigint(), c0 = process.cpuUsage();
  const layers = Polytree.sliceIntoLayers(mesh, layerHeight, box.min.z + layerHeight / 2, box.max.z);
  const seconds = Number(process.hrtime.bigint() - t0) / 1e9, cpu = cpuSeconds(c0);
  const record = { mesh: name, triangles, layerHeight, seconds, cpu, layers: layers.length, segments: layers.map((l) => l.length) };
  writeFileSync(join(out, `polyslice-sections-${name}-${h}.json`), JSON.stringify(record));
  console.log(`${name}: ${layers.length} layers of ${triangles} triangles sliced in ${seconds.toFixed(1)} s`);
} else if (what === 'split') {
  const Polytree = require('@jgphilpott/polytree');
  const time = (fn) => {
    const t0 = process.hrtime.bigint();
    fn();
    return Number(process.hrtime.bigint() - t0) / 1e9;
  };
  let tree;
  const build = time(() => { tree = Polytree.fromMesh(mesh); });
  const gather = Math.min(...[0, 1, 2].map(() => time(() => tree.getTriangles())));
  const z = (box.min.z + box.max.z) / 2;
  const gathered = tree.getTriangles();
  tree.getTriangles = () => gathered;
  const planeTest = time(() => Polytree.sliceIntoLayers(tree, layerHeight, z, z + 24.5 * layerHeight)) / 25;
  const record = { mesh: name, triangles, build, gather, planeTest };
  writeFileSync(join(out, `polyslice-split-${name}.json`), JSON.stringify(record));
  console.log(`${name}: fromMesh ${build.toFixed(2)} s; per layer: getTriangles ${gather.toFixed(3)} s, plane test ${record.planeTest.toFixed(3)} s`);
} else {
  const Polyslice = require('@jgphilpott/polyslice/src/index.js');
  const slicer = new Polyslice({
    layerHeight,
    nozzleDiameter: 0.4,
    shellWallThickness: 0.8,
    shellSkinThickness: 0.8,
    infillDensity: 20,
    infillPattern: 'grid',
    adhesionEnabled: false,
    supportEnabled: false,
    verbose: true,
  });
  const t0 = process.hrtime.bigint(), c0 = process.cpuUsage();
  const gcode = slicer.slice(mesh);
  const seconds = Number(process.hrtime.bigint() - t0) / 1e9, cpu = cpuSeconds(c0);
  writeFileSync(join(out, `polyslice-${name}-${h}.gcode`), gcode);
  const record = {
    mesh: name, triangles, layerHeight, seconds, cpu, layers: slicer.totalLayers,
    centerOffsetX: slicer.centerOffsetX, centerOffsetY: slicer.centerOffsetY,
  };
  writeFileSync(join(out, `polyslice-${name}-${h}.json`), JSON.stringify(record));
  console.log(`${name}: Polyslice sliced ${slicer.totalLayers} layers to G-code in ${seconds.toFixed(1)} s`);
}
