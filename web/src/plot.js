// The angle plot: every layer's angle against its index, as SVG.
// Up to a few thousand layers each layer is a dot (its own element, data-layer and
// data-angle attributes); above, each pixel column shows the range of its layers.
// The picture is drawn at the width it is shown at (one SVG unit per CSS pixel), so its
// text has the same size on a phone as on a desktop.
const FILL_CLASS = ['sparse', 'dense', 'solid', 'concentric', 'monotonic', 'rectilinear'];
const PAD = { left: 44, right: 10, top: 10, bottom: 28 };
/** Width of the picture (SVG units = CSS pixels) for a container `px` wide. */
export const plotWidth = (px) => Math.max(240, Math.round(px || 640));
const height = (w) => Math.round(Math.min(260, Math.max(200, w * 0.45)));
// Axis steps (degrees), smallest first: the axis fits the data with at most 6 intervals.
const STEPS = [0.5, 1, 2, 5, 10, 15, 30, 45, 90, 180, 360];

/** The angle axis's range and tick step for angles in [min, max]. */
export function angleAxis(min, max) {
  if (!(max - min > 1e-9)) {
    // One angle: an axis a step each side of it.
    const step = 15;
    const c = Math.round(min / step) * step;
    return { lo: c - step * 2, hi: c + step * 2, step };
  }
  const step = STEPS.find((s) => Math.ceil(max / s - 1e-9) - Math.floor(min / s + 1e-9) <= 6) ?? 360;
  const lo = Math.floor(min / step + 1e-9) * step;
  const hi = Math.ceil(max / step - 1e-9) * step;
  return { lo, hi: hi > lo ? hi : lo + step, step };
}

const esc = (s) => String(s).replace(/[&<>"]/g, (c) => `&#${c.charCodeAt(0)};`);
const wrap = (a) => ((a % 360) + 360) % 360;

/**
 * The plot's parts: the picture's `width` and `height` (SVG units = CSS pixels), its
 * accessible `label` and its `body` (the SVG's children), so that the page can redraw one
 * lasting <svg> element in place.
 */
export function plotParts(angles, fills, { from = 0, width = 640 } = {}) {
  const W = plotWidth(width);
  const H = height(W);
  const n = angles.length;
  const iw = W - PAD.left - PAD.right;
  const ih = H - PAD.top - PAD.bottom;
  const x = (i) => PAD.left + (n <= 1 ? iw / 2 : (i / (n - 1)) * iw);
  // Angles as they are when they span at most a turn (a sine around 0° stays whole),
  // else modulo 360.
  let min = Infinity;
  let max = -Infinity;
  for (let i = 0; i < n; i++) {
    if (angles[i] < min) min = angles[i];
    if (angles[i] > max) max = angles[i];
  }
  const raw = max - min <= 360;
  const { lo, hi, step } = raw ? angleAxis(min, max) : { lo: 0, hi: 360, step: 90 };
  const at = raw ? (a) => a : wrap;
  const y = (a) => PAD.top + ih - ((Math.min(at(a), hi - 1e-9) - lo) / (hi - lo)) * ih;
  const parts = [];
  parts.push(`<g class="axes">`);
  for (let k = 0; lo + k * step <= hi + 1e-9; k++) {
    const a = Number((lo + k * step).toFixed(6));
    const gy = (PAD.top + ih - ((a - lo) / (hi - lo)) * ih).toFixed(1);
    parts.push(`<line x1="${PAD.left}" x2="${W - PAD.right}" y1="${gy}" y2="${gy}" class="grid"/>`);
    parts.push(`<text x="${PAD.left - 4}" y="${Number(gy) + 4}" text-anchor="end">${a}°</text>`);
  }
  const ticks = n <= 1 ? [0] : [0, Math.round((n - 1) / 2), n - 1];
  for (const t of ticks) {
    parts.push(`<text x="${x(t)}" y="${H - 8}" text-anchor="middle">${t + from}</text>`);
  }
  parts.push(`</g>`);
  if (n <= 4000) {
    const r = n <= 200 ? 2.5 : n <= 1000 ? 1.6 : 1;
    parts.push(`<g class="layers">`);
    for (let i = 0; i < n; i++) {
      parts.push(`<circle class="${FILL_CLASS[fills[i]] ?? 'sparse'}" data-layer="${i + from}" data-angle="${esc(angles[i])}" cx="${x(i).toFixed(2)}" cy="${y(angles[i]).toFixed(2)}" r="${r}"/>`);
    }
    parts.push(`</g>`);
  } else {
    // Column ranges: one short vertical stroke per pixel column and wrapped-angle band.
    let d = '';
    const cols = Math.floor(iw);
    for (let c = 0; c < cols; c++) {
      const first = Math.floor((c / cols) * n);
      const end = Math.max(first + 1, Math.floor(((c + 1) / cols) * n));
      let cmin = Infinity;
      let cmax = -Infinity;
      for (let i = first; i < end; i++) {
        const a = at(angles[i]);
        if (a < cmin) cmin = a;
        if (a > cmax) cmax = a;
      }
      const px = (PAD.left + c + 0.5).toFixed(1);
      d += `M${px} ${y(cmin).toFixed(1)}V${(y(cmax) - 0.8).toFixed(1)}`;
    }
    parts.push(`<path class="columns" d="${d}"/>`);
  }
  parts.push(`<line class="cursor" x1="-10" x2="-10" y1="${PAD.top}" y2="${PAD.top + ih}"/>`);
  return { width: W, height: H, label: `Infill angle of each of ${n} layers`, body: parts.join('') };
}

/** The layer under a horizontal position (in the SVG's own units) of a `w`-wide plot. */
export function layerAt(svgX, n, w) {
  const iw = plotWidth(w) - PAD.left - PAD.right;
  if (n <= 1) return 0;
  const i = Math.round(((svgX - PAD.left) / iw) * (n - 1));
  return Math.max(0, Math.min(n - 1, i));
}

/** Where the cursor line of layer `i` goes (SVG units) in a `w`-wide plot. */
export function cursorX(i, n, w) {
  const iw = plotWidth(w) - PAD.left - PAD.right;
  return PAD.left + (n <= 1 ? iw / 2 : (i / (n - 1)) * iw);
}
