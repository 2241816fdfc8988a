// Test meshes as binary STL files, generated here (no fixture to go stale): a box and a
// closed cylinder. Shared by test/part.test.js and the playground's browser test
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

/** A box from the origin to [x, y, z], outward facing. */
export function box([x, y, z]) {
  const p = (i, j, k) => [i * x, j * y, k * z];
  const quad = (a, b, c, d) => [[a, b, c], [a, c, d]];
  return binaryStl([
    ...quad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)),
    ...quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)),
    ...quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)),
    ...quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)),
    ...quad(p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)),
    ...quad(p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)),
  ]);
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
