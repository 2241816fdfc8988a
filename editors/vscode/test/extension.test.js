// The extension's glue, with VS Code and the language client replaced by recording fakes:
// which command it starts, for which documents, with which settings, what the user is
// told when the server is missing (once, without holding up activation), and that
// changing `rotlang.server.path` or the restart command restarts the server. The real
// thing runs in code-server: e2e/e2e.test.js.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const Module = require('node:module');

// Two executables standing for the server (the extension checks the file exists and is
// executable before it starts a client).
const bin = fs.mkdtempSync(path.join(os.tmpdir(), 'rotlang-ext-'));
const fakeServer = path.join(bin, 'rotlang-lsp');
const otherServer = path.join(bin, 'other-lsp');
for (const f of [fakeServer, otherServer]) fs.writeFileSync(f, '#!/bin/sh\n', { mode: 0o755 });
process.on('exit', () => fs.rmSync(bin, { recursive: true, force: true }));

const doc = (file, languageId, text = '') => ({
  uri: { fsPath: file, path: file, toString: () => `file://${file}` },
  languageId,
  getText: () => text,
});
const PRESET = doc('/home/u/presets/fine.json', 'json', '{"sparse_infill_rotate_template": "0, 90"}');
const PACKAGE = doc('/home/u/app/package.json', 'json', '{"name": "app"}');
const ROT = doc('/home/u/t.rot', 'rotlang', '+30');

function fakes({ serverPath, startFails, documents = [ROT], errorsStayOpen = false }) {
  const log = { clients: [], errors: [], commands: {}, configListeners: [], openListeners: [] };
  let configured = serverPath;
  const vscode = {
    workspace: {
      textDocuments: documents,
      getConfiguration: (section) => ({
        section,
        get: (key) => (section === 'rotlang' && key === 'server.path' ? configured : undefined),
      }),
      onDidChangeConfiguration: (listener) => {
        log.configListeners.push(listener);
        return { dispose() {} };
      },
      onDidOpenTextDocument: (listener) => {
        log.openListeners.push(listener);
        return { dispose() {} };
      },
    },
    window: {
      // A notification the user leaves open never resolves.
      showErrorMessage: (message, ...actions) => {
        log.errors.push({ message, actions });
        return errorsStayOpen ? new Promise(() => {}) : Promise.resolve(undefined);
      },
    },
    commands: {
      registerCommand: (name, fn) => {
        log.commands[name] = fn;
        return { dispose() {} };
      },
      executeCommand: async () => {},
    },
  };
  class LanguageClient {
    constructor(id, name, serverOptions, clientOptions) {
      Object.assign(this, { id, name, serverOptions, clientOptions, running: false, sent: [] });
      log.clients.push(this);
    }
    async start() {
      if (startFails) throw new Error(`spawn ${this.serverOptions.run.command} EACCES`);
      this.running = true;
      // As the real client does: every open document in the selector, through the
      // middleware.
      for (const d of vscode.workspace.textDocuments) {
        await this.clientOptions.middleware.didOpen(d, async (x) => { this.sent.push(x.uri.path); });
      }
    }
    isRunning() {
      return this.running;
    }
    async stop() {
      if (!this.running) throw new Error("Client is not running and can't be stopped. It's current state is: startFailed");
      this.running = false;
    }
    async dispose() {
      this.running = false;
    }
  }
  const languageclient = { LanguageClient, TransportKind: { stdio: 0 }, RevealOutputChannelOn: { Info: 1, Warn: 2, Error: 3, Never: 4 } };
  return { vscode, languageclient, log, setPath: (p) => { configured = p; } };
}

/** Load extension.js afresh with the fakes in place of its imports. */
function loadExtension(f) {
  const original = Module._load;
  Module._load = function (request, ...rest) {
    if (request === 'vscode') return f.vscode;
    if (request === 'vscode-languageclient/node') return f.languageclient;
    return original.call(this, request, ...rest);
  };
  try {
    delete require.cache[require.resolve('../extension.js')];
    return require('../extension.js');
  } finally {
    Module._load = original;
  }
}

test('starts rotlang-lsp from PATH for .rot files and profiles', async () => {
  const savedPath = process.env.PATH;
  process.env.PATH = `${bin}${path.delimiter}${savedPath}`;
  try {
    const f = fakes({ serverPath: '', documents: [ROT, PACKAGE, PRESET] });
    const ext = loadExtension(f);
    const api = ext.activate({ subscriptions: [] });
    await api.started;
    assert.strictEqual(f.log.clients.length, 1);
    const client = f.log.clients[0];
    assert.strictEqual(client.serverOptions.run.command, fakeServer, 'rotlang-lsp as found on PATH');
    assert.ok(client.running);
    const languages = client.clientOptions.documentSelector.map((s) => s.language);
    assert.deepStrictEqual(languages, ['rotlang', 'json', 'jsonc', 'ini']);
    // package.json is not an OrcaSlicer preset: never sent.
    assert.deepStrictEqual(client.sent, [ROT.uri.path, PRESET.uri.path]);
    assert.strictEqual(client.clientOptions.synchronize.configurationSection, 'rotlang');
    assert.strictEqual(client.clientOptions.revealOutputChannelOn, 4, 'no notifications of the client\'s own');
    assert.strictEqual(client.clientOptions.initializationOptions.rotlang.section, 'rotlang');
    assert.ok(f.log.commands['rotlang.restartServer']);
    // Requests about a document the server was not given are not sent.
    let asked = 0;
    const next = () => { asked++; return 'answer'; };
    assert.strictEqual(client.clientOptions.middleware.provideHover(PACKAGE, {}, {}, next), undefined);
    assert.strictEqual(client.clientOptions.middleware.provideHover(PRESET, {}, {}, next), 'answer');
    assert.strictEqual(asked, 1);
    await ext.deactivate();
    assert.ok(!client.running);
  } finally {
    process.env.PATH = savedPath;
  }
});

test('OrcaSlicer presets, .ini exports and .rot files only: not every JSON file', () => {
  const ext = loadExtension(fakes({ serverPath: fakeServer }));
  assert.ok(ext.isRotlangDocument(ROT));
  assert.ok(ext.isRotlangDocument(PRESET), 'a template key');
  assert.ok(ext.isRotlangDocument(doc('/home/u/.config/OrcaSlicer/user/default/process/p.json', 'json', '{"name": "p"}')), 'OrcaSlicer\'s folder');
  assert.ok(ext.isRotlangDocument(doc('C:\\Users\\u\\AppData\\Roaming\\OrcaSlicer\\user\\1\\filament\\f.json', 'jsonc', '{}')));
  assert.ok(ext.isRotlangDocument(doc('/tmp/export.ini', 'ini', 'layer_height = 0.2')));
  assert.ok(!ext.isRotlangDocument(PACKAGE));
  assert.ok(!ext.isRotlangDocument(doc('/home/u/.vscode/settings.json', 'jsonc', '{"a": 1}')));
  assert.ok(!ext.isRotlangDocument(doc('/home/u/a.py', 'python', 'x = 1')));
});

test('no server is started while only unrelated JSON is open; it starts with the first preset', async () => {
  const documents = [PACKAGE];
  const f = fakes({ serverPath: fakeServer, documents });
  const ext = loadExtension(f);
  await ext.activate({ subscriptions: [] }).started;
  assert.strictEqual(f.log.clients.length, 0, 'package.json starts nothing');
  documents.push(PRESET);
  await f.log.openListeners[0](PRESET);
  assert.strictEqual(f.log.clients.length, 1);
  assert.deepStrictEqual(f.log.clients[0].sent, [PRESET.uri.path]);
  await ext.deactivate();
});

test('a configured path is used, and changing it restarts the server', async () => {
  const f = fakes({ serverPath: ` ${fakeServer} ` });
  const ext = loadExtension(f);
  await ext.activate({ subscriptions: [] }).started;
  assert.strictEqual(f.log.clients[0].serverOptions.run.command, fakeServer);
  f.setPath(otherServer);
  // Another setting: the running server gets it through the client, no restart.
  await f.log.configListeners[0]({ affectsConfiguration: (s) => s === 'rotlang.layers' });
  assert.strictEqual(f.log.clients.length, 1);
  await f.log.configListeners[0]({ affectsConfiguration: (s) => s === 'rotlang.server.path' });
  await f.log.commands['rotlang.restartServer'](); // waits for the restart under way too
  assert.strictEqual(f.log.clients.length, 3);
  assert.ok(!f.log.clients[0].running);
  assert.ok(!f.log.clients[1].running, 'the restart stopped it');
  assert.strictEqual(f.log.clients[2].serverOptions.run.command, otherServer);
  assert.ok(f.log.clients[2].running);
  await ext.deactivate();
});

test('a missing server is explained once, with how to install it', async () => {
  const f = fakes({ serverPath: undefined });
  const savedPath = process.env.PATH;
  process.env.PATH = '/nonexistent';
  try {
    const ext = loadExtension(f);
    await ext.activate({ subscriptions: [] }).started;
    assert.strictEqual(f.log.errors.length, 1);
    const { message, actions } = f.log.errors[0];
    assert.match(message, /could not start `rotlang-lsp`: no such executable on PATH/);
    assert.match(message, /cargo install --locked --path lsp/);
    assert.match(message, /rotlang\.server\.path/);
    assert.deepStrictEqual(actions, ['Open Settings']);
    assert.strictEqual(f.log.clients.length, 0, 'no client (its own notification would be a second)');
    await ext.deactivate();
  } finally {
    process.env.PATH = savedPath;
  }
});

// Issue 17: activation awaited the notification, so while it was open the restart command
// did not exist; a restart after a failed start tried to stop a client that never ran.
test('an open error notification holds up nothing; restart after a failed start works', async () => {
  const f = fakes({ serverPath: fakeServer, startFails: true, errorsStayOpen: true });
  const ext = loadExtension(f);
  const api = ext.activate({ subscriptions: [] });
  assert.ok(f.log.commands['rotlang.restartServer'], 'registered at once');
  await api.started; // ends although the notification stays open
  assert.strictEqual(f.log.errors.length, 1);
  assert.match(f.log.errors[0].message, /EACCES/);
  // Restart: no "Client is not running and can't be stopped".
  await f.log.commands['rotlang.restartServer']();
  assert.strictEqual(f.log.clients.length, 2);
  assert.strictEqual(f.log.errors.length, 2, 'the restart asked for: its failure is shown');
  // A bad path: one notification, not one per attempt.
  f.setPath('/nonexistent/rotlang-lsp');
  await f.log.configListeners[0]({ affectsConfiguration: (s) => s === 'rotlang.server.path' });
  await ext.deactivate();
  assert.strictEqual(f.log.errors.length, 3);
  assert.match(f.log.errors[2].message, /`\/nonexistent\/rotlang-lsp`: no such executable\./);
});
