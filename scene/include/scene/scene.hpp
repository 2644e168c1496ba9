// scene/scene.hpp — a scene to draw: one HNI, or every building of a city manifest (docs/CITY.md:
// its HNI placed and turned as the manifest says, and its complementary mesh), plus extra meshes;
// and the world box of their content, which the default camera fits.
//
// This is what `nut render` draws on either back-end, and what a viewer loads; it needs the core
// and this module only (no converter, Embree or GL).
#pragma once

#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/png_io.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::scene {

// An HNI placed in the world: its root block's minimum corner at originM, its axes turned by
// worldFromRoot about that corner. The image must be valid (nut::validate) and outlive its users.
struct PlacedHni {
  const Image* image = nullptr;
  glm::dvec3 originM{0.0};
  glm::dmat3 worldFromRoot{1.0};
};

// A rotation about +y by `degrees`, counter-clockwise seen from above (x -> (cos, 0, -sin)): the
// yaw of docs/FORMAT.md and of a city manifest's yaw_deg.
glm::dmat3 yawRotation(double degrees);

// A coarser level of a mesh, and the largest distance from the mesh's surface to it.
struct CoarserMesh {
  TriangleMesh mesh;
  double errorM = 0;
};

// Meshes whose coarser levels span under this many pixels at their nearest point stand in for
// them (meshPointers with a camera).
inline constexpr double kMeshLevelErrorPx = 1.0;

// The largest error a level of a mesh inside `box` may have for this camera: kMeshLevelErrorPx
// pixels at the box's nearest point to the eye (0 for an eye inside it). A level stands in for
// the mesh when its error is below this, so each renderer (the cpu scene, the viewers) picks the
// same level.
double meshLevelErrorAllowedM(const WorldBox& box, const Camera& camera);

// The level of a mesh inside `box` that the camera draws: 0 the mesh itself, k its k-th of
// `levels` (finest first, each with its errorM), the coarsest whose error is under
// meshLevelErrorAllowedM.
template <class Levels>
std::size_t meshLevel(const Levels& levels, const WorldBox& box, const Camera& camera) {
  const double allowedM = meshLevelErrorAllowedM(box, camera);
  std::size_t level = 0;
  for (const auto& coarser : levels) {
    if (!(coarser.errorM < allowedM)) break;
    ++level;
  }
  return level;
}

struct Scene {
  std::vector<PngFile> files;          // each HNI file once, in the order first named
  std::vector<PlacedHni> hnis;         // in the manifest's order; their images point into `files`,
                                       // which a move of the scene keeps where they are
  std::vector<TriangleMesh> meshes;    // complementary meshes, then the extra meshes
  std::vector<std::vector<CoarserMesh>> coarser;  // per mesh, its levels (complement_levels), finest first
  WorldBox bounds;                     // solid content of the HNIs and the meshes' vertices
  std::vector<std::string> warnings;   // from the mesh files, one line each naming the file

  // Every mesh at full detail.
  std::vector<const TriangleMesh*> meshPointers() const;
  // Every mesh as the camera sees it: the coarsest level whose error, seen from the eye at the
  // nearest point of the mesh's box, spans under kMeshLevelErrorPx pixels (a mesh around the eye
  // at full detail), as the HNIs' visual summaries stand in for far blocks under --lod auto.
  std::vector<const TriangleMesh*> meshPointers(const Camera& camera) const;
};

// Why loading failed: a file could not be read as a PNG or OBJ at all, or it was read and is not
// a valid HNI, manifest or mesh.
enum class LoadFailure { unreadable, invalid };

// Loads `input`, an HNI (PNG) or a city manifest (a file ending in .json, any case), and the
// meshes at meshPaths. Every HNI is validated; a file placed several times is read once and its
// instances share the image. Errors name the file, and the manifest's building where there is
// one; `failure`, when given, says which kind of failure it was.
Result<Scene> loadScene(const std::string& input, const std::vector<std::string>& meshPaths,
                        LoadFailure* failure = nullptr);

}  // namespace nut::scene
