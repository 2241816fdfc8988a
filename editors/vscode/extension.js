// The rotlang extension: starts rotlang-lsp for .rot files, .ini exports and OrcaSlicer
// JSON presets. Everything the user sees (diagnostics, hover, inlay hints, completion,
// formatting, semantic tokens) comes from the server; this file only decides which
// documents it sees, starts it, passes settings and says when it cannot start.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const vscode = require('vscode');
const { LanguageClient, RevealOutputChannelOn, TransportKind } = require('vscode-languageclient/node');

let client;
let starting; // the start under way, so that two starts never overlap
let lastFailure; // the message last shown, so that one failure is reported once

/** The server command: `rotlang.server.path`, else `rotlang-lsp` from PATH. */
function serverCommand() {
  const configured = vscode.workspace.getConfiguration('rotlang').get('server.path');
  return typeof configured === 'string' && configured.trim() !== '' ? configured.trim() : 'rotlang-lsp';
}

/**
 * The executable `command` names, looked up as the extension host will spawn it (a bare
 * name on the host's PATH, which VS Code sets from the login shell), or null. Checked
 * before the client starts: a language client that fails to spawn shows a notification of
 * its own, so a missing server would be reported twice.
 */
function resolveExecutable(command, env = process.env) {
  const executable = (file) => {
    try {
      fs.accessSync(file, fs.constants.X_OK);
      return fs.statSync(file).isFile();
    } catch {
      return false;
    }
  };
  if (command.includes('/') || command.includes('\\')) return executable(command) ? command : null;
  const exts = process.platform === 'win32' ? (env.PATHEXT || '.EXE;.CMD;.BAT').split(';') : [''];
  for (const dir of (env.PATH || '').split(path.delimiter)) {
    if (!dir) continue;
    for (const ext of exts) {
      const file = path.join(dir, command + ext);
      if (executable(file)) return file;
    }
  }
  return null;
}

const TEMPLATE_KEY = /"(?:sparse|solid)_infill_rotate_template"\s*:/;
// OrcaSlicer's own folders: its configuration (`OrcaSlicer/user/...`, `system/...`) on
// every platform, and the `resources/profiles` of its sources.
const ORCA_FOLDER = /[\\/](?:OrcaSlicer|orca-slicer)[\\/]|[\\/]resources[\\/]profiles[\\/]/i;

/**
 * Whether the server should see `document`: `.rot` files, `.ini` exports, and JSON only
 * when it is an OrcaSlicer preset (it has a rotate template key, or lives in OrcaSlicer's
 * folders). Other JSON files (package.json, settings) are never sent to it.
 */
function isRotlangDocument(document) {
  if (document.languageId === 'rotlang') return true;
  const file = document.uri.fsPath || document.uri.path || '';
  if (document.languageId === 'ini') return /\.ini$/i.test(file);
  if (document.languageId !== 'json' && document.languageId !== 'jsonc') return false;
  if (ORCA_FOLDER.test(file)) return true;
  return TEMPLATE_KEY.test(document.getText());
}

// Documents the server was told about: everything it is asked is about one of these.
const opened = new Set();
const known = (document) => opened.has(document.uri.toString());

/** Middleware that forwards a request only for documents the server was given. */
function onlyKnown() {
  const forward = (fn) => (document, ...rest) => {
    const next = rest[rest.length - 1];
    return known(document) ? next(document, ...rest.slice(0, -1)) : undefined;
  };
  const m = {
    didOpen: (document, next) => {
      if (!isRotlangDocument(document)) return Promise.resolve();
      opened.add(document.uri.toString());
      return next(document);
    },
    didChange: (event, next) => (known(event.document) ? next(event) : Promise.resolve()),
    didSave: (document, next) => (known(document) ? next(document) : Promise.resolve()),
    didClose: (document, next) => {
      if (!opened.delete(document.uri.toString())) return Promise.resolve();
      return next(document);
    },
  };
  for (const name of [
    'provideHover', 'provideCompletionItem', 'provideInlayHints', 'provideCodeActions',
    'provideDocumentFormattingEdits', 'provideDocumentRangeFormattingEdits',
    'provideDocumentSemanticTokens', 'provideDocumentSemanticTokensEdits',
    'provideDocumentRangeSemanticTokens', 'provideDocumentSymbols', 'provideFoldingRanges',
    'provideDocumentLinks', 'provideDocumentHighlights', 'provideCodeLenses', 'provideSignatureHelp',
  ]) {
    m[name] = forward(name);
  }
  return m;
}

function reportFailure(message) {
  // One failure, one notification: a restart or a settings change that fails the same
  // way says nothing new. Not awaited: the notification stays open as long as the user
  // likes, and nothing waits for it.
  if (message === lastFailure) return;
  lastFailure = message;
  vscode.window.showErrorMessage(message, 'Open Settings').then((choice) => {
    if (choice === 'Open Settings') {
      vscode.commands.executeCommand('workbench.action.openSettings', 'rotlang.server.path');
    }
  });
}

async function startNow() {
  const command = serverCommand();
  const install = 'Install it with `cargo install --locked --path lsp` from the rotlang repository, or set `rotlang.server.path`.';
  const resolved = resolveExecutable(command);
  if (!resolved) {
    reportFailure(`rotlang: could not start \`${command}\`: no such executable${command.includes('/') ? '' : ' on PATH'}. ${install}`);
    return;
  }
  const run = { command: resolved, transport: TransportKind.stdio };
  const candidate = new LanguageClient(
    'rotlang',
    'rotlang',
    { run, debug: run },
    {
      // The server reads .rot files, .ini exports and JSON presets. JSON documents are
      // offered by language and filtered by `onlyKnown` (a selector cannot look inside a
      // file): an unrelated JSON file is never sent.
      documentSelector: [
        { language: 'rotlang' },
        { language: 'json' },
        { language: 'jsonc' },
        { language: 'ini', pattern: '**/*.ini' },
      ],
      middleware: onlyKnown(),
      // The `rotlang` section is pushed on every change (the server also pulls it).
      synchronize: { configurationSection: 'rotlang' },
      initializationOptions: { rotlang: vscode.workspace.getConfiguration('rotlang') },
      // The client's own errors go to its output channel, not to notifications: a start
      // that fails is reported once, by this file, and a settings change that restarts the
      // server races the client's push of that change to the server being stopped
      // ("Sending notification workspace/didChangeConfiguration failed").
      revealOutputChannelOn: RevealOutputChannelOn.Never,
    },
  );
  try {
    await candidate.start();
    client = candidate;
    lastFailure = undefined;
  } catch (error) {
    client = undefined;
    try {
      await candidate.dispose();
    } catch {
      // A client that never started has nothing to stop.
    }
    reportFailure(`rotlang: could not start \`${command}\` (${error.message || error}). ${install}`);
  }
}

/** Stops the running server, if any (a client that failed to start is not running). */
async function stop() {
  const running = client;
  client = undefined;
  opened.clear();
  if (running && running.isRunning()) await running.stop();
}

/** (Re)starts the server; a start under way is waited for, never doubled. */
function restart() {
  const previous = starting ?? Promise.resolve();
  starting = previous.then(stop).then(startNow).finally(() => {
    if (starting === current) starting = undefined;
  });
  const current = starting;
  return current;
}

/** Starts the server when the first document it should see is opened. */
function startWhenNeeded() {
  if (client || starting) return starting;
  if (!vscode.workspace.textDocuments.some(isRotlangDocument)) return undefined;
  return restart();
}

function activate(context) {
  // Everything is registered before the server starts: a failed start (whose notification
  // may stay open) never leaves the restart command unregistered.
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration((event) => {
      // A new server path needs a new server; other settings reach the running one.
      if (event.affectsConfiguration('rotlang.server.path')) {
        lastFailure = undefined;
        restart();
      }
    }),
    vscode.commands.registerCommand('rotlang.restartServer', () => {
      lastFailure = undefined;
      return restart();
    }),
    vscode.workspace.onDidOpenTextDocument(() => startWhenNeeded()),
    { dispose: () => stop() },
  );
  // Returned for tests and other extensions; activation itself does not wait on it.
  return { started: startWhenNeeded() ?? Promise.resolve(), isRotlangDocument };
}

async function deactivate() {
  await starting;
  await stop();
}

module.exports = { activate, deactivate, isRotlangDocument, resolveExecutable };
