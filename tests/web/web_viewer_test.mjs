// The browser viewer (web/, docs/WEB.md) in headless Chromium, through puppeteer-core, against a
// real HTTP server on loopback (python3 -m http.server, as docs/WEB.md tells users to serve it):
//
//   city      a 100-building city written by `nut city`, the page written beside it by
//             `nut-viewer --export-web`, screenshotted from a fixed camera once it has streamed
//             in, and compared with the desktop viewer's OSMesa render of the same camera
//             (`nut-viewer --headless`): at least 99.5 % of pixels within 8/255, by `nut compare`;
//             the page without occlusion culling draws the same image; and W held moves the view.
//   bytes     every sample HNI and a PNG of each layout nut's reader widens, decoded by the page
//             and read back from the atlas texture: 0 bytes differ from libpng's decoding.
//   broken    the city with corrupt, truncated and missing PNGs: the page still settles, names
//             every failed file, draws the rest, and matches the desktop render of the same city.
//   complements  a generated LoD2 district converted by `nut convert --complement-levels 3`: each
//             building's GLB complement (meshopt-compressed) drawn with its HNI, near at full
//             detail and from four times as far under lod=auto at its coarser levels, each view
//             matching the desktop viewer's render and drawing the same complement triangles.
//
// node web_viewer_test.mjs --nut NUT --viewer NUT_VIEWER --fixtures WEB_PNG_FIXTURES --source ROOT
//   --work DIR [--only city|bytes|broken|complements]
// Exit status: 0 passed, 1 failed, 77 skipped (Chromium cannot start here; the reason is printed).
// On failure the screenshots, renders and diff images stay in DIR.

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { launch, open, serve } from './browser.mjs';

const SKIP = 77;
const args = Object.fromEntries(
  process.argv.slice(2).reduce((pairs, arg, i, all) => (arg.startsWith('--') ? [...pairs, [arg.slice(2), all[i + 1]]] : pairs), []));
for (const required of ['nut', 'viewer', 'fixtures', 'source', 'work'])
  if (!args[required]) {
    console.error(`usage: node web_viewer_test.mjs --${required} ... (see the header)`);
    process.exit(2);
  }
const work = path.resolve(args.work);
const SIZE = [640, 360];

let failures = 0;
function check(condition, message) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
  if (!condition) ++failures;
}

function run(command, commandArgs) {
  const result = spawnSync(command, commandArgs, { encoding: 'utf8' });
  if (result.status !== 0)
    throw new Error(`${path.basename(command)} ${commandArgs.join(' ')}: exit ${result.status}\n${result.stderr}${result.stdout}`);
  return result.stdout;
}

// The fixed camera: the city's centre from the default direction, closer than the fitted view.
function cameraFor(cityJson) {
  const city = JSON.parse(fs.readFileSync(cityJson, 'utf8'));
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (const b of city.buildings)
    for (let a = 0; a < 3; ++a) {
      min[a] = Math.min(min[a], b.bounds_m[0][a]);
      max[a] = Math.max(max[a], b.bounds_m[1][a]);
    }
  const target = min.map((v, a) => 0.5 * (v + max[a]));
  const radius = 0.5 * Math.hypot(...max.map((v, a) => v - min[a]));
  const from = [0.55, 0.45, 1.0], norm = Math.hypot(...from);
  return { eye: target.map((t, a) => t + (1.1 * radius * from[a]) / norm), target };
}

// Screenshot of the page's canvas once settled, with `extra` URL parameters: { status, messages }.
async function screenshot(browser, name, server, camera, shot, extra = {}) {
  const query = new URLSearchParams({
    eye: camera.eye.join(','), target: camera.target.join(','), fov: '40', size: `${SIZE[0]}x${SIZE[1]}`, ground: '0', hud: '0',
    ...extra,
  });
  const messages = [];
  const page = await open(browser, `${server.url}index.html?${query}`, SIZE, messages);
  const status = await page.evaluate(() => window.nutViewer);
  check(status.state === 'settled', `${name}: the page settled (${status.state}${status.error ? ': ' + status.error : ''})`);
  await (await page.$('#view')).screenshot({ path: shot });
  await page.close();
  return { status, messages };
}

// Screenshot of the page's canvas, and the desktop viewer's render of the same camera, compared;
// `extra` URL parameters for the page and `desktopArgs` for nut-viewer. Returns the page's
// { status, messages } and the desktop's last frame (its --stats).
async function compareWithDesktop(browser, name, server, cityDir, camera, extra = {}, desktopArgs = []) {
  const shot = path.join(work, `${name}-browser.png`);
  const { status, messages } = await screenshot(browser, name, server, camera, shot, extra);
  const cameraPath = path.join(work, `${name}-camera.json`);
  fs.writeFileSync(cameraPath, JSON.stringify({ fov_deg: 40, keyframes: [camera] }));
  const desktop = path.join(work, `${name}-desktop.png`), desktopStats = path.join(work, `${name}-desktop.json`);
  run(args.viewer, [path.join(cityDir, 'city.json'), '--headless', '--size', `${SIZE[0]}x${SIZE[1]}`, '--camera-path', cameraPath,
    '--screenshot', desktop, '--stats', desktopStats, ...desktopArgs]);
  const diff = path.join(work, `${name}-diff.png`);
  const result = JSON.parse(run(args.nut, ['compare', desktop, shot, '--json', '--diff', diff]));
  check(result.differing_pct <= 0.5,
    `${name}: ${(100 - result.differing_pct).toFixed(3)} % of pixels within 8/255 of the desktop render (at least 99.5 %; ` +
      `max difference ${result.max_difference}; diff ${diff})`);
  return { status, messages, desktopFrame: JSON.parse(fs.readFileSync(desktopStats, 'utf8')).frames.at(-1) };
}

// A 100-building city with the page beside it, as a user would make one.
function makeCity(cityDir) {
  fs.rmSync(cityDir, { recursive: true, force: true });
  run(args.nut, ['city', '--count', '100', '--out', cityDir, '--seed', '5', '--layout', 'grid']);
  run(args.viewer, ['--export-web', cityDir]);
}

async function cityTest(browser) {
  const cityDir = path.join(work, 'city100');
  makeCity(cityDir);
  const server = await serve(cityDir);
  try {
    const camera = cameraFor(path.join(cityDir, 'city.json'));
    const { status, messages } = await compareWithDesktop(browser, 'city', server, cityDir, camera);
    check(status.stats.waiting === 0 && status.stats.drawn >= 20,
      `city: ${status.stats.drawn} buildings drawn, ${status.stats.culledByOcclusion} hidden, ${status.stats.loaded} of ` +
        `${status.stats.known} loaded, none waiting`);
    check(status.failures.length === 0, `city: no file failed (${status.failures.join('; ')})`);
    const errors = messages.filter((m) => m.startsWith('error') || m.startsWith('pageerror'));
    check(errors.length === 0, `city: no errors in the console (${errors.join('; ')})`);
    // Occlusion culling skips only what is hidden: the same view without it is the same image.
    const unculled = path.join(work, 'city-browser-no-occlusion.png');
    const off = await screenshot(browser, 'city, no occlusion culling', server, camera, unculled, { occlusion: '0' });
    const same = JSON.parse(run(args.nut, ['compare', path.join(work, 'city-browser.png'), unculled, '--json', '--threshold', '0']));
    check(same.differing === 0 && off.status.stats.culledByOcclusion === 0,
      `city: the same image without occlusion culling (${same.differing} pixels differ; ${status.stats.culledByOcclusion} ` +
        `buildings were skipped as hidden, ${off.status.stats.drawn} drawn without)`);
    await flyTest(browser, server, camera);
  } finally {
    server.stop();
  }
}

// The fly camera: W held moves the view forward, and the page streams and settles again.
async function flyTest(browser, server, camera) {
  const query = new URLSearchParams({
    eye: camera.eye.join(','), target: camera.target.join(','), size: `${SIZE[0]}x${SIZE[1]}`, ground: '0', hud: '0',
  });
  const page = await open(browser, `${server.url}index.html?${query}`, SIZE, []);
  const before = path.join(work, 'fly-before.png'), after = path.join(work, 'fly-after.png');
  await (await page.$('#view')).screenshot({ path: before });
  await page.keyboard.down('KeyW');
  await page.waitForFunction(() => document.body.dataset.state === 'streaming', { timeout: 60000, polling: 50 });
  await page.keyboard.up('KeyW');
  await page.waitForFunction(() => document.body.dataset.state === 'settled', { timeout: 240000, polling: 200 });
  await (await page.$('#view')).screenshot({ path: after });
  await page.close();
  const moved = JSON.parse(run(args.nut, ['compare', before, after, '--json']));
  check(moved.differing_pct > 1, `city: W moves the camera forward (${moved.differing_pct.toFixed(1)} % of pixels changed)`);
}

async function bytesTest(browser) {
  const dir = path.join(work, 'bytes');
  fs.rmSync(dir, { recursive: true, force: true });
  const samples = fs.readdirSync(path.join(args.source, 'samples', 'hni')).filter((f) => f.endsWith('.png'))
    .map((f) => path.join(args.source, 'samples', 'hni', f));
  run(args.fixtures, [dir, ...samples]);
  run(args.viewer, ['--export-web', dir]);
  for (const file of ['bytes_check.html', 'bytes_check.js'])
    fs.copyFileSync(path.join(args.source, 'tests', 'web', file), path.join(dir, file));
  const server = await serve(dir);
  try {
    const messages = [];
    const page = await open(browser, `${server.url}bytes_check.html`, SIZE, messages);
    const result = await page.evaluate(() => window.bytesCheck);
    await page.close();
    check(!result.error, `bytes: the page ran (${result.error ?? 'ok'})`);
    for (const f of result.files ?? [])
      check(!f.error && f.decoded === 0 && f.uploaded === 0,
        `bytes: ${f.name} ${f.width}x${f.height}: ${f.error ?? `${f.decoded} bytes differ decoded, ${f.uploaded} after the texture`}`);
    check((result.files ?? []).length === samples.length + 11, `bytes: ${(result.files ?? []).length} files checked`);
  } finally {
    server.stop();
  }
}

async function brokenTest(browser) {
  const dir = path.join(work, 'broken');
  makeCity(dir);
  const city = JSON.parse(fs.readFileSync(path.join(dir, 'city.json'), 'utf8'));
  // Spread over the city, so that some are in view: two missing, two truncated, one with a byte
  // of its image data flipped (a CRC mismatch), one that is not a PNG at all.
  const pick = (k) => city.buildings[Math.floor((k * city.buildings.length) / 6 + 3)];
  const damaged = [0, 1, 2, 3, 4, 5].map(pick);
  fs.rmSync(path.join(dir, damaged[0].hni));
  fs.rmSync(path.join(dir, damaged[1].hni));
  for (const b of [damaged[2], damaged[3]]) {
    const file = path.join(dir, b.hni);
    fs.truncateSync(file, Math.floor(fs.statSync(file).size / 2));
  }
  const flipped = fs.readFileSync(path.join(dir, damaged[4].hni));
  flipped[flipped.length - 20] ^= 0xff;
  fs.writeFileSync(path.join(dir, damaged[4].hni), flipped);
  fs.writeFileSync(path.join(dir, damaged[5].hni), 'this is not a PNG\n');
  const server = await serve(dir);
  try {
    const camera = cameraFor(path.join(dir, 'city.json'));
    // The whole city in view, so that every damaged file is requested.
    camera.eye = camera.eye.map((e, a) => camera.target[a] + 2.2 * (e - camera.target[a]));
    const { status } = await compareWithDesktop(browser, 'broken', server, dir, camera);
    check(status.stats.failed === damaged.length && status.stats.loaded === city.buildings.length - damaged.length,
      `broken: ${status.stats.failed} failed, ${status.stats.loaded} loaded of ${city.buildings.length}`);
    for (const b of damaged)
      check(status.failures.some((f) => f.startsWith(`${b.name}: `)), `broken: the page reports ${b.name} (${status.failures.find((f) => f.startsWith(`${b.name}: `)) ?? 'not reported'})`);
  } finally {
    server.stop();
  }
}

async function complementsTest(browser) {
  const dir = path.join(work, 'district');
  fs.rmSync(dir, { recursive: true, force: true });
  run(args.nut, ['convert', path.join(args.source, 'tests', 'data', 'lod2_district_seed1.obj'), '-o', `${dir}/`, '--quiet',
    '--png-effort', 'small', '--complement-levels', '3']);
  run(args.viewer, ['--export-web', dir]);
  const city = JSON.parse(fs.readFileSync(path.join(dir, 'city.json'), 'utf8'));
  const withLevels = city.buildings.filter((b) => (b.complement_levels ?? []).length > 0).length;
  check(withLevels >= 3, `complements: ${withLevels} complements have coarser levels`);
  const server = await serve(dir);
  try {
    // Occlusion culling off on both sides, so that the triangle counts cover the same buildings.
    const near = cameraFor(path.join(dir, 'city.json'));
    const far = { ...near, eye: near.eye.map((e, a) => near.target[a] + 4 * (e - near.target[a])) };
    let farTriangles = 0, nearTriangles = 0, nearLoaded = 0;
    for (const [name, camera, lod] of [['complements-near', near, 'off'], ['complements-far', far, 'auto']]) {
      const { status, messages, desktopFrame } = await compareWithDesktop(browser, name, server, dir, camera,
        { occlusion: '0', lod: lod === 'auto' ? 'auto' : '0' }, ['--no-occlusion-culling', '--lod', lod]);
      check(status.failures.length === 0, `${name}: no file failed (${status.failures.join('; ')})`);
      const errors = messages.filter((m) => m.startsWith('error') || m.startsWith('pageerror'));
      check(errors.length === 0, `${name}: no errors in the console (${errors.join('; ')})`);
      check(status.stats.complementTriangles === desktopFrame.complement_triangles,
        `${name}: ${status.stats.complementTriangles} complement triangles drawn, the desktop ${desktopFrame.complement_triangles}`);
      if (lod === 'auto') farTriangles = status.stats.complementTriangles;
      else [nearTriangles, nearLoaded] = [status.stats.complementTriangles, status.stats.loaded];
    }
    check(farTriangles > 0 && farTriangles < nearTriangles, `complements: far at coarser levels (${farTriangles} triangles, near ${nearTriangles})`);
    // A truncated complement and one that is not a GLB fail their buildings, each named with its
    // file; the rest still draws and the page settles.
    const damaged = city.buildings.filter((b) => b.complement).slice(0, 2);
    const truncated = path.join(dir, damaged[0].complement);
    fs.truncateSync(truncated, Math.floor(fs.statSync(truncated).size / 2));
    fs.writeFileSync(path.join(dir, damaged[1].complement), 'this is not a GLB\n');
    const { status } = await screenshot(browser, 'complements-broken', server, near, path.join(work, 'complements-broken.png'),
      { occlusion: '0', lod: '0' });
    for (const b of damaged) {
      const reported = status.failures.find((f) => f.startsWith(`${b.name}: ${b.complement}: `));
      check(reported !== undefined, `complements-broken: the page reports ${b.complement} (${reported ?? status.failures.join('; ')})`);
    }
    check(status.failures.length === 2 && status.stats.loaded === nearLoaded - 2,
      `complements-broken: ${status.failures.length} failed, ${status.stats.loaded} loaded (${nearLoaded} before)`);
  } finally {
    server.stop();
  }
}

fs.mkdirSync(work, { recursive: true });
const { browser, skip } = await launch(args.source);
if (skip) {
  console.log(`SKIP ${skip}`);
  process.exit(SKIP);
}
try {
  const only = args.only;
  if (!only || only === 'city') await cityTest(browser);
  if (!only || only === 'broken') await brokenTest(browser);
  if (!only || only === 'bytes') await bytesTest(browser);
  if (!only || only === 'complements') await complementsTest(browser);
} catch (error) {
  console.log(`FAIL ${error.message}`);
  ++failures;
} finally {
  await browser.close();
}
console.log(failures ? `${failures} check(s) failed; files in ${work}` : 'all checks passed');
process.exit(failures ? 1 : 0);
