// hni_proxy.vert — one proxy box per HNI instance: the root block's box, slightly enlarged, whose
// back faces (front faces are culled) cover every pixel whose ray may hit the HNI, also with the
// eye inside the box. hni_raycast.frag casts the ray; the box only decides which pixels run it.
//
// References: Kuang et al. 2013, section 6 (rendering: "we render the bounding box of each
// building and ray-cast the HNI in the fragment shader"); docs/GL.md. Assembled after
// format_constants.glsl, common.glsl and hni_access.glsl. Drawn with glDrawArraysInstanced
// (36 vertices, no vertex buffer): the attributes are per instance.

layout(location = 0) in vec3 aEyeUnits;        // the eye in the instance's root-block frame, units
layout(location = 1) in vec3 aWorldFromRoot0;  // columns of the rotation from root frame to world
layout(location = 2) in vec3 aWorldFromRoot1;
layout(location = 3) in vec3 aWorldFromRoot2;
layout(location = 4) in ivec2 aAtlasOrigin;    // the HNI's origin in the atlas

// Projection times the camera's rotation; positions are relative to the eye (metres), so that
// world coordinates near 10^6 m cost no float precision. Infinite far plane, 1 mm near plane.
uniform mat4 uClipFromEye;

flat out vec3 vEyeUnits;
flat out mat3 vWorldFromRoot;
flat out ivec2 vAtlasOrigin;

// 12 triangles, counter-clockwise seen from outside; corner bits are x, y, z.
const int kBoxCorners[36] = int[](0, 6, 2, 0, 4, 6, 1, 3, 7, 1, 7, 5, 0, 5, 4, 0, 1, 5,
                                  2, 6, 7, 2, 7, 3, 0, 3, 1, 0, 2, 3, 4, 5, 7, 4, 7, 6);

void main() {
  gHniOrigin = aAtlasOrigin;
  vec3 size = blockSize(rootHeader());
  // The margin keeps the rasterised silhouette outside every ray that reaches the box; rays
  // through the margin miss the box in the ray caster and are discarded there.
  vec3 margin = vec3(1.0 + 1e-3 * max(size.x, max(size.y, size.z)));
  int corner = kBoxCorners[gl_VertexID];
  vec3 local = mix(-margin, size + margin, vec3(ivec3(corner, corner >> 1, corner >> 2) & 1));
  mat3 worldFromRoot = mat3(aWorldFromRoot0, aWorldFromRoot1, aWorldFromRoot2);
  gl_Position = uClipFromEye * vec4(worldFromRoot * (local - aEyeUnits) * kMetresPerUnit, 1.0);
  vEyeUnits = aEyeUnits;
  vWorldFromRoot = worldFromRoot;
  vAtlasOrigin = aAtlasOrigin;
}
