// Types of `rotlang/full` (full.js): everything of `rotlang`, plus profile reading and
// the infill preview.
import type { Options } from './rotlang.js';
export * from './rotlang.js';

export interface ProfileTemplate {
  /** `sparse_infill_rotate_template` or `solid_infill_rotate_template`; null for a `.rot` file. */
  key: string | null;
  object: string | null;
  target: 'sparse' | 'solid';
  text: string;
  /**
   * The base to evaluate this template with (`options.base`): the profile's infill
   * direction where the template is empty, else 0, as OrcaSlicer reads a profile.
   */
  base: number;
}

export interface Profile {
  kind: 'template' | 'json' | 'ini' | '3mf' | string;
  templates: ProfileTemplate[];
  /** The model the profile's settings give (a 20 mm tall object). */
  model: { layers: number; layerHeight: number; firstLayerHeight: number | null; bottomShells: number; topShells: number };
  /**
   * The profile's infill direction. OrcaSlicer turns an empty template only by it: use
   * each template's own `base`, not this, to evaluate a template.
   */
  base: number;
  notes: { message: string; error: boolean }[];
  /** Some note is an error (e.g. the JSON is broken after the templates). */
  hasErrors: boolean;
}

/**
 * The templates and model of a profile file, read by rotlang's profile reader: the name's
 * extension picks the kind (`.json`, `.jsonc`, `.ini`, `.rot`). Throws RotlangError (kind
 * 'profile') for a file that cannot be read at all.
 */
export function readProfile(name: string, content: string | Uint8Array | ArrayBuffer): Profile;


export interface PreviewOptions extends Options {
  /** The layer (default 0). */
  layer?: number;
  pattern?: 'lines' | 'grid' | 'triangles' | 'hexagons' | 'concentric' | 'gyroid' | 'spiral' | 'lightning' | 'cubic';
  /** Sparse density, 0 to 1 (default 0.2). */
  density?: number;
  shape?: 'square' | 'circle' | 'ring' | 'star' | 'l';
  /** The panel's side in pixels (default 320). */
  width?: number;
}
/** One layer's infill as printed, seen from above, as SVG (what `rotlang preview` draws). */
export function preview(text: string, options?: PreviewOptions): string;

export interface PlotOptions extends Options {
  /** Picture size in pixels (16 to 4096; default 960 × 560). */
  width?: number;
  height?: number;
}
/** The angle chart as SVG (what `rotlang plot` draws); throws for a template with errors. */
export function plot(text: string, options?: PlotOptions): string;

export interface MeshInfo {
  triangles: number;
  vertices: number;
  /** The mesh's bounding box corners, [x, y, z] in mm. */
  min: [number, number, number];
  max: [number, number, number];
  /** A 3MF's object names (`part` merges them, or takes one: `object`); empty for STL and OBJ. */
  objects: string[];
  /**
   * An OrcaSlicer project (a 3MF with settings): `part` takes its templates and settings
   * (an object's overrides first) where its options do not say, as `rotlang preview
   * project.3mf` does.
   */
  project: boolean;
}
/**
 * Reads a mesh file (the name's extension picks `.stl` (binary or ASCII), `.obj` or
 * `.3mf`) and keeps it for `part`. Throws RotlangError (kind 'model') when it cannot be read.
 */
export function readMesh(name: string, content: Uint8Array | ArrayBuffer | string): MeshInfo;

export type Point = [number, number];
/** One area of a layer: the sparse one, or the solid one (top and bottom surfaces). */
export interface PartArea {
  /** 'sparse', 'solid', or the template's solid sign that makes the layer solid. */
  fill: string;
  solid: boolean;
  angle: number;
  pattern: string;
  density: number;
  area_mm2: number;
  /** The area: polygons, each its outline then its holes. */
  region: Point[][][];
  length: number;
  travel: number;
  polylines: Point[][];
}
export interface PartLayer {
  index: number;
  bottom: number;
  top: number;
  /** The height of the cut (the layer's middle) above the mesh's lowest point. */
  z: number;
  /** The sparse template's angle, and the angle the solid area turns by. */
  angle: number;
  solid_angle: number;
  fill: string;
  /** 'sparse', 'sparse+solid', or the solid fill throughout ('solid' for a surface). */
  printed: string;
  pattern: string;
  density: number;
  /** Infill extruded and travelled on this layer (mm). */
  length: number;
  travel: number;
  /** Chains that could not be closed, and gaps bridged (holes in the mesh's surface). */
  open: number;
  bridged: number;
  /** The section: polygons, each its outline then its holes. */
  section: Point[][][];
  /**
   * The wall loops, outermost first: each wall's middle line, the section moved in by
   * (k + ½) line widths, as closed rings (first point repeated); a loop with no room in
   * the section is absent.
   */
  walls: Point[][];
  /** The areas that are not empty: the sparse one, then the solid one. */
  areas: PartArea[];
  /** Every path of the layer (the areas' in turn). */
  polylines: Point[][];
}
export interface PartOptions extends Omit<PreviewOptions, 'shape' | 'layer' | 'width'> {
  /** Wall loops around the infill, each a 0.4 mm line (default 2). */
  walls?: number;
  /**
   * The solid infill's template (`solid_infill_rotate_template`, `--solid-template`): it
   * turns the solid areas; without it they turn with the template. Their depth is the
   * model's `bottomShells` and `topShells`.
   */
  solidTemplate?: string;
  /**
   * True: no solid template, even where an OrcaSlicer project sets one
   * (`--no-solid-template`): the solid areas turn with the template, to compare the two on
   * the same part. Not with `solidTemplate` (RotlangError, kind 'options').
   */
  noSolidTemplate?: boolean;
  /**
   * A 3MF's object (`--object NAME`): that object alone, with its own settings in a
   * project; all objects merged by default. A name the file does not hold throws
   * RotlangError (kind 'options') listing its objects, with the CLI's message.
   */
  object?: string;
  /** The layers returned, `from` (included) to `to` (excluded); all by default. The summary counts every layer. */
  from?: number;
  to?: number;
}
export interface PartSettings {
  pattern: string; density: number; solid_pattern: string; line_width: number; walls: number;
  layer_height: number; layers: number; bottom_shell_layers: number; top_shell_layers: number;
  base: number;
}
/**
 * The mesh kept by `readMesh` (all its objects, or `object`), sliced at the middle of each
 * layer and filled under the template: what `rotlang preview --shape part.stl [--object
 * NAME] --format json` prints (the same code builds both). For an OrcaSlicer project, what
 * the options do not give is the project's (the object's overrides first), and an empty
 * template is the project's template, as the CLI reads them.
 */
export function part(text: string, options?: PartOptions): {
  template: string;
  solid_template: string | null;
  settings: PartSettings;
  summary: {
    layers: number; extrusion_mm: number; travel_mm: number; time_s: number;
    speed: number; travel_speed: number; open_layers: number; bridged: number;
    solid_extrusion_mm: number;
  };
  layers: PartLayer[];
};

/**
 * What `part(text, options)` would fill the part with, without slicing it: the template,
 * the solid template (null: the solid areas turn with the template), the settings, the
 * first layer's height and the solid template's base. For a project, its (or its object's)
 * own; the playground fills its editor and form with them.
 */
export function partSettings(text: string, options?: PartOptions): {
  template: string;
  solid_template: string | null;
  settings: PartSettings;
  first_layer_height: number | null;
  solid_base: number;
};
