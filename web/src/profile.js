// What the playground takes from a profile beyond rotlang's reading (its templates and
// model come from rotlang's profile reader, in the worker): the preset's name, infill
// pattern and density, for the preview.
export const MAX_PROFILE = 8 * 1024 * 1024;

function value(json, key) {
  let v = json[key];
  if (Array.isArray(v)) v = v[0];
  return v === undefined || v === null ? undefined : String(v);
}

/** `{ presetName, pattern, density }` of a JSON preset; empty for anything else. */
export function profileExtras(kind, bytes) {
  if (kind !== 'json') return {};
  try {
    const json = JSON.parse(new TextDecoder().decode(bytes));
    const density = value(json, 'sparse_infill_density');
    return {
      presetName: value(json, 'name'),
      pattern: value(json, 'sparse_infill_pattern'),
      density: density === undefined ? undefined : Number.parseFloat(density),
    };
  } catch {
    return {}; // jsonc, or JSON broken after the templates: rotlang read what it could
  }
}
