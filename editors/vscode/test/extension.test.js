// The extension's glue, with VS Code and the language client replaced by recording fakes
// (VS Code itself cannot run here): which command it starts, for which documents, with
// which settings, what the user is told when the server is missing, and that changing
// `rotlang.server.path` restarts the server.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const Module = require('node:module');

function fakes({ serverPath, startFails }) {
  const log = { clients: [], errors: [], commands: {}, configListeners: [] };
  let path = serverPath;
  const vscode = {
    workspace: {
      getConfiguration: (section) => ({
        section,
        get: (key) => (section === 'rotlang' && key === 'server.path' ? path : undefined),
      }),
      onDidChangeConfiguration: (listener) => {
        log.configListeners.push(listener);
        return { dispose() {} };
      },
    },
    window: {
      showErrorMessage: async (message, ...actions) => {
        log.errors.push({ message, actions });
        return undefined;
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
      Object.assign(this, { id, name, serverOptions, clientOptions, running: false });
      log.clients.push(this);
    }
    async start() {
      if (startFails) throw new Error(`spawn ${this.serverOptions.run.command} ENOENT`);
      this.running = true;
    }
    async stop() {
      this.running = false;
    }
  }
  const languageclient = { LanguageClient, TransportKind: { stdio: 0 } };
  return { vscode, languageclient, log, setPath: (p) => { path = p; } };
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
  const f = fakes({ serverPath: '' });
  const ext = loadExtension(f);
  const context = { subscriptions: [] };
  await ext.activate(context);
  assert.strictEqual(f.log.clients.length, 1);
  const client = f.log.clients[0];
  assert.strictEqual(client.serverOptions.run.command, 'rotlang-lsp');
  assert.ok(client.running);
  const languages = client.clientOptions.documentSelector.map((s) => s.language);
  assert.deepStrictEqual(languages, ['rotlang', 'json', 'jsonc', 'ini']);
  assert.strictEqual(client.clientOptions.synchronize.configurationSection, 'rotlang');
  assert.strictEqual(client.clientOptions.initializationOptions.rotlang.section, 'rotlang');
  assert.ok(f.log.commands['rotlang.restartServer']);
  await ext.deactivate();
  assert.ok(!client.running);
});

test('a configured path is used, and changing it restarts the server', async () => {
  const f = fakes({ serverPath: ' /opt/rotlang/bin/rotlang-lsp ' });
  const ext = loadExtension(f);
  await ext.activate({ subscriptions: [] });
  assert.strictEqual(f.log.clients[0].serverOptions.run.command, '/opt/rotlang/bin/rotlang-lsp');
  f.setPath('/usr/local/bin/rotlang-lsp');
  // Another setting: the running server gets it through the client, no restart.
  await f.log.configListeners[0]({ affectsConfiguration: (s) => s === 'rotlang.layers' });
  assert.strictEqual(f.log.clients.length, 1);
  await f.log.configListeners[0]({ affectsConfiguration: (s) => s === 'rotlang.server.path' });
  assert.strictEqual(f.log.clients.length, 2);
  assert.ok(!f.log.clients[0].running);
  assert.strictEqual(f.log.clients[1].serverOptions.run.command, '/usr/local/bin/rotlang-lsp');
  assert.ok(f.log.clients[1].running);
});

test('a missing server is explained, with how to install it', async () => {
  const f = fakes({ serverPath: undefined, startFails: true });
  const ext = loadExtension(f);
  await ext.activate({ subscriptions: [] });
  assert.strictEqual(f.log.errors.length, 1);
  const { message, actions } = f.log.errors[0];
  assert.match(message, /could not start `rotlang-lsp`/);
  assert.match(message, /cargo install --locked --path lsp/);
  assert.match(message, /rotlang\.server\.path/);
  assert.deepStrictEqual(actions, ['Open Settings']);
  await ext.deactivate();
});
