// Reading an OrcaSlicer profile (a process preset JSON, or a project's settings JSON):
// its templates and the model values the templates refer to. Runs in the worker.
const MAX_PROFILE = 8 * 1024 * 1024;

function value(json, key) {
  let v = json[key];
  if (Array.isArray(v)) v = v[0];
  if (v === undefined || v === null) return undefined;
  return String(v);
}

function number(json, key) {
  const v = value(json, key);
  if (v === undefined) return undefined;
  const n = Number.parseFloat(v);
  return Number.isFinite(n) ? n : undefined;
}

export function readProfile(name, text) {
  if (text.length > MAX_PROFILE) {
    throw Object.assign(new Error(`${name} is ${(text.length / 1048576).toFixed(1)} MB; profiles above 8 MB are refused`), { kind: 'limit' });
  }
  let json;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw Object.assign(new Error(`${name} is not a JSON profile: ${e.message}`), { kind: 'profile' });
  }
  if (!json || typeof json !== 'object' || Array.isArray(json)) {
    throw Object.assign(new Error(`${name} is JSON but not a profile (an object of settings)`), { kind: 'profile' });
  }
  const templates = [];
  for (const [key, target] of [['sparse_infill_rotate_template', 'sparse'], ['solid_infill_rotate_template', 'solid']]) {
    const t = value(json, key);
    if (t !== undefined) templates.push({ key, target, text: t });
  }
  if (templates.length === 0) {
    throw Object.assign(new Error(`${name} has no sparse_infill_rotate_template or solid_infill_rotate_template`), { kind: 'profile' });
  }
  const model = {
    layerHeight: number(json, 'layer_height'),
    firstLayerHeight: number(json, 'initial_layer_print_height'),
    bottomShells: number(json, 'bottom_shell_layers'),
    topShells: number(json, 'top_shell_layers'),
  };
  const density = value(json, 'sparse_infill_density');
  return {
    name: value(json, 'name') ?? name,
    templates,
    model,
    base: number(json, 'infill_direction'),
    pattern: value(json, 'sparse_infill_pattern'),
    density: density === undefined ? undefined : Number.parseFloat(density),
  };
}
