// All rotlang work runs here, off the main thread: a 1 MB template or a million layers
// never freezes the page. The main thread sends {id, op, args}; the answer is
// {id, ok, result} or {id, ok: false, error: {kind, message, diagnostics}}.
import { MAX_LAYERS, MAX_MESH, MAX_TEMPLATE } from './limits.js';
import { profileExtras, MAX_PROFILE } from './profile.js';

// Loaded lazily so that onmessage is set before the wasm is ready (messages sent
// meanwhile wait for it instead of being lost).
const rotlang = import('rotlang/full');

function refuse(kind, message) {
  return Object.assign(new Error(message), { kind });
}

function options(state) {
  const o = { target: state.target, model: state.model, base: state.base, seed: state.seed };
  if (state.dialect && state.dialect !== 'rotlang') o.dialect = state.dialect;
  return o;
}

function partOptions(state) {
  const { layers, ...model } = state.model;
  const o = {
    target: state.target, model, base: state.base, seed: state.seed,
    pattern: state.pattern, density: state.density, walls: state.walls,
  };
  if (state.object) o.object = state.object;
  // None, even a project's (the CLI's --no-solid-template); else the one typed.
  if (state.noSolidTemplate) {
    o.noSolidTemplate = true;
  } else if (state.solidTemplate) {
    if (state.solidTemplate.length > MAX_TEMPLATE) throw refuse('limit', 'the solid template is longer than the playground takes');
    o.solidTemplate = state.solidTemplate;
  }
  return o;
}

const ops = {
  async analyse(state) {
    const r = await rotlang;
    if (state.text.length > MAX_TEMPLATE) {
      throw refuse('limit', `the template has ${state.text.length.toLocaleString('en')} characters; the playground takes up to ${MAX_TEMPLATE.toLocaleString('en')}`);
    }
    const check = r.check(state.text, { target: state.target });
    const out = { check, layers: null, compat: [], transfer: [] };
    const layers = state.model.layers;
    if (layers > MAX_LAYERS) {
      out.refused = `${Number(layers).toLocaleString('en')} layers asked for; the playground evaluates up to ${MAX_LAYERS.toLocaleString('en')} (the CLI up to 100,000,000)`;
    } else if (!check.hasErrors || (state.dialect && state.dialect !== 'rotlang')) {
      try {
        // The base is added in either reading, as the library adds an embedder's base; a
        // profile's direction reaches it only for an empty template (main.js).
        const e = r.expand(state.text, options(state));
        // Each instruction's layers: first, last and how many.
        const ranges = e.instructions.map(() => ({ first: -1, last: -1, count: 0 }));
        for (let i = 0; i < e.instructionIndex.length; i++) {
          const k = e.instructionIndex[i];
          if (k < 0) continue;
          const g = ranges[k];
          if (g.first < 0) g.first = i;
          g.last = i;
          g.count++;
        }
        out.layers = { ...e, ranges };
        out.transfer = [e.angles.buffer, e.fills.buffer, e.instructionIndex.buffer];
      } catch (err) {
        if (err.kind === 'template') throw err;
        out.modelError = err.message;
      }
    }
    if (!out.refused) {
      try {
        out.compat = r.compat(state.text, { ...options(state), dialect: undefined });
      } catch (err) {
        out.compat = [];
      }
      try {
        out.compare = r.compare(state.text, { ...options(state), dialect: undefined });
      } catch (err) {
        out.compareError = err.message;
      }
    }
    if (typeof r.explain === 'function' && !check.hasErrors) {
      try {
        out.explain = r.explain(state.text, options(state));
      } catch {
        out.explain = null;
      }
    }
    return out;
  },
  async format({ text, target }) {
    const r = await rotlang;
    if (text.length > MAX_TEMPLATE) throw refuse('limit', 'the template is too long to format here');
    return r.format(text, { target });
  },
  // One layer's infill as printed (rotlang::infill), seen from above.
  async preview(state) {
    const r = await rotlang;
    return r.preview(state.text, {
      ...options(state), dialect: undefined, layer: state.layer, pattern: state.pattern,
      density: state.density, shape: state.shape, width: 320,
    });
  },
  // The angle chart against height (rotlang::plot).
  async plot(state) {
    const r = await rotlang;
    return r.plot(state.text, { ...options(state), dialect: undefined, width: state.width ?? 720, height: state.height ?? 420 });
  },
  // rotlang's own profile reader (JSON, jsonc, .ini, .rot, an OrcaSlicer .3mf project's
  // settings); a file of another name is read
  // as JSON, and refused when it holds no template.
  async profile({ name, bytes }) {
    const r = await rotlang;
    if (bytes.byteLength > MAX_PROFILE) {
      throw refuse('limit', `${name} is ${(bytes.byteLength / 1048576).toFixed(1)} MB; profiles above ${MAX_PROFILE / 1048576} MB are refused`);
    }
    const known = /\.(json|jsonc|ini|rot|3mf)$/i.test(name);
    const p = r.readProfile(known ? name : `${name}.json`, new Uint8Array(bytes));
    if (p.templates.length === 0) {
      const error = p.notes.find((n) => n.error);
      throw refuse('profile', error
        ? `${name} is not a profile rotlang can read: ${error.message}`
        : `${name} has no sparse_infill_rotate_template or solid_infill_rotate_template`);
    }
    return { ...p, ...profileExtras(p.kind, bytes), name };
  },
  // A mesh file (STL, OBJ, 3MF), read and kept in the wasm instance for `part`.
  async mesh({ name, bytes }) {
    const r = await rotlang;
    if (bytes.byteLength > MAX_MESH) {
      throw refuse('limit', `${name} is ${(bytes.byteLength / 1048576).toFixed(1)} MB; meshes above ${MAX_MESH / 1048576} MB are refused here (the CLI reads them)`);
    }
    return r.readMesh(name, new Uint8Array(bytes));
  },
  // The kept mesh (all its objects, or `state.object`) sliced and filled, every layer
  // (rotlang::slice::Part, as `rotlang preview --shape part.stl --format json`): as tall
  // as the mesh, so the model's layer count is left out. `solidTemplate` turns the solid
  // areas (absent: a project's, else they turn with the template).
  async part(state) {
    const r = await rotlang;
    return r.part(state.text, partOptions(state));
  },
  // What a project gives the part (of `object`): its templates and settings, the object's
  // overrides first (rotlang's reading, the CLI's), without slicing.
  async partSettings({ object }) {
    const r = await rotlang;
    return r.partSettings('', { object: object || undefined });
  },
  // The solid template's diagnostics (rotlang::check for solid_infill_rotate_template).
  async checkSolid({ text }) {
    const r = await rotlang;
    if (text.length > MAX_TEMPLATE) {
      throw refuse('limit', `the solid template has ${text.length.toLocaleString('en')} characters; the playground takes up to ${MAX_TEMPLATE.toLocaleString('en')}`);
    }
    return r.check(text, { target: 'solid' });
  },
  async signs() {
    return (await rotlang).signs();
  },
  async version() {
    return (await rotlang).version();
  },
};

self.onmessage = async ({ data: { id, op, args } }) => {
  try {
    const result = await ops[op](args);
    const transfer = result && result.transfer ? result.transfer : [];
    if (result && result.transfer) delete result.transfer;
    self.postMessage({ id, ok: true, result }, transfer);
  } catch (e) {
    self.postMessage({
      id,
      ok: false,
      error: { kind: e.kind ?? 'internal', message: e.message ?? String(e), diagnostics: e.diagnostics ?? null },
    });
  }
};
