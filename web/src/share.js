// The share link: template, model and view in the URL fragment (never sent to a server).
const FIELDS = {
  t: 'text', target: 'target', dialect: 'dialect', layers: 'layers', lh: 'layerHeight',
  flh: 'firstLayerHeight', b: 'bottomShells', top: 'topShells', base: 'base', seed: 'seed',
  layer: 'layer', pattern: 'pattern', density: 'density', shape: 'shape',
  // The part panel's: applied when the part (not in the link) is opened again.
  solid: 'solidTemplate', nosolid: 'noSolidTemplate', object: 'object',
};

export function encodeState(state) {
  const p = new URLSearchParams();
  for (const [key, name] of Object.entries(FIELDS)) {
    const v = state[name];
    if (v !== undefined && v !== null && v !== '') p.set(key, String(v));
  }
  return `#${p.toString()}`;
}

/** The state in a fragment, or null when it holds none. */
export function decodeState(hash) {
  const p = new URLSearchParams(hash.replace(/^#/, ''));
  if (!p.has('t')) return null;
  const state = {};
  for (const [key, name] of Object.entries(FIELDS)) {
    if (p.has(key)) state[name] = p.get(key);
  }
  return state;
}
