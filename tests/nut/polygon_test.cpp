// triangulatePolygon (nut/polygon.hpp) against what a triangulation of a simple polygon must be,
// checked without the algorithm: n - 2 triangles, each turning the polygon's way and lying inside
// it, their areas adding up to the polygon's (shoelace formula), every corner used. Convex polygons must give the
// fan (0, k, k + 1) around the first corner. Polygons are placed in planes of random
// orientation and read in both windings and from every starting corner.
#include <nut/polygon.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

namespace nut {
namespace {

using Outline = std::vector<glm::dvec2>;

double signedArea(const Outline& o) {
  double twice = 0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    const glm::dvec2 &p = o[i], &q = o[(i + 1) % o.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice;
}

// Even-odd test of a point strictly inside the outline (the test points are triangle centroids).
bool inside(const Outline& o, const glm::dvec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = o.size() - 1; i < o.size(); j = i++)
    if ((o[i].y > p.y) != (o[j].y > p.y) && p.x < (o[j].x - o[i].x) * (p.y - o[i].y) / (o[j].y - o[i].y) + o[i].x)
      in = !in;
  return in;
}

// A plane of random orientation and position: outline point (x, y) -> origin + x e1 + y e2.
struct Plane {
  glm::dvec3 origin, e1, e2;
  glm::dvec3 at(const glm::dvec2& p) const { return origin + p.x * e1 + p.y * e2; }
};

Plane randomPlane(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const glm::dvec3 a = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
  glm::dvec3 b = glm::dvec3(n(rng), n(rng), n(rng));
  b = glm::normalize(b - glm::dot(a, b) * a);
  return {glm::dvec3(n(rng), n(rng), n(rng)) * 100.0, a, b};
}

// Checks the triangulation of `outline` (counter-clockwise in its plane) read from corner `start`,
// in its own winding or reversed, placed in `plane`.
void expectTriangulates(const Outline& ccw, const Plane& plane, std::size_t start, bool reversed,
                        const std::string& what) {
  Outline o;
  for (std::size_t k = 0; k < ccw.size(); ++k) {
    const std::size_t i = reversed ? (start + ccw.size() - k) % ccw.size() : (start + k) % ccw.size();
    o.push_back(ccw[i]);
  }
  std::vector<glm::dvec3> corners;
  for (const glm::dvec2& p : o) corners.push_back(plane.at(p));
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangulatePolygon(corners, triangles);
  ASSERT_EQ(triangles.size(), o.size() - 2) << what;
  const double area = signedArea(o);
  double sum = 0;
  std::vector<bool> used(o.size(), false);
  for (const auto& t : triangles) {
    for (std::uint32_t c : t) used[c] = true;
    const Outline tri{o[t[0]], o[t[1]], o[t[2]]};
    const double a = signedArea(tri);
    EXPECT_GT(a * area, 0.0) << what << ": triangle " << t[0] << " " << t[1] << " " << t[2] << " turns the wrong way";
    EXPECT_TRUE(inside(o, (tri[0] + tri[1] + tri[2]) / 3.0))
        << what << ": triangle " << t[0] << " " << t[1] << " " << t[2] << " lies outside the polygon";
    sum += a;
  }
  EXPECT_NEAR(sum, area, 1e-9 * std::abs(area)) << what;
  // No corner left out: one in the middle of a straight run is shared with the neighbouring face,
  // and leaving it out would open a T-junction there.
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << what;
}

Outline regular(int n) {
  Outline o;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    o.emplace_back(std::cos(a), std::sin(a));
  }
  return o;
}

TEST(TriangulatePolygon, ConvexPolygonsGiveTheFanOfTheFirstCorner) {
  std::mt19937 rng(7);
  for (int n = 3; n <= 12; ++n)
    for (bool reversed : {false, true}) {
      const Plane plane = randomPlane(rng);
      std::vector<glm::dvec3> corners;
      Outline o = regular(n);
      if (reversed) std::reverse(o.begin(), o.end());
      for (const glm::dvec2& p : o) corners.push_back(plane.at(p));
      std::vector<std::array<std::uint32_t, 3>> triangles;
      triangulatePolygon(corners, triangles);
      ASSERT_EQ(triangles.size(), static_cast<std::size_t>(n - 2));
      for (std::uint32_t k = 1; k + 1 < static_cast<std::uint32_t>(n); ++k)
        EXPECT_EQ(triangles[k - 1], (std::array<std::uint32_t, 3>{0, k, k + 1})) << n << " corners";
    }
}

TEST(TriangulatePolygon, NonConvexPolygonsFromEveryCornerBothWaysInAnyPlane) {
  // An L (a floor plan), a U, a comb of five teeth, a five-pointed star and a spiral-like zigzag.
  const Outline l{{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 5}, {0, 5}};
  const Outline u{{0, 0}, {5, 0}, {5, 4}, {4, 4}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  Outline comb{{0, 0}, {10, 0}};
  for (int t = 4; t >= 0; --t) {
    comb.emplace_back(2 * t + 2, 3);
    comb.emplace_back(2 * t + 1.5, 3);
    comb.emplace_back(2 * t + 1.5, 1);
    comb.emplace_back(2 * t + 0.5, 1);
  }
  comb.emplace_back(0, 3);
  Outline star;
  for (int i = 0; i < 10; ++i) {
    const double a = std::numbers::pi * i / 5, r = i % 2 == 0 ? 1.0 : 0.38;
    star.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const Outline zigzag{{0, 0}, {8, 0}, {8, 1}, {1, 1}, {1, 2}, {8, 2}, {8, 3}, {1, 3}, {1, 4}, {8, 4}, {8, 5}, {0, 5}};
  std::mt19937 rng(11);
  for (const auto& [name, outline] : {std::pair{"L", l}, std::pair{"U", u}, std::pair{"comb", comb},
                                      std::pair{"star", star}, std::pair{"zigzag", zigzag}}) {
    ASSERT_GT(signedArea(outline), 0) << name;
    for (std::size_t start = 0; start < outline.size(); ++start)
      for (bool reversed : {false, true})
        expectTriangulates(outline, randomPlane(rng), start, reversed,
                           std::string(name) + " from corner " + std::to_string(start) + (reversed ? " reversed" : ""));
  }
}

TEST(TriangulatePolygon, RandomStarShapedPolygons) {
  // Corners at increasing angles and random distances from a centre: simple polygons with reflex
  // corners anywhere, up to 300 of them.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> radius(0.1, 1.0);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 4 + trial * 5;
    Outline o;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, r = radius(rng);
      o.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    expectTriangulates(o, randomPlane(rng), static_cast<std::size_t>(trial) % o.size(), trial % 2 == 1,
                       "star of " + std::to_string(n) + " corners, trial " + std::to_string(trial));
  }
}

TEST(TriangulatePolygon, AHoleJoinedByABridgeStaysOpen) {
  // A 10 x 10 square around a 4 x 4 hole, as OBJ writes a face with a hole: the outline, a bridge
  // from (0, 0) to (3, 3), the hole's outline the other way round, and back over the bridge. The
  // even-odd test sees the bridge twice, so a triangle over the hole counts as outside.
  const Outline keyhole{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}, {3, 3}, {3, 7}, {7, 7}, {7, 3}, {3, 3}};
  ASSERT_DOUBLE_EQ(signedArea(keyhole), 84.0);
  std::mt19937 rng(5);
  for (std::size_t start = 0; start < keyhole.size(); ++start)
    for (bool reversed : {false, true})
      expectTriangulates(keyhole, randomPlane(rng), start, reversed,
                         "from corner " + std::to_string(start) + (reversed ? " reversed" : ""));
}

TEST(TriangulatePolygon, CollinearCornersGiveNoFlatTriangle) {
  // A rectangle with a corner in the middle of its bottom edge: the fan's first triangle would be
  // flat; the ears are cut elsewhere.
  const Outline o{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}};
  std::mt19937 rng(3);
  for (std::size_t start = 0; start < o.size(); ++start)
    expectTriangulates(o, randomPlane(rng), start, false, "from corner " + std::to_string(start));
}

TEST(TriangulatePolygon, DegenerateInputStillGivesNMinusTwoTriangles) {
  // All corners on one line, or fewer than three: no area to cover, no crash, the count OBJ
  // readers expect.
  std::vector<std::array<std::uint32_t, 3>> triangles{{7, 7, 7}};  // replaced, not appended to
  triangulatePolygon(std::vector<glm::dvec3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, triangles);
  EXPECT_EQ(triangles.size(), 2u);
  triangulatePolygon(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}}, triangles);
  EXPECT_TRUE(triangles.empty());
  // A bow tie (self-intersecting): every corner is used, nothing crashes.
  triangulatePolygon(std::vector<glm::dvec3>{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}, triangles);
  EXPECT_EQ(triangles.size(), 2u);
}

}  // namespace
}  // namespace nut
