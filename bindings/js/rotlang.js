// rotlang for JavaScript: the WebAssembly build of the rotlang library behind a small
// synchronous API. An ES module for Node 20+ and browsers, no bundler needed: importing
// it loads rotlang.wasm (beside this file) once, with top-level await.
//
// The wasm exports plain C functions (see bindings/js/src/ffi.rs): this file copies the
// template and a JSON request into wasm memory, calls, and reads the JSON answer (and
// for expand, typed arrays) back.

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

const wasmUrl = new URL('./rotlang.wasm', import.meta.url);

async function compile(url) {
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

const wasmModule = await compile(wasmUrl);
let instance = await WebAssembly.instantiate(wasmModule, {});
let restarting = null;

// After a trap (an internal bug; never expected) the instance's state is unknown: start a
// fresh one. Synchronously where allowed (Node, workers), else in the background.
function restart() {
  instance = null;
  try {
    instance = new WebAssembly.Instance(wasmModule, {});
  } catch {
    restarting = WebAssembly.instantiate(wasmModule, {}).then((i) => {
      instance = i;
      restarting = null;
    });
  }
}

const encoder = new TextEncoder();
const decoder = new TextDecoder();

function exportsOrThrow() {
  if (!instance) {
    throw new RotlangError('internal', 'rotlang is restarting after an internal error; try again');
  }
  return instance.exports;
}

// Copies bytes into wasm memory; returns [ptr, len].
function put(ex, bytes) {
  const len = bytes.length;
  const ptr = ex.rotlang_alloc(len);
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

// The request JSON and the list heights (a Float64Array or null) of an options object.
// A model may use this API's camelCase names or the conformance models.json names.
function request(options) {
  if (options === undefined || options === null) options = {};
  if (typeof options !== 'object') throw new RotlangError('options', 'the options must be an object');
  const req = {};
  let heights = null;
  for (const [key, value] of Object.entries(options)) {
    if (value === undefined) continue;
    if (key !== 'model') {
      if (typeof value === 'number' && !Number.isFinite(value)) {
        throw new RotlangError('options', `\`${key}\` must be a finite number, not ${value}`);
      }
      req[key] = value;
      continue;
    }
    if (value === null) continue;
    if (typeof value !== 'object') throw new RotlangError('model', 'the model must be an object');
    const model = {};
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
      if (typeof v !== 'number' || !Number.isFinite(v)) {
        throw new RotlangError('model', `\`${k}\` must be a finite number, not ${JSON.stringify(v) ?? String(v)}`);
      }
      model[name] = v;
    }
    req.model = model;
  }
  return [JSON.stringify(req), heights];
}

// One call: copies inputs in, calls `name`, frees inputs, returns the JSON answer or
// throws the failure.
function call(name, text, options, withHeights = false) {
  const [req, heights] = request(options);
  const ex = exportsOrThrow();
  const textBytes = encoder.encode(textArg(text));
  const reqBytes = encoder.encode(req);
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
      if (count) new Float64Array(ex.memory.buffer, h[0], count).set(heights);
      code = ex[name](t[0], t[1], r[0], r[1], h[0], count);
    } else {
      code = ex[name](t[0], t[1], r[0], r[1]);
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
export function version() {
  const ex = exportsOrThrow();
  ex.rotlang_version();
  return readJson(ex).version;
}

/** The signs that may follow an angle: `{ sign, kind, meaning }` (for completion). */
export function signs() {
  const ex = exportsOrThrow();
  ex.rotlang_signs();
  return readJson(ex);
}

/** Every diagnostic of a template (errors and warnings); never throws for a bad template. */
export function check(text, options = {}) {
  return call('rotlang_check', text, options);
}

/** The canonical form of a template; throws a RotlangError (kind 'template') when it has errors. */
export function format(text, options = {}) {
  return call('rotlang_format', text, options).text;
}

/** The angle and fill of every layer (or of layers `from`..`to`) of a model. */
export function expand(text, options = {}) {
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
