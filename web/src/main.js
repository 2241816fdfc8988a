// The playground's page: wires the editor, the worker's analysis, the plot, the layer
// slider with its preview, the model form, profiles, compat findings and the share link.
import { createEditor, highlight, replaceAll, showDiagnostics } from './editor.js';
import { Engine } from './engine.js';
import { EXAMPLES } from './examples.js';
import { MAX_LAYERS, MAX_TEMPLATE } from './limits.js';
import { PartPanel, isMesh } from './part.js';
import { cursorX, layerAt, plotParts, plotWidth } from './plot.js';
import { decodeState, encodeState } from './share.js';

const $ = (id) => document.getElementById(id);
const FILLS = ['sparse', 'dense', 'solid', 'concentric', 'monotonic', 'rectilinear'];
const PATTERN_NAMES = ['lines', 'grid', 'triangles', 'hexagons', 'concentric', 'gyroid', 'spiral', 'lightning', 'cubic'];
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => `&#${c.charCodeAt(0)};`);
const deg = (a) => `${Number(a.toFixed(4))}°`;

let signs = [];
let analysis = null; // the last answer, for the text it was computed on
let analysedText = null;
let seq = 0;
let timer = null;

const engine = new Engine((error) => {
  part?.restarted();
  status(error.message, true);
});

function status(message, refused = false) {
  const s = $('status');
  s.textContent = message;
  s.classList.toggle('refused', refused);
}

// A refusal the next analysis must not overwrite (a shared link or a profile that was not
// taken whole): it stays until dismissed or replaced. `null` hides it.
function notice(message) {
  $('notice-text').textContent = message ?? '';
  $('notice').hidden = !message;
  if (message) status(message, true);
}
$('notice-close').addEventListener('click', () => notice(null));

const chars = (n) => `${n.toLocaleString('en')} characters`;
const CAP = chars(MAX_TEMPLATE);

// The state of a share link, without a template longer than the editor takes (the
// initial document and a replacement would otherwise skip the editor's own check).
function sharedState(s) {
  if (s && typeof s.text === 'string' && s.text.length > MAX_TEMPLATE) {
    notice(`Refused the shared link's template: it has ${chars(s.text.length)}; the playground takes up to ${CAP}. The editor keeps ${view ? 'its template' : 'the default template'}; the link's model and view were applied (the template is left out of the address).`);
    const { text, ...rest } = s;
    // The browser copies the address into every later request it makes (the worker, the
    // wasm): a megabyte-long one costs seconds each time.
    history.replaceState(null, '', location.pathname + location.search + encodeState(rest));
    return rest;
  }
  return s;
}

// ---- model and view state -------------------------------------------------------

function num(id) {
  const v = $(id).value.trim();
  return v === '' ? undefined : Number(v);
}

function modelState() {
  return {
    layers: num('layers'),
    layerHeight: num('layer-height'),
    firstLayerHeight: num('first-layer'),
    bottomShells: num('bottom-shells'),
    topShells: num('top-shells'),
  };
}

function viewState() {
  const m = modelState();
  return {
    text: view.state.doc.toString(),
    target: $('target').value,
    dialect: $('dialect').value,
    layers: m.layers,
    layerHeight: m.layerHeight,
    firstLayerHeight: m.firstLayerHeight,
    bottomShells: m.bottomShells,
    topShells: m.topShells,
    base: num('base'),
    seed: num('seed'),
    layer: Number($('layer-slider').value),
    pattern: $('pattern').value,
    density: num('density'),
    shape: $('shape').value,
    // Only while a part is open (empty values are left out of the link).
    solidTemplate: part.info ? $('solid-template').value : '',
    noSolidTemplate: part.info && $('no-solid-template').checked ? '1' : '',
    object: part.info ? $('object').value : '',
  };
}

function applyState(s) {
  const set = (id, v) => { if (v !== undefined && v !== null) $(id).value = v; };
  set('target', s.target);
  set('dialect', s.dialect);
  set('layers', s.layers);
  set('layer-height', s.layerHeight);
  set('first-layer', s.firstLayerHeight);
  set('bottom-shells', s.bottomShells);
  set('top-shells', s.topShells);
  set('base', s.base);
  set('seed', s.seed);
  set('pattern', s.pattern);
  set('density', s.density);
  set('shape', s.shape);
  if (s.layer !== undefined) pendingLayer = Number(s.layer);
  // A shared part's solid template and object: the part is a local file, not in the
  // link; they are applied to it when it is opened (now, if one is).
  if (s.solidTemplate !== undefined || s.object !== undefined || s.noSolidTemplate !== undefined) {
    part.want({ solidTemplate: s.solidTemplate, object: s.object, noSolidTemplate: s.noSolidTemplate === '1' });
  }
  if (typeof s.text === 'string' && s.text !== view.state.doc.toString()) replaceAll(view, s.text);
  schedule(0);
}

// ---- analysis -------------------------------------------------------------------

// An edit makes a shown share link stale: it goes, and so does the state in the address.
function edited() {
  if ($('share-link').hidden) return;
  $('share-link').hidden = true;
  history.replaceState(null, '', location.pathname + location.search);
}

function schedule(delay = 120) {
  clearTimeout(timer);
  timer = setTimeout(() => { timer = null; analyse(); }, delay);
}

let pendingLayer = null;
let analysedRequest = null; // what the last analysis was asked, for the preview and chart

// What an analysis of the page as it is now asks the worker.
function currentRequest() {
  const s = viewState();
  const model = modelState();
  if (model.firstLayerHeight === undefined) delete model.firstLayerHeight;
  return { text: s.text, target: s.target, dialect: s.dialect, model, base: s.base, seed: s.seed };
}

let answered = 0; // the seq of the last analysis that came back (stale or not)
let answeredRequest = null; // the request of the last answer that was shown

async function analyse() {
  const req = currentRequest();
  const { text } = req;
  const id = ++seq;
  status('checking…');
  let r;
  try {
    r = await engine.request('analyse', req);
  } catch (e) {
    if (id !== seq) return;
    answeredRequest = req;
    status(e.message, true);
    return;
  } finally {
    answered = Math.max(answered, id);
  }
  if (id !== seq || text !== view.state.doc.toString()) return; // stale
  analysis = r;
  analysedText = text;
  analysedRequest = req;
  answeredRequest = req;
  showDiagnostics(view, [...r.check.diagnostics, ...(r.compat ?? []).map((d) => ({ ...d, severity: 'info' }))]);
  renderProblems(r.check);
  renderCompat(r);
  $('explain').textContent = words(r, req);
  if (r.refused) {
    status(`refused: ${r.refused}`, true);
  } else if (r.modelError) {
    status(`model: ${r.modelError}`, true);
  } else if (r.check.hasErrors && !r.layers) {
    const n = r.check.diagnostics.filter((d) => d.severity === 'error').length;
    status(`${n}${r.check.omitted ? '+' : ''} error${n === 1 ? '' : 's'}: fix ${n === 1 ? 'it' : 'them'} to see the angles`);
  } else if (r.layers) {
    const l = r.layers;
    status(`${l.layers.toLocaleString('en')} layers · ${l.instructions.length} instruction${l.instructions.length === 1 ? '' : 's'}`);
  }
  renderPlot();
  part.schedule();
}

// The template in words (rotlang::explain describes the template, not the base), with
// the base direction and the reading said first when they change what is drawn.
function words(r, req) {
  if (typeof r.explain !== 'string') return '';
  const lines = [];
  const base = Number(req.base ?? 0);
  if (base && r.layers) {
    lines.push(`The base direction, ${deg(base)} (a profile's infill direction), is added to every angle below: 0° is drawn at ${deg(base)}.`);
  }
  if (req.dialect === 'orcaslicer' && r.compare?.firstDifference) {
    const d = r.compare.firstDifference;
    lines.push(`OrcaSlicer reads this template differently from layer ${d.layer} (see the OrcaSlicer panel); the plot and the layer show its reading, the words below rotlang's.`);
  }
  return [...lines, r.explain].join('\n\n');
}

function renderProblems(check) {
  const ul = $('problems');
  ul.replaceChildren();
  for (const d of check.diagnostics.slice(0, 20)) {
    const li = document.createElement('li');
    li.className = d.severity;
    li.innerHTML = `${esc(d.message)} <small>(${esc(d.code)}, column ${d.column})</small>`;
    if (d.fix) {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = `Fix: ${d.fix.title}`;
      b.addEventListener('click', () => {
        if (view.state.doc.toString() !== analysedText) return;
        view.dispatch({ changes: { from: d.fix.startUtf16, to: d.fix.endUtf16, insert: d.fix.replacement } });
        view.focus();
      });
      li.append(' ', b);
    }
    ul.append(li);
  }
  if (check.diagnostics.length > 20 || check.omitted) {
    const li = document.createElement('li');
    li.textContent = `… and ${check.diagnostics.length - 20 + check.omitted} more`;
    ul.append(li);
  }
}

function renderCompat(r) {
  const ul = $('compat-list');
  ul.replaceChildren();
  const add = (html) => { const li = document.createElement('li'); li.innerHTML = html; ul.append(li); };
  const c = r.compare;
  if (r.compareError) add(`not compared: ${esc(r.compareError)}`);
  if (!c) return;
  if (c.rotlangErrors) {
    add('rotlang rejects this template; OrcaSlicer reads it anyway. Choose <em>as OrcaSlicer reads it</em> to plot its angles.');
  } else if (c.firstDifference) {
    const d = c.firstDifference;
    add(`OrcaSlicer reads it differently: from layer ${d.layer} (${deg(d.rotlang)} in rotlang, ${deg(d.orcaslicer)} in OrcaSlicer); ${c.differingLayers} of ${c.layers} layers differ.`);
  }
  if (c.solidLayersLost > 0) {
    add(`OrcaSlicer has no solid signs: ${c.solidLayersLost} solid layer${c.solidLayersLost === 1 ? '' : 's'} would be sparse there.`);
  }
  const coded = new Set();
  for (const d of r.compat ?? []) {
    coded.add(d.code);
    add(`<code>${esc(d.code)}</code> ${esc(d.message)}${d.fix ? ` <small>(fix: ${esc(d.fix.title)})</small>` : ''}`);
  }
  for (const f of c.findings) {
    if (!coded.has(f.code)) add(`<code>${esc(f.code)}</code> ${esc(f.message)}`);
  }
  if (!ul.children.length) add('OrcaSlicer reads this template as rotlang does on this model.');
}

// ---- plot, slider, preview -----------------------------------------------------------

// One lasting <svg> element, redrawn in place: a reader holding it (a screen reader, a
// test) never holds a detached picture after a redraw or a resize.
const SVG_NS = 'http://www.w3.org/2000/svg';
const plotSvg = document.createElementNS(SVG_NS, 'svg');
plotSvg.setAttribute('class', 'plot');
plotSvg.setAttribute('role', 'img');
$('plot').append(plotSvg);
let drawn = { layers: null, width: 0 }; // what the picture shows

function drawPlot() {
  const l = analysis?.layers;
  const width = plotWidth($('plot').clientWidth);
  if (!l) {
    plotSvg.replaceChildren();
    plotSvg.setAttribute('display', 'none');
    drawn = { layers: null, width };
    return;
  }
  const p = plotParts(l.angles, l.fills, { width });
  plotSvg.setAttribute('width', p.width);
  plotSvg.setAttribute('height', p.height);
  plotSvg.setAttribute('viewBox', `0 0 ${p.width} ${p.height}`);
  plotSvg.setAttribute('aria-label', p.label);
  plotSvg.removeAttribute('display');
  plotSvg.innerHTML = p.body;
  drawn = { layers: l, width };
}

// Why the Angles panel has no plot, in words (an empty box says nothing).
function plotMessage(r) {
  if (!r || r.layers) return null;
  if (r.refused) return `No angles: ${r.refused}.`;
  if (r.modelError) return `No angles: the model is not valid (${r.modelError}).`;
  const errors = r.check.diagnostics.filter((d) => d.severity === 'error');
  if (errors.length) {
    const d = errors[0];
    const more = errors.length + r.check.omitted - 1;
    return `No angles: rotlang cannot read this template (${d.message}, column ${d.column}${more > 0 ? `, and ${more} more` : ''}). Fix it, or choose "as OrcaSlicer reads it" to plot OrcaSlicer's angles.`;
  }
  return 'No angles for this template.';
}

function renderPlot() {
  const l = analysis?.layers;
  drawPlot();
  const message = plotMessage(analysis);
  $('plot-message').textContent = message ?? '';
  $('plot-message').hidden = !message;
  $('plot-message').classList.toggle('error', Boolean(message));
  if (!l) {
    $('preview').innerHTML = '';
    $('layer-info').textContent = '';
    $('chart-svg').innerHTML = '';
    return;
  }
  $('chart-svg').innerHTML = '';
  if ($('chart').open) renderChart();
  const slider = $('layer-slider');
  slider.max = String(Math.max(0, l.angles.length - 1));
  if (pendingLayer !== null) {
    slider.value = String(Math.min(pendingLayer, l.angles.length - 1));
    pendingLayer = null;
  }
  renderLayer();
}

function renderLayer() {
  const l = analysis?.layers;
  if (!l) return;
  const i = Math.min(Number($('layer-slider').value), l.angles.length - 1);
  const angle = l.angles[i];
  const fill = FILLS[l.fills[i]];
  const k = l.instructionIndex[i];
  const ins = k >= 0 ? l.instructions[k] : null;
  $('layer-info').textContent = `layer ${i}: ${deg(angle)}${fill !== 'sparse' ? ` (${fill})` : ''}${ins ? ` · ${ins.text}` : ' · holds'}`;
  const cursor = plotSvg.querySelector('.cursor');
  if (cursor) {
    const x = cursorX(i, l.angles.length, cursor.ownerSVGElement.viewBox.baseVal.width);
    cursor.setAttribute('x1', x);
    cursor.setAttribute('x2', x);
  }
  if (part.active()) part.cut(i);
  else schedulePreview(i);
  highlight(view, ins && view.state.doc.toString() === analysedText
    ? { from: ins.startUtf16, to: ins.endUtf16, title: `governs layer ${i}` }
    : null);
}

// What the preview of `layer` draws: the template in rotlang's reading. In OrcaSlicer's,
// rotlang::infill draws rotlang's angles only, so it is given the layer's angle as
// OrcaSlicer computes it (the analysis's, base included) as a one-angle template: the
// picture shows the angle the layer text and the plot give.
function previewRequest(layer) {
  const l = analysis?.layers;
  if (analysedRequest?.dialect !== 'orcaslicer' || !l) return analysedRequest;
  const angle = l.angles[Math.min(layer, l.angles.length - 1)];
  return { ...analysedRequest, dialect: 'rotlang', text: String(Number(angle.toFixed(9))), base: 0 };
}

// The preview is drawn by rotlang in the worker; while the slider moves only the last
// layer asked for is drawn.
let previewSeq = 0;
let previewTimer = null;
let previewsInFlight = 0;
function schedulePreview(layer) {
  clearTimeout(previewTimer);
  previewTimer = setTimeout(async () => {
    previewTimer = null;
    const id = ++previewSeq;
    if (part.active()) return;
    previewsInFlight++;
    const density = Math.min(100, Math.max(1, num('density') ?? 20)) / 100;
    try {
      const svg = await engine.request('preview', {
        ...previewRequest(layer), layer, pattern: $('pattern').value, density, shape: $('shape').value,
      });
      if (id === previewSeq && !part.active()) $('preview').innerHTML = svg;
    } catch (e) {
      if (id === previewSeq) $('preview').textContent = `no preview: ${e.message}`;
    } finally {
      previewsInFlight--;
    }
  }, 30);
}

async function renderChart() {
  if (!analysedRequest || !analysis?.layers) return;
  if (analysedRequest.dialect === 'orcaslicer') {
    // rotlang::plot draws rotlang's reading only; the plot above is OrcaSlicer's.
    $('chart-svg').textContent = 'This chart draws rotlang\'s reading only; the plot above shows the angles as OrcaSlicer reads them.';
    return;
  }
  try {
    // At the width it is shown at: rotlang draws its text at 12 px.
    const width = Math.max(300, Math.round($('chart-svg').clientWidth || 720));
    $('chart-svg').innerHTML = await engine.request('plot', {
      ...analysedRequest, width, height: Math.round(Math.min(420, Math.max(340, width * 0.6))),
    });
  } catch (e) {
    $('chart-svg').textContent = `no chart: ${e.message}`;
  }
}
$('chart').addEventListener('toggle', () => { if ($('chart').open) renderChart(); });

function setLayer(i) {
  const slider = $('layer-slider');
  slider.value = String(Math.max(0, Math.min(Number(slider.max), i)));
  renderLayer();
}

$('layer-slider').addEventListener('input', renderLayer);
for (const id of ['pattern', 'density', 'shape']) $(id).addEventListener('input', renderLayer);
for (const id of ['pattern', 'density']) $(id).addEventListener('input', () => part.schedule());

// ---- a part (mesh file) -------------------------------------------------------------

const density = () => Math.min(100, Math.max(1, num('density') ?? 20)) / 100;
// The part's model is the form's without its layer count: the part is as tall as the
// mesh, and the form's count follows the part's (onAnswer), so that the plot, the slider
// and the 3D view have the same layers.
const part = new PartPanel(engine, {
  request: () => {
    const r = currentRequest();
    const { layers, ...model } = r.model;
    return {
      text: r.text, target: r.target, model, base: r.base, seed: r.seed,
      pattern: $('pattern').value, density: density(), walls: num('walls'),
    };
  },
  layer: () => Number($('layer-slider').value),
  onAnswer: (a) => {
    const n = a.summary.layers;
    if (part.fresh) {
      part.fresh = false;
      pendingLayer = n - 1;
    }
    if (num('layers') !== n) {
      $('layers').value = String(n);
      edited();
      schedule(0);
    } else if (pendingLayer !== null) {
      const top = pendingLayer;
      pendingLayer = null;
      setLayer(top);
    }
  },
  onClose: () => renderLayer(),
  onFile: (f) => loadMesh(f),
  // A project's (or its chosen object's) templates and settings, as rotlang reads them
  // for the part (the CLI's reading): into the editor and the form, as a profile's are.
  onSettings: (s) => {
    const t = s.settings;
    $('walls').value = String(t.walls);
    applyState({
      target: 'sparse', text: s.template, base: t.base,
      layerHeight: t.layer_height, firstLayerHeight: s.first_layer_height ?? '',
      bottomShells: t.bottom_shell_layers, topShells: t.top_shell_layers,
      pattern: PATTERN_NAMES.includes(t.pattern) ? t.pattern : undefined,
      density: Number((t.density * 100).toFixed(4)),
    });
  },
});

$('plot').addEventListener('mousemove', (e) => {
  const svg = plotSvg;
  const l = analysis?.layers;
  if (drawn.layers !== l || !l) return;
  const box = svg.getBoundingClientRect();
  const vb = svg.viewBox.baseVal;
  setLayer(layerAt(((e.clientX - box.left) / box.width) * vb.width, l.angles.length, vb.width));
});
// Both pictures are drawn at the width they are shown at: redrawn when it changes (a
// scroll bar that comes with the first picture narrows the page).
new ResizeObserver(() => {
  if (plotWidth($('plot').clientWidth) === drawn.width || !analysis?.layers) return;
  drawPlot();
  renderLayer();
  if ($('chart').open) renderChart();
}).observe($('plot'));
$('plot').addEventListener('keydown', (e) => {
  const step = { ArrowLeft: -1, ArrowRight: 1, PageDown: -10, PageUp: 10 }[e.key];
  if (step === undefined) return;
  e.preventDefault();
  setLayer(Number($('layer-slider').value) + step);
});

// ---- hover --------------------------------------------------------------------------

function hover(pos) {
  const l = analysis?.layers;
  const text = view.state.doc.toString();
  if (!analysis || text !== analysedText) return null;
  const instructions = l?.instructions ?? analysis.check.instructions;
  const k = instructions.findIndex((s) => s.startUtf16 <= pos && pos <= s.endUtf16);
  if (k < 0) return null;
  const ins = instructions[k];
  const dom = document.createElement('div');
  dom.className = 'tip';
  let html = `<code>${esc(ins.text)}</code>`;
  const words = l?.words?.[k];
  if (words) html += ` ${esc(words)}`;
  if (l) {
    const g = l.ranges[k];
    html += g.count === 0
      ? '<br>governs no layer of this model'
      : `<br>governs ${g.count} of ${l.layers} layers: ${g.first === g.last ? `layer ${g.first}` : `layers ${g.first}–${g.last}`}`
        + ` (${deg(l.angles[g.first])} … ${deg(l.angles[g.last])})`;
  }
  dom.innerHTML = html;
  return dom;
}

// ---- formatting, examples, share, profiles -------------------------------------------

async function format() {
  try {
    const text = await engine.request('format', { text: view.state.doc.toString(), target: $('target').value });
    if (text !== view.state.doc.toString()) replaceAll(view, text);
    status('formatted');
  } catch (e) {
    status(e.kind === 'template' ? 'fix the errors before formatting' : e.message, true);
  }
}
$('format').addEventListener('click', format);

for (const [t, words] of EXAMPLES) {
  const o = document.createElement('option');
  o.value = t;
  o.textContent = `${t}: ${words}`;
  $('examples').append(o);
}
$('examples').addEventListener('change', (e) => {
  if (!e.target.value) return;
  replaceAll(view, e.target.value);
  e.target.value = '';
});

$('share').addEventListener('click', async () => {
  const hash = encodeState(viewState());
  history.replaceState(null, '', hash);
  const link = $('share-link');
  link.value = location.href;
  link.hidden = false;
  link.focus();
  link.select();
  try {
    await navigator.clipboard.writeText(location.href);
    status('share link copied');
  } catch {
    status('share link ready: copy it from the box');
  }
});
window.addEventListener('hashchange', () => {
  const s = decodeState(location.hash);
  if (s) applyState(sharedState(s));
});

// The base a profile's template is evaluated with: the library's one reading of a profile
// (rotlang::profile::ProfileModel::options, both readings alike), given with each template
// by `readProfile` (the direction turns an empty template only).
const profileBase = (t) => t.base;

// `quiet`: a 3MF opened for its mesh is read for a project's templates too, and says
// nothing when it has none.
async function loadProfile(file, { quiet = false } = {}) {
  try {
    const bytes = await file.arrayBuffer();
    const p = await engine.request('profile', { name: file.name, bytes });
    const title = p.presetName ?? p.name;
    const named = (t) => `${t.key ?? 'template'}${t.object ? ` (${t.object})` : ''}`;
    // A template over the editor's cap is not loaded; the profile is applied only with a
    // template that fits, and the notice says what was left out.
    const fits = (t) => t.text.length <= MAX_TEMPLATE;
    const first = p.templates.find(fits);
    const tooLong = p.templates.filter((t) => !fits(t))
      .map((t) => `${named(t)} (${chars(t.text.length)})`).join(', ');
    if (!first) {
      if (quiet) return;
      notice(`Refused ${title}: ${tooLong} ${p.templates.length === 1 ? 'is' : 'are'} longer than the ${CAP} the playground takes. Nothing from the profile was applied.`);
      return;
    }
    const holder = $('profile-templates');
    holder.replaceChildren();
    const m = p.model;
    applyState({
      // With a part open, the part gives the layer count (its height over the layer height).
      layers: part.active() ? undefined : m.layers, layerHeight: m.layerHeight, firstLayerHeight: m.firstLayerHeight ?? '',
      bottomShells: m.bottomShells, topShells: m.topShells, base: profileBase(first),
      pattern: PATTERN_NAMES.includes(p.pattern) ? p.pattern : undefined,
      density: Number.isFinite(p.density) ? p.density : undefined,
      target: first.target, text: first.text,
    });
    notice(tooLong
      ? `From ${title}: not loaded ${tooLong}, longer than the ${CAP} the playground takes. Applied: the model and ${named(first)}.`
      : null);
    const label = document.createElement('p');
    label.textContent = `Profile ${title}: ${p.templates.length} template${p.templates.length === 1 ? '' : 's'}`;
    holder.append(label);
    for (const t of p.templates) {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = `${named(t)}: ${t.text.length > 40 ? `${t.text.slice(0, 40)}…` : t.text || '(empty)'}`;
      if (fits(t)) {
        b.addEventListener('click', () => applyState({ target: t.target, text: t.text, base: profileBase(t) }));
      } else {
        b.disabled = true;
        b.textContent += ` (not loaded: ${chars(t.text.length)})`;
      }
      holder.append(b, ' ');
    }
    const notes = p.notes.filter((n) => n.error || /not set/.test(n.message) === false);
    if (notes.length) {
      const ul = document.createElement('ul');
      for (const n of notes.slice(0, 5)) {
        const li = document.createElement('li');
        li.textContent = n.message;
        ul.append(li);
      }
      holder.append(ul);
    }
  } catch (e) {
    if (!quiet) notice(`refused: ${e.message}`);
  }
}

// A mesh file: an OrcaSlicer .3mf project's templates and settings first (when it has
// any), then its objects as the part.
async function loadMesh(file) {
  if (/\.3mf$/i.test(file.name)) await loadProfile(file, { quiet: true });
  await part.open(file);
}
$('profile').addEventListener('change', async (e) => {
  const file = e.target.files?.[0];
  if (file) await loadProfile(file);
  e.target.value = '';
});
document.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
document.addEventListener('dragleave', (e) => { if (!e.relatedTarget) document.body.classList.remove('dragging'); });
document.addEventListener('drop', async (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  const file = e.dataTransfer?.files?.[0];
  if (file && isMesh(file.name)) await loadMesh(file);
  else if (file) await loadProfile(file);
});

for (const id of ['target', 'dialect', 'layers', 'layer-height', 'first-layer', 'bottom-shells', 'top-shells', 'base', 'seed']) {
  $(id).addEventListener('input', () => { edited(); schedule(); });
}
for (const id of ['layer-slider', 'pattern', 'density', 'shape', 'solid-template', 'object']) $(id).addEventListener('input', edited);
// "In words" is open on a wide screen; on a phone it would push the plot far down.
if (matchMedia('(min-width: 821px)').matches) $('words').open = true;
$('layers').max = String(MAX_LAYERS * 50);

// ---- start ------------------------------------------------------------------------

let view = null;
const initial = sharedState(decodeState(location.hash));
view = createEditor($('editor'), initial?.text ?? '+10L25%, -10l25%, -10L25%, +10l25%', {
  onChange: () => { edited(); schedule(); },
  onRefused: (m) => status(m, true),
  format,
  hover,
  signs: () => signs,
});
if (initial) applyState(initial);
schedule(0);
engine.request('signs').then((s) => { signs = s; }).catch(() => {});
engine.request('version').then((v) => { $('version').textContent = `rotlang ${v}`; }).catch(() => {});
// Whether the page shows what its controls ask for: no analysis or preview waiting or
// under way, the last answer is for the page as it is, and the plot is drawn from it at
// the width it is shown at. The browser tests wait for this instead of for time.
function idle() {
  if (timer !== null || answered !== seq || previewTimer !== null || previewsInFlight > 0) return false;
  if (!part.idle()) return false;
  if (JSON.stringify(answeredRequest) !== JSON.stringify(currentRequest())) return false;
  const l = analysis?.layers;
  return !l || (drawn.layers === l && drawn.width === plotWidth($('plot').clientWidth));
}

// For the browser tests and the curious: the editor view.
window.rotlangPlayground = {
  view, engine, state: () => viewState(), analysis: () => analysis, analysedText: () => analysedText, idle,
  part: () => part.inspect(),
};
