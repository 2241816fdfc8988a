// The browser test harness: serves web/dist on 127.0.0.1 (a static server, as a user's
// would be) and drives Debian's Chromium through playwright-core.
import { createServer } from 'node:http';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, extname, join, normalize, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
export const dist = resolve(here, '../dist');
/** The npm package, served unbundled under /pkg/ to check it works with no bundler. */
const pkg = resolve(here, '../../bindings/js');
const PKG_PAGE = `<!doctype html><meta charset="utf-8"><title>rotlang, no bundler</title>
<script type="module">
  import { check, expand, format } from './rotlang.js';
  window.result = {
    message: check('+30X5').diagnostics[0].message,
    formatted: format('0 90'),
    angles: [...expand('0, 90', { model: { layers: 4 } }).angles],
  };
</script>`;
/** Screenshots go to target/playground/ (test artifacts, not committed). */
export const artifacts = resolve(process.env.ROTLANG_ARTIFACTS ?? resolve(here, '../../target/playground'));

const TYPES = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.css': 'text/css',
  '.wasm': 'application/wasm', '.svg': 'image/svg+xml', '.png': 'image/png', '.json': 'application/json',
};

export function serve() {
  const server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    if (path === '/pkg/') {
      res.writeHead(200, { 'content-type': TYPES['.html'] }).end(PKG_PAGE);
      return;
    }
    const root = path.startsWith('/pkg/') ? pkg : dist;
    let file = normalize(join(root, path.replace(/^\/pkg\//, '/')));
    if (!file.startsWith(root) || (root === pkg && !/\/(rotlang|lib)\.(js|wasm)$/.test(file))) {
      res.writeHead(403).end();
      return;
    }
    try {
      if (statSync(file).isDirectory()) file = join(file, 'index.html');
      const body = readFileSync(file);
      res.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' }).end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return new Promise((ok) => server.listen(0, '127.0.0.1', () => ok(server)));
}

export async function launch() {
  const profile = mkdtempSync(join(tmpdir(), 'rotlang-chromium-'));
  // A persistent context on a fresh, empty profile directory (Playwright takes the
  // --user-data-dir this way).
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1280, height: 900 },
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      // WebGL (the part's 3D view) on the CPU: with no GPU, Chromium draws WebGL through
      // SwiftShader only when told to.
      '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
    ],
  });
  // Every wait is for an event (an element, the page's idle state); this bound only says
  // when a wait has failed, and is wide enough for a machine under heavy load.
  context.setDefaultTimeout(120_000);
  mkdirSync(artifacts, { recursive: true });
  return {
    context,
    cleanup: async () => {
      await context.close();
      rmSync(profile, { recursive: true, force: true });
    },
  };
}
