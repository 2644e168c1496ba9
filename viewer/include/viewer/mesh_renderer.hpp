// viewer/mesh_renderer.hpp — triangle meshes rasterised with the shared camera and shading
// (shaders/mesh.vert, shaders/mesh.frag): a building's complementary mesh beside its HNI, or a
// whole mesh for comparison with the ray casters (`nut render-mesh --backend gl`).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/triangle_mesh.hpp>

#include <viewer/context.hpp>
#include <viewer/frame_view.hpp>
#include <viewer/gl_object.hpp>
#include <viewer/shader_library.hpp>

namespace nut::viewer {

// A mesh on the GPU. Vertices are stored relative to its bounds centre (the anchor), so that
// float precision goes to the mesh and not to its distance from the world origin; each triangle
// has its own three vertices with its face normal (computed in double) and material. Degenerate
// triangles, which have no normal and which no ray can hit, are dropped.
class GpuMesh {
 public:
  // Errors: a triangle or material index out of range, a material count that does not match.
  static Result<GpuMesh> upload(const Gl& gl, const TriangleMesh& mesh);

  const WorldBox& bounds() const { return bounds_; }
  std::size_t triangleCount() const { return opaqueVertices_ / 3 + translucent_.size() / 3; }
  // The vertex data it holds: unindexed, 28 bytes a vertex (position, normal, material).
  std::size_t bufferBytes() const {
    return (static_cast<std::size_t>(opaqueVertices_) + translucent_.size()) * sizeof(Vertex);
  }

 private:
  friend class MeshRenderer;
  struct Vertex {
    float position[3];
    float normal[3];
    std::uint8_t material[4];  // r, g, b, opacity
  };
  explicit GpuMesh(const Gl& gl) : gl_(&gl) {}
  const Gl* gl_;
  WorldBox bounds_;
  glm::dvec3 anchorM{0.0};
  GlObject vertexArray_, opaqueBuffer_;
  GLsizei opaqueVertices_ = 0;
  // Translucent triangles stay on the CPU too: they are sorted back to front for every frame.
  std::vector<Vertex> translucent_;
  GlObject translucentArray_, translucentBuffer_;
};

// The mesh program: the files MeshRenderer builds, and the browser viewer's export assembles as
// GLSL ES for its boxes (docs/WEB.md).
ProgramSpec meshProgramSpec();

class MeshRenderer {
 public:
  static Result<MeshRenderer> create(const Context& context, const ShaderLibrary& library, int glslVersion = 0);

  // Opaque triangles with depth test (GL_LESS) and depth write, no blending.
  void drawOpaque(const FrameView& view, const GpuMesh& mesh) const;
  // Depth-tests the opaque vertices [first, first + count) of the mesh (GL_LEQUAL) without writing
  // colour or depth: an occlusion query's probe.
  void probe(const FrameView& view, const GpuMesh& mesh, GLint first, GLsizei count) const;
  // Translucent triangles sorted back to front (by centroid distance), blended over what is drawn,
  // depth-tested without writing depth. Draw them after everything opaque and after the HNIs.
  void drawTranslucent(const FrameView& view, GpuMesh& mesh) const;

 private:
  MeshRenderer(const Gl& gl, Program program) : gl_(&gl), program_(std::move(program)) {}
  void setUniforms(const FrameView& view, const GpuMesh& mesh) const;
  const Gl* gl_;
  Program program_;
};

}  // namespace nut::viewer
