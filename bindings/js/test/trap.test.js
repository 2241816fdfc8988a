// A trap inside the wasm (a bug, never expected) becomes a RotlangError and a fresh
// instance, not a dead module. The real module cannot be made to trap on purpose, so a
// stand-in with the same exports, whose `rotlang_check` traps, is bound by the same code.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import binaryen from 'binaryen';
import { bind, RotlangError } from '../lib.js';

const WAT = `(module
  (memory (export "memory") 1)
  (data (i32.const 0) "{\\"version\\":\\"stand-in\\"}")
  (func (export "rotlang_alloc") (param i32) (result i32) (i32.const 1024))
  (func (export "rotlang_dealloc") (param i32 i32))
  (func (export "rotlang_out_ptr") (result i32) (i32.const 0))
  (func (export "rotlang_out_len") (result i32) (i32.const 22))
  (func (export "rotlang_version") (result i32) (i32.const 0))
  (func (export "rotlang_check") (param i32 i32 i32 i32) (result i32) unreachable))`;

test('a trap is a RotlangError, and the next call works on a fresh instance', async () => {
  const m = binaryen.parseText(WAT);
  const bytes = m.emitBinary();
  m.dispose();
  const api = await bind(await WebAssembly.compile(bytes));
  assert.throws(() => api.check('0'), (e) => e instanceof RotlangError && e.kind === 'internal');
  assert.equal(api.version(), 'stand-in');
  assert.throws(() => api.check('0'), (e) => e instanceof RotlangError && e.kind === 'internal');
  assert.equal(api.version(), 'stand-in');
});
