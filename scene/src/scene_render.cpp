// The CPU render of HNIs and meshes in one image (scene/scene_render.hpp).
#include <scene/scene_render.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

namespace nut::scene {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where the ray is inside the box: [t0, t1] with t0 >= 0, or t0 > t1 when it misses it.
std::pair<double, double> clipToBox(const WorldBox& box, const glm::dvec3& origin, const glm::dvec3& direction) {
  double t0 = 0, t1 = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (direction[a] == 0) {
      if (origin[a] < box.min[a] || origin[a] > box.max[a]) return {1, 0};
      continue;
    }
    double near = (box.min[a] - origin[a]) / direction[a], far = (box.max[a] - origin[a]) / direction[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return {t0, t1};
}

// The HNIs a ray has been cast into, so that one lying in several cells of the grid is cast once
// (when more than fit, an HNI may be cast again: the same answer, only time lost).
class CastAlready {
 public:
  bool contains(std::uint32_t instance) const {
    return std::find(ids_.begin(), ids_.begin() + static_cast<std::ptrdiff_t>(count_), instance) !=
           ids_.begin() + static_cast<std::ptrdiff_t>(count_);
  }
  void add(std::uint32_t instance) {
    if (count_ < ids_.size()) ids_[count_++] = instance;
  }

 private:
  std::array<std::uint32_t, 32> ids_{};
  std::size_t count_ = 0;
};

}  // namespace

// An HNI where a placed HNI stands: its caster was made for another instance's origin, and the
// ray is moved by `shift` (that origin minus this one) before it is cast.
struct SceneRenderer::Instance {
  const HniRayCaster* caster = nullptr;
  glm::dvec3 shift{0.0};
  WorldBox box;  // world box of this instance's root block
};

// The instances binned on a uniform grid over the ground (x and z) their boxes cover, about two
// cells per instance, and walked cell by cell along a ray (Amanatides and Woo's traversal).
class SceneRenderer::GroundGrid {
 public:
  explicit GroundGrid(const std::vector<Instance>& instances) {
    if (instances.empty()) return;
    bounds_ = instances.front().box;
    for (const Instance& i : instances) bounds_.min = glm::min(bounds_.min, i.box.min), bounds_.max = glm::max(bounds_.max, i.box.max);
    const glm::dvec3 extent = bounds_.size();
    const double side = std::sqrt(std::max(extent.x * extent.z, 1e-12) / (2.0 * static_cast<double>(instances.size())));
    columns_ = std::clamp(static_cast<int>(std::ceil(extent.x / side)), 1, kMaxCells);
    rows_ = std::clamp(static_cast<int>(std::ceil(extent.z / side)), 1, kMaxCells);
    cellSize_ = {std::max(extent.x / columns_, 1e-9), std::max(extent.z / rows_, 1e-9)};
    cells_.resize(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_));
    for (std::size_t n = 0; n < instances.size(); ++n) {
      const WorldBox& b = instances[n].box;
      for (int z = rowOf(b.min.z); z <= rowOf(b.max.z); ++z)
        for (int x = columnOf(b.min.x); x <= columnOf(b.max.x); ++x) cells_[index(x, z)].push_back(static_cast<std::uint32_t>(n));
    }
  }

  // Calls visit(instances of the cell, ray parameter where the ray leaves the cell) for the cells
  // the ray crosses, nearest first, until visit returns false.
  template <typename Visit>
  void walk(const glm::dvec3& origin, const glm::dvec3& direction, const Visit& visit) const {
    if (cells_.empty()) return;
    const auto [t0, t1] = clipToBox(bounds_, origin, direction);
    if (!(t0 <= t1)) return;
    const glm::dvec3 start = origin + t0 * direction;
    int x = columnOf(start.x), z = rowOf(start.z);
    // Ray parameters of the next cell face along x and z, and between two of them.
    const auto next = [](double o, double d, double lo, double size, int i) {
      return d == 0 ? kInfinity : (lo + (i + (d > 0 ? 1 : 0)) * size - o) / d;
    };
    double nextX = next(origin.x, direction.x, bounds_.min.x, cellSize_.x, x);
    double nextZ = next(origin.z, direction.z, bounds_.min.z, cellSize_.y, z);
    const double deltaX = direction.x == 0 ? kInfinity : cellSize_.x / std::abs(direction.x);
    const double deltaZ = direction.z == 0 ? kInfinity : cellSize_.y / std::abs(direction.z);
    while (true) {
      const double exit = std::min({nextX, nextZ, t1});
      if (!visit(cells_[index(x, z)], exit) || exit >= t1) return;
      if (nextX <= nextZ) {
        x += direction.x > 0 ? 1 : -1, nextX += deltaX;
        if (x < 0 || x >= columns_) return;
      } else {
        z += direction.z > 0 ? 1 : -1, nextZ += deltaZ;
        if (z < 0 || z >= rows_) return;
      }
    }
  }

 private:
  static constexpr int kMaxCells = 1024;  // per side
  int columnOf(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - bounds_.min.x) / cellSize_.x)), 0, columns_ - 1);
  }
  int rowOf(double z) const { return std::clamp(static_cast<int>(std::floor((z - bounds_.min.z) / cellSize_.y)), 0, rows_ - 1); }
  std::size_t index(int x, int z) const {
    return static_cast<std::size_t>(z) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(x);
  }

  WorldBox bounds_;
  int columns_ = 0, rows_ = 0;
  glm::dvec2 cellSize_{1.0};  // along x and z
  std::vector<std::vector<std::uint32_t>> cells_;
};

SceneRenderer::SceneRenderer(SceneRenderer&&) noexcept = default;
SceneRenderer& SceneRenderer::operator=(SceneRenderer&&) noexcept = default;
SceneRenderer::~SceneRenderer() = default;

SceneRenderer::SceneRenderer(const std::vector<PlacedHni>& hnis, std::unique_ptr<const MeshTracer> meshes)
    : meshes_(std::move(meshes)) {
  // Casters by image, each with the turn it was made for.
  std::map<const Image*, std::vector<std::pair<glm::dmat3, const HniRayCaster*>>> made;
  for (const PlacedHni& hni : hnis) {
    auto& forImage = made[hni.image];
    const auto same = std::find_if(forImage.begin(), forImage.end(), [&](const auto& m) { return m.first == hni.worldFromRoot; });
    Instance instance;
    if (same != forImage.end()) {
      instance.caster = same->second;
    } else {
      casters_.push_back(std::make_unique<HniRayCaster>(*hni.image, hni.originM, hni.worldFromRoot));
      instance.caster = casters_.back().get();
      forImage.emplace_back(hni.worldFromRoot, instance.caster);
    }
    instance.shift = instance.caster->originM() - hni.originM;
    const WorldBox box = instance.caster->bounds();
    instance.box = {box.min - instance.shift, box.max - instance.shift};
    instances_.push_back(instance);
  }
  grid_ = std::make_unique<GroundGrid>(instances_);
}

RayResult SceneRenderer::trace(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                               const RayCastOptions& options) const {
  RayResult nearest;
  nearest.distanceM = kInfinity;
  CastAlready cast;
  grid_->walk(originM, direction, [&](const std::vector<std::uint32_t>& cell, double cellExit) {
    for (const std::uint32_t n : cell) {
      const Instance& instance = instances_[n];
      const auto [entry, exit] = clipToBox(instance.box, originM, direction);
      if (!(entry <= exit) || entry >= nearest.distanceM || cast.contains(n)) continue;  // a miss, behind, or done
      cast.add(n);
      const RayResult r = instance.caster->trace(originM + instance.shift, direction, pixelAngle, options);
      nearest.iterations += r.iterations;
      nearest.capped = nearest.capped || r.capped;
      // A capped ray is never silent: it shows at the HNI's box unless something is in front.
      const double distance = r.capped ? entry : r.hit ? r.distanceM : kInfinity;
      if (distance < nearest.distanceM) {
        nearest.hit = r.hit, nearest.distanceM = distance, nearest.normal = r.normal, nearest.colour = r.colour;
      }
    }
    return nearest.distanceM > cellExit;  // an HNI only in later cells starts beyond this cell
  });
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

}  // namespace nut::scene
