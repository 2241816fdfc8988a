//! Triangle meshes: reading STL (binary and ASCII) and OBJ files (crate `rotlang-geometry`).
//!
//! The readers are written here rather than taken from a crate: each format is a few
//! dozen lines, and a reader of our own reports what it could not read with a position
//! instead of failing the whole file. Identical vertices are merged (STL repeats every
//! vertex in each of its triangles), so that the slicer can chain a section's segments by
//! the mesh edges they cross.

use std::collections::HashMap;
use std::fmt;

/// A triangle mesh in millimetres.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub vertices: Vec<[f64; 3]>,
    /// Counter-clockwise seen from outside (what STL and OBJ promise; the slicer does not
    /// rely on it: sections are read even-odd).
    pub triangles: Vec<[u32; 3]>,
}

/// Why a mesh could not be read.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshError(pub String);

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for MeshError {}

/// The most triangles a mesh may have (about 1.2 GB as binary STL): more is an error,
/// not an out-of-memory.
pub const MAX_TRIANGLES: usize = 25_000_000;

impl Mesh {
    /// Reads an STL (binary or ASCII) or OBJ file's bytes; `name` (the file name) picks
    /// the format by its extension, else the content does.
    pub fn read(name: &str, bytes: &[u8]) -> Result<Mesh, MeshError> {
        let lower = name.to_ascii_lowercase();
        if lower.ends_with(".obj") {
            let text = std::str::from_utf8(bytes)
                .map_err(|e| MeshError(format!("the OBJ file is not UTF-8: {e}")))?;
            return Mesh::from_obj(text);
        }
        Mesh::from_stl(bytes)
    }

    /// Reads an STL file: binary when its size is what its triangle count says (an ASCII
    /// file may begin with `solid` too), ASCII otherwise.
    pub fn from_stl(bytes: &[u8]) -> Result<Mesh, MeshError> {
        if bytes.len() >= 84 {
            let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
            if n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len()) {
                return Mesh::from_binary_stl(&bytes[84..], n);
            }
        }
        let text = std::str::from_utf8(bytes).map_err(|_| {
            MeshError("not an STL file: neither binary (its size does not match its triangle count) nor ASCII text".into())
        })?;
        Mesh::from_ascii_stl(text)
    }

    fn from_binary_stl(body: &[u8], n: usize) -> Result<Mesh, MeshError> {
        if n > MAX_TRIANGLES {
            return Err(MeshError(format!(
                "the STL has {n} triangles; at most {MAX_TRIANGLES} are read"
            )));
        }
        let mut builder = Builder::with_capacity(n);
        for t in body.chunks_exact(50) {
            let f = |o: usize| f32::from_le_bytes([t[o], t[o + 1], t[o + 2], t[o + 3]]) as f64;
            // Bytes 0–11 are the normal, recomputed from the vertices by whoever needs it.
            let v = [12, 24, 36].map(|o| [f(o), f(o + 4), f(o + 8)]);
            builder.triangle(v)?;
        }
        Ok(builder.mesh)
    }

    fn from_ascii_stl(text: &str) -> Result<Mesh, MeshError> {
        let mut builder = Builder::with_capacity(0);
        let mut corners = Vec::with_capacity(3);
        let mut seen_solid = false;
        for (number, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("solid") => seen_solid = true,
                Some("vertex") => {
                    let v: Vec<f64> = words.filter_map(|w| w.parse().ok()).collect();
                    if v.len() != 3 {
                        return Err(MeshError(format!(
                            "line {}: a vertex needs three numbers: {line:?}",
                            number + 1
                        )));
                    }
                    corners.push([v[0], v[1], v[2]]);
                }
                Some("endloop") => {
                    // A facet of more than three vertices (allowed by some writers): a fan.
                    for k in 1..corners.len().saturating_sub(1) {
                        builder.triangle([corners[0], corners[k], corners[k + 1]])?;
                    }
                    corners.clear();
                }
                _ => {}
            }
        }
        if !seen_solid {
            return Err(MeshError(
                "not an STL file (no `solid` in an ASCII file)".into(),
            ));
        }
        Ok(builder.mesh)
    }

    /// Reads the vertices (`v`) and faces (`f`, polygons fanned into triangles; `1/2/3`
    /// forms and negative indices) of an OBJ file; everything else is ignored.
    pub fn from_obj(text: &str) -> Result<Mesh, MeshError> {
        let mut positions: Vec<[f64; 3]> = Vec::new();
        let mut builder = Builder::with_capacity(0);
        for (number, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            let bad = |what: &str| MeshError(format!("line {}: {what}: {line:?}", number + 1));
            match words.next() {
                Some("v") => {
                    let v: Vec<f64> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                    if v.len() != 3 {
                        return Err(bad("a vertex needs three numbers"));
                    }
                    if v.iter().any(|c| !c.is_finite()) {
                        return Err(bad("a vertex is not finite"));
                    }
                    positions.push([v[0], v[1], v[2]]);
                }
                Some("f") => {
                    let mut corners = Vec::new();
                    for w in words {
                        let index: i64 = w
                            .split('/')
                            .next()
                            .and_then(|i| i.parse().ok())
                            .ok_or_else(|| bad("a face corner is not an index"))?;
                        let resolved = if index < 0 {
                            positions.len() as i64 + index
                        } else {
                            index - 1
                        };
                        let p = usize::try_from(resolved)
                            .ok()
                            .and_then(|i| positions.get(i))
                            .ok_or_else(|| bad("a face names a vertex that is not defined"))?;
                        corners.push(*p);
                    }
                    for k in 1..corners.len().saturating_sub(1) {
                        builder.triangle([corners[0], corners[k], corners[k + 1]])?;
                    }
                }
                _ => {}
            }
        }
        Ok(builder.mesh)
    }

    /// The lowest and highest corner of the mesh's bounding box; `None` when empty.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.vertices.iter();
        let first = *it.next()?;
        Some(it.fold((first, first), |(lo, hi), v| {
            (
                [lo[0].min(v[0]), lo[1].min(v[1]), lo[2].min(v[2])],
                [hi[0].max(v[0]), hi[1].max(v[1]), hi[2].max(v[2])],
            )
        }))
    }

    /// Writes the mesh as binary STL (tests and scripts build meshes with it).
    pub fn to_binary_stl(&self) -> Vec<u8> {
        let mut out = vec![0u8; 80];
        out.extend((self.triangles.len() as u32).to_le_bytes());
        for t in &self.triangles {
            out.extend([0u8; 12]);
            for &i in t {
                for c in self.vertices[i as usize] {
                    out.extend((c as f32).to_le_bytes());
                }
            }
            out.extend([0u8; 2]);
        }
        out
    }

    /// Adds `other`'s triangles to this mesh (its vertices after this mesh's): how a
    /// 3MF's objects are merged into one part and how test meshes are built of blocks.
    pub fn append(&mut self, other: &Mesh) {
        let base = self.vertices.len() as u32;
        self.vertices.extend(&other.vertices);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
    }

    /// The part of a 3MF's `objects` (as `read_3mf` gives them) that `object` names: all
    /// of them merged (`None`), or the one named. An unknown name is an error naming the
    /// file's objects. One choice for `rotlang preview --object` and the playground.
    pub fn pick(
        file: &str,
        objects: &[(String, Mesh)],
        object: Option<&str>,
    ) -> Result<Mesh, MeshError> {
        let mut merged = Mesh::default();
        let mut found = false;
        for (n, m) in objects {
            if object.is_none_or(|o| o == n) {
                found = true;
                merged.append(m);
            }
        }
        if !found {
            let names: Vec<&str> = objects.iter().map(|(n, _)| n.as_str()).collect();
            return Err(MeshError(format!(
                "{file} has no object {:?}; its objects: {}",
                object.unwrap_or_default(),
                names.join(", ")
            )));
        }
        Ok(merged)
    }

    /// Moves every vertex by `offset`.
    pub fn translate(&mut self, offset: [f64; 3]) {
        for v in &mut self.vertices {
            for k in 0..3 {
                v[k] += offset[k];
            }
        }
    }
}

/// Builds a mesh, merging identical vertices and dropping triangles with a repeated
/// corner (no area: they add nothing to any section).
struct Builder {
    mesh: Mesh,
    index: HashMap<[u64; 3], u32>,
}

impl Builder {
    fn with_capacity(n: usize) -> Builder {
        Builder {
            mesh: Mesh {
                vertices: Vec::with_capacity(n / 2),
                triangles: Vec::with_capacity(n),
            },
            index: HashMap::with_capacity(n / 2),
        }
    }

    fn vertex(&mut self, v: [f64; 3]) -> Result<u32, MeshError> {
        if v.iter()
            .any(|c| !c.is_finite() || c.abs() > crate::infill::MAX_COORDINATE)
        {
            return Err(MeshError(format!(
                "a vertex {v:?} is not finite or beyond ±{} mm",
                crate::infill::MAX_COORDINATE
            )));
        }
        // +0.0 and −0.0 are one point.
        let key = v.map(|c| (c + 0.0).to_bits());
        let next = self.mesh.vertices.len() as u32;
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            self.mesh.vertices.push(v);
        }
        Ok(i)
    }

    fn triangle(&mut self, corners: [[f64; 3]; 3]) -> Result<(), MeshError> {
        if self.mesh.triangles.len() >= MAX_TRIANGLES {
            return Err(MeshError(format!(
                "the mesh has more than {MAX_TRIANGLES} triangles"
            )));
        }
        let [a, b, c] = [
            self.vertex(corners[0])?,
            self.vertex(corners[1])?,
            self.vertex(corners[2])?,
        ];
        if a != b && b != c && a != c {
            self.mesh.triangles.push([a, b, c]);
        }
        Ok(())
    }
}

/// Meshes for tests, benchmarks and examples.
pub mod shapes {
    use super::Mesh;
    use std::f64::consts::TAU;

    /// A box from (0, 0, 0) to `size`.
    pub fn cuboid(size: [f64; 3]) -> Mesh {
        let [x, y, z] = size;
        let vertices = vec![
            [0.0, 0.0, 0.0],
            [x, 0.0, 0.0],
            [x, y, 0.0],
            [0.0, y, 0.0],
            [0.0, 0.0, z],
            [x, 0.0, z],
            [x, y, z],
            [0.0, y, z],
        ];
        let triangles = vec![
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 6],
            [4, 6, 7],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        Mesh {
            vertices,
            triangles,
        }
    }

    /// A tube standing on z = 0: `outer` and `inner` radii (no hole when `inner` is 0),
    /// `height` tall, `segments` around.
    pub fn tube(outer: f64, inner: f64, height: f64, segments: usize) -> Mesh {
        let n = segments.max(3);
        let mut m = Mesh::default();
        let ring = |r: f64, z: f64, m: &mut Mesh| -> u32 {
            let start = m.vertices.len() as u32;
            for i in 0..n {
                let a = TAU * i as f64 / n as f64;
                m.vertices
                    .push([r * crate::math::cos(a), r * crate::math::sin(a), z]);
            }
            start
        };
        let (ob, ot) = (ring(outer, 0.0, &mut m), ring(outer, height, &mut m));
        let n32 = n as u32;
        let next = |i: u32| (i + 1) % n32;
        for i in 0..n32 {
            m.triangles.push([ob + i, ob + next(i), ot + next(i)]);
            m.triangles.push([ob + i, ot + next(i), ot + i]);
        }
        if inner > 0.0 {
            let (ib, it) = (ring(inner, 0.0, &mut m), ring(inner, height, &mut m));
            for i in 0..n32 {
                m.triangles.push([ib + i, it + next(i), ib + next(i)]);
                m.triangles.push([ib + i, it + i, it + next(i)]);
                // Annular caps.
                m.triangles.push([ob + i, ib + next(i), ob + next(i)]);
                m.triangles.push([ob + i, ib + i, ib + next(i)]);
                m.triangles.push([ot + i, ot + next(i), it + next(i)]);
                m.triangles.push([ot + i, it + next(i), it + i]);
            }
        } else {
            let (cb, ct) = (m.vertices.len() as u32, m.vertices.len() as u32 + 1);
            m.vertices.push([0.0, 0.0, 0.0]);
            m.vertices.push([0.0, 0.0, height]);
            for i in 0..n32 {
                m.triangles.push([cb, ob + next(i), ob + i]);
                m.triangles.push([ct, ot + i, ot + next(i)]);
            }
        }
        m
    }

    /// A torus about the z axis, lying on z = 0: `major` and `minor` radii.
    pub fn torus(major: f64, minor: f64, around: usize, across: usize) -> Mesh {
        let (n, k) = (around.max(3), across.max(3));
        let mut m = Mesh::default();
        for i in 0..n {
            let a = TAU * i as f64 / n as f64;
            for j in 0..k {
                let b = TAU * j as f64 / k as f64;
                let r = major + minor * crate::math::cos(b);
                m.vertices.push([
                    r * crate::math::cos(a),
                    r * crate::math::sin(a),
                    minor + minor * crate::math::sin(b),
                ]);
            }
        }
        let at = |i: usize, j: usize| ((i % n) * k + (j % k)) as u32;
        for i in 0..n {
            for j in 0..k {
                m.triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                m.triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        m
    }

    /// The surface swept by turning `profile` (radius, height pairs, from a point on the
    /// axis round to another on the axis) about the z axis, `segments` around: any lathe
    /// part, closed.
    pub fn revolved(profile: &[(f64, f64)], segments: usize) -> Mesh {
        let n = segments.max(3) as u32;
        let mut m = Mesh::default();
        // Each profile point: one vertex on the axis, or a ring.
        let mut rings: Vec<(u32, bool)> = Vec::new();
        for &(r, z) in profile {
            let start = m.vertices.len() as u32;
            if r <= 0.0 {
                m.vertices.push([0.0, 0.0, z]);
                rings.push((start, false));
            } else {
                for i in 0..n {
                    let a = TAU * i as f64 / n as f64;
                    m.vertices
                        .push([r * crate::math::cos(a), r * crate::math::sin(a), z]);
                }
                rings.push((start, true));
            }
        }
        let next = |i: u32| (i + 1) % n;
        for w in rings.windows(2) {
            let ((a, ra), (b, rb)) = (w[0], w[1]);
            for i in 0..n {
                match (ra, rb) {
                    (true, true) => {
                        m.triangles.push([a + i, a + next(i), b + next(i)]);
                        m.triangles.push([a + i, b + next(i), b + i]);
                    }
                    (false, true) => m.triangles.push([a, b + next(i), b + i]),
                    (true, false) => m.triangles.push([a + i, a + next(i), b]),
                    (false, false) => {}
                }
            }
        }
        m
    }

    /// A vase (a real part's shape, built here rather than downloaded): a foot, a belly
    /// 60 mm across, a waist and a flared lip, 80 mm tall, hollow above its 3 mm floor
    /// with 2 mm walls; its sections are discs low down and rings of changing size above.
    pub fn vase(segments: usize) -> Mesh {
        let outer = |z: f64| {
            // Belly at a third of the height, waist at 80%, lip flaring at the top.
            let t = z / 80.0;
            20.0 + 10.0 * crate::math::sin(std::f64::consts::PI * t * 1.5).max(-0.6)
                + 6.0 * t.powi(6)
        };
        let mut profile = vec![(0.0, 0.0)];
        let steps = 64;
        for k in 0..=steps {
            let z = 80.0 * k as f64 / steps as f64;
            profile.push((outer(z), z));
        }
        for k in (0..=steps).rev() {
            let z = 3.0 + 77.0 * k as f64 / steps as f64;
            profile.push((outer(z) - 2.0, z));
        }
        profile.push((0.0, 3.0));
        revolved(&profile, segments)
    }

    /// A stepped block: a `base` block (x, y, z sizes) with a `tower` (x, y, z) standing
    /// on it at its x = 0, y = 0 corner: the base's top beside the tower is a top surface
    /// under which a slicer prints solid layers, while the tower above stays sparse.
    pub fn step(base: [f64; 3], tower: [f64; 3]) -> Mesh {
        let mut m = cuboid(base);
        let mut top = cuboid(tower);
        top.translate([0.0, 0.0, base[2]]);
        m.append(&top);
        m
    }

    /// A T standing on its foot: a `foot`-wide square column `height` tall under a wide
    /// slab (the overhang), both `depth` deep.
    pub fn overhang(foot: f64, slab: f64, height: f64, thickness: f64) -> Mesh {
        let mut m = cuboid([foot, foot, height]);
        let mut top = cuboid([slab, foot, thickness]);
        top.translate([(foot - slab) / 2.0, 0.0, height]);
        m.append(&top);
        m
    }
}

#[cfg(feature = "3mf")]
mod threemf;
#[cfg(feature = "3mf")]
pub use threemf::read_3mf;

#[cfg(test)]
mod tests;
