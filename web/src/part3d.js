// The part's layers stacked in 3D (three.js, WebGL): each layer's section outline and its
// infill paths as line segments at the layer's height, the sparse infill in blue and the
// solid areas' (top and bottom surfaces) in purple, the layers above the slider's hidden
// (the slider cuts through the part) and the slider's own layer highlighted.
// Loaded only when a mesh is opened, so the page's first load does not carry three.js.
import {
  BufferGeometry, Color, Float32BufferAttribute, Group, LineBasicMaterial, LineSegments,
  PerspectiveCamera, Scene, Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { splitPaths } from './part.js';

const MATERIALS = {
  outline: new LineBasicMaterial({ color: 0x5b6577 }),
  infill: new LineBasicMaterial({ color: 0x2f7ed8, transparent: true, opacity: 0.55 }),
  currentOutline: new LineBasicMaterial({ color: 0x111111 }),
  currentInfill: new LineBasicMaterial({ color: 0xe8590c }),
  solid: new LineBasicMaterial({ color: 0x9c36b5, transparent: true, opacity: 0.7 }),
  currentSolid: new LineBasicMaterial({ color: 0x5f1d7a }),
};

// Segment pairs (x, y, z per corner) of a layer's section rings (closed) and polylines.
function segments(lines, z, closed) {
  const out = [];
  for (const line of lines) {
    const n = line.length;
    const last = closed && n > 2 && (line[0][0] !== line[n - 1][0] || line[0][1] !== line[n - 1][1]) ? n : n - 1;
    for (let i = 0; i < last; i += 1) {
      const a = line[i];
      const b = line[(i + 1) % n];
      out.push(a[0], a[1], z, b[0], b[1], z);
    }
  }
  return new Float32BufferAttribute(out, 3);
}

function lines(position, material) {
  const g = new BufferGeometry();
  g.setAttribute('position', position);
  g.computeBoundingBox();
  return new LineSegments(g, material);
}

export class PartView {
  constructor(holder) {
    this.holder = holder;
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    this.renderer.domElement.setAttribute('role', 'img');
    this.renderer.domElement.setAttribute('aria-label', 'The part\'s layers in 3D: drag to turn, scroll to zoom');
    holder.append(this.renderer.domElement);
    this.scene = new Scene();
    this.scene.background = new Color(0xffffff);
    this.camera = new PerspectiveCamera(35, 4 / 3, 0.1, 10_000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.stack = new Group();
    this.scene.add(this.stack);
    this.layers = [];
    this.current = -1;
    this.framed = null;
    new ResizeObserver(() => this.resize()).observe(holder);
    this.resize();
  }

  resize() {
    const width = Math.max(200, this.holder.clientWidth);
    const height = Math.round(Math.min(440, Math.max(220, width * 0.75)));
    this.renderer.setSize(width, height);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  // Looks at the mesh's bounding box from the front right, above (again only for a new mesh,
  // so that a turned view stays turned while the template changes).
  frame(info) {
    const key = JSON.stringify([info.min, info.max]);
    if (this.framed === key) return;
    this.framed = key;
    const min = new Vector3(...info.min);
    const max = new Vector3(...info.max);
    const centre = min.clone().add(max).multiplyScalar(0.5);
    const size = Math.max(1e-3, max.clone().sub(min).length());
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).add(new Vector3(0.9, -1.3, 0.9).normalize().multiplyScalar(size * 1.35));
    this.camera.near = size / 100;
    this.camera.far = size * 20;
    this.camera.updateProjectionMatrix();
    this.controls.update();
  }

  /** Replaces the stack by the part's layers (`part(...).layers`). */
  show(info, partLayers) {
    for (const l of this.layers) {
      l.outline.geometry.dispose();
      l.infill.geometry.dispose();
      l.solid.geometry.dispose();
    }
    this.stack.clear();
    this.layers = partLayers.map((l) => {
      const group = new Group();
      const outline = lines(segments(l.section.flat(), l.z, true), MATERIALS.outline);
      const paths = splitPaths(l);
      const infill = lines(segments(paths.sparse, l.z, false), MATERIALS.infill);
      const solid = lines(segments(paths.solid, l.z, false), MATERIALS.solid);
      group.add(outline, infill, solid);
      this.stack.add(group);
      return { index: l.index, z: l.z, group, outline, infill, solid };
    });
    this.frame(info);
    this.current = -1;
  }

  /** Shows the layers up to `index` (the slider's), that one highlighted. */
  cut(index) {
    this.current = index;
    for (const l of this.layers) {
      l.group.visible = l.index <= index;
      const now = l.index === index;
      l.outline.material = now ? MATERIALS.currentOutline : MATERIALS.outline;
      l.infill.material = now ? MATERIALS.currentInfill : MATERIALS.infill;
      l.solid.material = now ? MATERIALS.currentSolid : MATERIALS.solid;
    }
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  /**
   * What is drawn, read back from the scene's geometry (for the browser tests): per
   * layer, the vertex counts and bounding boxes of its outline, sparse infill and solid
   * infill, their colours and main directions, and whether it is shown; and how many pixels of the canvas differ from the background.
   */
  inspect() {
    const box = (o) => ({
      vertices: o.geometry.getAttribute('position').count,
      min: o.geometry.boundingBox ? o.geometry.boundingBox.min.toArray() : null,
      max: o.geometry.boundingBox ? o.geometry.boundingBox.max.toArray() : null,
    });
    const points = (o) => Array.from(o.geometry.getAttribute('position').array);
    // The direction (degrees, 0 to 180, whole) holding the most length of the segments.
    const direction = (o) => {
      const a = o.geometry.getAttribute('position').array;
      const length = new Map();
      for (let i = 0; i + 5 < a.length; i += 6) {
        const [dx, dy] = [a[i + 3] - a[i], a[i + 4] - a[i + 1]];
        const d = Math.round(((Math.atan2(dy, dx) * 180) / Math.PI + 360) % 180) % 180;
        length.set(d, (length.get(d) ?? 0) + Math.hypot(dx, dy));
      }
      let best = null;
      for (const [d, l] of length) if (best === null || l > length.get(best)) best = d;
      return best;
    };
    return {
      layers: this.layers.map((l) => ({
        index: l.index,
        z: l.z,
        visible: l.group.visible,
        current: l.index === this.current,
        outline: { ...box(l.outline), points: points(l.outline) },
        infill: { ...box(l.infill), color: l.infill.material.color.getHex(), direction: direction(l.infill) },
        solid: { ...box(l.solid), color: l.solid.material.color.getHex(), direction: direction(l.solid) },
      })),
      current: this.current,
      drawnPixels: this.drawnPixels(),
    };
  }

  drawnPixels() {
    const gl = this.renderer.getContext();
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let n = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250) n += 1;
    return n;
  }
}
