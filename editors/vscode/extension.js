// The rotlang extension: starts rotlang-lsp for .rot files and OrcaSlicer JSON profiles.
// Everything the user sees (diagnostics, hover, inlay hints, completion, formatting,
// semantic tokens) comes from the server; this file only starts it and passes settings.
'use strict';

const vscode = require('vscode');
const { LanguageClient, TransportKind } = require('vscode-languageclient/node');

let client;

/** The server command: `rotlang.server.path`, else `rotlang-lsp` from PATH. */
function serverCommand() {
  const configured = vscode.workspace.getConfiguration('rotlang').get('server.path');
  return typeof configured === 'string' && configured.trim() !== '' ? configured.trim() : 'rotlang-lsp';
}

async function start(context) {
  const command = serverCommand();
  const run = { command, transport: TransportKind.stdio };
  client = new LanguageClient(
    'rotlang',
    'rotlang',
    { run, debug: run },
    {
      // .rot files, and JSON profiles: the server reads the template keys of any JSON file
      // and leaves the rest alone, so every JSON document is offered to it.
      documentSelector: [
        { language: 'rotlang' },
        { language: 'json' },
        { language: 'jsonc' },
        { language: 'ini', pattern: '**/*.ini' },
      ],
      // The `rotlang` section is pushed on every change (the server also pulls it).
      synchronize: { configurationSection: 'rotlang' },
      initializationOptions: { rotlang: vscode.workspace.getConfiguration('rotlang') },
    },
  );
  try {
    await client.start();
  } catch (error) {
    const choice = await vscode.window.showErrorMessage(
      `rotlang: could not start \`${command}\` (${error.message || error}). ` +
        'Install it with `cargo install --locked --path lsp` from the rotlang repository, ' +
        'or set `rotlang.server.path`.',
      'Open Settings',
    );
    if (choice === 'Open Settings') {
      vscode.commands.executeCommand('workbench.action.openSettings', 'rotlang.server.path');
    }
    client = undefined;
  }
}

async function activate(context) {
  await start(context);
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      // A new server path needs a new server; other settings reach the running one.
      if (event.affectsConfiguration('rotlang.server.path')) {
        if (client) await client.stop();
        await start(context);
      }
    }),
    vscode.commands.registerCommand('rotlang.restartServer', async () => {
      if (client) await client.stop();
      await start(context);
    }),
  );
}

async function deactivate() {
  if (client) await client.stop();
}

module.exports = { activate, deactivate };
