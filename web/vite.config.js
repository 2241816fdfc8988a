// The playground is a static site: `vite build` writes web/dist, which any static file
// server hosts (python3 -m http.server -d web/dist). Relative asset paths (`base: './'`)
// so it works under any sub-path; nothing is fetched from another host.
import { defineConfig } from 'vite';

export default defineConfig({
  base: './',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    // Top-level await (the rotlang package loads its wasm with it).
    target: 'es2022',
    // Keep rotlang.wasm a file of its own (streamed, cached), never a data: URL.
    assetsInlineLimit: 0,
    // three.js (the part's 3D view, ~550 KB) is its own chunk, loaded only when a mesh is
    // opened: not a cost of the page's first load.
    chunkSizeWarningLimit: 600,
  },
  worker: { format: 'es' },
});
