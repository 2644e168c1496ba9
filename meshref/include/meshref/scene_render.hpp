// meshref/scene_render.hpp — the CPU render of a scene: HNIs placed in the world (each at its
// origin, turned about it) and triangle meshes (complementary meshes, props), drawn into one image
// in which each pixel shows the nearest opaque surface any of them has on its ray.
//
// It is what `nut render` draws on its CPU back-end for a city manifest or an HNI with `--mesh`,
// and how the converter's fidelity tests draw a conversion (HNI + complementary mesh) to compare it
// with its source. The HNIs are ray-cast by nut::HniRayCaster, the meshes ray-traced by Embree
// (embree_renderer.hpp); camera and shading are docs/RENDERING.md's.
//
// Limit: a translucent surface tints only what lies behind it in its own HNI or mesh. Where
// nothing of its own is behind it, the pixel shows the next object's nearest opaque surface
// untinted, or the background. (The GL back-end blends translucent meshes over everything and
// has a narrower limit of its own: docs/GL.md, "Limits".)
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <meshref/embree_renderer.hpp>
#include <meshref/obj.hpp>
#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>

namespace nut::meshref {

// An HNI placed in the world: its root block's minimum corner at originM, its axes turned by
// worldFromRoot about that corner. The image must be valid (nut::validate) and outlive the scene.
struct PlacedHni {
  const Image* image = nullptr;
  glm::dvec3 originM{0.0};
  glm::dmat3 worldFromRoot{1.0};
};

// A rotation about +y by `degrees`, counter-clockwise seen from above (x -> (cos, 0, -sin)): the
// yaw of docs/FORMAT.md and of a city manifest's yaw_deg.
glm::dmat3 yawRotation(double degrees);

// The meshes as one: positions and triangles appended in order, each mesh's materials after the
// previous ones', warnings dropped.
TriangleMesh mergeMeshes(const std::vector<const TriangleMesh*>& meshes);

class SceneRenderer {
 public:
  // Prepares a caster per HNI image and turn (instances of one image with one turn share it: a
  // street of identical houses decodes its house once), a grid over the ground of the HNIs' boxes,
  // and one Embree scene of all the meshes. Errors: Embree cannot start or build.
  static Result<SceneRenderer> create(const std::vector<PlacedHni>& hnis, const std::vector<const TriangleMesh*>& meshes);

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

  SceneRenderer();
  std::vector<std::unique_ptr<HniRayCaster>> casters_;  // stable addresses: instances point at them
  std::vector<Instance> instances_;
  std::unique_ptr<GroundGrid> grid_;
  std::optional<EmbreeRenderer> meshes_;
};

}  // namespace nut::meshref
