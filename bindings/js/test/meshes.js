// Test meshes as binary STL files, generated here (no fixture to go stale): a box and a
// closed cylinder; and a 3MF project holding boxes placed by its build's transforms. Shared by test/part.test.js and the playground's browser test
// (web/test/part.test.js). Normals are left zero: readers recompute or ignore them.

/** Binary STL of the triangles (each three [x, y, z] corners). */
export function binaryStl(triangles) {
  const bytes = new Uint8Array(84 + 50 * triangles.length);
  const view = new DataView(bytes.buffer);
  view.setUint32(80, triangles.length, true);
  triangles.forEach((t, i) => {
    let at = 84 + 50 * i + 12;
    for (const corner of t) {
      for (const v of corner) {
        view.setFloat32(at, v, true);
        at += 4;
      }
    }
  });
  return bytes;
}

/** A box from the origin to [x, y, z], outward facing: binary STL. */
export function box(size) {
  return binaryStl(boxTriangles(size));
}

/** The twelve triangles of a box from the origin to [x, y, z]. */
export function boxTriangles([x, y, z]) {
  const p = (i, j, k) => [i * x, j * y, k * z];
  const quad = (a, b, c, d) => [[a, b, c], [a, c, d]];
  return [
    ...quad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)),
    ...quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)),
    ...quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)),
    ...quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)),
    ...quad(p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)),
    ...quad(p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)),
  ];
}

/** A closed cylinder of `radius` and `height` on the plate, centred on the origin, with `segments` sides. */
export function cylinder(radius, height, segments) {
  const rim = (i, z) => {
    const a = (2 * Math.PI * (i % segments)) / segments;
    return [radius * Math.cos(a), radius * Math.sin(a), z];
  };
  const triangles = [];
  for (let i = 0; i < segments; i += 1) {
    const [a0, a1, b0, b1] = [rim(i, 0), rim(i + 1, 0), rim(i, height), rim(i + 1, height)];
    triangles.push([a0, a1, b1], [a0, b1, b0]);
    triangles.push([[0, 0, 0], a1, a0], [[0, 0, height], b0, b1]);
  }
  return binaryStl(triangles);
}

/**
 * A 3MF (a zip of `3D/3dmodel.model` and the `entries` given, e.g. OrcaSlicer's
 * `Metadata/project_settings.config`, stored uncompressed) with `objects`, each
 * `{ name, triangles, at: [x, y, z] }`: placed by a build item's translation.
 */
export function threeMf(objects, entries = {}) {
  const resources = objects.map((o, k) => {
    const index = new Map();
    const vertices = [];
    const tris = o.triangles.map((t) => t.map((c) => {
      const key = c.join(' ');
      if (!index.has(key)) {
        index.set(key, vertices.length);
        vertices.push(`<vertex x="${c[0]}" y="${c[1]}" z="${c[2]}"/>`);
      }
      return index.get(key);
    }));
    const triangles = tris.map(([a, b, c]) => `<triangle v1="${a}" v2="${b}" v3="${c}"/>`);
    return `<object id="${k + 1}" name="${o.name}" type="model"><mesh><vertices>${vertices.join('')}</vertices>`
      + `<triangles>${triangles.join('')}</triangles></mesh></object>`;
  });
  const items = objects.map((o, k) => `<item objectid="${k + 1}" transform="1 0 0 0 1 0 0 0 1 ${o.at.join(' ')}"/>`);
  const model = '<?xml version="1.0" encoding="UTF-8"?>\n'
    + '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
    + `<resources>${resources.join('')}</resources><build>${items.join('')}</build></model>`;
  const files = { '3D/3dmodel.model': model, ...entries };
  return storedZip(Object.entries(files).map(([n, text]) => [n, new TextEncoder().encode(text)]));
}

/**
 * OrcaSlicer's `Metadata/model_settings.config` giving each object of `overrides`
 * (`{ name: { key: value } }`) its own settings, as a project saved with per-object
 * settings holds them.
 */
export function modelSettings(overrides) {
  const objects = Object.entries(overrides).map(([name, values], k) => `  <object id="${k + 1}">\n`
    + `    <metadata key="name" value="${name}"/>\n`
    + Object.entries(values).map(([key, v]) => `    <metadata key="${key}" value="${v}"/>\n`).join('')
    + '  </object>\n');
  return `<?xml version="1.0" encoding="UTF-8"?>\n<config>\n${objects.join('')}</config>\n`;
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k += 1) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// A zip of `files` ([name, bytes] pairs), stored: a local header and the data of each,
// then the central directory and its end record.
function storedZip(files) {
  const enc = new TextEncoder();
  const parts = [];
  const central = [];
  let offset = 0;
  // The fields local and central headers share, from "version needed" on.
  const common = (v, p, name, data) => {
    v.setUint16(p, 20, true); // version needed
    v.setUint16(p + 2, 0, true); // flags
    v.setUint16(p + 4, 0, true); // stored
    v.setUint32(p + 6, 0x00210000, true); // 1980-01-01 00:00
    v.setUint32(p + 10, crc32(data), true);
    v.setUint32(p + 14, data.length, true);
    v.setUint32(p + 18, data.length, true);
    v.setUint16(p + 22, name.length, true);
  };
  for (const [n, data] of files) {
    const name = enc.encode(n);
    const local = new Uint8Array(30 + name.length);
    const lv = new DataView(local.buffer);
    lv.setUint32(0, 0x04034b50, true);
    common(lv, 4, name, data);
    local.set(name, 30);
    const entry = new Uint8Array(46 + name.length);
    const cv = new DataView(entry.buffer);
    cv.setUint32(0, 0x02014b50, true);
    cv.setUint16(4, 20, true); // version made by
    common(cv, 6, name, data);
    cv.setUint32(42, offset, true);
    entry.set(name, 46);
    parts.push(local, data);
    central.push(entry);
    offset += local.length + data.length;
  }
  const size = central.reduce((n, c) => n + c.length, 0);
  const end = new Uint8Array(22);
  const ev = new DataView(end.buffer);
  ev.setUint32(0, 0x06054b50, true);
  ev.setUint16(8, files.length, true);
  ev.setUint16(10, files.length, true);
  ev.setUint32(12, size, true);
  ev.setUint32(16, offset, true);
  const all = [...parts, ...central, end];
  const out = new Uint8Array(all.reduce((n, b) => n + b.length, 0));
  let at = 0;
  for (const b of all) {
    out.set(b, at);
    at += b.length;
  }
  return out;
}
