// Exact welding of positions (weld.hpp).
#include "weld.hpp"

#include <unordered_map>

namespace nut::converter {

Welded weld(const std::vector<glm::dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  Welded w;
  std::unordered_map<glm::dvec3, std::uint32_t, PositionHash> ids;
  ids.reserve(positions.size());
  std::vector<std::uint32_t> idOf(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    auto [it, inserted] = ids.try_emplace(positions[v], static_cast<std::uint32_t>(w.points.size()));
    if (inserted) w.points.push_back(positions[v]);
    idOf[v] = it->second;
  }
  w.triangles.reserve(triangles.size());
  for (const auto& t : triangles) w.triangles.push_back({idOf[t[0]], idOf[t[1]], idOf[t[2]]});
  return w;
}

}  // namespace nut::converter
