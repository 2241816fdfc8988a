// A minimal LSP client for the grammar test: asks rotlang-lsp (ROTLANG_LSP, else
// `rotlang-lsp` on PATH) for the semantic tokens of a document. Those come from the
// library's parser, so they say what every part of a template is; the TextMate grammar
// must agree with them.
'use strict';

const { spawn } = require('node:child_process');

class Client {
  constructor(command = process.env.ROTLANG_LSP || 'rotlang-lsp') {
    this.child = spawn(command, [], { stdio: ['pipe', 'pipe', 'inherit'] });
    this.buffer = Buffer.alloc(0);
    this.pending = new Map();
    this.nextId = 1;
    this.child.stdout.on('data', (chunk) => this.receive(chunk));
    this.exited = new Promise((resolve) => this.child.on('exit', resolve));
  }

  receive(chunk) {
    this.buffer = Buffer.concat([this.buffer, chunk]);
    for (;;) {
      const headerEnd = this.buffer.indexOf('\r\n\r\n');
      if (headerEnd < 0) return;
      const length = Number(/Content-Length: (\d+)/i.exec(this.buffer.subarray(0, headerEnd).toString())[1]);
      if (this.buffer.length < headerEnd + 4 + length) return;
      const body = this.buffer.subarray(headerEnd + 4, headerEnd + 4 + length).toString('utf8');
      this.buffer = this.buffer.subarray(headerEnd + 4 + length);
      const message = JSON.parse(body);
      if (message.id !== undefined && message.method === undefined && this.pending.has(message.id)) {
        this.pending.get(message.id)(message);
        this.pending.delete(message.id);
      } else if (message.id !== undefined && message.method !== undefined) {
        this.send({ jsonrpc: '2.0', id: message.id, result: null });
      }
    }
  }

  send(message) {
    const body = Buffer.from(JSON.stringify(message), 'utf8');
    this.child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
    this.child.stdin.write(body);
  }

  request(method, params) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`${method}: no answer in 20 s`)), 20000);
      this.pending.set(id, (m) => {
        clearTimeout(timer);
        if (m.error) reject(new Error(`${method}: ${m.error.message}`));
        else resolve(m.result);
      });
      this.send({ jsonrpc: '2.0', id, method, params });
    });
  }

  notify(method, params) {
    this.send({ jsonrpc: '2.0', method, params });
  }

  async initialize() {
    // UTF-16 columns, as JavaScript strings count.
    const init = await this.request('initialize', { processId: null, rootUri: null, capabilities: {} });
    this.notify('initialized', {});
    const legend = init.capabilities.semanticTokensProvider.legend;
    this.types = legend.tokenTypes;
    this.modifiers = legend.tokenModifiers;
  }

  /** The tokens of a `.rot` text: {line, start, length, type, modifiers[]}. */
  async tokens(uri, text) {
    this.notify('textDocument/didOpen', { textDocument: { uri, languageId: 'rotlang', version: 1, text } });
    const result = await this.request('textDocument/semanticTokens/full', { textDocument: { uri } });
    this.notify('textDocument/didClose', { textDocument: { uri } });
    const out = [];
    let line = 0;
    let start = 0;
    const d = result ? result.data : [];
    for (let i = 0; i < d.length; i += 5) {
      line += d[i];
      start = d[i] === 0 ? start + d[i + 1] : d[i + 1];
      const modifiers = this.modifiers.filter((_, bit) => d[i + 4] & (1 << bit));
      out.push({ line, start, length: d[i + 2], type: this.types[d[i + 3]], modifiers });
    }
    return out;
  }

  async close() {
    await this.request('shutdown', null);
    this.notify('exit', null);
    await this.exited;
  }
}

module.exports = { Client };
