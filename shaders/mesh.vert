// mesh.vert — triangle meshes (a building's complementary mesh, ground, trees, or a whole mesh
// rendered for comparison) with the camera every renderer shares.
//
// References: Kuang et al. 2013, section 5 (non-axis-aligned faces stay a complementary mesh,
// drawn with the HNIs) and section 6 (meshes and HNIs mixed by the depth buffer); docs/RENDERING.md
// (camera, depth). Assembled after format_constants.glsl and common.glsl. Vertices are not shared:
// each triangle carries its own face normal and material, so the shading is flat as on the CPU.

layout(location = 0) in vec3 aPosition;  // metres, relative to the mesh's anchor
layout(location = 1) in vec3 aNormal;    // unit face normal
layout(location = 2) in vec4 aMaterial;  // sRGB bytes and opacity byte, 0..255

uniform vec3 uAnchorFromEye;  // the anchor relative to the eye, metres
uniform mat4 uClipFromEye;    // projection (the camera's near and far) times the camera rotation

out vec3 vFromEye;
flat out vec3 vNormal;
flat out vec4 vMaterial;

void main() {
  vFromEye = uAnchorFromEye + aPosition;
  vNormal = aNormal;
  vMaterial = aMaterial;
  gl_Position = uClipFromEye * vec4(vFromEye, 1.0);
}
