// The complements' levels of detail (converter/mesh_lod.hpp): fewer triangles at each level, the
// error the converter stores checked by a brute-force distance written here (point to triangle,
// no acceleration structure), colour outlines kept, and a flat surface decimated without error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include <converter/mesh_lod.hpp>

namespace nut::converter {
namespace {

// Distance from p to triangle abc, by the closest point on the triangle (Ericson, Real-Time
// Collision Detection, 5.1.5), in double.
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + d1 / (d1 - d3) * ab));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + d2 / (d2 - d6) * ac));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return glm::length(p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)));
  const double denominator = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denominator) + ac * (vc * denominator)));
}

// surfaceDistance, by brute force over every pair of sample and triangle.
double bruteForceDistance(const TriangleMesh& from, const TriangleMesh& to) {
  double worst = 0;
  for (const glm::dvec3& p : surfaceSamples(from)) {
    double nearest = INFINITY;
    for (const auto& t : to.triangles)
      nearest = std::min(nearest, pointTriangleDistance(p, to.positions[t[0]], to.positions[t[1]], to.positions[t[2]]));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// An n x n grid of quads over [0, size]^2 in the xz plane at height y(x, z), each quad two
// triangles; material 1 where x > split, 0 elsewhere. Offset by `at` (city coordinates).
template <typename Height>
TriangleMesh grid(int n, double size, double split, const glm::dvec3& at, const Height& y) {
  TriangleMesh m;
  m.name = "grid";
  m.materials = {{200, 60, 60, 255, 0}, {60, 60, 200, 255, 0}};
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, z = size * j / n;
      m.positions.push_back(at + glm::dvec3(x, y(x, z), z));
    }
  const auto v = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint16_t material = size * (i + 0.5) / n > split ? 1 : 0;
      m.triangles.push_back({v(i, j), v(i, j + 1), v(i + 1, j)});
      m.triangles.push_back({v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)});
      m.triangleMaterial.insert(m.triangleMaterial.end(), 2, material);
    }
  return m;
}

TEST(MeshLod, AFlatWallDecimatesWithoutErrorAndKeepsItsColourOutline) {
  const glm::dvec3 city(683000.0, 400.0, 247000.0);
  const TriangleMesh wall = grid(24, 12.0, 5.0, city, [](double, double) { return 0.0; });
  const std::vector<MeshLevel> levels = meshLevels(wall);
  ASSERT_FALSE(levels.empty());
  const TriangleMesh& first = levels.front().mesh;
  EXPECT_LT(first.triangles.size(), wall.triangles.size() / 10) << "a flat wall needs few triangles";
  EXPECT_LT(levels.front().errorM, 1e-6);
  EXPECT_NEAR(first.area(), wall.area(), 1e-6 * wall.area());
  // Every triangle keeps to its material's side of the outline at x = 5 m.
  for (std::size_t t = 0; t < first.triangles.size(); ++t)
    for (const std::uint32_t v : first.triangles[t]) {
      const double x = first.positions[v].x - city.x;
      if (first.triangleMaterial[t] == 0) {
        EXPECT_LE(x, 5.0 + 1e-9);
      } else {
        EXPECT_GE(x, 5.0 - 1e-9);
      }
    }
}

TEST(MeshLod, EachLevelHasFewerTrianglesAndItsErrorIsTheMeasuredOne) {
  // A rough roof: 30 cm waves over 20 m.
  const TriangleMesh roof = grid(40, 20.0, 20.0, glm::dvec3(0.0),
                                 [](double x, double z) { return 0.3 * std::sin(0.9 * x) * std::cos(0.7 * z); });
  const std::vector<MeshLevel> levels = meshLevels(roof);
  ASSERT_GE(levels.size(), 2u);
  std::size_t previous = roof.triangles.size();
  double previousError = 0;
  for (const MeshLevel& level : levels) {
    std::printf("rough roof of %zu triangles: a level of %zu, error %.4f m\n", roof.triangles.size(),
                level.mesh.triangles.size(), level.errorM);
    EXPECT_LE(static_cast<double>(level.mesh.triangles.size()), kLevelShrink * static_cast<double>(previous));
    previous = level.mesh.triangles.size();
    EXPECT_NEAR(level.errorM, std::max(bruteForceDistance(roof, level.mesh), bruteForceDistance(level.mesh, roof)),
                1e-9);
    EXPECT_GE(level.errorM, previousError);
    previousError = level.errorM;
  }
  // The first level's tolerance (5 cm) holds at the vertices; between them the error stays small.
  EXPECT_LT(levels.front().errorM, 0.1);
}

TEST(MeshLod, AMeshWithNothingToRemoveHasNoLevels) {
  TriangleMesh one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  one.triangleMaterial = {0};
  one.materials = {kDefaultMaterial};
  EXPECT_TRUE(meshLevels(one).empty());
  EXPECT_TRUE(meshLevels(TriangleMesh{}).empty());
}

}  // namespace
}  // namespace nut::converter
