// Types of the npm package `rotlang` (rotlang.js). Every function is synchronous: the
// module loads its WebAssembly with top-level await when it is imported.

/** Fill names, indexed by the bytes of `ExpandResult.fills`. */
export const FILLS: readonly ['sparse', 'dense', 'solid', 'concentric', 'monotonic', 'rectilinear'];
export type Fill = (typeof FILLS)[number];
/** The infill preview's patterns (rotlang/full). */
export const PATTERNS: readonly ['lines', 'grid', 'triangles', 'hexagons', 'concentric', 'gyroid', 'spiral', 'lightning', 'cubic'];
/** The infill preview's outlines, 20 mm across (rotlang/full). */
export const SHAPES: readonly ['square', 'circle', 'ring', 'star', 'l'];

export type ErrorKind = 'template' | 'model' | 'options' | 'limit' | 'profile' | 'unavailable' | 'internal';

/** Thrown on bad input (never a crash): `kind` says what was wrong. */
export class RotlangError extends Error {
  readonly name: 'RotlangError';
  readonly kind: ErrorKind;
  /** For kind 'template': the template's diagnostics. */
  readonly diagnostics: Diagnostic[] | null;
}

/** A span in both units: UTF-8 bytes (the core's) and UTF-16 code units (JS string indices). */
export interface Span {
  start: number;
  end: number;
  startUtf16: number;
  endUtf16: number;
}

export interface Label extends Span {
  message: string;
  primary: boolean;
}

export interface Fix extends Span {
  title: string;
  replacement: string;
}

/** One diagnostic; its own span is the primary label's. */
export interface Diagnostic extends Span {
  /** Stable code, e.g. `rotlang::unknown-sign`. */
  code: string;
  severity: 'error' | 'warning';
  message: string;
  /** One-based line and column (characters) of the start. */
  line: number;
  column: number;
  help: string | null;
  labels: Label[];
  fix: Fix | null;
}

export interface Instruction extends Span {
  text: string;
}

/**
 * A model: `layers` uniform layers (or `height` mm of them), or the list `layerHeights`;
 * `layerHeight` is the standard height `h` (default 0.2). The conformance corpus's
 * models.json names (`layer_heights`, `layer_height`, `bottom_shell_layers`,
 * `top_shell_layers`, `first_layer_height`) are accepted too. Default: the
 * documentation's 20 mm cube (100 × 0.2 mm).
 */
export interface Model {
  layers?: number;
  height?: number;
  layerHeights?: ArrayLike<number>;
  layerHeight?: number;
  firstLayerHeight?: number;
  bottomShells?: number;
  topShells?: number;
}

export interface Options {
  /** Which setting the template is for (solid signs are errors in a solid template). */
  target?: 'sparse' | 'solid';
  /**
   * How the text is read: rotlang's grammar, or exactly as OrcaSlicer's own code reads it
   * (any text, valid or not; its angles, with finite ones where it hangs or yields NaN).
   */
  dialect?: 'rotlang' | 'orcaslicer';
  model?: Model;
  /** The base direction in degrees (the profile's infill direction), within ±1e9. */
  base?: number;
  /** The seed of the random joints `~` and `^`: a whole number from 0 to 2^53 − 1. */
  seed?: number;
}

export interface ExpandOptions extends Options {
  /** First layer to return (default 0). */
  from?: number;
  /** One past the last layer to return (default: the top). At most 10,000,000 per call. */
  to?: number;
}

export interface CheckResult {
  diagnostics: Diagnostic[];
  hasErrors: boolean;
  /** Diagnostics found beyond the cap of 100 and not listed. */
  omitted: number;
  errors: number;
  warnings: number;
  /** Every instruction that could be read. */
  instructions: Instruction[];
}

export interface Finding {
  code: string;
  message: string;
  firstLayer: number;
  layers: number;
}

export interface ExpandResult {
  /** Layers in the model. */
  layers: number;
  from: number;
  to: number;
  /** Degrees, base included, not wrapped; one per layer `from`..`to`. */
  angles: Float64Array;
  /** Indices into FILLS. */
  fills: Uint8Array;
  /** Index into `instructions` of the instruction that governs each layer; -1 when it holds. */
  instructionIndex: Int32Array;
  instructions: Instruction[];
  /** rotlang dialect: each instruction in plain words (as the editor hover says it). */
  words: string[];
  model: { layers: number; layerHeight: number; height: number; bottomShells: number; topShells: number };
  dialect: 'rotlang' | 'orcaslicer';
  /** OrcaSlicer dialect: where OrcaSlicer hangs, crashes or computes NaN, in the layers returned. */
  findings: Finding[];
}

export interface Comparison {
  /** Layers in the model. */
  layers: number;
  /** The template has errors in rotlang (then only OrcaSlicer's findings are given). */
  rotlangErrors: boolean;
  /** The first layer whose direction differs (modulo 360), or null. */
  firstDifference: { layer: number; rotlang: number; orcaslicer: number } | null;
  differingLayers: number;
  /** Layers that rotlang fills solid and OrcaSlicer (which has no solid signs) leaves sparse. */
  solidLayersLost: number;
  findings: Finding[];
}

export interface Sign {
  sign: string;
  kind: 'joint' | 'solid' | 'unit' | 'mark';
  meaning: string;
}

export function version(): string;
export function check(text: string, options?: Options): CheckResult;
/** The canonical form; throws RotlangError (kind 'template') when the template has errors. */
export function format(text: string, options?: Options): string;
export function expand(text: string, options?: ExpandOptions): ExpandResult;
export function signs(): Sign[];

export function compare(text: string, options?: Options): Comparison;
/** The template in plain words on the model (what `rotlang explain TEMPLATE` prints). */
export function explain(text: string, options?: Options): string;
export interface CodeDoc {
  code: string;
  severity: 'error' | 'warning';
  summary: string;
  explanation: string;
  example: string;
  fix: string;
}
/**
 * The OrcaSlicer compat lint: where OrcaSlicer reads the template differently (codes
 * `orcaslicer::…`), by rule and on the model, with fixes where one keeps both readings.
 */
export function compat(text: string, options?: Options): Diagnostic[];

/** A diagnostic code explained (what `rotlang explain CODE` prints); null for an unknown code. */
export function explainCode(code: string): CodeDoc | null;
