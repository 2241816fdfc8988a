// The VS Code extension for real: the packaged .vsix installed into code-server (VS Code
// served to a browser), driven through Debian's Chromium by playwright-core, with the
// built rotlang-lsp. A `.rot` file and an OrcaSlicer preset get the language, colours,
// squiggles at the right columns, Problems entries, hover, completion, inlay hints and a
// quick fix; a missing server is reported once, and the restart command works while that
// notification is open.
//
// Environment (set by lsp/tests/vscode.rs): ROTLANG_LSP (the server), ROTLANG_VSIX (the
// package), ROTLANG_E2E_DIR (a fresh folder for code-server's data and the screenshots),
// CHROMIUM (default /usr/bin/chromium).
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
const codeServer = join(here, 'node_modules/code-server/out/node/entry.js');
const server = process.env.ROTLANG_LSP;
const vsix = process.env.ROTLANG_VSIX;
const dir = resolve(process.env.ROTLANG_E2E_DIR ?? join(here, '../../../target/vscode-e2e'));
const shots = join(dir, 'screenshots');
const data = join(dir, 'user-data');
const workspace = join(dir, 'workspace');
const machineSettings = join(data, 'Machine/settings.json');

const ROT = '+30X5, +30/50 %\n0, +10L25%\n';
// A preset as OrcaSlicer writes it (in a folder of OrcaSlicer's layout).
const PRESET_DIR = join(workspace, 'OrcaSlicer/user/default/process');
const PRESET = `{
    "from": "User",
    "inherits": "0.20mm Standard @BBL X1C",
    "name": "Fine 0.12",
    "layer_height": "0.12",
    "sparse_infill_rotate_template": "0, +45X, 90",
    "version": "2.3.0.4"
}
`;

let codeServerProcess;
let browser;
let page;
let base;

function writeMachineSettings(path) {
  // `rotlang.server.path` is machine-overridable: code-server keeps it here.
  writeFileSync(machineSettings, JSON.stringify({ 'rotlang.server.path': path }, null, 2));
}

before(async () => {
  assert.ok(server && vsix, 'ROTLANG_LSP and ROTLANG_VSIX are set');
  rmSync(dir, { recursive: true, force: true });
  for (const d of [shots, join(data, 'Machine'), join(data, 'User'), PRESET_DIR]) mkdirSync(d, { recursive: true });
  writeFileSync(join(workspace, 'demo.rot'), ROT);
  writeFileSync(join(PRESET_DIR, 'Fine 0.12.json'), PRESET);
  writeMachineSettings(server);
  // A quiet workbench: nothing opens by itself, nothing is fetched from the internet.
  writeFileSync(join(data, 'User/settings.json'), JSON.stringify({
    'workbench.startupEditor': 'none',
    'security.workspace.trust.enabled': false,
    'telemetry.telemetryLevel': 'off',
    'extensions.autoCheckUpdates': false,
    'extensions.autoUpdate': false,
    'update.mode': 'none',
    'workbench.enableExperiments': false,
    'workbench.tips.enabled': false,
    'git.enabled': false,
    'chat.disableAIFeatures': true,
    'editor.inlayHints.enabled': 'on',
    'files.autoSave': 'off',
  }, null, 2));
  const config = join(dir, 'config.yaml');
  writeFileSync(config, 'auth: none\n');
  const common = ['--config', config, '--user-data-dir', data, '--extensions-dir', join(dir, 'extensions')];
  const install = spawnSync(process.execPath, [codeServer, ...common, '--install-extension', vsix], { encoding: 'utf8' });
  assert.equal(install.status, 0, `code-server --install-extension: ${install.stdout}${install.stderr}`);
  assert.match(install.stdout, /successfully installed/);

  codeServerProcess = spawn(process.execPath, [
    codeServer, ...common, '--auth', 'none', '--bind-addr', '127.0.0.1:0', '--disable-telemetry',
    '--disable-update-check', '--disable-workspace-trust', '--disable-getting-started-override', workspace,
  ], { stdio: ['ignore', 'pipe', 'pipe'] });
  let log = '';
  base = await new Promise((ok, fail) => {
    const seen = (chunk) => {
      log += chunk;
      const m = /HTTP server listening on (http:\/\/127\.0\.0\.1:\d+\/)/.exec(log);
      if (m) ok(m[1]);
    };
    codeServerProcess.stdout.on('data', seen);
    codeServerProcess.stderr.on('data', seen);
    codeServerProcess.on('exit', (code) => fail(new Error(`code-server exited (${code}): ${log}`)));
  });
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking', '--disable-component-update'],
  });
  page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  // Every wait is for an element or a state; this bound only says when one has failed,
  // wide enough for a machine under heavy load.
  page.setDefaultTimeout(Number(process.env.ROTLANG_E2E_TIMEOUT_MS ?? 120_000));
  await page.goto(`${base}?folder=${encodeURIComponent(workspace)}`);
  await page.locator('.monaco-workbench .explorer-folders-view').waitFor();
});

after(async () => {
  await browser?.close();
  codeServerProcess?.kill();
});

const shot = (name) => page.screenshot({ path: join(shots, `${name}.png`) });

async function command(name) {
  await page.keyboard.press('F1');
  const input = page.locator('.quick-input-widget input.input');
  await input.waitFor();
  await input.fill(`>${name}`);
  await page.locator('.quick-input-list .monaco-list-row.focused', { hasText: name }).waitFor();
  await page.keyboard.press('Enter');
}

async function openFile(name) {
  await page.keyboard.press('Control+P');
  const input = page.locator('.quick-input-widget input.input');
  await input.waitFor();
  await input.fill(name);
  // The list filters as it goes: Enter once the focused row is the file.
  await page.locator('.quick-input-list .monaco-list-row.focused', { hasText: name }).waitFor();
  await page.keyboard.press('Enter');
  await page.locator(`.tab.active[aria-label^="${name}"]`).waitFor();
  await page.locator('.editor-instance .monaco-editor .view-line').first().waitFor();
}

/** The characters of the document under each error squiggle, line by line. */
function squiggled(kind = 'error') {
  return page.evaluate((kind) => {
    const editor = document.querySelector('.editor-instance .monaco-editor');
    const lines = [...editor.querySelectorAll('.view-lines .view-line')]
      .sort((a, b) => a.getBoundingClientRect().top - b.getBoundingClientRect().top);
    const out = [];
    for (const s of editor.querySelectorAll(`.squiggly-${kind}`)) {
      const sq = s.getBoundingClientRect();
      const row = s.parentElement.getBoundingClientRect();
      const line = lines.findIndex((l) => Math.abs(l.getBoundingClientRect().top - row.top) < 2);
      let chars = '';
      // Each character's box, from the text as drawn (inlay hints are drawn text too,
      // but no squiggle lies under one).
      const walker = document.createTreeWalker(lines[line], NodeFilter.SHOW_TEXT);
      for (let node = walker.nextNode(); node; node = walker.nextNode()) {
        for (let i = 0; i < node.length; i++) {
          const r = document.createRange();
          r.setStart(node, i);
          r.setEnd(node, i + 1);
          const b = r.getBoundingClientRect();
          const mid = (b.left + b.right) / 2;
          if (mid > sq.left && mid < sq.right) chars += node.data[i];
        }
      }
      out.push({ line: line + 1, chars });
    }
    return out.sort((a, b) => a.line - b.line || a.chars.localeCompare(b.chars));
  }, kind);
}

/** The Problems panel's entries (message and position). */
async function problems() {
  await command('View: Focus Problems');
  await page.locator('.markers-panel').waitFor();
  return page.locator('.markers-panel .monaco-list-row').allTextContents();
}

test('a .rot file: language, colours, squiggles, Problems, inlay hints, hover, completion, a quick fix', async () => {
  await openFile('demo.rot');
  await page.locator('#status\\.editor\\.mode', { hasText: 'Infill rotation template' }).waitFor();
  // Squiggles on `X` (unknown sign) and `%` (a unit cut off by a space), nowhere else.
  await page.waitForFunction(() => document.querySelectorAll('.editor-instance .squiggly-error').length === 2);
  assert.deepEqual(await squiggled(), [{ line: 1, chars: 'X' }, { line: 1, chars: '%' }].sort((a, b) => a.chars.localeCompare(b.chars)));
  // Colours: once the server's semantic tokens are drawn (the grammar's come first), the
  // number, the sign and the unit of `+10L25%` each in a colour of its own, none the plain
  // text's.
  const colours = await page.waitForFunction(() => {
    const lines = [...document.querySelectorAll('.editor-instance .view-lines .view-line')];
    const second = lines.sort((a, b) => a.getBoundingClientRect().top - b.getBoundingClientRect().top)[1];
    const colour = (text) => {
      const span = [...second.querySelectorAll('span > span')].find((s) => s.textContent === text);
      return span ? getComputedStyle(span).color : null;
    };
    const c = { plain: colour(',\u00a0'), number: colour('25'), sign: colour('L'), unit: colour('%') };
    return new Set(Object.values(c)).size === 4 && !Object.values(c).includes(null) && c;
  }).then((h) => h.jsonValue());
  assert.ok(colours.number !== colours.plain && colours.sign !== colours.plain && colours.unit !== colours.plain);
  // Inlay hints: the turn each instruction resolves to, drawn after it.
  await page.locator('.editor-instance .view-line', { hasText: '0°→10° over 25 layers' }).waitFor();
  await shot('rot');
  // Problems: both errors, at line 1, columns 4 and 15.
  const rows = await problems();
  const text = rows.join('\n');
  assert.match(text, /unknown sign `X`.*\[Ln 1, Col 4\]/);
  assert.match(text, /the unit `%` is cut off from its number.*\[Ln 1, Col 15\]/);
  await shot('problems');
  await command('View: Focus Active Editor Group');

  // Hover over `+10L25%` (line 2): what it does, on the model.
  const hint = page.locator('.editor-instance .view-line', { hasText: '0°→10° over 25 layers' });
  const target = hint.locator('span > span', { hasText: /^L$/ });
  await target.hover();
  const hover = page.locator('.monaco-hover:not(.hidden)', { hasText: '+10L25%' });
  await hover.waitFor();
  assert.match(await hover.textContent(), /layers/);
  await shot('hover');
  await page.keyboard.press('Escape');

  // The quick fix on `%`: cursor there, Ctrl+. and the server's fix.
  await page.keyboard.press('Control+G');
  await page.locator('.quick-input-widget input.input').fill(':1:15');
  await page.keyboard.press('Enter');
  await page.keyboard.press('Control+Period');
  const fix = page.locator('.action-widget .monaco-list-row', { hasText: 'remove the space' });
  await fix.waitFor();
  await shot('quick-fix');
  // The list takes the keyboard: down to the fix (the focused row), then Enter.
  for (let i = 0; i < 10 && !(await page.locator('.action-widget .monaco-list-row.focused', { hasText: 'remove the space' }).count()); i++) {
    await page.keyboard.press('ArrowDown');
  }
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => document.querySelectorAll('.editor-instance .squiggly-error').length === 1);
  assert.deepEqual(await squiggled(), [{ line: 1, chars: 'X' }]);

  // Completion after an angle: the signs with their meaning.
  await page.keyboard.press('Control+End');
  await page.keyboard.type('+20');
  await page.keyboard.press('Control+Space');
  const suggest = page.locator('.suggest-widget .monaco-list-row');
  await suggest.first().waitFor();
  const labels = await suggest.allTextContents();
  // The list shows its first rows (it is virtual): joint signs, each with its kind.
  assert.ok(labels.some((l) => /^\/joint sign/.test(l)), labels.join(' | '));
  assert.ok(labels.some((l) => /^Ljoint sign/.test(l)), labels.join(' | '));
  await shot('completion');
  await page.keyboard.press('Escape');
  // Saved as edited: the fix and the typed text are in the file.
  await page.keyboard.press('Control+S');
  await page.locator('.tab.active:not(.dirty)').waitFor();
  assert.equal(readFileSync(join(workspace, 'demo.rot'), 'utf8'), '+30X5, +30/50%\n0, +10L25%\n+20');
});

test('an OrcaSlicer preset: JSON, the template checked in place', async () => {
  await openFile('Fine 0.12.json');
  await page.locator('#status\\.editor\\.mode', { hasText: /^JSON/ }).waitFor();
  // `X` is no sign of the language: squiggled inside the string, line 6.
  await page.waitForFunction(() => document.querySelectorAll('.editor-instance .squiggly-error').length >= 1);
  assert.deepEqual(await squiggled(), [{ line: 6, chars: 'X' }]);
  await page.locator('.editor-instance .view-line', { hasText: '0° for 1 layer' }).waitFor();
  const rows = (await problems()).join('\n');
  const column = PRESET.split('\n')[5].indexOf('X') + 1;
  assert.match(rows, new RegExp(`\`X\`.*\\[Ln 6, Col ${column}\\]`));
  await shot('preset');
  await command('View: Focus Active Editor Group');
});

test('a missing server is reported once; restart works while the notification is open', async () => {
  await openFile('demo.rot');
  const later = join(dir, 'bin/rotlang-lsp');
  writeMachineSettings(later);
  const toast = page.locator('.notification-toast', { hasText: `could not start \`${later}\`` });
  await toast.waitFor();
  // The server was stopped: its diagnostics went with it.
  await page.waitForFunction(() => document.querySelectorAll('.editor-instance .squiggly-error').length === 0);
  // Absence takes a span of time to show: two seconds more, then every notification is
  // counted (the old client added "couldn't create connection" and a failed stop).
  await page.waitForTimeout(2000);
  await command('Notifications: Show Notifications');
  const all = page.locator('.notifications-center .notification-list-item');
  await all.first().waitFor();
  const messages = await all.allTextContents();
  const ours = messages.filter((m) => /rotlang|could not start|couldn't create connection|can't be stopped/.test(m));
  assert.equal(ours.length, 1, ours.join('\n'));
  assert.match(ours[0], /no such executable\..*cargo install --locked --path lsp/);
  await shot('missing-server');
  // The server appears where the setting points; the restart command (activation did not
  // wait on the notification) starts it.
  mkdirSync(dirname(later), { recursive: true });
  symlinkSync(server, later);
  await command('rotlang: Restart the language server');
  await page.waitForFunction(() => document.querySelectorAll('.editor-instance .squiggly-error').length === 1);
  assert.deepEqual(await squiggled(), [{ line: 1, chars: 'X' }]);
});
