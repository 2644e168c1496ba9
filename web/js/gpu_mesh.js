// gpu_mesh.js — a building's complementary mesh on the GPU, drawn by the mesh program as
// viewer::GpuMesh and viewer::MeshRenderer draw it: vertices relative to the mesh's box centre
// (the anchor), computed in double, so that float precision goes to the mesh and not to its
// distance from the world origin; each triangle its own three vertices with its face normal and
// material; degenerate triangles dropped; opaque triangles drawn with depth writes, translucent
// ones kept on the CPU and drawn back to front after everything opaque.

import { length, sub } from './camera.js';

// Interleaved vertices of the mesh program (shaders/mesh.vert): position and normal as floats,
// material as four bytes (0..255, not normalised).
export const MESH_STRIDE = 28;

// The mesh program's vertex layout over `buffer`, in a new vertex array.
export function meshVertexArray(gl, buffer) {
  const array = gl.createVertexArray();
  gl.bindVertexArray(array);
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  gl.vertexAttribPointer(0, 3, gl.FLOAT, false, MESH_STRIDE, 0);
  gl.vertexAttribPointer(1, 3, gl.FLOAT, false, MESH_STRIDE, 12);
  gl.vertexAttribPointer(2, 4, gl.UNSIGNED_BYTE, false, MESH_STRIDE, 24);
  for (let attribute = 0; attribute < 3; ++attribute) gl.enableVertexAttribArray(attribute);
  gl.bindVertexArray(null);
  gl.bindBuffer(gl.ARRAY_BUFFER, null);
  return array;
}

export class GpuMesh {
  // mesh: what readGlb returns.
  constructor(gl, mesh) {
    this.gl = gl;
    const p = mesh.positions;
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (const index of mesh.triangles)
      for (let a = 0; a < 3; ++a) {
        min[a] = Math.min(min[a], p[3 * index + a]);
        max[a] = Math.max(max[a], p[3 * index + a]);
      }
    this.bounds = { min, max };
    this.anchorM = min.map((v, a) => 0.5 * (v + max[a]));

    const opaque = [], translucent = [];
    for (let t = 0; t < mesh.triangleMaterial.length; ++t) {
      const corner = [0, 1, 2].map((k) => [0, 1, 2].map((a) => p[3 * mesh.triangles[3 * t + k] + a]));
      const u = sub(corner[1], corner[0]), v = sub(corner[2], corner[0]);
      const normal = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
      const n = length(normal);
      if (!(n > 0) || !Number.isFinite(n)) continue;
      const m = mesh.materials[mesh.triangleMaterial[t]];
      (m.opacity === 255 ? opaque : translucent).push({ corner, normal: normal.map((c) => c / n), m });
    }
    this.opaqueVertices = 3 * opaque.length;
    this.translucent = translucent.map((t) => ({
      ...t,
      centroid: [0, 1, 2].map((a) => (t.corner[0][a] + t.corner[1][a] + t.corner[2][a]) / 3),
    }));
    this.opaqueBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.opaqueBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.vertices(opaque), gl.STATIC_DRAW);
    this.opaqueArray = meshVertexArray(gl, this.opaqueBuffer);
    this.translucentBuffer = gl.createBuffer();
    this.translucentArray = meshVertexArray(gl, this.translucentBuffer);
  }

  get triangleCount() {
    return this.opaqueVertices / 3 + this.translucent.length;
  }

  // Triangles as interleaved vertices, relative to the anchor.
  vertices(triangles) {
    const data = new ArrayBuffer(3 * triangles.length * MESH_STRIDE);
    const floats = new Float32Array(data), bytes = new Uint8Array(data);
    let vertex = 0;
    for (const { corner, normal, m } of triangles)
      for (const c of corner) {
        floats.set(sub(c, this.anchorM), vertex * (MESH_STRIDE / 4));
        floats.set(normal, vertex * (MESH_STRIDE / 4) + 3);
        bytes.set([m.r, m.g, m.b, m.opacity], vertex * MESH_STRIDE + 24);
        ++vertex;
      }
    return data;
  }

  setUniforms(view, program) {
    const gl = this.gl;
    gl.useProgram(program.id);
    gl.uniform3fv(program.uniform('uAnchorFromEye'), sub(this.anchorM, view.camera.eye));
    gl.uniformMatrix4fv(program.uniform('uClipFromEye'), false, view.clipFromEye);
    gl.enable(gl.DEPTH_TEST);
  }

  drawOpaque(view, program) {
    if (this.opaqueVertices === 0) return;
    const gl = this.gl;
    this.setUniforms(view, program);
    gl.depthFunc(gl.LESS);
    gl.depthMask(true);
    gl.bindVertexArray(this.opaqueArray);
    gl.drawArrays(gl.TRIANGLES, 0, this.opaqueVertices);
    gl.bindVertexArray(null);
  }

  // Back to front by the distance of each triangle's centroid from the eye, blended over what is
  // drawn, depth-tested without writing depth.
  drawTranslucent(view, program) {
    if (this.translucent.length === 0) return;
    const gl = this.gl;
    const eye = view.camera.eye;
    const sorted = this.translucent.map((t) => ({ t, d: length(sub(t.centroid, eye)) })).sort((a, b) => b.d - a.d).map((s) => s.t);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.translucentBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.vertices(sorted), gl.STREAM_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    this.setUniforms(view, program);
    gl.depthFunc(gl.LESS);
    gl.depthMask(false);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.bindVertexArray(this.translucentArray);
    gl.drawArrays(gl.TRIANGLES, 0, 3 * sorted.length);
    gl.bindVertexArray(null);
    gl.disable(gl.BLEND);
    gl.depthMask(true);
  }

  delete() {
    const gl = this.gl;
    for (const buffer of [this.opaqueBuffer, this.translucentBuffer]) gl.deleteBuffer(buffer);
    for (const array of [this.opaqueArray, this.translucentArray]) gl.deleteVertexArray(array);
  }
}
