// rotlang for JavaScript: the WebAssembly build of the rotlang library behind a small
// synchronous API. An ES module for Node 20+ and browsers, no bundler needed: importing
// it loads rotlang.wasm (beside this file) once, with top-level await.
import { bind, compile } from './lib.js';

export { FILLS, PATTERNS, SHAPES, RotlangError } from './lib.js';

const api = await bind(await compile(new URL('./rotlang.wasm', import.meta.url)));

export const {
  version, signs, check, format, explain, explainCode, compare, compat, expand,
} = api;
