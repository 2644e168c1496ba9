// Stretching a hierarchy along its root's axes (converter/scale_hierarchy.hpp).
#include <converter/scale_hierarchy.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace nut::converter {

namespace {

using Factors = std::array<double, 3>;

class Stretcher {
 public:
  Stretcher(const Hierarchy& source, Hierarchy& out) : source_(source), out_(out) {}

  // The id in `out` of source block `id` stretched by `f` in its own frame.
  Result<BlockId> stretch(BlockId id, const Factors& f) {
    const auto key = std::make_pair(id, f);
    if (auto it = done_.find(key); it != done_.end()) return it->second;
    Block b = source_.blocks[id];
    for (std::size_t a = 0; a < 3; ++a)
      for (double& bound : b.boundsM[a]) bound *= f[a];
    // A plane n . p <= d through the stretch p' = F p is (F^-1 n) . p' <= d, normalised.
    for (PlaneCut& cut : b.cuts)
      for (CutPlane& plane : cut.planes) {
        const glm::dvec3 n = plane.normal / glm::dvec3(f[0], f[1], f[2]);
        const double length = glm::length(n);
        plane = {n / length, plane.offsetM / length};
      }
    for (Redirection& r : b.redirections) {
      if (r.rotation.yaw != 0 && std::abs(f[0] - f[2]) > 1e-12 * std::max(f[0], f[2]))
        return Error{"block " + std::to_string(id) +
                     ": a redirection turned by a yaw cannot be stretched differently along x and z"};
      // Target axis c lies along parent axis p[c] (the cube rotation's column c); a yaw turns
      // x and z into each other, which stretch alike here.
      const glm::mat<3, 3, int> cube = cubeRotationMatrix(r.rotation.cube);
      Factors targetFactors{};
      for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
          if (cube[c][row] != 0) targetFactors[static_cast<std::size_t>(c)] = f[static_cast<std::size_t>(row)];
      for (int a = 0; a < 3; ++a) r.offsetM[a] *= f[static_cast<std::size_t>(a)];
      auto target = stretch(r.target, targetFactors);
      if (!target) return target.error();
      r.target = *target;
    }
    b.lodFootprintM *= *std::min_element(f.begin(), f.end());
    const BlockId newId = out_.addBlock(std::move(b));
    done_.emplace(key, newId);
    return newId;
  }

 private:
  const Hierarchy& source_;
  Hierarchy& out_;
  std::map<std::pair<BlockId, Factors>, BlockId> done_;
};

}  // namespace

Result<Hierarchy> scaleHierarchy(const Hierarchy& h, const glm::dvec3& factors) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(factors[a]) || factors[a] <= 0)
      return Error{"scale factors must be positive and finite, got " + std::to_string(factors[a])};
  if (!h.textures.empty()) return Error{"a hierarchy with texture infos cannot be stretched"};
  if (Status s = checkHierarchy(h); !s) return s.error();
  Hierarchy out;
  out.materials = h.materials;
  Stretcher stretcher(h, out);
  auto root = stretcher.stretch(h.root, {factors.x, factors.y, factors.z});
  if (!root) return root.error();
  out.root = *root;
  return out;
}

}  // namespace nut::converter
