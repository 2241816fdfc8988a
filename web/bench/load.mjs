// How long the playground takes to load and show its first analysis in Chromium (built
// site, web/dist, served from 127.0.0.1): with no link, with a share link whose template
// is over the cap (70,000 characters) and with a 1 MB one, which the page refuses before
// it makes the editor. A benchmark, not a test: the times depend on the machine and its
// load. `npm run build` first, then `node bench/load.mjs [RUNS]` here.
import { launch, serve } from '../test/harness.js';

const runs = Number(process.argv[2] ?? 5);
const server = await serve();
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await launch();
const cases = [
  ['no link', ''],
  ['link, 70,000 characters', `#t=${encodeURIComponent('+1, '.repeat(17_500))}`],
  ['link, 1 MB', `#t=${encodeURIComponent('+10L25%, '.repeat(120_000))}`],
];
for (const [name, hash] of cases) {
  const times = [];
  for (let i = 0; i < runs; i++) {
    const page = await browser.context.newPage();
    const start = performance.now();
    await page.goto(base + hash);
    await page.waitForFunction(() => window.rotlangPlayground?.analysis() && window.rotlangPlayground.idle());
    times.push(performance.now() - start);
    await page.close();
  }
  times.sort((a, b) => a - b);
  console.log(`${name.padEnd(26)} median ${times[times.length >> 1].toFixed(0)} ms, fastest ${times[0].toFixed(0)} ms (${runs} loads)`);
}
await browser.cleanup();
server.close();
