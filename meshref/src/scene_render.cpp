// The CPU render of HNIs and meshes in one image (meshref/scene_render.hpp).
#include <meshref/scene_render.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>


namespace nut::meshref {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where the ray enters the box (0 when it starts inside), or +infinity when it misses it.
double entryDistance(const WorldBox& box, const glm::dvec3& origin, const glm::dvec3& direction) {
  double tNear = 0, tFar = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (direction[a] == 0) {
      if (origin[a] < box.min[a] || origin[a] > box.max[a]) return kInfinity;
      continue;
    }
    double t0 = (box.min[a] - origin[a]) / direction[a], t1 = (box.max[a] - origin[a]) / direction[a];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
  }
  return tNear <= tFar ? tNear : kInfinity;
}

}  // namespace

glm::dmat3 yawRotation(double degrees) {
  const double r = degrees * std::numbers::pi / 180;
  const double c = std::cos(r), s = std::sin(r);
  return glm::dmat3(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));  // columns
}

TriangleMesh mergeMeshes(const std::vector<const TriangleMesh*>& meshes) {
  TriangleMesh out;
  out.bounds = {glm::dvec3(kInfinity), glm::dvec3(-kInfinity)};
  for (const TriangleMesh* mesh : meshes) {
    const auto firstVertex = static_cast<std::uint32_t>(out.positions.size());
    const auto firstMaterial = static_cast<std::uint32_t>(out.materials.size());
    out.positions.insert(out.positions.end(), mesh->positions.begin(), mesh->positions.end());
    for (const auto& t : mesh->triangles) out.triangles.push_back({t[0] + firstVertex, t[1] + firstVertex, t[2] + firstVertex});
    for (std::uint32_t m : mesh->triangleMaterial) out.triangleMaterial.push_back(m + firstMaterial);
    out.materials.insert(out.materials.end(), mesh->materials.begin(), mesh->materials.end());
    if (mesh->triangles.empty()) continue;
    out.bounds.min = glm::min(out.bounds.min, mesh->bounds.min);
    out.bounds.max = glm::max(out.bounds.max, mesh->bounds.max);
  }
  if (out.triangles.empty()) out.bounds = {};
  return out;
}

Result<SceneRenderer> SceneRenderer::create(const std::vector<PlacedHni>& hnis, const std::vector<const TriangleMesh*>& meshes) {
  SceneRenderer scene;
  for (const PlacedHni& hni : hnis) {
    scene.casters_.push_back(std::make_unique<HniRayCaster>(*hni.image, hni.originM, hni.worldFromRoot));
    scene.boxes_.push_back(scene.casters_.back()->bounds());
  }
  TriangleMesh merged = mergeMeshes(meshes);
  if (!merged.triangles.empty()) {
    auto renderer = EmbreeRenderer::create(merged);
    if (!renderer) return renderer.error();
    scene.meshes_.emplace(std::move(*renderer));
  }
  return scene;
}

RayResult SceneRenderer::trace(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                               const RayCastOptions& options) const {
  RayResult nearest;
  nearest.distanceM = kInfinity;
  for (std::size_t i = 0; i < casters_.size(); ++i) {
    const double entry = entryDistance(boxes_[i], originM, direction);
    if (entry >= nearest.distanceM) continue;  // a miss, or behind what is already hit
    const RayResult r = casters_[i]->trace(originM, direction, pixelAngle, options);
    nearest.iterations += r.iterations;
    nearest.capped = nearest.capped || r.capped;
    // A capped ray is never silent: it shows at the HNI's box unless something is in front.
    const double distance = r.capped ? entry : r.hit ? r.distanceM : kInfinity;
    if (distance < nearest.distanceM) {
      nearest.hit = r.hit, nearest.distanceM = distance, nearest.normal = r.normal, nearest.colour = r.colour;
    }
  }
  if (meshes_) {
    const MeshHit h = meshes_->trace(originM, direction);
    if (h.hit && h.distanceM < nearest.distanceM) {
      nearest.hit = true, nearest.distanceM = h.distanceM, nearest.normal = h.normal, nearest.colour = h.colour;
    }
  }
  if (!nearest.hit) nearest.distanceM = 0;  // as HniRayCaster::trace leaves it
  return nearest;
}

RenderOutput SceneRenderer::render(const Camera& camera, const RayCastOptions& options, int threads, RenderStats* stats) const {
  return renderRays(
      camera, [&](const glm::dvec3& eye, const glm::dvec3& dir, double pixelAngle) { return trace(eye, dir, pixelAngle, options); },
      threads, stats);
}

}  // namespace nut::meshref
