// The Part panel: a mesh file (STL, 3MF, OBJ) opened or dropped is read by rotlang in the
// worker (`readMesh`), then sliced and filled under the template at every change
// (`part`: rotlang::slice::Part, the answer of `rotlang preview --shape part.stl --format
// json`). The layers are drawn stacked in 3D (part3d.js, three.js) and the slider's layer
// from above in the Layer panel.
import { MAX_MESH } from './limits.js';

/** A layer's paths: those of its sparse area and those of its solid area (top and bottom surfaces). */
export function splitPaths(layer) {
  const of = (solid) => (layer.areas ?? []).filter((a) => a.solid === solid).flatMap((a) => a.polylines);
  return { sparse: of(false), solid: of(true) };
}

const $ = (id) => document.getElementById(id);
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => `&#${c.charCodeAt(0)};`);
const mm = (v) => `${Number(v.toFixed(2))}`;
// Slicing a large mesh in the worker takes longer than an analysis.
const PART_TIMEOUT_MS = 60_000;

export const isMesh = (name) => /\.(stl|3mf|obj)$/i.test(name);

/**
 * One layer of the part from above, as SVG, at the mesh's scale: its section, its solid
 * area (tinted) and the paths of its sparse and solid areas in their own colours.
 */
export function layerSvg(info, layer, nozzle = 0.4, side = 320) {
  const [x0, y0] = info.min;
  const [x1, y1] = info.max;
  const pad = Math.max(x1 - x0, y1 - y0, 1e-3) * 0.04;
  const w = x1 - x0 + 2 * pad;
  const h = y1 - y0 + 2 * pad;
  // y up, as seen from above (SVG's y goes down).
  const pt = ([x, y]) => `${mm(x - x0 + pad)},${mm(y1 + pad - y)}`;
  const section = layer.section.flat().map((r) => `M${r.map(pt).join('L')}Z`).join('');
  const paths = splitPaths(layer);
  const d = (lines) => lines.map((p) => `M${p.map(pt).join('L')}`).join('');
  const solidArea = (layer.areas ?? []).filter((a) => a.solid).flatMap((a) => a.region.flat())
    .map((r) => `M${r.map(pt).join('L')}Z`).join('');
  const solid = (layer.areas ?? []).find((a) => a.solid);
  const what = layer.printed === 'sparse+solid' ? `sparse ${layer.pattern} at ${Number(layer.angle.toFixed(2))}° with solid surfaces at ${Number(solid.angle.toFixed(2))}°`
    : solid && layer.printed !== 'sparse' ? `${layer.printed} ${solid.pattern} at ${Number(solid.angle.toFixed(2))}°`
      : `${layer.fill} ${layer.pattern} at ${Number(layer.angle.toFixed(2))}°`;
  const label = `layer ${layer.index} of the part at z ${mm(layer.z)} mm: ${what}`;
  return `<svg class="part-layer" xmlns="http://www.w3.org/2000/svg" viewBox="0 0 ${mm(w)} ${mm(h)}" width="${side}" height="${Math.round((side * h) / w)}" role="img" aria-label="${esc(label)}">`
    + `<path class="section" d="${section}" stroke-width="${mm(nozzle / 2)}"/>`
    + `<path class="solid-area" d="${solidArea}"/>`
    + `<path class="infill" d="${d(paths.sparse)}" stroke-width="${mm(nozzle)}"/>`
    + `<path class="solid" d="${d(paths.solid)}" stroke-width="${mm(nozzle)}"/></svg>`;
}

export class PartPanel {
  /**
   * `engine`: the worker; `request()`: what a part is sliced with now (template, model,
   * pattern, density, walls); `layer()`: the slider's layer; `onAnswer(answer)`: a new
   * part was drawn (the page matches its model's layer count to it); `onClose()`.
   */
  constructor(engine, { request, layer, onAnswer, onClose, onFile }) {
    Object.assign(this, { engine, request, layer, onAnswer, onClose });
    this.file = null; // { name, bytes }
    this.info = null;
    this.loaded = false; // the worker holds this file's mesh
    this.answer = null;
    this.answerKey = null; // the request the answer (or the error) is for
    this.error = null;
    this.timer = null;
    this.inFlight = 0;
    this.seq = 0;
    this.view = null;
    this.drawn = null; // the answer the 3D view shows
    $('mesh').addEventListener('change', async (e) => {
      const file = e.target.files?.[0];
      if (file) await (onFile ?? ((f) => this.open(f)))(file);
      e.target.value = '';
    });
    $('mesh-close').addEventListener('click', () => this.close());
    $('walls').addEventListener('input', () => this.schedule());
  }

  active() {
    return this.file !== null;
  }

  /** The worker was restarted: its mesh is gone. */
  restarted() {
    this.loaded = false;
  }

  message(text, refused = false) {
    $('part-info').textContent = text;
    $('part-info').classList.toggle('refused', refused);
  }

  async open(file) {
    if (file.size > MAX_MESH) {
      this.message(`refused: ${file.name} is ${(file.size / 1048576).toFixed(1)} MB; meshes above ${MAX_MESH / 1048576} MB are refused here (the CLI reads them)`, true);
      return;
    }
    this.inFlight++;
    try {
      const bytes = await file.arrayBuffer();
      this.message(`reading ${file.name}…`);
      const info = await this.engine.request('mesh', { name: file.name, bytes });
      Object.assign(this, { file: { name: file.name, bytes }, info, loaded: true, answer: null, answerKey: null, error: null });
      this.fresh = true; // the slider goes to the top layer: the whole part is seen
      $('mesh-close').hidden = false;
      $('view3d').hidden = false;
      $('shape').disabled = true;
      // The part's height over the layer height gives the count (onAnswer in main.js).
      $('layers').disabled = true;
      this.describe();
      this.schedule(0);
    } catch (e) {
      this.message(`refused: ${e.message}`, true);
    } finally {
      this.inFlight--;
    }
  }

  close() {
    Object.assign(this, { file: null, info: null, answer: null, answerKey: null, error: null, drawn: null });
    this.seq++;
    $('mesh-close').hidden = true;
    $('view3d').hidden = true;
    $('shape').disabled = false;
    $('layers').disabled = false;
    this.message('');
    this.onClose();
  }

  describe() {
    const { info, file, answer } = this;
    const size = info.max.map((v, i) => mm(v - info.min[i])).join(' × ');
    let text = `${file.name}: ${info.triangles.toLocaleString('en')} triangles, ${size} mm`;
    if (info.objects.length > 1) text += ` (${info.objects.length} objects: ${info.objects.join(', ')})`;
    if (answer) {
      const s = answer.summary;
      text += ` · ${s.layers} layers, infill ${mm(s.extrusion_mm / 1000)} m (${mm(s.solid_extrusion_mm / 1000)} m solid), travel ${mm(s.travel_mm / 1000)} m, ${Math.round(s.time_s / 60)} min at ${s.speed} mm/s`;
      if (s.open_layers) text += ` · ${s.open_layers} layers have sections that could not be closed (holes in the mesh)`;
    }
    if (this.error) text += ` · not sliced: ${this.error}`;
    this.message(text, Boolean(this.error));
  }

  schedule(delay = 60) {
    if (!this.file) return;
    clearTimeout(this.timer);
    this.timer = setTimeout(() => { this.timer = null; this.run(); }, delay);
  }

  async run() {
    const req = this.request();
    const key = JSON.stringify(req);
    if (key === this.answerKey) return;
    const id = ++this.seq;
    const file = this.file;
    this.inFlight++;
    try {
      if (!this.loaded) {
        await this.engine.request('mesh', { name: file.name, bytes: file.bytes });
        this.loaded = true;
      }
      const answer = await this.engine.request('part', req, PART_TIMEOUT_MS);
      if (id !== this.seq) return;
      Object.assign(this, { answer, answerKey: key, error: null });
      await this.draw();
      this.onAnswer(answer);
    } catch (e) {
      if (id !== this.seq) return;
      Object.assign(this, { answerKey: key, error: e.kind === 'template' ? 'fix the template first' : e.message });
    } finally {
      this.inFlight--;
      if (id === this.seq && this.file) this.describe();
    }
  }

  async draw() {
    if (!this.view) {
      const { PartView } = await import('./part3d.js');
      this.view = new PartView($('view3d'));
    }
    this.view.show(this.info, this.answer.layers);
    this.drawn = this.answer;
    this.cut(this.layer());
  }

  /** The slider moved to `index`: the 3D view cut there, and that layer from above. */
  cut(index) {
    const a = this.answer;
    if (!a || !this.view || this.drawn !== a) return;
    const i = Math.max(0, Math.min(index, a.layers.length - 1));
    this.view.cut(i);
    if (a.layers[i]) $('preview').innerHTML = layerSvg(this.info, a.layers[i]);
  }

  /** Nothing waiting or under way, and the view shows the answer for the page as it is. */
  idle() {
    if (this.timer !== null || this.inFlight > 0) return false;
    if (!this.file) return true;
    if (this.answerKey !== JSON.stringify(this.request())) return false;
    return Boolean(this.error) || (this.drawn === this.answer && this.view.current === Math.min(this.layer(), this.answer.layers.length - 1));
  }

  /** For the browser tests: the mesh, the summary and what the 3D view draws. */
  inspect() {
    return {
      name: this.file?.name ?? null,
      info: this.info,
      summary: this.answer?.summary ?? null,
      error: this.error,
      scene: this.view && this.drawn ? this.view.inspect() : null,
    };
  }
}
