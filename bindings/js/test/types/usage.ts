// A small program on the package's types: `npm run typecheck` (tsc --noEmit) compiles it
// against rotlang.d.ts and full.d.ts, so a declaration that no longer fits its use fails
// the Node suite. Never run: types only.
import { check, compare, compat, expand, explain, explainCode, FILLS, format, RotlangError, signs, version } from 'rotlang';
import type { Diagnostic, ExpandResult, Fill, Model } from 'rotlang';
import { part, partSettings, plot, preview, readMesh, readProfile } from 'rotlang/full';
import type { MeshInfo, PartArea, PartLayer, Profile } from 'rotlang/full';

const v: string = version();
const c = check('+30X5', { target: 'sparse' });
const first: Diagnostic | undefined = c.diagnostics[0];
const where: [number, number] | null = first ? [first.startUtf16, first.endUtf16] : null;
const fixed: string | null = first?.fix?.replacement ?? null;
const canonical: string = format('0 90');

const model: Model = { layers: 500, layerHeight: 0.2, firstLayerHeight: 0.3, bottomShells: 3, topShells: 4 };
const r: ExpandResult = expand('+10L25%, -10l25%', { model, from: 0, to: 100, base: 45, seed: 1 });
const angles: Float64Array = r.angles;
const fill: Fill = FILLS[r.fills[42]];
const governing: string | undefined = r.instructions[r.instructionIndex[42]]?.text;
const orca = expand('0 90', { dialect: 'orcaslicer', model: { layerHeights: [0.2, 0.2, 0.2] } });
const hangs: number[] = orca.findings.map((f) => f.firstLayer);

const cmp = compare('0 90', { model });
const differs: number | undefined = cmp.firstDifference?.layer;
const lint: Diagnostic[] = compat('10!, 5*', { model });
const words: string = explain('+30/50%', { model });
const doc = explainCode('rotlang::unknown-sign');
const summary: string | undefined = doc?.summary;
const meanings: string[] = signs().map((s) => `${s.sign} (${s.kind}): ${s.meaning}`);

try {
  expand('+30X5');
} catch (e) {
  if (e instanceof RotlangError && e.kind === 'template') {
    const spans: number[] = (e.diagnostics ?? []).map((d) => d.start);
    void spans;
  }
}

const profile: Profile = readProfile('pla.json', Uint8Array.of(0x7b, 0x7d));
const sparse = profile.templates.find((t) => t.target === 'sparse')?.text;
const svg: string = preview('+30', { layer: 3, pattern: 'gyroid', shape: 'star', density: 0.2, width: 320 });
const chart: string = plot('+30', { width: 640, height: 400, model });

export const used = [v, where, fixed, canonical, angles, fill, governing, hangs, differs, lint, words, summary, meanings, sparse, svg, chart];

// A mesh read once, then sliced and filled under a template.
const mesh: MeshInfo = readMesh('cube.stl', new Uint8Array(84));
const height: number = mesh.max[2] - mesh.min[2];
const sliced = part('+45', { pattern: 'gyroid', density: 0.15, walls: 2, from: 0, to: 10, model: { layerHeight: 0.2 } });
const layer: PartLayer = sliced.layers[0];
const outline: [number, number][] = layer.section[0][0];
const minutes: number = sliced.summary.time_s / 60 + height + outline.length + layer.polylines.length;
// Top and bottom surfaces turned by a solid template: each layer's areas say which is solid.
const shelled = part('+45', { solidTemplate: '90', model: { topShells: 3, bottomShells: 2 } });
const solidAreas: PartArea[] = shelled.layers[0].areas.filter((a) => a.solid);
const printed: string = shelled.layers[0].printed;
const solidShare: number = shelled.summary.solid_extrusion_mm / shelled.summary.extrusion_mm;
const solidText: string | null = shelled.solid_template;
export const usedPart = [minutes, solidAreas, printed, solidShare, solidText, shelled.settings.walls];
// One object of a 3MF project, and what the project gives it, without slicing.
const objectName: string | undefined = mesh.objects[0];
const fromProject = mesh.project ? partSettings('', { object: objectName }) : null;
const one = part('', { object: objectName, solidTemplate: fromProject?.solid_template ?? undefined });
export const usedObject = [one.settings.layer_height, fromProject?.first_layer_height, fromProject?.settings.walls];
