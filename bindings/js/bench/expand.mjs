// The Node side of "JS expand of 100k layers against native": `node bench/expand.mjs`
// (after `node build.mjs`). The same template and model as benches/expand.rs, whose
// native numbers come from `cargo bench -p rotlang-wasm --bench expand`.
import { expand } from '../rotlang.js';

const TEMPLATE = '5, 10!, +20, +10L25%, -10l25%';
const LAYERS = 100_000;
const options = { model: { layers: LAYERS, layerHeight: 0.2, firstLayerHeight: 0.3 } };

for (let i = 0; i < 20; i++) expand(TEMPLATE, options); // warm-up (JIT, memory growth)
const samples = [];
for (let i = 0; i < 100; i++) {
  const t = process.hrtime.bigint();
  const r = expand(TEMPLATE, options);
  samples.push(Number(process.hrtime.bigint() - t) / 1e6);
  if (r.angles.length !== LAYERS) throw new Error('wrong layer count');
}
samples.sort((a, b) => a - b);
const median = samples[samples.length >> 1];
console.log(`JS expand of ${LAYERS.toLocaleString('en')} layers: median ${median.toFixed(3)} ms, fastest ${samples[0].toFixed(3)} ms (${((median * 1e6) / LAYERS).toFixed(1)} ns/layer) over ${samples.length} runs`);
