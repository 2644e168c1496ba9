// main.js — the browser viewer's page: reads the URL parameters, the city manifest and the
// generated programs, and runs the frame loop with the fly camera, the HUD and the progress bar.
//
// URL parameters (docs/WEB.md): city (manifest URL, default city.json), eye, target (x,y,z in
// metres), fov (vertical, degrees), size (WxH: a fixed canvas, for screenshots), lookup
// (exact | heuristic), lod (pixels, or auto), heat (1: iteration heat-map), iterations, ground
// (0: none), proxies (0: none), hud (0: no overlays), summary (pixels), budget (MiB of atlas
// pages), frustum (0: no frustum culling), occlusion (0: no occlusion culling), order (manifest:
// no front-to-back order).
//
// For tests and scripts, window.nutViewer holds { state: 'loading' | 'streaming' | 'settled' |
// 'error', stats, failures, error }, and <body data-state> follows state.

import { parseCity, manifestBounds } from './city.js';
import { depthRange, fitCamera, length, sub } from './camera.js';
import { CityRenderer, DEFAULT_CAST, DEFAULT_OPTIONS } from './city_renderer.js';
import { FlyCamera } from './fly_camera.js';

const status = { state: 'loading', stats: null, failures: [], error: null };
window.nutViewer = status;

function setState(state) {
  status.state = state;
  document.body.dataset.state = state;
}

function fail(message) {
  status.error = message;
  setState('error');
  const box = document.getElementById('error');
  box.textContent = message;
  box.hidden = false;
  console.error(message);
}

function vectorParam(params, name) {
  if (!params.has(name)) return null;
  const v = params.get(name).split(',').map(Number);
  if (v.length !== 3 || !v.every(Number.isFinite)) throw new Error(`URL parameter ${name}=${params.get(name)}: expected x,y,z in metres`);
  return v;
}

function numberParam(params, name, fallback, min = -Infinity) {
  if (!params.has(name)) return fallback;
  const v = Number(params.get(name));
  if (!Number.isFinite(v) || v < min) throw new Error(`URL parameter ${name}=${params.get(name)}: expected a number of at least ${min}`);
  return v;
}

const megabytes = (bytes) => (bytes / (1 << 20)).toFixed(1);

async function start() {
  const params = new URLSearchParams(location.search);
  const cityUrl = new URL(params.get('city') ?? 'city.json', location.href);
  let generated;
  try {
    generated = await import('./generated.js');
  } catch (error) {
    throw new Error(`js/generated.js: ${error.message} (write the page with nut-viewer --export-web DIR)`);
  }

  const response = await fetch(cityUrl).catch((error) => {
    throw new Error(`${cityUrl}: ${error.message}`);
  });
  if (!response.ok) throw new Error(`${cityUrl}: HTTP ${response.status} ${response.statusText}`.trimEnd());
  const city = parseCity(await response.text(), cityUrl.pathname);
  if (city.buildings.length === 0) throw new Error(`${cityUrl.pathname}: no buildings`);
  document.title = `${city.name || 'city'} — nut`;

  // hud=0: the canvas alone, for screenshots.
  if (params.get('hud') === '0') document.body.classList.add('bare');
  const canvas = document.getElementById('view');
  const size = params.get('size');
  if (size) {
    const m = /^(\d+)x(\d+)$/.exec(size);
    if (!m || +m[1] < 1 || +m[2] < 1 || +m[1] > 16384 || +m[2] > 16384) throw new Error(`URL parameter size=${size}: expected WxH`);
    canvas.width = +m[1];
    canvas.height = +m[2];
    canvas.classList.add('fixed');
    canvas.style.width = `${canvas.width}px`;
    canvas.style.height = `${canvas.height}px`;
  }
  // Without ?size, the drawing buffer follows the window; returns whether it changed.
  const followWindow = () => {
    if (size) return false;
    const w = Math.round(canvas.clientWidth * devicePixelRatio), h = Math.round(canvas.clientHeight * devicePixelRatio);
    if (w <= 0 || h <= 0 || (canvas.width === w && canvas.height === h)) return false;
    canvas.width = w;
    canvas.height = h;
    return true;
  };
  followWindow(); // before the camera is fitted to the canvas's aspect
  // No alpha in the drawing buffer: the caster leaves alpha 0 where it drew (hni_raycast.frag), and
  // the page must not show through. No multisampling: the image is the desktop viewer's.
  const gl = canvas.getContext('webgl2', { alpha: false, antialias: false, depth: true, premultipliedAlpha: false });
  if (!gl) throw new Error('this browser has no WebGL2');

  const box = manifestBounds(city);
  const fov = numberParam(params, 'fov', 40, 1);
  const fitted = fitCamera(box, canvas.width, canvas.height, fov);
  const fixedCamera = { eye: vectorParam(params, 'eye') ?? fitted.eye, target: vectorParam(params, 'target') ?? fitted.target };
  const options = {
    ground: params.get('ground') !== '0',
    proxies: params.get('proxies') !== '0',
    frustumCulling: params.get('frustum') !== '0',
    occlusionCulling: params.get('occlusion') !== '0',
    frontToBack: params.get('order') !== 'manifest',
    summaryBelowPx: numberParam(params, 'summary', 0, 0),
    maxAtlasPages: Math.max(1, Math.floor(numberParam(params, 'budget', 256, 1) / ((4 * DEFAULT_OPTIONS.atlasPageSize ** 2) / (1 << 20)))),
  };
  const cast = {
    ...DEFAULT_CAST,
    exactLookup: (params.get('lookup') ?? 'exact') !== 'heuristic',
    lodAuto: params.get('lod') === 'auto',
    lodPx: params.get('lod') === 'auto' ? 0 : numberParam(params, 'lod', 0, 0),
    heatMap: params.get('heat') === '1',
    maxIterations: numberParam(params, 'iterations', generated.constants.maxIterations, 1),
  };
  const renderer = new CityRenderer(gl, generated, city, new URL('.', cityUrl), options);
  const fly = new FlyCamera(canvas, { ...fixedCamera }, Math.max(5, 0.05 * length(sub(box.max, box.min))));
  let flown = false; // the fixed camera until the user moves: its view is the desktop viewer's

  const hud = document.getElementById('hud');
  const progress = document.getElementById('progress');
  const failuresBox = document.getElementById('failures');
  // When the last frames were drawn: their spacing is the frame time the user sees, which the
  // time to issue the GL calls is not (the GPU works after they return).
  const drawnAt = [];
  let last = performance.now(), idle = false;
  setState('streaming');

  const frame = (now) => {
    const seconds = Math.min(0.1, (now - last) / 1000);
    last = now;
    const moved = fly.update(seconds);
    flown ||= moved;
    const changed = followWindow() || moved;
    // A settled, unchanged view is not drawn again.
    if (status.state === 'settled' && !changed) {
      idle = true;
      return requestAnimationFrame(frame);
    }
    const eye = flown ? fly.eye : fixedCamera.eye;
    const camera = {
      eye, target: flown ? fly.target() : fixedCamera.target, up: [0, 1, 0], fovYDeg: fov,
      width: canvas.width, height: canvas.height, ...depthRange(eye, box),
    };
    gl.viewport(0, 0, canvas.width, canvas.height);
    const [r, g, b] = generated.constants.background;
    gl.clearColor(r / 255, g / 255, b / 255, 1);
    gl.clearDepth(1);
    gl.depthMask(true);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    let stats;
    try {
      stats = renderer.drawFrame(camera, cast);
    } catch (error) {
      return fail(error.message);
    }
    if (idle) drawnAt.length = 0; // the pause is not a frame
    idle = false;
    drawnAt.push(now);
    if (drawnAt.length > 30) drawnAt.shift();
    stats.frameMs = drawnAt.length > 1 ? (drawnAt.at(-1) - drawnAt[0]) / (drawnAt.length - 1) : null;
    status.stats = stats;
    status.failures = renderer.failures;
    hud.textContent =
      (stats.frameMs ? `${(1000 / stats.frameMs).toFixed(1)} fps · ${stats.frameMs.toFixed(0)} ms a frame\n` : 'fps: measuring\n') +
      `buildings ${stats.loaded} loaded / ${stats.known} · ${stats.drawn} drawn · culled ${stats.culledByFrustum} by the frustum, ` +
      `${stats.culledByOcclusion} hidden` + (stats.complementTriangles ? ` · ${stats.complementTriangles} mesh triangles` : '') + '\n' +
      `${megabytes(stats.bytesStreamed)} MB streamed · atlas ${megabytes(stats.atlasBytes)} MB` +
      (stats.failed ? ` · ${stats.failed} failed` : '') + (stats.overBudget ? ' · over budget' : '');
    const done = stats.drawn + stats.asSummary;
    progress.hidden = stats.settled;
    progress.value = done / Math.max(1, done + stats.waiting);
    if (renderer.failures.length) {
      failuresBox.hidden = false;
      failuresBox.textContent = `${renderer.failures.length} file(s) failed:\n` + renderer.failures.slice(0, 8).join('\n') +
        (renderer.failures.length > 8 ? '\n…' : '');
    }
    if (stats.newFailures.length) stats.newFailures.forEach((f) => console.warn(f));
    setState(stats.settled ? 'settled' : 'streaming');
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

start().catch((error) => fail(error.message));
