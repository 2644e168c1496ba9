// glb.js — a building's complementary mesh from a binary glTF (GLB) file, read as nut's reader
// reads it (scene/glb.hpp): the default scene's nodes placed by their matrices or TRS, composed in
// double; triangle primitives with float or quantized positions (KHR_mesh_quantization) and 8, 16
// or 32-bit indices or none; buffer views compressed with EXT_meshopt_compression (no filter),
// decoded by meshoptimizer's own decoder; a triangle's material is its primitive's base colour
// factor as sRGB bytes, opacity from alpha under BLEND (MASK: all or nothing). Everything else
// that file may hold is refused with one error naming the file and the glTF object.

import { MeshoptDecoder } from './meshopt_decoder.mjs';

const GLB_MAGIC = 0x46546c67, CHUNK_JSON = 0x4e4f534a, CHUNK_BIN = 0x004e4942;
const MAX_NODE_DEPTH = 64;
const READ_EXTENSIONS = ['EXT_meshopt_compression', 'KHR_mesh_quantization', 'KHR_materials_unlit'];
const COMPONENT_BYTES = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
const MESHOPT_MODES = ['ATTRIBUTES', 'TRIANGLES', 'INDICES'];

const isIndex = (v) => Number.isSafeInteger(v) && v >= 0;

// Column-major 4x4 matrices, as glTF stores them.
function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let c = 0; c < 4; ++c)
    for (let r = 0; r < 4; ++r)
      for (let k = 0; k < 4; ++k) out[4 * c + r] += a[4 * k + r] * b[4 * c + k];
  return out;
}
const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

function numbers(value, count) {
  return Array.isArray(value) && value.length === count && value.every((v) => typeof v === 'number' && Number.isFinite(v))
    ? value : null;
}

// A node's own transform, or null when its fields are not numbers.
function localTransform(node) {
  if ('matrix' in node) return numbers(node.matrix, 16);
  const t = 'translation' in node ? numbers(node.translation, 3) : [0, 0, 0];
  const q = 'rotation' in node ? numbers(node.rotation, 4) : [0, 0, 0, 1];
  const s = 'scale' in node ? numbers(node.scale, 3) : [1, 1, 1];
  if (!t || !q || !s) return null;
  const n = Math.hypot(...q);
  const [x, y, z, w] = n > 0 ? q.map((v) => v / n) : [0, 0, 0, 1];
  const turn = n > 0 ? [
    1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),
    2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
    2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y),
  ] : [1, 0, 0, 0, 1, 0, 0, 0, 1];
  const out = [...IDENTITY];
  for (let c = 0; c < 3; ++c)
    for (let r = 0; r < 3; ++r) out[4 * c + r] = turn[3 * c + r] * s[c];
  out[12] = t[0], out[13] = t[1], out[14] = t[2];
  return out;
}

// One component as a number, normalized as glTF's KHR_mesh_quantization says.
function component(data, offset, type, normalized) {
  switch (type) {
    case 5120: { const v = data.getInt8(offset); return normalized ? Math.max(v / 127, -1) : v; }
    case 5121: { const v = data.getUint8(offset); return normalized ? v / 255 : v; }
    case 5122: { const v = data.getInt16(offset, true); return normalized ? Math.max(v / 32767, -1) : v; }
    case 5123: { const v = data.getUint16(offset, true); return normalized ? v / 65535 : v; }
    case 5125: return data.getUint32(offset, true);
    default: return data.getFloat32(offset, true);
  }
}

class GlbReader {
  constructor(buffer, name) {
    this.name = name;
    this.views = new Map(); // decoded buffer views by index
    this.materialSlots = new Map(); // glTF material index (-1: the default) -> mesh material
    this.mesh = { positions: [], triangles: [], triangleMaterial: [], materials: [] };
    this.container(new DataView(buffer));
  }

  fail(what) {
    return new Error(`${this.name}: ${what}`);
  }

  container(bytes) {
    if (bytes.byteLength < 20) throw this.fail(`not a GLB file: ${bytes.byteLength} bytes, shorter than its header`);
    if (bytes.getUint32(0, true) !== GLB_MAGIC) throw this.fail('not a GLB file (no glTF magic)');
    if (bytes.getUint32(4, true) !== 2) throw this.fail(`GLB version ${bytes.getUint32(4, true)}, not 2`);
    const length = bytes.getUint32(8, true);
    if (length > bytes.byteLength) throw this.fail(`truncated: the header declares ${length} bytes, the file has ${bytes.byteLength}`);
    const jsonLength = bytes.getUint32(12, true);
    if (bytes.getUint32(16, true) !== CHUNK_JSON) throw this.fail('the first chunk is not JSON');
    if (20 + jsonLength > length) throw this.fail('the JSON chunk runs past the end of the file');
    try {
      this.gltf = JSON.parse(new TextDecoder().decode(new Uint8Array(bytes.buffer, bytes.byteOffset + 20, jsonLength)));
    } catch {
      this.gltf = null;
    }
    if (this.gltf === null || typeof this.gltf !== 'object' || Array.isArray(this.gltf)) throw this.fail('the JSON chunk is not a glTF JSON object');
    const next = 20 + ((jsonLength + 3) & ~3);
    this.bin = new Uint8Array(0);
    if (next + 8 <= length && bytes.getUint32(next + 4, true) === CHUNK_BIN) {
      const binLength = bytes.getUint32(next, true);
      if (next + 8 + binLength > length) throw this.fail('the BIN chunk runs past the end of the file');
      this.bin = new Uint8Array(bytes.buffer, bytes.byteOffset + next + 8, binLength);
    }
    const version = this.gltf.asset?.version;
    if (typeof version !== 'string' || !version.startsWith('2.')) throw this.fail('not glTF 2.0 (asset.version)');
    for (const ext of Array.isArray(this.gltf.extensionsRequired) ? this.gltf.extensionsRequired : [])
      if (!READ_EXTENSIONS.includes(ext)) throw this.fail(`requires the extension ${ext}, which is not read`);
  }

  element(array, i) {
    const a = this.gltf[array];
    return Array.isArray(a) && isIndex(i) && i < a.length && a[i] !== null && typeof a[i] === 'object' ? a[i] : null;
  }

  buffer(index) {
    const b = this.element('buffers', index);
    if (!b) throw this.fail(`buffer ${index} does not exist`);
    if ('uri' in b) throw this.fail(`buffer ${index} is external (uri), which is not read`);
    if (index !== 0) throw this.fail(`buffer ${index} has no data (only buffer 0 is the BIN chunk)`);
    if (!isIndex(b.byteLength) || b.byteLength > this.bin.length) throw this.fail('buffer 0 declares more bytes than the BIN chunk has');
    return this.bin.subarray(0, b.byteLength);
  }

  // The bytes of buffer view `index`, decoded once if meshopt-compressed.
  view(index) {
    if (this.views.has(index)) return this.views.get(index);
    const where = `bufferView ${index}`;
    const v = this.element('bufferViews', index);
    if (!v) throw this.fail(`${where} does not exist`);
    const meshopt = v.extensions?.EXT_meshopt_compression;
    const source = meshopt ?? v;
    const offset = source.byteOffset ?? 0, length = source.byteLength;
    if (!isIndex(offset) || !isIndex(length)) throw this.fail(`${where}: no byteLength`);
    const data = this.buffer(source.buffer);
    if (offset + length > data.length) throw this.fail(`${where} lies outside its buffer`);
    let bytes = data.subarray(offset, offset + length);
    if (meshopt) {
      const { count, byteStride: stride, mode } = meshopt;
      if (!isIndex(count) || !isIndex(stride) || !MESHOPT_MODES.includes(mode))
        throw this.fail(`${where}: EXT_meshopt_compression without byteStride, count or mode`);
      if ((meshopt.filter ?? 'NONE') !== 'NONE') throw this.fail(`${where}: the meshopt filter "${meshopt.filter}" is not read`);
      // A meshopt stream decodes to at most 64 times its size (nut's reader has the same bound).
      if (stride === 0 || stride > 256 || count * stride > 64 * length + 4096)
        throw this.fail(`${where}: ${count} elements of ${stride} bytes cannot come from ${length} compressed bytes`);
      const target = new Uint8Array(count * stride);
      try {
        MeshoptDecoder.decodeGltfBuffer(target, count, stride, bytes, mode);
      } catch (error) {
        throw this.fail(`${where}: the meshopt data is corrupt (${error.message})`);
      }
      bytes = target;
    }
    this.views.set(index, bytes);
    return bytes;
  }

  // An accessor's elements as numbers, `components` per element, with its layout checked.
  accessor(index, type, components, indices) {
    const where = `accessor ${index}`;
    const a = this.element('accessors', index);
    if (!a) throw this.fail(`${where} does not exist`);
    if ('sparse' in a) throw this.fail(`${where} is sparse, which is not read`);
    if (a.type !== type) throw this.fail(`${where} is not a ${type}`);
    const { bufferView, count, componentType } = a;
    const offset = a.byteOffset ?? 0;
    if (!isIndex(bufferView) || !isIndex(count) || !isIndex(componentType) || !isIndex(offset))
      throw this.fail(`${where}: no bufferView, count or componentType`);
    const bytesEach = COMPONENT_BYTES[componentType] ?? 0;
    const integerIndex = componentType === 5121 || componentType === 5123 || componentType === 5125;
    if (bytesEach === 0 || (indices && !integerIndex) || (!indices && componentType === 5125))
      throw this.fail(`${where}: component type ${componentType} is not valid here`);
    const data = this.view(bufferView);
    const elementBytes = bytesEach * components;
    const declared = this.element('bufferViews', bufferView).byteStride;
    const stride = isIndex(declared) ? declared : elementBytes;
    if (count > 0 && (stride < elementBytes || offset + (count - 1) * stride + elementBytes > data.length))
      throw this.fail(`${where} lies outside bufferView ${bufferView}`);
    const dv = new DataView(data.buffer, data.byteOffset, data.byteLength);
    const out = new Float64Array(count * components);
    for (let e = 0; e < count; ++e)
      for (let c = 0; c < components; ++c)
        out[e * components + c] = component(dv, offset + e * stride + c * bytesEach, componentType, a.normalized === true);
    return out;
  }

  material(index) {
    const key = index ?? -1;
    if (this.materialSlots.has(key)) return this.materialSlots.get(key);
    let m = { r: 255, g: 255, b: 255, opacity: 255 };
    if (index !== undefined) {
      const g = this.element('materials', index);
      if (!g) throw this.fail(`material ${index} does not exist`);
      const pbr = g.pbrMetallicRoughness;
      const factor = pbr && 'baseColorFactor' in pbr ? numbers(pbr.baseColorFactor, 4) : [1, 1, 1, 1];
      if (!factor) throw this.fail(`material ${index}: baseColorFactor is not four numbers`);
      const byte = (x) => Math.round(255 * Math.min(Math.max(x, 0), 1));
      m = { r: byte(factor[0]), g: byte(factor[1]), b: byte(factor[2]), opacity: 255 };
      if (g.alphaMode === 'BLEND') m.opacity = byte(factor[3]);
      if (g.alphaMode === 'MASK') m.opacity = factor[3] >= (typeof g.alphaCutoff === 'number' ? g.alphaCutoff : 0.5) ? 255 : 0;
    }
    this.mesh.materials.push(m);
    this.materialSlots.set(key, this.mesh.materials.length - 1);
    return this.mesh.materials.length - 1;
  }

  primitive(p, transform, where) {
    if ((p.mode ?? 4) !== 4) return; // points and lines are left out, as nut's reader does
    const position = p.attributes?.POSITION;
    if (!isIndex(position)) throw this.fail(`${where} has no POSITION`);
    const positions = this.accessor(position, 'VEC3', 3, false);
    const vertexCount = positions.length / 3;
    const indices = 'indices' in p ? this.accessor(p.indices, 'SCALAR', 1, true) : Float64Array.from({ length: vertexCount }, (_, i) => i);
    if (indices.length % 3 !== 0) throw this.fail(`${where}: ${indices.length} indices, not whole triangles`);
    if ('material' in p && !isIndex(p.material)) throw this.fail(`${where}: its material is not an index`);
    const material = this.material(p.material);
    const base = this.mesh.positions.length / 3;
    const t = transform;
    for (let v = 0; v < vertexCount; ++v) {
      const [x, y, z] = positions.subarray(3 * v, 3 * v + 3);
      const world = [0, 1, 2].map((r) => t[r] * x + t[4 + r] * y + t[8 + r] * z + t[12 + r]);
      if (!world.every(Number.isFinite)) throw this.fail(`${where}: vertex ${v} is not a finite position`);
      this.mesh.positions.push(...world);
    }
    for (let i = 0; i < indices.length; i += 3) {
      const tri = [indices[i], indices[i + 1], indices[i + 2]];
      for (const k of tri) if (k >= vertexCount) throw this.fail(`${where}: index ${k} past its ${vertexCount} vertices`);
      if (tri[0] === tri[1] || tri[1] === tri[2] || tri[0] === tri[2]) continue;
      this.mesh.triangles.push(base + tri[0], base + tri[1], base + tri[2]);
      this.mesh.triangleMaterial.push(material);
    }
  }

  node(index, parent, depth) {
    const where = `node ${index}`;
    if (depth > MAX_NODE_DEPTH) throw this.fail(`${where}: the node tree is deeper than ${MAX_NODE_DEPTH} (a cycle?)`);
    const n = this.element('nodes', index);
    if (!n) throw this.fail(`${where} does not exist`);
    const local = localTransform(n);
    if (!local) throw this.fail(`${where}: its matrix, translation, rotation or scale is not numbers`);
    const transform = multiply(parent, local);
    if ('mesh' in n) {
      const primitives = this.element('meshes', n.mesh)?.primitives;
      if (!Array.isArray(primitives)) throw this.fail(`mesh ${n.mesh} does not exist or has no primitives`);
      primitives.forEach((p, k) => this.primitive(p ?? {}, transform, `mesh ${n.mesh} primitive ${k}`));
    }
    for (const child of Array.isArray(n.children) ? n.children : []) {
      if (!isIndex(child)) throw this.fail(`${where}: a child is not a node index`);
      this.node(child, transform, depth + 1);
    }
  }

  // The default scene's root nodes; without scenes, every node no other node holds.
  read() {
    const nodes = Array.isArray(this.gltf.nodes) ? this.gltf.nodes : [];
    let roots = [];
    if (Array.isArray(this.gltf.scenes) && this.gltf.scenes.length > 0) {
      const s = this.gltf.scene ?? 0;
      if (!isIndex(s) || s >= this.gltf.scenes.length) throw this.fail(`scene ${s} does not exist`);
      roots = (this.gltf.scenes[s]?.nodes ?? []).filter(isIndex);
    } else {
      const isChild = nodes.map(() => false);
      for (const n of nodes) for (const c of n?.children ?? []) if (isIndex(c) && c < nodes.length) isChild[c] = true;
      roots = nodes.map((_, i) => i).filter((i) => !isChild[i]);
    }
    for (const r of roots) this.node(r, IDENTITY, 0);
    if (this.mesh.triangles.length === 0) throw this.fail('no triangles');
    return this.mesh;
  }
}

// The mesh of a GLB file's bytes: { positions (world metres, 3 numbers a vertex), triangles (3
// indices each), triangleMaterial, materials: [{ r, g, b, opacity }] }. `name` names it in errors.
export async function readGlb(buffer, name) {
  await MeshoptDecoder.ready;
  return new GlbReader(buffer, name).read();
}
