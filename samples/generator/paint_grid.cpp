// Painted boxes to a greedy-merged surface (paint_grid.hpp).
#include "paint_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>

namespace nut::samples {

namespace {

// Coordinates that differ by less than this are one (the OBJ writer's lattice).
constexpr double kEpsilon = 5e-5;

std::vector<double> unique(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > kEpsilon) out.push_back(x);
  return out;
}

int indexOf(const std::vector<double>& coords, double x) {
  return static_cast<int>(std::lower_bound(coords.begin(), coords.end(), x - kEpsilon) - coords.begin());
}

}  // namespace

void PaintGrid::box(const glm::dvec3& lo, const glm::dvec3& hi, int material) {
  boxes_.push_back({glm::min(lo, hi), glm::max(lo, hi), material});
}

void PaintGrid::emit(ObjBuilder& out) const {
  std::array<std::vector<double>, 3> coords;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> all;
    for (const Box& b : boxes_) {
      all.push_back(b.lo[a]);
      all.push_back(b.hi[a]);
    }
    coords[static_cast<std::size_t>(a)] = unique(std::move(all));
  }
  const std::array<int, 3> n{static_cast<int>(coords[0].size()) - 1, static_cast<int>(coords[1].size()) - 1,
                             static_cast<int>(coords[2].size()) - 1};
  const auto at = [&](int x, int y, int z) {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(n[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(z));
  };
  std::vector<int> cells(static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(n[2]), PaintGrid::kCarve);
  for (const Box& b : boxes_) {
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[static_cast<std::size_t>(a)] = indexOf(coords[static_cast<std::size_t>(a)], b.lo[a]);
      hi[static_cast<std::size_t>(a)] = indexOf(coords[static_cast<std::size_t>(a)], b.hi[a]);
    }
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x) cells[at(x, y, z)] = b.material;
  }
  const auto cell = [&](std::array<int, 3> c) {
    for (int a = 0; a < 3; ++a)
      if (c[static_cast<std::size_t>(a)] < 0 || c[static_cast<std::size_t>(a)] >= n[static_cast<std::size_t>(a)]) return PaintGrid::kCarve;
    return cells[at(c[0], c[1], c[2])];
  };

  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const int nu = n[static_cast<std::size_t>(u)], nv = n[static_cast<std::size_t>(v)];
    std::vector<int> face(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv));
    for (int k = 0; k <= n[static_cast<std::size_t>(a)]; ++k) {
      // +(m + 1): solid below, face towards +a; -(m + 1): solid above, face towards -a.
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
          std::array<int, 3> below{}, above{};
          below[static_cast<std::size_t>(a)] = k - 1;
          above[static_cast<std::size_t>(a)] = k;
          below[static_cast<std::size_t>(u)] = above[static_cast<std::size_t>(u)] = i;
          below[static_cast<std::size_t>(v)] = above[static_cast<std::size_t>(v)] = j;
          const int mb = cell(below), ma = cell(above);
          face[static_cast<std::size_t>(i + nu * j)] = (mb >= 0) == (ma >= 0) ? 0 : mb >= 0 ? mb + 1 : -(ma + 1);
        }
      // Greedy rectangles of equal value.
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
          const int value = face[static_cast<std::size_t>(i + nu * j)];
          if (value == 0) continue;
          int i1 = i + 1;
          while (i1 < nu && face[static_cast<std::size_t>(i1 + nu * j)] == value) ++i1;
          int j1 = j + 1;
          for (; j1 < nv; ++j1) {
            bool row = true;
            for (int x = i; x < i1 && row; ++x) row = face[static_cast<std::size_t>(x + nu * j1)] == value;
            if (!row) break;
          }
          for (int y = j; y < j1; ++y)
            for (int x = i; x < i1; ++x) face[static_cast<std::size_t>(x + nu * y)] = 0;
          const double pa = coords[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
          const double u0 = coords[static_cast<std::size_t>(u)][static_cast<std::size_t>(i)], u1 = coords[static_cast<std::size_t>(u)][static_cast<std::size_t>(i1)];
          const double v0 = coords[static_cast<std::size_t>(v)][static_cast<std::size_t>(j)], v1 = coords[static_cast<std::size_t>(v)][static_cast<std::size_t>(j1)];
          const auto point = [&](double pu, double pv) {
            glm::dvec3 p;
            p[a] = pa;
            p[u] = pu;
            p[v] = pv;
            return p;
          };
          const int material = std::abs(value) - 1;
          if (value > 0) out.quad(point(u0, v0), point(u1, v0), point(u1, v1), point(u0, v1), material);
          else out.quad(point(u0, v0), point(u0, v1), point(u1, v1), point(u1, v0), material);
        }
    }
  }
}

}  // namespace nut::samples
