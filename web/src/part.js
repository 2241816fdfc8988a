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
 * One layer of the part from above, as SVG, at the mesh's scale: its section, its wall
 * loops (grey), its solid area (tinted) and the paths of its sparse and solid areas in
 * their own colours.
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
  // Each wall loop's middle line (closed rings, outermost first), a line wide.
  const walls = (layer.walls ?? []).map((r) => `M${r.map(pt).join('L')}`).join('');
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
    + `<path class="walls" d="${walls}" stroke-width="${mm(nozzle)}"/>`
    + `<path class="infill" d="${d(paths.sparse)}" stroke-width="${mm(nozzle)}"/>`
    + `<path class="solid" d="${d(paths.solid)}" stroke-width="${mm(nozzle)}"/></svg>`;
}

export class PartPanel {
  /**
   * `engine`: the worker; `request()`: what a part is sliced with now (template, model,
   * pattern, density, walls; the panel adds its object and solid template); `layer()`:
   * the slider's layer; `onAnswer(answer)`: a new part was drawn (the page matches its
   * model's layer count to it); `onSettings(s)`: an OrcaSlicer project (or its chosen
   * object) gives these templates and settings (`partSettings`), for the page's editor
   * and model form; `onClose()`.
   */
  constructor(engine, { request, layer, onAnswer, onClose, onFile, onSettings }) {
    Object.assign(this, { engine, request, layer, onAnswer, onClose, onSettings });
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
    // The solid template's check (rotlang::check, solid target): the text last checked,
    // the checks under way, and the newest one's number.
    this.solid = { checked: '', inFlight: 0, seq: 0, diagnostics: [], refused: null };
    // A share link's object and solid template, for the next part opened.
    this.wanted = null;
    // The project's (or its object's) own solid template, for the message under the field.
    this.projectSolid = null;
    $('mesh').addEventListener('change', async (e) => {
      const file = e.target.files?.[0];
      if (file) await (onFile ?? ((f) => this.open(f)))(file);
      e.target.value = '';
    });
    $('mesh-close').addEventListener('click', () => this.close());
    $('walls').addEventListener('input', () => this.schedule());
    $('object').addEventListener('change', () => this.chooseObject());
    $('solid-template').addEventListener('input', () => {
      this.checkSolid();
      this.schedule();
    });
    $('no-solid-template').addEventListener('change', () => {
      this.noSolid($('no-solid-template').checked);
      this.schedule(0);
    });
  }

  /**
   * A share link's object and solid template (either may be undefined): chosen on the
   * part open now, else kept for the next one opened (the link holds no mesh). The
   * link's solid template wins over a project's, as it was when the link was made.
   */
  async want({ object, solidTemplate, noSolidTemplate = false }) {
    if (!this.info) {
      this.wanted = { object, solidTemplate, noSolidTemplate };
      return;
    }
    if (object !== undefined && (object === '' || this.info.objects.includes(object)) && $('object').value !== object) {
      $('object').value = object;
      this.fresh = true;
      await this.fromProject();
    }
    if (typeof solidTemplate === 'string') {
      $('solid-template').value = solidTemplate;
      this.checkSolid();
    }
    this.noSolid(noSolidTemplate);
    this.schedule(0);
  }

  /**
   * No solid template (`on`), not even the project's: the solid areas turn with the
   * template, as `rotlang preview --no-solid-template`. The field keeps its text, unused.
   */
  noSolid(on) {
    $('no-solid-template').checked = on;
    $('solid-template').disabled = on;
    this.describeSolid();
  }

  /** What the part is sliced with now: the page's request, this panel's object and solid template. */
  current() {
    const r = this.request();
    const object = $('object').value;
    const solid = $('solid-template').value;
    if (object) r.object = object;
    if ($('no-solid-template').checked) r.noSolidTemplate = true;
    else if (solid) r.solidTemplate = solid;
    return r;
  }

  // The 3MF's objects in the chooser: all of them (what `rotlang preview project.3mf`
  // slices without --object), or one.
  listObjects(info) {
    const select = $('object');
    const options = [new Option('all objects', ''), ...info.objects.map((n) => new Option(n, n))];
    select.replaceChildren(...options);
    select.value = '';
    $('object-choice').hidden = info.objects.length < 2;
  }

  // An OrcaSlicer project gives the part (of the chosen object) its templates and
  // settings, as the CLI reads them: they fill the editor, the model form and the solid
  // template, where the user can change them.
  async fromProject() {
    if (!this.info?.project) return;
    this.inFlight++;
    try {
      const s = await this.engine.request('partSettings', { object: $('object').value });
      $('solid-template').value = s.solid_template ?? '';
      this.projectSolid = s.solid_template ?? null;
      this.checkSolid();
      this.onSettings?.(s);
    } catch (e) {
      this.message(`refused: ${e.message}`, true);
    } finally {
      this.inFlight--;
    }
  }

  async chooseObject() {
    this.fresh = true;
    await this.fromProject();
    this.schedule(0);
  }

  /** Checks the solid template as typed; its diagnostics go below it. */
  checkSolid() {
    const text = $('solid-template').value;
    const id = ++this.solid.seq;
    this.solid.inFlight++;
    this.engine.request('checkSolid', { text })
      .then((check) => { if (id === this.solid.seq) Object.assign(this.solid, { diagnostics: check.diagnostics, refused: null }); })
      .catch((e) => { if (id === this.solid.seq) Object.assign(this.solid, { diagnostics: [], refused: e.message }); })
      .finally(() => {
        this.solid.inFlight--;
        if (id !== this.solid.seq) return;
        this.solid.checked = text;
        this.describeSolid();
      });
  }

  // Under the solid template: its errors and warnings, each with its column and its span
  // marked in the text; else what turns the solid areas.
  describeSolid() {
    const text = $('solid-template').value;
    const msg = $('solid-message');
    // None asked for: the field's text (and its diagnostics) is not used.
    if ($('no-solid-template').checked) {
      $('solid-template').setAttribute('aria-invalid', 'false');
      msg.classList.remove('error');
      msg.textContent = 'No solid template: the solid areas (top and bottom surfaces) turn with the template'
        + (this.projectSolid ? ` (the project's \`${this.projectSolid}\` is not used).` : '.');
      return;
    }
    const shown = this.solid.checked === text ? this.solid.diagnostics : [];
    const errors = shown.filter((d) => d.severity === 'error');
    $('solid-template').setAttribute('aria-invalid', String(errors.length > 0 || Boolean(this.solid.refused)));
    msg.classList.toggle('error', errors.length > 0 || Boolean(this.solid.refused));
    if (this.solid.refused) {
      msg.textContent = `refused: ${this.solid.refused}`;
      return;
    }
    if (shown.length) {
      msg.innerHTML = shown.slice(0, 3).map((d) => {
        const [a, b] = [d.startUtf16, Math.max(d.endUtf16, d.startUtf16)];
        const marked = `${esc(text.slice(0, a))}<mark>${esc(text.slice(a, b) || ' ')}</mark>${esc(text.slice(b))}`;
        return `${d.severity} at column ${d.column}: ${esc(d.message)}${d.help ? ` (${esc(d.help)})` : ''} <code>${marked}</code>`;
      }).join('<br>') + (errors.length ? '<br>The part keeps its last good solid template until this one is fixed.' : '');
      return;
    }
    const used = this.answer?.solid_template;
    msg.textContent = text ? ''
      : typeof used === 'string' ? `The project's solid template \`${used}\` turns the solid areas; type one to override it.`
        : 'No solid template: the solid areas (top and bottom surfaces) turn with the template.';
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
      $('solid-row').hidden = false;
      this.listObjects(info);
      const wanted = this.wanted;
      this.wanted = null;
      if (wanted?.object && info.objects.includes(wanted.object)) $('object').value = wanted.object;
      this.projectSolid = null;
      await this.fromProject();
      if (typeof wanted?.solidTemplate === 'string') {
        $('solid-template').value = wanted.solidTemplate;
        this.checkSolid();
      }
      // A new part starts with its own solid template, unless a share link said none.
      this.noSolid(Boolean(wanted?.noSolidTemplate));
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
    $('solid-row').hidden = true;
    $('object-choice').hidden = true;
    $('object').replaceChildren(new Option('all objects', ''));
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
    const object = $('object').value;
    if (object) text += ` · object ${object} alone${info.project ? ', with its own settings' : ''}`;
    if (answer) {
      const s = answer.summary;
      text += ` · ${s.layers} layers, infill ${mm(s.extrusion_mm / 1000)} m (${mm(s.solid_extrusion_mm / 1000)} m solid), travel ${mm(s.travel_mm / 1000)} m, ${Math.round(s.time_s / 60)} min at ${s.speed} mm/s`;
      if (s.open_layers) text += ` · ${s.open_layers} layers have sections that could not be closed (holes in the mesh)`;
    }
    if (this.error) text += ` · not sliced: ${this.error}`;
    this.message(text, Boolean(this.error));
    this.describeSolid();
  }

  schedule(delay = 60) {
    if (!this.file) return;
    clearTimeout(this.timer);
    this.timer = setTimeout(() => { this.timer = null; this.run(); }, delay);
  }

  async run() {
    const req = this.current();
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
      const solid = e.kind === 'template' && /solid template/.test(e.message);
      const error = solid ? 'the solid template has errors (below); the view shows the last good part'
        : e.kind === 'template' ? 'fix the template first' : e.message;
      Object.assign(this, { answerKey: key, error });
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
    if (this.timer !== null || this.inFlight > 0 || this.solid.inFlight > 0) return false;
    if (!this.file) return true;
    if (this.solid.checked !== $('solid-template').value) return false;
    if (this.answerKey !== JSON.stringify(this.current())) return false;
    return Boolean(this.error) || (this.drawn === this.answer && this.view.current === Math.min(this.layer(), this.answer.layers.length - 1));
  }

  /** For the browser tests: the mesh, the summary and what the 3D view draws. */
  inspect() {
    return {
      name: this.file?.name ?? null,
      info: this.info,
      object: $('object').value || null,
      template: this.answer?.template ?? null,
      solidTemplate: this.answer?.solid_template ?? null,
      summary: this.answer?.summary ?? null,
      error: this.error,
      scene: this.view && this.drawn ? this.view.inspect() : null,
    };
  }
}
