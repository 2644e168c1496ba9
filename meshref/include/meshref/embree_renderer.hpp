// meshref/embree_renderer.hpp — the mesh reference renderer: a triangle mesh ray-traced with
// Embree 3, with the camera and shading of nut/camera.hpp (docs/RENDERING.md).
//
// It is what NUT output is compared against (`nut compare`) and its speed peer, so it draws the
// same picture an HNI of the same building should give: one ray per pixel centre, the shared
// shading with the face's geometric normal turned to the viewer, the same background, and
// translucent faces composited front to back like translucent cells.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/triangle_mesh.hpp>
#include <scene/scene_render.hpp>

namespace nut::meshref {

struct MeshRenderOutput {
  Image colour;                  // RGBA8, alpha 255
  std::vector<float> distanceM;  // per pixel, row 0 first; +infinity where no opaque face was hit
};

struct MeshRenderStats {
  double seconds = 0;        // rendering only; the scene is built once in create()
  double raysPerSecond = 0;  // primary rays (pixels) per second
  int threads = 0;
};

// Translucent faces a ray composites at most; behind them it sees the background.
inline constexpr int kMaxTranslucentLayers = 64;

// How render() hands the primary rays to Embree. Every mode gives the same hits (Embree's robust
// triangle test is the same code at every width); what differs is how much traversal the rays
// of neighbouring pixels share. A ray that passes a translucent face goes on one ray at a time.
enum class EmbreeRays {
  Single,    // rtcIntersect1 per pixel
  Packet8,   // rtcIntersect8 on 4x2 pixel blocks
  Packet16,  // rtcIntersect16 on 4x4 pixel blocks
  Stream,    // rtcIntersect1M on each 16x16 tile, flagged coherent
};

class EmbreeRenderer final : public scene::MeshTracer {
 public:
  // Builds the Embree scene once (a robust BVH over the mesh; Embree's builder uses all cores).
  // Vertices are stored relative to the mesh's bounds centre, so float precision is spent on the
  // building and not on its distance from the world origin. Errors: Embree cannot start or build.
  static Result<EmbreeRenderer> create(const TriangleMesh& mesh);

  EmbreeRenderer(EmbreeRenderer&&) noexcept;
  EmbreeRenderer& operator=(EmbreeRenderer&&) noexcept;
  ~EmbreeRenderer();

  // World bounding box of the mesh (what the default camera is fitted to).
  WorldBox bounds() const;

  // One ray: world origin (metres) and unit direction. The distance is refined in double
  // precision against the plane of the face Embree found. Safe to call from many threads.
  scene::MeshHit trace(const glm::dvec3& originM, const glm::dvec3& direction) const override;

  // Renders every pixel of the camera's image with `threads` threads (0 = all cores), in 16x16
  // tiles handed out in order; the output does not depend on the thread count.
  MeshRenderOutput render(const Camera& camera, int threads = 0, MeshRenderStats* stats = nullptr,
                          EmbreeRays rays = EmbreeRays::Single) const;

  // Seconds create() spent building the scene.
  double buildSeconds() const;

 private:
  struct Scene;
  explicit EmbreeRenderer(std::unique_ptr<Scene> scene);
  std::unique_ptr<Scene> scene_;
};

// The meshes as one Embree scene for scene::SceneRenderer (mergeMeshes first); null when they
// have no triangles. Errors: the merge's, or Embree cannot start or build.
Result<std::unique_ptr<const scene::MeshTracer>> traceMeshes(const std::vector<const TriangleMesh*>& meshes);

}  // namespace nut::meshref
