// fullscreen.vert — one triangle that covers the viewport, from gl_VertexID alone (no buffers),
// with texture coordinates 0..1 over the viewport: the vertex stage of post-processes.
//
// References: none in the paper (post-processing is the renderer's); docs/GL.md. Assembled after
// format_constants.glsl and common.glsl.

out vec2 vUv;

void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0), (2,0), (0,2)
  vUv = corner;
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
