// Colours for the template's parts: numbers, joint signs, solid signs, units, runtime
// marks and separators. A token-level tokenizer only; the grammar (in the wasm) decides
// what is valid and reports it as diagnostics.
import { StreamLanguage, HighlightStyle, syntaxHighlighting } from '@codemirror/language';
import { tags } from '@lezer/highlight';

const template = StreamLanguage.define({
  name: 'rotlang',
  token(stream) {
    if (stream.eatSpace()) return null;
    if (stream.eat(',')) return 'punctuation';
    if (stream.match(/^[+-]?(\d+(\.\d*)?|\.\d+)(:\d+(\.\d*)?)?/)) return 'number';
    if (stream.match(/^(mm|cm|m|%|'|")/)) return 'unit';
    if (stream.match(/^[/NnZz$LlUuQq~^|#]/)) return 'operator';
    if (stream.match(/^[DSOMR]/)) return 'keyword';
    if (stream.match(/^[BT]/)) return 'atom';
    if (stream.match(/^[*!-]/)) return 'meta';
    stream.next();
    return 'invalid';
  },
  tokenTable: { unit: tags.unit },
});

const style = HighlightStyle.define([
  { tag: tags.number, color: '#1a5fb4' },
  { tag: tags.operator, color: '#a51d2d', fontWeight: '600' },
  { tag: tags.keyword, color: '#613583', fontWeight: '600' },
  { tag: tags.unit, color: '#26a269' },
  { tag: tags.atom, color: '#c64600' },
  { tag: tags.meta, color: '#986a44' },
  { tag: tags.punctuation, color: '#77767b' },
]);

export const templateLanguage = [template, syntaxHighlighting(style)];
