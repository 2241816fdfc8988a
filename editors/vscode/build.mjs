// Bundles the client (extension.js and vscode-languageclient) into dist/extension.js with
// esbuild, so the .vsix carries one file instead of node_modules; copies the repository's
// LICENSE beside the manifest for vsce. Run by `vsce package` (vscode:prepublish).
import { build } from 'esbuild';
import { copyFileSync } from 'node:fs';

await build({
  entryPoints: ['extension.js'],
  bundle: true,
  outfile: 'dist/extension.js',
  platform: 'node',
  target: 'node18',
  format: 'cjs',
  external: ['vscode'],
  minify: true,
  sourcemap: false,
  logLevel: 'warning',
});
copyFileSync('../../LICENSE', 'LICENSE');
