// rotlang/full: everything in rotlang.js, plus what the playground needs beyond the core
// package (reading profile files, the infill preview, meshes sliced into layers), from rotlang-full.wasm. A separate module so that
// rotlang.wasm stays small for those who need only the language.
import { bind, compile } from './lib.js';

export { FILLS, PATTERNS, SHAPES, RotlangError } from './lib.js';

const api = await bind(await compile(new URL('./rotlang-full.wasm', import.meta.url)));

export const {
  version, signs, check, format, explain, explainCode, compare, compat, expand, plot, readProfile,
  preview, readMesh, part, partSettings,
} = api;
