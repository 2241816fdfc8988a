// The template editor: CodeMirror 6 with rotlang's diagnostics (squiggles, messages,
// quick fixes), hover, completion of signs, formatting and the highlight of the
// instruction that governs a chosen layer. Everything comes from the worker's analysis.
import { EditorState, StateEffect, StateField } from '@codemirror/state';
import { EditorView, Decoration, hoverTooltip, keymap, lineNumbers, drawSelection, highlightActiveLine, tooltips } from '@codemirror/view';
import { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
import { setDiagnostics, lintKeymap } from '@codemirror/lint';
import { autocompletion, completionKeymap } from '@codemirror/autocomplete';
import { MAX_TEMPLATE } from './limits.js';
import { templateLanguage } from './highlight.js';

const setGoverning = StateEffect.define();
const governing = StateField.define({
  create: () => Decoration.none,
  update(deco, tr) {
    deco = deco.map(tr.changes);
    for (const e of tr.effects) {
      if (!e.is(setGoverning)) continue;
      const r = e.value;
      deco = r && r.to > r.from && r.to <= tr.state.doc.length
        ? Decoration.set([Decoration.mark({ class: 'cm-governing', attributes: { title: r.title ?? '' } }).range(r.from, r.to)])
        : Decoration.none;
    }
    return deco;
  },
  provide: (f) => EditorView.decorations.from(f),
});

/**
 * `host` element; `hooks`: onChange(text), onRefused(message), format(), hover(pos) →
 * DOM node or null, signs() → [{sign, kind, meaning}].
 */
export function createEditor(host, text, hooks) {
  const completeSigns = (context) => {
    const before = context.matchBefore(/[0-9.%*!#'"a-zA-Z/~^|$:-]*$/);
    const explicit = context.explicit;
    // Offer signs after an angle (or a sign), or on Ctrl-Space.
    if (!explicit && (!before || before.text === '' || !/[0-9.*!]$/.test(before.text))) return null;
    const signs = hooks.signs();
    if (!signs.length) return null;
    return {
      from: context.pos,
      options: signs.map((s) => ({ label: s.sign, type: s.kind === 'joint' ? 'function' : s.kind === 'unit' ? 'unit' : 'keyword', detail: s.kind, info: s.meaning })),
      validFor: /^$/,
    };
  };
  const state = EditorState.create({
    doc: text,
    extensions: [
      lineNumbers(),
      history(),
      // Tooltips keep below the page's header: a box that would not fit above the line
      // there (the lint's opens above) opens below it instead of covering the heading.
      tooltips({
        tooltipSpace: () => ({
          top: document.querySelector('header')?.getBoundingClientRect().bottom ?? 0,
          left: 0, right: window.innerWidth, bottom: window.innerHeight,
        }),
      }),
      drawSelection(),
      highlightActiveLine(),
      EditorView.lineWrapping,
      templateLanguage,
      governing,
      autocompletion({ override: [completeSigns], activateOnTyping: true }),
      hoverTooltip((view, pos) => {
        const dom = hooks.hover(pos);
        // Below the line: above it, the box would cover the page's heading.
        return dom ? { pos, above: false, create: () => ({ dom }) } : null;
      }, { hoverTime: 250 }),
      // Refuse an edit that would make the template larger than the playground takes.
      // An edit that does not lengthen it always passes (Backspace on a text already over
      // the cap must work: the cap is about growth).
      EditorState.transactionFilter.of((tr) => {
        if (tr.docChanged && tr.newDoc.length > MAX_TEMPLATE && tr.newDoc.length > tr.startState.doc.length) {
          hooks.onRefused(`refused: that would make the template ${tr.newDoc.length.toLocaleString('en')} characters long; the playground edits up to ${MAX_TEMPLATE.toLocaleString('en')} (real templates are a few dozen; the rotlang CLI checks any size)`);
          return [];
        }
        return tr;
      }),
      EditorView.updateListener.of((u) => {
        if (u.docChanged) hooks.onChange(u.state.doc.toString());
      }),
      keymap.of([
        { key: 'Shift-Alt-f', run: () => { hooks.format(); return true; } },
        ...completionKeymap,
        ...lintKeymap,
        ...defaultKeymap,
        ...historyKeymap,
      ]),
      EditorView.contentAttributes.of({ 'aria-label': 'Template', spellcheck: 'false', autocapitalize: 'off', autocorrect: 'off' }),
    ],
  });
  return new EditorView({ state, parent: host });
}

/** Shows rotlang's diagnostics (as `check` returns them) as squiggles with quick fixes. */
export function showDiagnostics(view, diagnostics) {
  const len = view.state.doc.length;
  const list = diagnostics.map((d) => {
    const from = Math.min(d.startUtf16, len);
    const to = Math.min(Math.max(d.endUtf16, from), len);
    const actions = [];
    if (d.fix) {
      const f = d.fix;
      actions.push({
        name: f.title,
        // Positions relative to the diagnostic, which CodeMirror maps through edits.
        apply(v, dFrom) {
          const start = dFrom + (f.startUtf16 - d.startUtf16);
          const end = start + (f.endUtf16 - f.startUtf16);
          v.dispatch({ changes: { from: start, to: end, insert: f.replacement } });
        },
      });
    }
    return {
      from,
      to,
      severity: d.severity === 'error' ? 'error' : d.severity === 'info' ? 'info' : 'warning',
      source: d.code,
      message: d.help ? `${d.message}\nhelp: ${d.help}` : d.message,
      actions,
    };
  });
  view.dispatch(setDiagnostics(view.state, list));
}

/** Highlights `range` ({from, to} in UTF-16 offsets) or clears the highlight (null). */
export function highlight(view, range) {
  view.dispatch({ effects: setGoverning.of(range) });
}

export function replaceAll(view, text) {
  view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
}
