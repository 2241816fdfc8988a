// How compare.mjs (five shapes) and compare-mesh.mjs (a sliced mesh) measure infill: printed
// density, largest gap, length outside the region or in the wall band, and direction, the
// same for both programs. A region is the area inside the walls, given as rings plus two
// queries (inside, distance to its boundary): polygonRegion for drawn outlines, annulusRegion
// for a torus's sections (exact, and fast on 80 mm sections).

export const W = 0.4; // nozzle and line width (mm)
const H = 0.05; // raster cell (mm)

function segDist2(p, a, b) {
  const ex = b[0] - a[0], ey = b[1] - a[1];
  const l2 = ex * ex + ey * ey;
  let t = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0;
  t = Math.max(0, Math.min(1, t));
  const dx = p[0] - a[0] - t * ex, dy = p[1] - a[1] - t * ey;
  return dx * dx + dy * dy;
}

/// A region bounded by polygon rings (outer, then holes, any orientation): even-odd inside.
export function polygonRegion(rings) {
  const xs = rings.flat().map((p) => p[0]), ys = rings.flat().map((p) => p[1]);
  return {
    rings,
    bounds: [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)],
    inside(p) {
      let c = false;
      for (const r of rings)
        for (let i = 0, j = r.length - 1; i < r.length; j = i++) {
          const [ax, ay] = r[j], [bx, by] = r[i];
          if ((ay <= p[1]) !== (by <= p[1]) && ax + ((p[1] - ay) * (bx - ax)) / (by - ay) > p[0]) c = !c;
        }
      return c;
    },
    boundaryDist(p) {
      let d = Infinity;
      for (const r of rings) for (let i = 0, j = r.length - 1; i < r.length; j = i++) d = Math.min(d, segDist2(p, r[j], r[i]));
      return Math.sqrt(d);
    },
  };
}

/// The ring between radii rIn and rOut about (cx, cy) (rIn 0: a disc).
export function annulusRegion(cx, cy, rIn, rOut) {
  const circle = (r) => Array.from({ length: 1440 }, (_, i) => {
    const a = (2 * Math.PI * i) / 1440;
    return [cx + r * Math.cos(a), cy + r * Math.sin(a)];
  });
  return {
    rings: rIn > 0 ? [circle(rOut), circle(rIn)] : [circle(rOut)],
    bounds: [cx - rOut, cy - rOut, cx + rOut, cy + rOut],
    inside(p) {
      const r = Math.hypot(p[0] - cx, p[1] - cy);
      return r < rOut && r > rIn;
    },
    boundaryDist(p) {
      const r = Math.hypot(p[0] - cx, p[1] - cy);
      return rIn > 0 ? Math.min(Math.abs(rOut - r), Math.abs(r - rIn)) : Math.abs(rOut - r);
    },
  };
}

// 1-D squared distance transform (lower envelope of parabolas).
function edt1(f, n) {
  const d = new Float64Array(n), v = new Int32Array(n), z = new Float64Array(n + 1);
  let k = 0;
  v[0] = 0; z[0] = -Infinity; z[1] = Infinity;
  for (let q = 1; q < n; q++) {
    if (f[q] === Infinity) continue;
    if (f[v[k]] === Infinity) { v[k] = q; continue; }
    let s;
    for (;;) {
      s = (f[q] + q * q - (f[v[k]] + v[k] * v[k])) / (2 * q - 2 * v[k]);
      if (s <= z[k] && k > 0) k--; else break;
    }
    if (s <= z[k]) { v[k] = q; continue; }
    k++; v[k] = q; z[k] = s; z[k + 1] = Infinity;
  }
  k = 0;
  for (let q = 0; q < n; q++) {
    while (z[k + 1] < q) k++;
    d[q] = f[v[k]] === Infinity ? Infinity : (q - v[k]) ** 2 + f[v[k]];
  }
  return d;
}

/// Printed density, largest gap (mm), length outside the region or in a hole (mm), length
/// closer than half a line to the boundary (mm), and direction of `paths` in `region`.
export function measure(region, paths) {
  const { rings } = region;
  const x0 = region.bounds[0] - 1, y0 = region.bounds[1] - 1;
  const nx = Math.ceil((region.bounds[2] + 1 - x0) / H), ny = Math.ceil((region.bounds[3] + 1 - y0) / H);
  const grid = new Float64Array(nx * ny).fill(Infinity);
  const mark = (x, y) => {
    const i = Math.floor((x - x0) / H), j = Math.floor((y - y0) / H);
    if (i >= 0 && j >= 0 && i < nx && j < ny) grid[j * nx + i] = 0;
  };
  const trace = (a, b) => {
    const n = Math.ceil(Math.hypot(b[0] - a[0], b[1] - a[1]) / (H / 2)) + 1;
    for (let k = 0; k <= n; k++) mark(a[0] + ((b[0] - a[0]) * k) / n, a[1] + ((b[1] - a[1]) * k) / n);
  };
  // The walls stand on the region's boundary; the infill's lines are where it printed.
  for (const r of rings) for (let i = 0, j = r.length - 1; i < r.length; j = i++) trace(r[j], r[i]);
  let length = 0, outside = 0, wall = 0;
  const step = 0.02;
  for (const p of paths)
    for (let s = 1; s < p.length; s++) {
      const a = p[s - 1], b = p[s];
      const l = Math.hypot(b[0] - a[0], b[1] - a[1]);
      length += l;
      trace(a, b);
      const n = Math.max(1, Math.ceil(l / step));
      for (let k = 0; k < n; k++) {
        const q = [a[0] + ((b[0] - a[0]) * (k + 0.5)) / n, a[1] + ((b[1] - a[1]) * (k + 0.5)) / n];
        if (!region.inside(q)) outside += l / n;
        else if (region.boundaryDist(q) < W / 2 - 0.02) wall += l / n;
      }
    }
  // Exact distance transform: columns then rows.
  const col = new Float64Array(ny);
  for (let i = 0; i < nx; i++) {
    for (let j = 0; j < ny; j++) col[j] = grid[j * nx + i];
    const d = edt1(col, ny);
    for (let j = 0; j < ny; j++) grid[j * nx + i] = d[j];
  }
  let gap = 0, cells = 0;
  for (let j = 0; j < ny; j++) {
    const d = edt1(grid.subarray(j * nx, (j + 1) * nx), nx);
    for (let i = 0; i < nx; i++) {
      const p = [x0 + (i + 0.5) * H, y0 + (j + 0.5) * H];
      if (!region.inside(p)) continue;
      if (region.boundaryDist(p) >= W / 2) cells++;
      gap = Math.max(gap, Math.sqrt(d[i]) * H);
    }
  }
  const area = cells * H * H; // the infill area: the region inset by half a nozzle
  return { length, density: (length * W) / area, gap: 2 * gap, outside, wall, rotation: rotation(paths) };
}

/// The direction (degrees mod 180) carrying the most line length.
export function rotation(paths) {
  const bins = new Float64Array(180);
  for (const p of paths)
    for (let s = 1; s < p.length; s++) {
      const dx = p[s][0] - p[s - 1][0], dy = p[s][1] - p[s - 1][1];
      const a = ((Math.atan2(dy, dx) * 180) / Math.PI + 360) % 180;
      bins[Math.round(a) % 180] += Math.hypot(dx, dy);
    }
  let best = 0;
  for (let i = 1; i < 180; i++) if (bins[i] > bins[best]) best = i;
  return best;
}

/// The extruding moves of G-code as polylines (a move with E extrudes). With `byLayer`, the
/// moves are grouped by Polyslice's `M117 LAYER: n of N` marks and `; TYPE: X` sections:
/// [{ layer: n, types: { X: polylines } }, ...].
export function parseGcode(gcode, byLayer = false) {
  const paths = [];
  const layers = [];
  let types = null;
  let type = null;
  let pos = null;
  let current = null;
  for (const line of gcode.split('\n')) {
    if (byLayer) {
      const l = /^M117 LAYER: (\d+)/.exec(line);
      if (l) {
        types = {};
        layers.push({ layer: +l[1], types });
        type = null;
        current = null;
        continue;
      }
      const t = /^; TYPE: ([\w-]+)/.exec(line);
      if (t) {
        type = t[1];
        current = null;
        continue;
      }
    }
    if (!/^G[01]\s/.test(line)) continue;
    const x = /X(-?[\d.]+)/.exec(line);
    const y = /Y(-?[\d.]+)/.exec(line);
    const next = [x ? +x[1] : pos?.[0], y ? +y[1] : pos?.[1]];
    if (next[0] === undefined) continue;
    if (/\sE-?[\d.]/.test(line) && pos) {
      if (!current) {
        current = [pos];
        if (!byLayer) paths.push(current);
        else if (types && type) (types[type] ??= []).push(current);
      }
      current.push(next);
    } else {
      current = null;
    }
    pos = next;
  }
  return byLayer ? layers : paths;
}
