// node scripts/web-screenshot.mjs ROOT CITY_DIR OUT.png: the page of CITY_DIR (written by
// nut-viewer --export-web) served on loopback and screenshotted at 960x540 with its HUD, from a
// street-corner camera, once everything in view has streamed in (scripts/web-screenshot.sh).
import fs from 'node:fs';
import path from 'node:path';

import { launch, open, serve } from '../tests/web/browser.mjs';

const [root, cityDir, out] = process.argv.slice(2);
const city = JSON.parse(fs.readFileSync(path.join(cityDir, 'city.json'), 'utf8'));
const min = [0, 1, 2].map((a) => Math.min(...city.buildings.map((b) => b.bounds_m[0][a])));
const max = [0, 1, 2].map((a) => Math.max(...city.buildings.map((b) => b.bounds_m[1][a])));
// Above a corner of the city, looking across it.
const eye = [min[0] - 20, 45, max[2] + 20];
const target = [0.5 * (min[0] + max[0]), 0, 0.5 * (min[2] + max[2])];
const { browser, skip } = await launch(root);
if (skip) throw new Error(skip);
const server = await serve(cityDir);
try {
  const messages = [];
  const query = new URLSearchParams({ eye: eye.join(','), target: target.join(','), fov: '50', size: '960x540' });
  const page = await open(browser, `${server.url}index.html?${query}`, [960, 540], messages);
  const status = await page.evaluate(() => window.nutViewer);
  if (status.state !== 'settled') throw new Error(`the page did not settle: ${status.error ?? status.state}`);
  await (await page.$('#view')).screenshot({ path: out });
  console.error(`web-screenshot: ${out}: ${status.stats.drawn} buildings drawn, ${status.stats.loaded} loaded`);
} finally {
  server.stop();
  await browser.close();
}
