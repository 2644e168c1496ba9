// city_renderer.js — a city manifest streamed and drawn frame by frame in WebGL2, with the desktop
// viewer's policy (viewer/city_renderer.hpp): the buildings the camera can see are fetched nearest
// first, a bounded number at a time; decoded HNIs are uploaded into atlas pages in bounded slices
// per frame; when the pages (the memory budget) are full, the page seen least recently is emptied;
// buildings are frustum-culled, drawn front to back, one instanced draw per page; a building whose
// box was hidden in the last frame that tested it is skipped (occlusion culling); a building not
// loaded yet is drawn as its grey box, a far one as its summary box, and a file that fails to
// load or decode is reported and drawn as missing; a building's complementary mesh (GLB) is drawn
// with it, under lod=auto as the coarsest of its levels whose error spans under a pixel, each
// level fetched when a frame first wants it. The frame never waits for a file.

import { AtlasPages } from './atlas.js';
import { manifestBounds, placedBox, yawRotation } from './city.js';
import { FrameView, length, sub } from './camera.js';
import { buildProgram } from './gl_programs.js';
import { readGlb } from './glb.js';
import { GpuMesh, MESH_STRIDE, meshVertexArray } from './gpu_mesh.js';
import { decodePng, readHniRoot } from './hni_png.js';

const PROXY_GREY = [175, 175, 175];
const GROUND = [196, 198, 190];

export const DEFAULT_OPTIONS = {
  frustumCulling: true,
  // Each frame, every drawn building's box, enlarged by 1 % and 5 cm, is depth-tested against the
  // finished frame in an occlusion query; a building none of whose box passed is skipped until a
  // later query finds it visible. A building whose box holds the eye is always drawn.
  occlusionCulling: true,
  frontToBack: true,
  proxies: true,
  summaryBelowPx: 0, // a loaded building whose largest side spans fewer pixels: its summary box
  ground: true,
  maxOutstanding: 16, // fetches in flight at once
  uploadBytesPerFrame: 4 << 20, // at least one HNI a frame is uploaded
  atlasPageSize: 4096,
  maxAtlasPages: 4, // the memory budget: 4 pages of 4096^2 RGBA8 = 256 MiB
};

// Ray-casting options, as nut::RayCastOptions.
export const DEFAULT_CAST = { exactLookup: true, lodPx: 0, lodAuto: false, maxIterations: 512, heatMap: false };

// A building's box enlarged by 1 % and 5 cm, so that its own surfaces never hide its probe.
function probeBox(box) {
  const grow = [0, 1, 2].map((a) => 0.01 * (box.max[a] - box.min[a]) + 0.05);
  return { min: box.min.map((v, a) => v - grow[a]), max: box.max.map((v, a) => v + grow[a]) };
}

// Whether p lies in the box: an eye inside a probe box cannot test it.
const holds = (box, p) => [0, 1, 2].every((a) => p[a] >= box.min[a] && p[a] <= box.max[a]);

// The six faces of a box (corner bits x = c & 1, y = c & 2, z = c & 4), counter-clockwise seen
// from outside, with their normals: +x, -x, +y, -y, +z, -z.
const FACES = [[1, 3, 7, 5], [0, 4, 6, 2], [2, 6, 7, 3], [0, 1, 5, 4], [4, 5, 7, 6], [0, 2, 3, 1]];
const FACE_NORMALS = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]];

// Per-instance data of the ray caster (shaders/hni_proxy.vert): eye in root units, the rotation's
// three columns, the atlas origin as two integers.
const INSTANCE_STRIDE = 56;

export class CityRenderer {
  // base: the URL of the manifest's folder; a building's HNI is base + hni.
  constructor(gl, generated, city, base, options = {}) {
    this.gl = gl;
    this.constants = generated.constants;
    this.city = city;
    this.base = base;
    this.options = { ...DEFAULT_OPTIONS, ...options };
    this.programs = {
      heuristic: buildProgram(gl, generated.programs.hniHeuristic),
      exact: buildProgram(gl, generated.programs.hniExact),
      mesh: buildProgram(gl, generated.programs.mesh),
    };
    this.pages = new AtlasPages(gl, this.options.atlasPageSize, this.options.maxAtlasPages);
    this.buildings = city.buildings.map((b) => ({
      state: 'unrequested', // requested, loaded, failed
      lastSeen: 0,
      evicted: false,
      originM: b.positionM,
      worldFromRoot: yawRotation(b.yawDeg),
      bounds: b.boundsM,
      slot: null,
      rootSizeM: null,
      summary: null,
      query: null, // its occlusion query, while one is in flight
      queryFrame: 0, // the frame that issued it
      occluded: false, // the last query's answer
      answerFrame: 0, // the frame that issued the query of that answer
      // With a complementary mesh: its levels (0 the mesh itself, k its k-th coarser level), each
      // { mesh: GpuMesh once loaded, requested }, and the box of those loaded.
      complement: b.complement ? Array.from({ length: 1 + b.complementLevels.length }, () => ({ mesh: null, requested: false })) : [],
      complementBox: null,
    }));
    this.cityBox = manifestBounds(city);
    this.uploadQueue = []; // { building, image, root }
    this.finished = []; // fetches that completed since the last frame
    this.failures = []; // "name: message", every failure so far
    this.outstanding = 0;
    this.frame = 0;
    this.counts = { bytesStreamed: 0, loaded: 0, failed: 0, evicted: 0, refetched: 0 };
    this.settled = false;
    // The first frame of the current run of frames with one view and nothing left to stream.
    this.stillSince = Infinity;
    this.lastView = '';

    this.hniVertexArray = gl.createVertexArray();
    this.instanceBuffer = gl.createBuffer();
    gl.bindVertexArray(this.hniVertexArray);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.instanceBuffer);
    gl.vertexAttribPointer(0, 3, gl.FLOAT, false, INSTANCE_STRIDE, 0);
    for (let column = 0; column < 3; ++column) gl.vertexAttribPointer(1 + column, 3, gl.FLOAT, false, INSTANCE_STRIDE, 12 + 12 * column);
    gl.vertexAttribIPointer(4, 2, gl.INT, INSTANCE_STRIDE, 48);
    for (let attribute = 0; attribute < 5; ++attribute) {
      gl.enableVertexAttribArray(attribute);
      gl.vertexAttribDivisor(attribute, 1);
    }
    this.meshBuffer = gl.createBuffer();
    this.meshVertexArray = meshVertexArray(gl, this.meshBuffer);
  }

  // Fetches and decodes a building's HNI (when `withImage`) and the level of its complementary mesh
  // (when `level` is not null); the result waits in `finished` for the next frame. Every failure
  // (network, HTTP, decoding, header) names the file.
  async load(index, withImage, level) {
    const entry = this.city.buildings[index];
    const done = { building: index, bytes: 0, level };
    let file = '';
    const fetched = async (path) => {
      file = path;
      const response = await fetch(new URL(path, this.base));
      if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`.trimEnd());
      const buffer = await response.arrayBuffer();
      done.bytes += buffer.byteLength;
      return buffer;
    };
    try {
      if (withImage) {
        done.image = await decodePng(await fetched(entry.hni));
        done.root = readHniRoot(done.image, this.constants);
      }
      if (level !== null) {
        const path = level === 0 ? entry.complement : entry.complementLevels[level - 1].path;
        if (!/\.glb$/i.test(path)) {
          file = path;
          throw new Error('the browser viewer reads complementary meshes as GLB (nut convert writes them so by default)');
        }
        done.complement = await readGlb(await fetched(path), path);
      }
    } catch (error) {
      done.error = error.message.startsWith(`${file}: `) ? error.message : `${file}: ${error.message}`;
    }
    this.finished.push(done);
  }

  // Fetches a building not loaded yet, with the level of its complement the camera wants now.
  request(index, camera, lodAuto) {
    const b = this.buildings[index];
    let level = null;
    if (b.complement.length > 0) {
      level = this.wantedLevel(index, camera, lodAuto);
      b.complement[level].requested = true;
    }
    ++this.outstanding;
    this.load(index, true, level);
  }

  // A failed building is never drawn or fetched again.
  fail(index, message, newFailures) {
    const b = this.buildings[index];
    if (b.state === 'failed') return;
    if (b.state === 'loaded') --this.counts.loaded;
    b.state = 'failed';
    ++this.counts.failed;
    newFailures.push(`${this.city.buildings[index].name}: ${message}`);
  }

  // Finished loads join the upload queue; failures are final.
  receive() {
    const newFailures = [];
    for (const done of this.finished.splice(0)) {
      --this.outstanding;
      this.counts.bytesStreamed += done.bytes;
      if (done.error) this.fail(done.building, done.error, newFailures);
      else this.uploadQueue.push(done);
    }
    return newFailures;
  }

  // A level of a building's complementary mesh onto the GPU; its box joins the building's, which
  // is culled and tested as one.
  addComplementLevel(index, mesh, level) {
    const b = this.buildings[index];
    const gpu = new GpuMesh(this.gl, mesh);
    const grow = (box) => ({ min: box.min.map((v, a) => Math.min(v, gpu.bounds.min[a])), max: box.max.map((v, a) => Math.max(v, gpu.bounds.max[a])) });
    b.complementBox = grow(b.complementBox ?? gpu.bounds);
    b.bounds = grow(b.bounds);
    b.complement[level].mesh?.delete();
    b.complement[level].mesh = gpu;
  }

  // The level of a building's complementary mesh the camera wants: under lod=auto the coarsest
  // whose error spans under a pixel at the nearest point of the levels' box (before any has
  // arrived, of the building's box), as nut's renderers pick it (scene::meshLevel).
  wantedLevel(index, camera, lodAuto) {
    const b = this.buildings[index];
    const box = b.complementBox ?? b.bounds;
    if (!lodAuto || !box) return 0;
    const nearest = camera.eye.map((e, a) => Math.min(Math.max(e, box.min[a]), box.max[a]));
    const pixelAngle = (2 * Math.tan((0.5 * camera.fovYDeg * Math.PI) / 180)) / camera.height;
    const allowedM = this.constants.meshLevelErrorPx * length(sub(camera.eye, nearest)) * pixelAngle;
    let level = 0;
    for (const coarser of this.city.buildings[index].complementLevels) {
      if (!(coarser.errorM < allowedM)) break;
      ++level;
    }
    return level;
  }

  // The level to draw: the one wanted when it has arrived; else it is fetched, and the nearest
  // level loaded stands in (finer first), so the frame never waits for a file.
  complementToDraw(index, camera, lodAuto) {
    const levels = this.buildings[index].complement;
    if (levels.length === 0) return null;
    const wanted = this.wantedLevel(index, camera, lodAuto);
    if (levels[wanted].mesh) return levels[wanted].mesh;
    if (!levels[wanted].requested) {
      levels[wanted].requested = true;
      ++this.outstanding;
      this.settled = false;
      this.load(index, false, wanted);
    }
    for (let k = wanted - 1; k >= 0; --k) if (levels[k].mesh) return levels[k].mesh;
    for (let k = wanted + 1; k < levels.length; ++k) if (levels[k].mesh) return levels[k].mesh;
    return null;
  }

  // Empties the page whose buildings were seen least recently, unless one was seen this frame.
  evictLeastRecentlySeenPage() {
    const lastSeen = this.pages.pages.map(() => 0);
    for (const b of this.buildings) if (b.state === 'loaded') lastSeen[b.slot.page] = Math.max(lastSeen[b.slot.page], b.lastSeen);
    if (lastSeen.length === 0) return false;
    const oldest = lastSeen.indexOf(Math.min(...lastSeen));
    if (lastSeen[oldest] >= this.frame) return false;
    for (const b of this.buildings)
      if (b.state === 'loaded' && b.slot.page === oldest) {
        b.state = 'unrequested';
        b.evicted = true;
        this.dropQuery(b);
        for (const level of b.complement) {
          level.mesh?.delete();
          Object.assign(level, { mesh: null, requested: false });
        }
        b.complementBox = null;
        --this.counts.loaded;
        ++this.counts.evicted;
      }
    this.pages.clear(oldest);
    return true;
  }

  // A slice of the upload queue into the atlas: up to the per-frame bytes, at least one HNI.
  upload(stats, newFailures) {
    let bytes = 0, taken = 0;
    for (; taken < this.uploadQueue.length && (taken === 0 || bytes < this.options.uploadBytesPerFrame); ++taken) {
      const { building, image, root, complement, level } = this.uploadQueue[taken];
      const b = this.buildings[building];
      if (!image) {
        // A level of the complement alone, for a building loaded before (dropped if evicted since).
        if (b.state === 'loaded') this.addComplementLevel(building, complement, level);
        continue;
      }
      if (!this.pages.fits(image) && !this.evictLeastRecentlySeenPage()) {
        stats.overBudget = true; // stays queued until the view moves on
        break;
      }
      bytes += image.pixels.length;
      try {
        b.slot = this.pages.place(image);
      } catch (error) {
        this.fail(building, error.message, newFailures);
        continue;
      }
      b.rootSizeM = root.sizeUnits.map((u) => u * this.constants.metresPerUnit);
      b.summary = root.summary;
      b.bounds = placedBox(b.originM, b.worldFromRoot, b.rootSizeM);
      if (complement) this.addComplementLevel(building, complement, level);
      b.state = 'loaded';
      ++this.counts.loaded;
      ++stats.uploaded;
    }
    this.uploadQueue.splice(0, taken);
  }

  dropQuery(b) {
    if (b.query) this.gl.deleteQuery(b.query);
    b.query = null;
    b.occluded = false;
  }

  // The answers of earlier frames' queries that have arrived (WebGL2 gives none within the frame
  // that asked); one still in flight keeps its building's previous answer. Returns how many
  // buildings changed between hidden and visible.
  collectOcclusion() {
    const gl = this.gl;
    let changed = 0;
    for (const b of this.buildings) {
      if (!b.query || !gl.getQueryParameter(b.query, gl.QUERY_RESULT_AVAILABLE)) continue;
      const occluded = !gl.getQueryParameter(b.query, gl.QUERY_RESULT);
      if (occluded !== b.occluded) ++changed;
      b.occluded = occluded;
      b.answerFrame = b.queryFrame;
      gl.deleteQuery(b.query);
      b.query = null;
    }
    return changed;
  }

  // After the frame: one query per building drawn or skipped as hidden, its probe box against the
  // frame's depth, without writing colour or depth.
  issueOcclusionQueries(view, tested) {
    const gl = this.gl;
    const probed = tested.filter((i) => !this.buildings[i].query);
    if (probed.length === 0) return;
    this.uploadBoxes(view, probed.map((i) => ({ ...probeBox(this.buildings[i].bounds), colours: Array(6).fill(PROXY_GREY) })));
    gl.depthFunc(gl.LEQUAL);
    gl.depthMask(false);
    gl.colorMask(false, false, false, false);
    gl.bindVertexArray(this.meshVertexArray);
    probed.forEach((i, k) => {
      const b = this.buildings[i];
      b.query = gl.createQuery();
      b.queryFrame = this.frame;
      gl.beginQuery(gl.ANY_SAMPLES_PASSED_CONSERVATIVE, b.query);
      gl.drawArrays(gl.TRIANGLES, 36 * k, 36);
      gl.endQuery(gl.ANY_SAMPLES_PASSED_CONSERVATIVE);
    });
    gl.bindVertexArray(null);
    gl.colorMask(true, true, true, true);
    gl.depthMask(true);
  }

  // Receive, cull, upload a slice and request what the view needs next; the visible buildings,
  // nearest first.
  prepare(view, lodAuto, stats, newFailures) {
    ++this.frame;
    newFailures.push(...this.receive());
    const eye = view.camera.eye;
    const visible = [];
    this.buildings.forEach((b, i) => {
      if (b.state === 'failed') return;
      if (this.options.frustumCulling && b.bounds && !view.mayBeVisible(b.bounds)) {
        ++stats.culledByFrustum;
        return;
      }
      const centre = b.bounds ? [0, 1, 2].map((a) => 0.5 * (b.bounds.min[a] + b.bounds.max[a])) : b.originM;
      visible.push({ building: i, distance: length(sub(centre, eye)) });
      b.lastSeen = this.frame;
    });
    visible.sort((x, y) => x.distance - y.distance || x.building - y.building);
    this.upload(stats, newFailures);

    for (const v of visible) {
      const b = this.buildings[v.building];
      if (b.state === 'loaded') continue;
      ++stats.waiting;
      if (b.state !== 'unrequested' || this.outstanding >= this.options.maxOutstanding) continue;
      b.state = 'requested';
      if (b.evicted) ++this.counts.refetched;
      this.request(v.building, view.camera, lodAuto);
    }
    this.settled = stats.waiting === 0 && this.uploadQueue.length === 0 && this.outstanding === 0;
    return visible;
  }

  // Draws a frame into the bound framebuffer (cleared by the caller). Returns the frame's stats.
  drawFrame(camera, cast = DEFAULT_CAST) {
    const gl = this.gl;
    const stats = {
      known: this.buildings.length, drawn: 0, culledByFrustum: 0, culledByOcclusion: 0, waiting: 0, proxies: 0, asSummary: 0,
      complementTriangles: 0, uploaded: 0, overBudget: false,
    };
    const newFailures = [];
    const view = new FrameView(camera);
    const occlusion = this.options.occlusionCulling;
    const occlusionChanged = occlusion ? this.collectOcclusion() : 0;
    const visible = this.prepare(view, cast.lodAuto, stats, newFailures);

    // Boxes first, which the depth test keeps in front of what is ray-cast behind them.
    const boxes = [];
    const summarised = new Set();
    if (this.options.ground && this.buildings.length > 0) {
      const all = this.cityBox;
      const margin = 0.5 * length(sub(all.max, all.min)) + 100;
      boxes.push({
        min: [all.min[0] - margin, all.min[1] - 0.1, all.min[2] - margin],
        max: [all.max[0] + margin, all.min[1], all.max[2] + margin],
        colours: Array(6).fill(GROUND),
      });
    }
    for (const v of visible) {
      const b = this.buildings[v.building];
      if (b.state !== 'loaded' && this.options.proxies && b.bounds) {
        boxes.push({ min: b.bounds.min, max: b.bounds.max, colours: Array(6).fill(PROXY_GREY) });
        ++stats.proxies;
      }
      if (b.state === 'loaded' && this.options.summaryBelowPx > 0 &&
          Math.max(...b.rootSizeM) < this.options.summaryBelowPx * Math.max(v.distance, 1e-3) * view.pixelAngle) {
        boxes.push({ originM: b.originM, worldFromRoot: b.worldFromRoot, sizeM: b.rootSizeM, colours: b.summary });
        summarised.add(v.building);
        ++stats.asSummary;
      }
    }
    this.drawBoxes(view, boxes);

    // One instanced draw per page, pages in the order of their nearest building, nearest first
    // within a page (or in manifest order without front-to-back).
    const order = visible.filter((v) => this.buildings[v.building].state === 'loaded' && !summarised.has(v.building)).map((v) => v.building);
    if (!this.options.frontToBack) order.sort((x, y) => x - y);
    const perPage = new Map();
    const tested = []; // the buildings this frame's occlusion queries test
    const meshes = []; // the complementary meshes of those drawn, at their levels
    for (const i of order) {
      const b = this.buildings[i];
      const testable = occlusion && !holds(probeBox(b.bounds), view.camera.eye);
      if (testable) tested.push(i);
      if (testable && b.occluded) {
        ++stats.culledByOcclusion;
        continue;
      }
      const page = b.slot.page;
      if (!perPage.has(page)) perPage.set(page, []);
      perPage.get(page).push(i);
      ++stats.drawn;
      const mesh = this.complementToDraw(i, view.camera, cast.lodAuto);
      if (mesh) {
        meshes.push(mesh);
        stats.complementTriangles += mesh.triangleCount;
      }
    }
    // Opaque meshes before the HNIs and translucent ones after, as nut-viewer draws them.
    for (const mesh of meshes) mesh.drawOpaque(view, this.programs.mesh);
    for (const [page, instances] of perPage) this.drawHnis(view, page, instances, cast);
    for (const mesh of meshes) mesh.drawTranslucent(view, this.programs.mesh);
    if (occlusion) this.issueOcclusionQueries(view, tested);

    // Settled: everything in view is loaded, and every building skipped as hidden was found hidden
    // by a query of this view with nothing left to stream (earlier ones may have tested it against
    // the grey box of a building still loading, or from elsewhere).
    const viewKey = JSON.stringify(camera);
    if (!this.settled || viewKey !== this.lastView) this.stillSince = Infinity;
    else if (this.stillSince === Infinity) this.stillSince = this.frame;
    this.lastView = viewKey;
    const answered = tested.every((i) => !this.buildings[i].occluded || this.buildings[i].answerFrame >= this.stillSince);
    Object.assign(stats, this.counts, {
      atlasBytes: this.pages.bytes(), settled: this.settled && occlusionChanged === 0 && (!occlusion || answered),
    });
    this.failures.push(...newFailures);
    stats.newFailures = newFailures;
    return stats;
  }

  // Boxes with the mesh program: axis-aligned { min, max } or placed { originM, worldFromRoot,
  // sizeM }, each face its own colour; positions relative to the eye, computed in double.
  drawBoxes(view, boxes) {
    if (boxes.length === 0) return;
    const gl = this.gl;
    const vertices = this.uploadBoxes(view, boxes);
    gl.depthFunc(gl.LESS);
    gl.depthMask(true);
    gl.bindVertexArray(this.meshVertexArray);
    gl.drawArrays(gl.TRIANGLES, 0, vertices);
    gl.bindVertexArray(null);
  }

  // The boxes' vertices into the mesh buffer, 36 a box in order, with the mesh program bound and
  // the depth test on. Returns the vertex count.
  uploadBoxes(view, boxes) {
    const gl = this.gl;
    const eye = view.camera.eye;
    const data = new ArrayBuffer(boxes.length * 36 * MESH_STRIDE);
    const floats = new Float32Array(data), bytes = new Uint8Array(data);
    let vertex = 0;
    for (const box of boxes) {
      const corner = [], normals = [];
      for (let c = 0; c < 8; ++c) {
        const t = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
        if (box.min) corner.push(t.map((s, a) => (s ? box.max[a] : box.min[a]) - eye[a]));
        else {
          const local = t.map((s, a) => s * box.sizeM[a]);
          const r = box.worldFromRoot;
          corner.push([0, 1, 2].map((a) => box.originM[a] + r[0][a] * local[0] + r[1][a] * local[1] + r[2][a] * local[2] - eye[a]));
        }
      }
      for (let f = 0; f < 6; ++f) {
        const n = FACE_NORMALS[f];
        normals[f] = box.min ? n : [0, 1, 2].map((a) => box.worldFromRoot[0][a] * n[0] + box.worldFromRoot[1][a] * n[1] + box.worldFromRoot[2][a] * n[2]);
        for (const k of [0, 1, 2, 0, 2, 3]) {
          const p = corner[FACES[f][k]];
          const o = vertex * (MESH_STRIDE / 4);
          floats.set(p, o);
          floats.set(normals[f], o + 3);
          bytes.set([...box.colours[f].slice(0, 3), 255], vertex * MESH_STRIDE + 24);
          ++vertex;
        }
      }
    }
    const program = this.programs.mesh;
    gl.useProgram(program.id);
    gl.uniform3f(program.uniform('uAnchorFromEye'), 0, 0, 0);
    gl.uniformMatrix4fv(program.uniform('uClipFromEye'), false, view.clipFromEye);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.meshBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STREAM_DRAW);
    gl.enable(gl.DEPTH_TEST);
    return vertex;
  }

  // The ray caster over one page's buildings (viewer::HniRenderer::draw).
  drawHnis(view, page, instances, cast) {
    const gl = this.gl;
    const data = new ArrayBuffer(instances.length * INSTANCE_STRIDE);
    const floats = new Float32Array(data), ints = new Int32Array(data);
    const eye = view.camera.eye;
    instances.forEach((i, k) => {
      const b = this.buildings[i];
      const o = k * (INSTANCE_STRIDE / 4);
      const d = sub(eye, b.originM);
      // The eye in the root block's frame, in units: the transposed rotation times the offset.
      for (let a = 0; a < 3; ++a) {
        const r = b.worldFromRoot[a];
        floats[o + a] = (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / this.constants.metresPerUnit;
      }
      for (let c = 0; c < 3; ++c) floats.set(b.worldFromRoot[c], o + 3 + 3 * c);
      ints[o + 12] = b.slot.origin[0];
      ints[o + 13] = b.slot.origin[1];
    });
    gl.bindBuffer(gl.ARRAY_BUFFER, this.instanceBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STREAM_DRAW);

    const program = cast.exactLookup ? this.programs.exact : this.programs.heuristic;
    gl.useProgram(program.id);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.pages.texture(page));
    gl.uniform1i(program.uniform('uHni'), 0);
    gl.uniformMatrix4fv(program.uniform('uClipFromEye'), false, view.proxyClipFromEye);
    gl.uniform3fv(program.uniform('uForward'), view.forward);
    gl.uniform3fv(program.uniform('uRight'), view.right);
    gl.uniform3fv(program.uniform('uUp'), view.up);
    gl.uniform2f(program.uniform('uTanHalf'), view.tanHalfX, view.tanHalfY);
    gl.uniform2f(program.uniform('uViewportSize'), view.camera.width, view.camera.height);
    gl.uniform2fv(program.uniform('uDepthFromEyeZ'), view.depthFromEyeZ);
    gl.uniform1f(program.uniform('uPixelAngle'), view.pixelAngle);
    gl.uniform1f(program.uniform('uLodPx'), cast.lodPx);
    gl.uniform1i(program.uniform('uLodAuto'), cast.lodAuto ? 1 : 0);
    gl.uniform1i(program.uniform('uMaxIterations'), cast.maxIterations);
    gl.uniform1i(program.uniform('uHeatMap'), cast.heatMap ? 1 : 0);

    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL); // capped rays are drawn at depth 1, the cleared value
    gl.depthMask(true);
    gl.enable(gl.CULL_FACE);
    gl.cullFace(gl.FRONT);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.SRC_ALPHA);
    gl.bindVertexArray(this.hniVertexArray);
    gl.drawArraysInstanced(gl.TRIANGLES, 0, 36, instances.length);
    gl.bindVertexArray(null);
    gl.disable(gl.BLEND);
    gl.disable(gl.CULL_FACE);
  }
}
