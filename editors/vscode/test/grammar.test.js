// The TextMate grammar against the parser, on every corpus template: each part the
// language server's semantic tokens name (sign, angle, runtime mark, solid sign, joint,
// flip, count, unit) must carry the grammar's scope for that part, character by
// character, and the grammar must give no part scope where the parser sees none.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('node:fs');
const path = require('node:path');
const { Client } = require('./lsp.js');
const { loadGrammar, tokenize } = require('./textmate.js');

const corpus = process.env.ROTLANG_CORPUS || path.join(__dirname, '..', '..', '..', 'corpus');

/** The grammar's scope for a semantic token (by its modifier; `B`/`T` by type). */
function expectedScope(token) {
  const part = token.modifiers[0];
  if (part === 'count' && token.type === 'variable') return 'variable.language.count.rotlang';
  return {
    sign: 'keyword.operator.sign.rotlang',
    angle: 'constant.numeric.angle.rotlang',
    runtime: 'keyword.control.runtime.rotlang',
    solid: 'support.constant.solid.rotlang',
    joint: 'keyword.operator.joint.rotlang',
    flip: 'keyword.operator.flip.rotlang',
    count: 'constant.numeric.count.rotlang',
    unit: 'keyword.other.unit.rotlang',
  }[part];
}

const PART_SCOPES = new Set([
  'keyword.operator.sign.rotlang',
  'constant.numeric.angle.rotlang',
  'keyword.control.runtime.rotlang',
  'support.constant.solid.rotlang',
  'keyword.operator.joint.rotlang',
  'keyword.operator.flip.rotlang',
  'constant.numeric.count.rotlang',
  'variable.language.count.rotlang',
  'keyword.other.unit.rotlang',
]);

function templates(dir) {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) return templates(p);
    return e.name.endsWith('.rot') ? [p] : [];
  });
}

/** The part scope of each character of a line, from TextMate tokens. */
function scopesByChar(lineTokens) {
  const out = [];
  for (const t of lineTokens) {
    const part = t.scopes.find((s) => PART_SCOPES.has(s)) || null;
    for (let i = t.start; i < t.end; i++) out[i] = part;
  }
  return out;
}

test('every corpus template gets the scopes the parser gives its parts', async () => {
  const files = templates(corpus).sort();
  assert.ok(files.length >= 200, `only ${files.length} templates under ${corpus}`);
  const grammar = await loadGrammar();
  const client = new Client();
  await client.initialize();
  let checked = 0;
  const failures = [];
  try {
    for (const file of files) {
      // One trailing newline is not part of the template (corpus/README.md).
      const text = fs.readFileSync(file, 'utf8').replace(/\r?\n$/, '');
      const lines = tokenize(grammar, text).map(scopesByChar);
      const tokens = await client.tokens('file:///corpus/' + path.basename(file), text);
      const expected = lines.map(() => []);
      for (const token of tokens) {
        const scope = expectedScope(token);
        for (let i = token.start; i < token.start + token.length; i++) {
          expected[token.line][i] = scope;
          const got = lines[token.line][i];
          checked++;
          if (got !== scope) {
            failures.push(`${path.relative(corpus, file)}:${token.line + 1}:${i + 1}: ${token.modifiers[0]} ` +
              `${JSON.stringify(text.split(/\r\n|\r|\n/)[token.line].slice(token.start, token.start + token.length))}` +
              ` has ${got}, expected ${scope}`);
          }
        }
      }
      // And, in valid templates, no part scope where the parser sees no part. (Invalid
      // ones hold instructions the grammar cannot judge: `1e999`, `+30/1:0` are well
      // formed, and the parser gives no tokens for an instruction it rejects.)
      if (!path.relative(corpus, file).startsWith('valid')) continue;
      lines.forEach((line, l) => line.forEach((got, i) => {
        if (got && !expected[l][i]) {
          failures.push(`${path.relative(corpus, file)}:${l + 1}:${i + 1}: ${got} where the parser has no part`);
        }
      }));
    }
  } finally {
    await client.close();
  }
  assert.deepStrictEqual(failures, []);
  assert.ok(checked > 1000, `only ${checked} characters checked`);
});

test('the grammar reads the ambiguous signs by their place', async () => {
  const grammar = await loadGrammar();
  const scopeAt = (text, i) => scopesByChar(tokenize(grammar, text)[0])[i];
  // `#` before a count is a joint, after it a unit.
  assert.strictEqual(scopeAt('+30#5#', 3), 'keyword.operator.joint.rotlang');
  assert.strictEqual(scopeAt('+30#5#', 5), 'keyword.other.unit.rotlang');
  // `-` before the angle is a sign, before the count a flip.
  assert.strictEqual(scopeAt('-10/-5', 0), 'keyword.operator.sign.rotlang');
  assert.strictEqual(scopeAt('-10/-5', 4), 'keyword.operator.flip.rotlang');
  // `m` after a count is a unit; `M` is a solid sign; `%` after an angle belongs to it.
  assert.strictEqual(scopeAt('+1/5m', 4), 'keyword.other.unit.rotlang');
  assert.strictEqual(scopeAt('240M3', 3), 'support.constant.solid.rotlang');
  assert.strictEqual(scopeAt('25%', 2), 'constant.numeric.angle.rotlang');
  // Text that is no instruction gets no part scope (the server reports it).
  assert.strictEqual(scopeAt('+30X5', 0), null);
  // Digits are ASCII digits only (`３０` is an error).
  assert.strictEqual(scopeAt('３０', 0), null);
  // A template quoted whole: the quotes are punctuation, the inside is read as usual.
  const quote = tokenize(grammar, '"0, 90"')[0][0];
  assert.ok(quote.scopes.includes('punctuation.definition.quote.rotlang'), quote.scopes.join(' '));
  assert.strictEqual(scopeAt('"0, 90"', 0), null);
  assert.strictEqual(scopeAt('"0, 90"', 1), 'constant.numeric.angle.rotlang');
  assert.strictEqual(scopeAt('"0, 90"', 5), 'constant.numeric.angle.rotlang');
  // An inch sign after a count is a unit, not a closing quote.
  assert.strictEqual(scopeAt('+1/2"', 4), 'keyword.other.unit.rotlang');
  // Lines end at \r as well.
  assert.strictEqual(tokenize(grammar, '0\r+30').length, 2);
});
