// rotlang/full: the angle chart and the infill preview (rotlang::plot, rotlang::infill).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { PATTERNS, SHAPES, RotlangError, plot, preview } from '../full.js';

// Directions (degrees modulo 180) of the preview's stroked paths: each path's first and
// last points (SVG's y axis points down).
export function pathDirections(svg) {
  const out = [];
  for (const m of svg.matchAll(/<path d="([^"]+)" fill="none" stroke="hsl[^"]*"/g)) {
    const pts = [...m[1].matchAll(/[ML](-?[\d.]+) (-?[\d.]+)/g)].map((p) => [Number(p[1]), Number(p[2])]);
    if (pts.length < 2) continue;
    const [[x1, y1], [x2, y2]] = [pts[0], pts[pts.length - 1]];
    if (Math.hypot(x2 - x1, y2 - y1) < 5) continue; // too short to measure
    const a = (Math.atan2(-(y2 - y1), x2 - x1) * 180) / Math.PI;
    out.push(((a % 180) + 180) % 180);
  }
  return out;
}

test('plot: the angle chart as SVG', () => {
  const svg = plot('0, 90', { width: 640, height: 320 });
  assert.match(svg, /^<svg/);
  assert.match(svg, /height \(mm\)/);
  assert.throws(() => plot('+30X5'), (e) => e instanceof RotlangError && e.kind === 'template');
  assert.throws(() => plot('0', { width: 1e6 }), (e) => e.kind === 'options');
});

test('preview: layer 49 of +30/50% on the cube has lines at 30°', () => {
  const svg = preview('+30/50%', { layer: 49, pattern: 'lines', density: 0.2, shape: 'square' });
  assert.match(svg, /layer 49/);
  const dirs = pathDirections(svg);
  assert.ok(dirs.length > 3, `${dirs.length} lines`);
  for (const d of dirs) assert.ok(Math.abs(d - 30) < 0.5, `a line at ${d}°`);
  const first = pathDirections(preview('+30/50%', { layer: 0 }));
  assert.ok(first.every((d) => Math.abs(d - 30) > 5), 'layer 0 is not at 30°');
});

test('preview: every pattern and shape draws; bad values are refused', () => {
  for (const pattern of PATTERNS) {
    for (const shape of SHAPES) {
      assert.match(preview('+45', { layer: 3, pattern, shape, density: 0.15 }), /<svg/, `${pattern} on ${shape}`);
    }
  }
  assert.throws(() => preview('0', { pattern: 'voronoi' }), (e) => e.kind === 'options');
  assert.throws(() => preview('0', { density: 0 }), (e) => e.kind === 'options');
  assert.throws(() => preview('0', { layer: 100 }), (e) => e.kind === 'options');
  assert.throws(() => preview('0', { density: 2 }), (e) => e instanceof RotlangError && e.kind === 'options');
});

test('plot: the title fits a narrow picture (cut with an ellipsis), whole in a wide one', () => {
  const text = '+10L25%, -10l25%, -10L25%, +10l25%';
  const title = (svg) => svg.match(/<text[^>]*font-weight="bold">([^<]*)<\/text>/)[1];
  const narrow = title(plot(text, { width: 320, height: 360 }));
  assert.ok(narrow.endsWith('…'), narrow);
  // 15 px bold, about 9 px a character, from x = 72 to 24 px before the edge.
  assert.ok(narrow.length * 9 <= 320 - 96, `${narrow.length} characters in 320 px: ${narrow}`);
  assert.equal(title(plot(text, { width: 960 })), `template: ${text}`);
});
