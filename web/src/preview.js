// The infill of one layer, seen from above: lines at the layer's angle, clipped to the
// part's outline. The playground's own drawing, used while the rotlang build has no
// infill preview: it draws the line directions of line-based patterns (lines, grid,
// triangles) at the chosen density; it is not a toolpath.
const SIZE = 20; // mm, the documentation's cube
const LINE_WIDTH = 0.45; // mm

const SHAPES = {
  square: `<rect x="${-SIZE / 2}" y="${-SIZE / 2}" width="${SIZE}" height="${SIZE}"/>`,
  circle: `<circle cx="0" cy="0" r="${SIZE / 2}"/>`,
  hexagon: `<polygon points="${[0, 1, 2, 3, 4, 5].map((k) => {
    const a = (Math.PI / 3) * k;
    return `${((SIZE / 2) * Math.cos(a)).toFixed(3)},${((SIZE / 2) * Math.sin(a)).toFixed(3)}`;
  }).join(' ')}"/>`,
};

const PATTERN_DIRECTIONS = { lines: [0], rectilinear: [0], grid: [0, 90], triangles: [0, 60, 120] };

/** `angle` in degrees (counter-clockwise from +X, as a slicer's plate is seen from above). */
export function previewSvg(angle, { pattern = 'lines', density = 15, shape = 'square', solid = false } = {}) {
  const dirs = PATTERN_DIRECTIONS[pattern] ?? [0];
  const d = solid ? 1 : Math.min(1, Math.max(0.01, density / 100));
  // Each set of lines carries its share of the density.
  const spacing = Math.max(LINE_WIDTH, (LINE_WIDTH * dirs.length) / d);
  const reach = SIZE * 0.75;
  const lines = [];
  for (const extra of dirs) {
    const a = ((angle + extra) * Math.PI) / 180;
    const [dx, dy] = [Math.cos(a), Math.sin(a)];
    const [nx, ny] = [-dy, dx];
    const count = Math.ceil(reach / spacing);
    for (let k = -count; k <= count; k++) {
      const [cx, cy] = [nx * k * spacing, ny * k * spacing];
      // SVG's y axis points down: negate y so that angles turn counter-clockwise.
      const p = (v) => v.toFixed(4);
      lines.push(`<line x1="${p(cx - dx * reach)}" y1="${p(-(cy - dy * reach))}" x2="${p(cx + dx * reach)}" y2="${p(-(cy + dy * reach))}"/>`);
    }
  }
  const outline = SHAPES[shape] ?? SHAPES.square;
  const h = SIZE / 2 + 1;
  return `<svg xmlns="http://www.w3.org/2000/svg" class="preview" viewBox="${-h} ${-h} ${2 * h} ${2 * h}" role="img" aria-label="Infill lines at ${Number(angle.toFixed(4))}°">`
    + `<defs><clipPath id="outline">${outline}</clipPath></defs>`
    + `<g class="outline">${outline}</g>`
    + `<g class="infill" clip-path="url(#outline)" stroke-width="${(LINE_WIDTH * 0.7).toFixed(2)}" data-angle="${angle}">${lines.join('')}</g>`
    + `</svg>`;
}
