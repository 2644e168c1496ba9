// mesh.frag — the shared shading of docs/RENDERING.md on a mesh face: the face normal turned to
// the viewer, the fixed light, sRGB bytes without linearisation.
//
// References: Kuang et al. 2013, section 6 (complementary meshes drawn with the HNIs);
// docs/RENDERING.md "Shading". Assembled after format_constants.glsl and common.glsl. Opaque faces
// write alpha 1; translucent ones are blended back to front with glBlendFunc(GL_SRC_ALPHA,
// GL_ONE_MINUS_SRC_ALPHA), which composites as the CPU renderers do front to back.

in vec3 vFromEye;
flat in vec3 vNormal;
flat in vec4 vMaterial;

out vec4 fragColour;

void main() {
  fragColour = vec4(shade(vMaterial.rgb, vNormal, normalize(vFromEye)) / 255.0, vMaterial.a / 255.0);
}
