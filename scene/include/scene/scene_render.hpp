// scene/scene_render.hpp — the CPU render of a scene: HNIs placed in the world (each at its
// origin, turned about it) and triangle meshes (complementary meshes, props), drawn into one image
// in which each pixel shows the nearest opaque surface any of them has on its ray.
//
// It is what `nut render` draws on its CPU back-end for a city manifest or an HNI with `--mesh`,
// and how the converter's fidelity tests draw a conversion (HNI + complementary mesh) to compare it
// with its source. The HNIs are ray-cast by nut::HniRayCaster, the meshes by a MeshTracer (the
// Embree reference, meshref/embree_renderer.hpp, in builds that have it); camera and shading are
// docs/RENDERING.md's.
//
// Limit: a translucent surface tints only what lies behind it in its own HNI or mesh. Where
// nothing of its own is behind it, the pixel shows the next object's nearest opaque surface
// untinted, or the background. (The GL back-end blends translucent meshes over everything and
// has a narrower limit of its own: docs/GL.md, "Limits".)
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>
#include <scene/scene.hpp>

namespace nut::scene {

// What one ray found in the meshes.
struct MeshHit {
  bool hit = false;  // an opaque face was reached
  double distanceM = std::numeric_limits<double>::infinity();  // along the ray to that face
  glm::dvec3 normal{0.0};            // unit geometric normal of that face, facing the ray
  std::uint32_t triangle = 0;        // index of that face in the mesh
  std::array<std::uint8_t, 3> colour = kBackground;  // shaded, translucent faces composited
};

// A ray tracer over the scene's meshes, shading as docs/RENDERING.md says.
class MeshTracer {
 public:
  virtual ~MeshTracer() = default;
  // One ray: world origin (metres) and unit direction. Safe to call from many threads.
  virtual MeshHit trace(const glm::dvec3& originM, const glm::dvec3& direction) const = 0;
};

class SceneRenderer {
 public:
  // Prepares a caster per HNI image and turn (instances of one image with one turn share it: a
  // street of identical houses decodes its house once) and a grid over the ground of the HNIs'
  // boxes; the meshes, if any, are traced by `meshes`.
  SceneRenderer(const std::vector<PlacedHni>& hnis, std::unique_ptr<const MeshTracer> meshes);

  SceneRenderer(SceneRenderer&&) noexcept;
  SceneRenderer& operator=(SceneRenderer&&) noexcept;
  ~SceneRenderer();

  // One ray: the nearest opaque hit of any HNI or mesh (its distance, normal and colour), the cell
  // visits of every HNI the ray was cast into, and capped when one of them capped it. A ray an HNI
  // capped is drawn in kCappedColour unless something opaque lies in front of that HNI's box.
  // The ray walks the ground grid front to back and is cast only into HNIs whose box it meets
  // before the nearest hit so far, so that a frame costs what its pixels see, not pixels times
  // buildings. Thread-safe.
  RayResult trace(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                  const RayCastOptions& options) const;

  // renderRays (nut/raycast.hpp) with trace().
  RenderOutput render(const Camera& camera, const RayCastOptions& options, int threads = 0,
                      RenderStats* stats = nullptr) const;

 private:
  struct Instance;
  class GroundGrid;

  std::vector<std::unique_ptr<HniRayCaster>> casters_;  // stable addresses: instances point at them
  std::vector<Instance> instances_;
  std::unique_ptr<GroundGrid> grid_;
  std::unique_ptr<const MeshTracer> meshes_;
};

}  // namespace nut::scene
