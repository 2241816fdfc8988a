// The JS side of rotlang's wasm modules (rotlang.wasm, and rotlang-infill.wasm when
// built): rotlang.js binds this to its module and exports the functions.
//
// The wasm exports plain C functions (see bindings/js/src/ffi.rs): `bind` copies the
// template (UTF-8) and the options (a Float64Array of slots) into wasm memory, calls, and
// reads the JSON answer (and for expand, typed arrays) back.

/** Fill names, indexed by the bytes of `expand(...).fills`. */
export const FILLS = Object.freeze(['sparse', 'dense', 'solid', 'concentric', 'monotonic', 'rectilinear']);

/** Thrown by every function on bad input: never a crash, always a reason. */
export class RotlangError extends Error {
  constructor(kind, message, diagnostics = null) {
    super(message);
    this.name = 'RotlangError';
    /** 'template' | 'model' | 'options' | 'limit' | 'unavailable' | 'internal' */
    this.kind = kind;
    /** For kind 'template': the template's diagnostics (as `check` returns them). */
    this.diagnostics = diagnostics;
  }
}

/** Compiles the wasm module at `url` (a file: URL in Node, fetched elsewhere). */
export async function compile(url) {
  if (url.protocol === 'file:') {
    // Node (and Deno, Bun): read the file; fetch() does not take file: URLs there.
    // The module name is in a variable so that bundlers leave it alone.
    const fsName = 'node:fs/promises';
    const { readFile } = await import(/* @vite-ignore */ fsName);
    return WebAssembly.compile(await readFile(url));
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`rotlang: cannot load ${url}: HTTP ${response.status}`);
  return WebAssembly.compile(await response.arrayBuffer());
}

const encoder = new TextEncoder();
const decoder = new TextDecoder();

// Copies bytes into wasm memory; returns [ptr, len].
function put(ex, bytes) {
  const len = bytes.length;
  const ptr = ex.rotlang_alloc(len);
  if (ptr === 0) throw new RotlangError('limit', `cannot allocate ${len} bytes for the input`);
  new Uint8Array(ex.memory.buffer, ptr, len).set(bytes);
  return [ptr, len];
}

function readJson(ex) {
  const ptr = ex.rotlang_out_ptr();
  const len = ex.rotlang_out_len();
  return JSON.parse(decoder.decode(new Uint8Array(ex.memory.buffer, ptr, len)));
}

function textArg(text) {
  if (typeof text !== 'string') {
    throw new RotlangError('options', `the template must be a string, not ${text === null ? 'null' : typeof text}`);
  }
  return text;
}

// The request crosses into wasm as a Float64Array of slots (src/options.rs `slot`), the
// last a bit mask of the slots given (so a NaN given is not taken for an absent value).
// Keys and types are checked here; target and dialect names, the numbers' ranges and the
// model are read in wasm by `rotlang::api`, as the C and Python bindings read theirs.
const SLOTS = {
  target: 0, dialect: 1, layers: 2, height: 3, layerHeight: 4, firstLayerHeight: 5,
  bottomShells: 6, topShells: 7, base: 8, seed: 9, from: 10, to: 11,
  layer: 12, density: 13, pattern: 14, shape: 15, width: 16,
};
// Top-level `height` is the picture's; the model's `height` (slot 3) is inside `model`.
const PICTURE_HEIGHT = 17;
const PRESENT = 18;
const SLOT_COUNT = 19;
/** The preview's patterns and outlines (indices cross into wasm; src/api.rs `SHAPES`). */
export const PATTERNS = Object.freeze(['lines', 'grid', 'triangles', 'hexagons', 'concentric', 'gyroid', 'spiral', 'lightning', 'cubic']);
export const SHAPES = Object.freeze(['square', 'circle', 'ring', 'star', 'l']);
// The names wasm reads (`rotlang_choice`).
const CHOICES = { target: 0, dialect: 1 };

// A model may use this API's camelCase names or the conformance models.json names.
const MODEL_KEYS = {
  layers: 'layers',
  height: 'height',
  layerHeight: 'layerHeight',
  layer_height: 'layerHeight',
  firstLayerHeight: 'firstLayerHeight',
  first_layer_height: 'firstLayerHeight',
  bottomShells: 'bottomShells',
  bottom_shell_layers: 'bottomShells',
  topShells: 'topShells',
  top_shell_layers: 'topShells',
};

// A number for wasm to check (NaN and infinities included: the shared API refuses them
// with the message every binding gives).
function number(kind, name, v) {
  if (typeof v !== 'number') {
    throw new RotlangError(kind, `\`${name}\` must be a number, not ${JSON.stringify(v) ?? String(v)}`);
  }
  return v;
}

// The number of a target or dialect name, read in wasm.
function choice(ex, key, value) {
  const [ptr, len] = put(ex, encoder.encode(String(value)));
  try {
    const i = ex.rotlang_choice(CHOICES[key], ptr, len);
    if (i < 0) {
      const answer = readJson(ex);
      throw new RotlangError(answer.kind, answer.message);
    }
    return i;
  } finally {
    ex.rotlang_dealloc(ptr, len);
  }
}

function finite(kind, name, v) {
  if (typeof v !== 'number' || !Number.isFinite(v)) {
    throw new RotlangError(kind, `\`${name}\` must be a finite number, not ${typeof v === 'number' ? v : JSON.stringify(v) ?? String(v)}`);
  }
  return v;
}

// The request slots and the list heights (a Float64Array or null) of an options object.
function request(ex, options) {
  if (options === undefined || options === null) options = {};
  if (typeof options !== 'object') throw new RotlangError('options', 'the options must be an object');
  const slots = new Float64Array(SLOT_COUNT).fill(NaN);
  let present = 0;
  const set = (slot, v) => {
    slots[slot] = v;
    present += 2 ** slot;
  };
  let heights = null;
  for (const [key, value] of Object.entries(options)) {
    if (value === undefined || value === null) continue;
    if (key in CHOICES) {
      set(SLOTS[key], choice(ex, key, value));
    } else if (key === 'pattern' || key === 'shape') {
      const names = { pattern: PATTERNS, shape: SHAPES }[key];
      const i = names.indexOf(typeof value === 'string' ? value.trim().toLowerCase() : value);
      if (i < 0) {
        throw new RotlangError('options', `unknown ${key} \`${value}\`; expected ${names.map((n) => `\`${n}\``).join(' or ')}`);
      }
      set(SLOTS[key], i);
    } else if (key === 'height') {
      set(PICTURE_HEIGHT, finite('options', key, value));
    } else if (key === 'base' || key === 'seed') {
      set(SLOTS[key], number('options', key, value));
    } else if (['from', 'to', 'layer', 'density', 'width'].includes(key)) {
      set(SLOTS[key], finite('options', key, value));
    } else if (key === 'model') {
      if (typeof value !== 'object') throw new RotlangError('model', 'the model must be an object');
      for (const [k, v] of Object.entries(value)) {
        if (v === undefined || v === null || k === 'description') continue;
        if (k === 'layerHeights' || k === 'layer_heights') {
          if (!(Array.isArray(v) || ArrayBuffer.isView(v))) {
            throw new RotlangError('model', '`layerHeights` must be an array of numbers');
          }
          heights = v instanceof Float64Array ? v : Float64Array.from(v, Number);
          if (heights.length === 0) throw new RotlangError('model', 'the model has no layers');
          continue;
        }
        const name = MODEL_KEYS[k];
        if (!name) throw new RotlangError('model', `unknown model field \`${k}\``);
        set(SLOTS[name], number('model', k, v));
      }
    } else {
      throw new RotlangError('options', `unknown option \`${key}\``);
    }
  }
  slots[PRESENT] = present;
  return [slots, heights];
}

/** The API on one compiled module (each call of `bind` has its own instance). */
export async function bind(wasmModule) {
  let instance = await WebAssembly.instantiate(wasmModule, {});

  // After a trap (an internal bug; never expected) the instance's state is unknown: start a
  // fresh one. Synchronously where allowed (Node, workers), else in the background.
  function restart() {
    instance = null;
    try {
      instance = new WebAssembly.Instance(wasmModule, {});
    } catch {
      WebAssembly.instantiate(wasmModule, {}).then((i) => {
        instance = i;
      });
    }
  }

  function exportsOrThrow() {
    if (!instance) {
      throw new RotlangError('internal', 'rotlang is restarting after an internal error; try again');
    }
    return instance.exports;
  }

  // One call: copies inputs in, calls `name`, frees inputs, returns the JSON answer or
  // throws the failure.
  function call(name, text, options, withHeights = false) {
    const ex = exportsOrThrow();
    const [slots, heights] = request(ex, options);
    const textBytes = encoder.encode(textArg(text));
    const reqBytes = new Uint8Array(slots.buffer);
    let t = null;
    let r = null;
    let h = null;
    try {
      t = put(ex, textBytes);
      r = put(ex, reqBytes);
      let code;
      if (withHeights) {
        const count = heights ? heights.length : 0;
        h = [ex.rotlang_alloc(count * 8), count * 8];
        if (h[0] === 0) throw new RotlangError('limit', `cannot allocate ${count} layer heights`);
        if (count) new Float64Array(ex.memory.buffer, h[0], count).set(heights);
        code = ex[name](t[0], t[1], r[0], SLOT_COUNT, h[0], count);
      } else {
        code = ex[name](t[0], t[1], r[0], SLOT_COUNT);
      }
      const answer = readJson(ex);
      if (code !== 0) throw new RotlangError(answer.kind, answer.message, answer.diagnostics ?? null);
      return answer;
    } catch (e) {
      if (e instanceof WebAssembly.RuntimeError || e instanceof RangeError) {
        // A trap (or memory that cannot grow): the instance is not usable any more.
        t = r = h = null;
        restart();
        throw new RotlangError('internal', `rotlang failed internally (${e.message}); the input was refused`);
      }
      throw e;
    } finally {
      for (const block of [t, r, h]) if (block) ex.rotlang_dealloc(block[0], block[1]);
    }
  }

  /** The version of the rotlang library in the wasm module. */
  function version() {
    const ex = exportsOrThrow();
    ex.rotlang_version();
    return readJson(ex).version;
  }

  /** The signs that may follow an angle: `{ sign, kind, meaning }` (for completion). */
  function signs() {
    const ex = exportsOrThrow();
    ex.rotlang_signs();
    return readJson(ex);
  }

  /** Every diagnostic of a template (errors and warnings); never throws for a bad template. */
  function check(text, options = {}) {
    const answer = call('rotlang_check', text, options);
    // The instructions come as four u32 a span (bytes, then UTF-16 units), not as JSON: a
    // megabyte template has a quarter of a million of them (src/api.rs `check`).
    const ex = instance.exports;
    const n = ex.rotlang_spans_len();
    const flat = new Uint32Array(ex.memory.buffer, ex.rotlang_spans_ptr(), n);
    const instructions = new Array(n >> 2);
    for (let i = 0, k = 0; k < n; i += 1, k += 4) {
      const startUtf16 = flat[k + 2];
      const endUtf16 = flat[k + 3];
      instructions[i] = {
        start: flat[k], end: flat[k + 1], startUtf16, endUtf16, text: text.slice(startUtf16, endUtf16),
      };
    }
    ex.rotlang_release();
    answer.instructions = instructions;
    return answer;
  }

  /** The canonical form of a template; throws a RotlangError (kind 'template') when it has errors. */
  function format(text, options = {}) {
    return call('rotlang_format', text, options).text;
  }

  /** The template in plain words on the model: each instruction with the layers it governs. */
  function explain(text, options = {}) {
    return call('rotlang_explain', text, options, true).text;
  }

  /** A diagnostic code (`rotlang::unknown-sign`) explained, with an example and the fix; null if unknown. */
  function explainCode(code) {
    return call('rotlang_explain_code', code, {});
  }

  /**
   * How OrcaSlicer's own reading of the text differs from rotlang's on the model: the first
   * layer whose direction differs, the solid layers it loses, and where it hangs, crashes or
   * computes NaN (`findings`).
   */
  function compare(text, options = {}) {
    return call('rotlang_compare', text, options, true);
  }

  /** The angle and fill of every layer (or of layers `from`..`to`) of a model. */
  function expand(text, options = {}) {
    const answer = call('rotlang_expand', text, options, true);
    const ex = instance.exports;
    const n = ex.rotlang_layers_len();
    const buf = ex.memory.buffer;
    // Copies: the wasm memory is reused (and may move) on the next call.
    const angles = new Float64Array(buf, ex.rotlang_angles_ptr(), n).slice();
    const fills = new Uint8Array(buf, ex.rotlang_fills_ptr(), n).slice();
    const instructionIndex = new Int32Array(buf, ex.rotlang_instructions_ptr(), n).slice();
    ex.rotlang_release();
    return { ...answer, angles, fills, instructionIndex };
  }

  /** OrcaSlicer compat diagnostics (codes `orcaslicer::…`), with spans and fixes like check's. */
  function compat(text, options = {}) {
    return call('rotlang_compat', text, options, true).diagnostics;
  }

  /**
   * The templates and model of a profile file: `name` picks the kind by its extension
   * (`.json`, `.jsonc`, `.ini`, `.rot`); `content` is its text or bytes.
   */
  function readProfile(name, content) {
    if (typeof name !== 'string') throw new RotlangError('options', 'the profile name must be a string');
    const bytes = typeof content === 'string' ? encoder.encode(content)
      : content instanceof Uint8Array ? content
        : ArrayBuffer.isView(content) || content instanceof ArrayBuffer ? new Uint8Array(content.buffer ?? content)
          : null;
    if (!bytes) throw new RotlangError('options', 'the profile content must be a string or bytes');
    const ex = exportsOrThrow();
    let n = null;
    let b = null;
    try {
      n = put(ex, encoder.encode(name));
      b = put(ex, bytes);
      const code = ex.rotlang_profile(n[0], n[1], b[0], b[1]);
      const answer = readJson(ex);
      if (code !== 0) throw new RotlangError(answer.kind, answer.message, null);
      return answer;
    } catch (e) {
      if (e instanceof WebAssembly.RuntimeError) {
        n = b = null;
        restart();
        throw new RotlangError('internal', `rotlang failed internally (${e.message}); the input was refused`);
      }
      throw e;
    } finally {
      for (const block of [n, b]) if (block) ex.rotlang_dealloc(block[0], block[1]);
    }
  }

  /** The angle chart as SVG (`rotlang plot`): options as expand's, plus `width`, `height` (px). */
  function plot(text, options = {}) {
    return call('rotlang_plot', text, options, true).svg;
  }

  /**
   * One layer's infill as printed, seen from above, as SVG (`rotlang preview`): options as
   * expand's, plus `layer`, `pattern` (PATTERNS), `density` (0 to 1), `shape` (SHAPES) and
   * `width` (the panel's side, px).
   */
  function preview(text, options = {}) {
    return call('rotlang_preview', text, options, true).svg;
  }

  /**
   * Reads a mesh file (`name` picks STL, OBJ or 3MF by its extension; `content` its bytes)
   * and keeps it for `part`: `{ triangles, vertices, min, max, objects }`.
   */
  function readMesh(name, content) {
    if (typeof name !== 'string') throw new RotlangError('options', 'the mesh name must be a string');
    const bytes = content instanceof Uint8Array ? content
      : ArrayBuffer.isView(content) ? new Uint8Array(content.buffer, content.byteOffset, content.byteLength)
        : content instanceof ArrayBuffer ? new Uint8Array(content)
          : typeof content === 'string' ? encoder.encode(content) : null;
    if (!bytes) throw new RotlangError('options', 'the mesh content must be bytes or a string');
    return withInputs('rotlang_mesh', [encoder.encode(name), bytes], []);
  }

  /**
   * The kept mesh (`readMesh`) sliced at its layers and filled under the template, as
   * `rotlang preview --shape part.stl --format json`: `{ template, solid_template, settings,
   * summary, layers }`, each layer with its `z`, `angle`, `fill`, `printed`, `section`
   * (polygons: outline then holes, `[x, y]` points), `areas` (the sparse and the solid one,
   * each with its region and paths) and infill `polylines`. Options as expand's (the model
   * is as tall as the mesh unless it gives `layers` or `height`; its `bottomShells` and
   * `topShells` are the solid surfaces' depths; `from`/`to` pick the layers returned), plus
   * `pattern`, `density`, `walls` (wall loops, 2 when absent), `solidTemplate` (turns
   * the solid areas, as `--solid-template`; without it they turn with the template, or
   * with a project's solid template), `noSolidTemplate` (true: they turn with the
   * template even where a project sets a solid template, as `--no-solid-template`) and
   * `object` (a 3MF's object, as `--object`: that object alone, with its overrides; all
   * objects merged when absent). For an OrcaSlicer project, what the options do not give
   * is the project's (the object's overrides first), and an empty template is its
   * template, as `rotlang preview project.3mf` reads it.
   */
  function part(text, options = {}) {
    return partCall(text, options, false);
  }

  /**
   * What `part(text, options)` fills the part with, without slicing it: `{ template,
   * solid_template, settings, first_layer_height, solid_base }` (an OrcaSlicer project's
   * templates and settings, `object`'s overrides first, where the options do not say).
   */
  function partSettings(text, options = {}) {
    const { template, solid_template, settings, first_layer_height, solid_base } = partCall(text, options, true);
    return { template, solid_template, settings, first_layer_height, solid_base };
  }

  function partCall(text, options, settingsOnly) {
    const { walls, solidTemplate, noSolidTemplate, object, ...rest } = options ?? {};
    if (walls !== undefined && walls !== null) finite('options', 'walls', walls);
    const solid = solidTemplate !== undefined && solidTemplate !== null;
    if (solid && typeof solidTemplate !== 'string') {
      throw new RotlangError('options', `\`solidTemplate\` must be a string, not ${JSON.stringify(solidTemplate) ?? String(solidTemplate)}`);
    }
    if (noSolidTemplate !== undefined && noSolidTemplate !== null && typeof noSolidTemplate !== 'boolean') {
      throw new RotlangError('options', `\`noSolidTemplate\` must be true or false, not ${JSON.stringify(noSolidTemplate) ?? String(noSolidTemplate)}`);
    }
    // As the CLI's --solid-template and --no-solid-template: one or the other.
    if (solid && noSolidTemplate === true) {
      throw new RotlangError('options', '`solidTemplate` and `noSolidTemplate` cannot be given together: a solid template, or none');
    }
    const named = object !== undefined && object !== null;
    if (named && typeof object !== 'string') {
      throw new RotlangError('options', `\`object\` must be a string (a 3MF object's name), not ${JSON.stringify(object) ?? String(object)}`);
    }
    const [slots] = request(exportsOrThrow(), rest);
    const inputs = [encoder.encode(textArg(text)), encoder.encode(solid ? solidTemplate : ''),
      encoder.encode(named ? object : ''), new Uint8Array(slots.buffer)];
    return withInputs('rotlang_part', inputs, [walls ?? NaN, solid ? 1 : noSolidTemplate === true ? 2 : 0, named ? 1 : 0, settingsOnly ? 1 : 0], true);
  }

  // Copies the byte inputs in, calls `name` with their (pointer, length) pairs (a request's
  // length counted in slots) then `extra`, frees them, returns the answer or throws.
  function withInputs(name, inputs, extra, lastIsRequest = false) {
    const ex = exportsOrThrow();
    const blocks = [];
    try {
      for (const b of inputs) blocks.push(put(ex, b));
      const args = blocks.flatMap((b, i) => (lastIsRequest && i === blocks.length - 1 ? [b[0], SLOT_COUNT] : b));
      const code = ex[name](...args, ...extra);
      const answer = readJson(ex);
      if (code !== 0) throw new RotlangError(answer.kind, answer.message, answer.diagnostics ?? null);
      ex.rotlang_release();
      return answer;
    } catch (e) {
      if (e instanceof WebAssembly.RuntimeError || e instanceof RangeError) {
        blocks.length = 0;
        restart();
        throw new RotlangError('internal', `rotlang failed internally (${e.message}); the input was refused`);
      }
      throw e;
    } finally {
      for (const block of blocks) ex.rotlang_dealloc(block[0], block[1]);
    }
  }

  const api = { version, signs, check, format, explain, explainCode, compare, compat, expand };
  // In rotlang-full.wasm only.
  if (instance.exports.rotlang_profile) api.readProfile = readProfile;
  if (instance.exports.rotlang_preview) Object.assign(api, { plot, preview });
  if (instance.exports.rotlang_part) Object.assign(api, { readMesh, part, partSettings });
  return api;
}
