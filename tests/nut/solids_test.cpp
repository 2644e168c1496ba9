// tests/solids_test.cpp — the 69 cell solids: catalogue and numbering, volumes, and ray hits
// (float and double) checked against the inside test on seeded random rays and on rays along
// axes, faces, edges and corners.
//
// Tolerance: solidContains is exact, but a computed hit point lies on a surface only up to
// rounding. A point within about kBand<T> of the solid's surface may therefore be judged either
// way (classify() calls it Side::Band); kBand is 1e-9 for double and 1e-5 for float, in unit-cube
// units. Rays that only touch the cube (chord shorter than kBand) are checked for a finite hit
// near the solid only.
#include <nut/solids.hpp>
#include <nut/format.hpp>
#include <nut/hierarchy.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace {

using glm::dvec3;
using nut::Solid;
using nut::SolidGroup;

constexpr std::array kGroups{
    SolidGroup::Box,
    SolidGroup::Wedge,
    SolidGroup::Pyramid,
    SolidGroup::InversePyramid,
    SolidGroup::QuarterCylinder,
    SolidGroup::InverseQuarterCylinder,
    SolidGroup::SphereOctant,
    SolidGroup::InverseSphereOctant,
};

Solid solidAt(int index) { return Solid{static_cast<std::uint8_t>(index)}; }

Solid named(const std::string& name) {
  for (int i = 0; i < nut::kSolidCount; ++i) {
    if (nut::solidName(solidAt(i)) == name) return solidAt(i);
  }
  ADD_FAILURE() << "no solid named " << name;
  return {};
}

// ---------------------------------------------------------------------------------------------
// Catalogue

TEST(SolidCatalogue, GroupsCoverTheCatalogueInOrder) {
  int total = 0;
  for (SolidGroup g : kGroups) {
    for (int o = 0; o < nut::groupOrientationCount(g); ++o) {
      const Solid s = nut::makeSolid(g, o);
      EXPECT_EQ(s.index, total) << "the numbering is part of the HNI format";
      ++total;
    }
  }
  EXPECT_EQ(total, nut::kSolidCount);
  EXPECT_EQ(nut::groupOrientationCount(SolidGroup::Box), 1);
  EXPECT_EQ(nut::groupOrientationCount(SolidGroup::Wedge), 12);
  EXPECT_EQ(nut::groupOrientationCount(SolidGroup::InverseSphereOctant), 8);
}

TEST(SolidCatalogue, GroupAndOrientationRoundTrip) {
  for (int i = 0; i < nut::kSolidCount; ++i) {
    const Solid s = solidAt(i);
    const int orientation = nut::solidOrientation(s);
    EXPECT_GE(orientation, 0);
    EXPECT_LT(orientation, nut::groupOrientationCount(nut::solidGroup(s)));
    EXPECT_EQ(nut::makeSolid(nut::solidGroup(s), orientation), s) << i;
  }
}

TEST(SolidCatalogue, NamesAreUniqueAndPinned) {
  std::set<std::string> names;
  for (int i = 0; i < nut::kSolidCount; ++i) names.insert(nut::solidName(solidAt(i)));
  EXPECT_EQ(names.size(), static_cast<std::size_t>(nut::kSolidCount));

  EXPECT_EQ(nut::solidName(solidAt(0)), "box");
  EXPECT_EQ(nut::solidName(solidAt(3)), "wedge-x-c2");
  EXPECT_EQ(nut::solidName(solidAt(12)), "wedge-z-c3");
  EXPECT_EQ(nut::solidName(solidAt(18)), "pyramid-c5");
  EXPECT_EQ(nut::solidName(solidAt(26)), "inverse-pyramid-c5");
  EXPECT_EQ(nut::solidName(solidAt(38)), "quarter-cylinder-z-c1");
  EXPECT_EQ(nut::solidName(solidAt(45)), "inverse-quarter-cylinder-y-c0");
  EXPECT_EQ(nut::solidName(solidAt(56)), "octant-c3");
  EXPECT_EQ(nut::solidName(solidAt(64)), "inverse-octant-c3");
}

// Hand-computed from the orientation encoding in solids.hpp, so the numbering cannot drift.
TEST(SolidCatalogue, OrientationConvention) {
  struct Case {
    const char* solid;
    dvec3 inside, outside;
  };
  const Case cases[] = {
      {"box", {0.5, 0.5, 0.5}, {1.01, 0.5, 0.5}},
      // Wedge x, corner 0: y + z <= 1.
      {"wedge-x-c0", {0.5, 0.1, 0.1}, {0.5, 0.9, 0.9}},
      // Wedge x, corner 3: (1 - y) + (1 - z) <= 1.
      {"wedge-x-c3", {0.5, 0.9, 0.9}, {0.5, 0.1, 0.1}},
      // Wedge y: u = z, v = x; corner 1 flips u: (1 - z) + x <= 1, i.e. x <= z.
      {"wedge-y-c1", {0.1, 0.5, 0.9}, {0.9, 0.5, 0.1}},
      // Wedge z: u = x, v = y; corner 2 flips v: x + (1 - y) <= 1, i.e. x <= y.
      {"wedge-z-c2", {0.1, 0.9, 0.5}, {0.9, 0.1, 0.5}},
      {"pyramid-c0", {0.1, 0.1, 0.1}, {0.5, 0.5, 0.5}},
      // Corner 6 = (0, 1, 1): x + (1 - y) + (1 - z) <= 1.
      {"pyramid-c6", {0.1, 0.9, 0.9}, {0.1, 0.1, 0.1}},
      {"inverse-pyramid-c0", {0.9, 0.9, 0.9}, {0.1, 0.1, 0.1}},
      // Quarter cylinder x, corner 0: y^2 + z^2 <= 1.
      {"quarter-cylinder-x-c0", {0.5, 0.7, 0.7}, {0.5, 0.75, 0.75}},
      // Quarter cylinder z, corner 1: (1 - x)^2 + y^2 <= 1.
      {"quarter-cylinder-z-c1", {0.9, 0.9, 0.5}, {0.1, 0.9, 0.5}},
      {"inverse-quarter-cylinder-x-c0", {0.5, 0.9, 0.9}, {0.5, 0.1, 0.1}},
      {"octant-c0", {0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}},
      {"octant-c7", {0.9, 0.9, 0.9}, {0.1, 0.1, 0.1}},
      {"inverse-octant-c0", {0.9, 0.9, 0.9}, {0.5, 0.5, 0.5}},
  };
  for (const Case& c : cases) {
    const Solid s = named(c.solid);
    EXPECT_TRUE(nut::solidContains(s, c.inside)) << c.solid;
    EXPECT_FALSE(nut::solidContains(s, c.outside)) << c.solid;
  }
}

TEST(SolidContains, BoundaryCountsAsInside) {
  EXPECT_TRUE(nut::solidContains(named("wedge-x-c0"), {0.5, 0.5, 0.5}));
  EXPECT_TRUE(nut::solidContains(named("pyramid-c0"), {1.0, 0.0, 0.0}));
  EXPECT_TRUE(nut::solidContains(named("inverse-pyramid-c0"), {1.0, 0.0, 0.0}));
  EXPECT_TRUE(nut::solidContains(named("octant-c0"), {0.0, 1.0, 0.0}));
  EXPECT_TRUE(nut::solidContains(named("inverse-octant-c0"), {0.0, 1.0, 0.0}));
  EXPECT_TRUE(nut::solidContains(named("box"), {1.0, 1.0, 0.0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(nut::solidContains(named("box"), {nan, 0.5, 0.5}));
}

// ---------------------------------------------------------------------------------------------
// Volumes

TEST(SolidVolume, ClosedForms) {
  const double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("box")), 1.0);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("wedge-y-c2")), 0.5);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("pyramid-c4")), 1.0 / 6);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("inverse-pyramid-c4")), 5.0 / 6);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("quarter-cylinder-x-c3")), pi / 4);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("inverse-quarter-cylinder-x-c3")), 1 - pi / 4);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("octant-c1")), pi / 6);
  EXPECT_DOUBLE_EQ(nut::solidVolume(named("inverse-octant-c1")), 1 - pi / 6);
}

class EverySolid : public ::testing::TestWithParam<int> {
 protected:
  Solid solid() const { return solidAt(GetParam()); }
};

TEST_P(EverySolid, MonteCarloVolumeMatchesClosedForm) {
  constexpr int kSamples = 200000;
  std::mt19937 rng(1234u + static_cast<unsigned>(GetParam()));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside = 0;
  for (int i = 0; i < kSamples; ++i) {
    const dvec3 p(unit(rng), unit(rng), unit(rng));
    inside += nut::solidContains(solid(), p) ? 1 : 0;
  }
  const double volume = nut::solidVolume(solid());
  const double estimate = static_cast<double>(inside) / kSamples;
  const double standardError = std::sqrt(volume * (1 - volume) / kSamples);
  EXPECT_NEAR(estimate, volume, 4 * standardError + 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Rays against the inside test

template <typename T>
using Vec = glm::vec<3, T>;

template <typename T>
constexpr double kBand = 1e-9;
template <>
constexpr double kBand<float> = 1e-5;

// Allowed | |normal| - 1 |.
template <typename T>
constexpr double kUnitTolerance = 1e-12;
template <>
constexpr double kUnitTolerance<float> = 1e-6;

enum class Side { Inside, Outside, Band };

// Side::Band when p could be moved to either side by at most about 2 * band: some point within
// band is outside, and p is within band of the cube and some point within band, projected onto
// the cube, is inside. Projecting onto the cube lets thin parts of a solid (a wedge's edge, the
// cusp between an inverse quarter cylinder and a cube face) count as near, which 14 sample
// directions alone would miss.
Side classify(Solid s, const dvec3& p, double band) {
  const double d = 1 / std::sqrt(3.0);
  static const std::array<dvec3, 15> kOffsets{{
      {0, 0, 0},  {1, 0, 0},  {-1, 0, 0},  {0, 1, 0},   {0, -1, 0}, {0, 0, 1},   {0, 0, -1},
      {d, d, d},  {d, d, -d}, {d, -d, d},  {d, -d, -d}, {-d, d, d}, {-d, d, -d}, {-d, -d, d},
      {-d, -d, -d},
  }};
  const auto onCube = [](const dvec3& q) { return glm::clamp(q, dvec3(0), dvec3(1)); };
  bool mayBeInside = false, mayBeOutside = false;
  if (glm::distance(p, onCube(p)) <= band) {
    for (const dvec3& o : kOffsets) mayBeInside |= nut::solidContains(s, onCube(p + band * o));
  }
  for (const dvec3& o : kOffsets) mayBeOutside |= !nut::solidContains(s, p + band * o);
  if (mayBeInside && mayBeOutside) return Side::Band;
  return mayBeInside ? Side::Inside : Side::Outside;
}

bool insideOpenCube(const dvec3& p) {
  return p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1 && p.z > 0 && p.z < 1;
}

bool insideClosedCube(const dvec3& p) {
  return p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= 0 && p.z <= 1;
}

template <typename T>
struct Chord {
  T tEnter, tExit;
};

// The caller's part of the job: the ray's t >= 0 part inside the unit cube (slabs, computed in T).
template <typename T>
std::optional<Chord<T>> clipToCube(const Vec<T>& origin, const Vec<T>& dir) {
  T lo = 0, hi = std::numeric_limits<T>::max();
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0) {
      if (origin[i] < 0 || origin[i] > 1) return std::nullopt;
      continue;
    }
    const T t0 = (0 - origin[i]) / dir[i], t1 = (1 - origin[i]) / dir[i];
    lo = std::max(lo, std::min(t0, t1));
    hi = std::min(hi, std::max(t0, t1));
  }
  if (lo > hi) return std::nullopt;
  return Chord<T>{lo, hi};
}

struct Ray {
  dvec3 origin, dir;
};

struct RayStats {
  int entryHits = 0, surfaceHits = 0, misses = 0;
  int touches = 0;         // hits where the ray only touches the cube
  int skippedNormals = 0;  // surface hits too close to a cube face for the normal steps
};

// The ray as the T path sees it (rounded to T), evaluated in double.
struct RayPoints {
  dvec3 origin, dir;
  dvec3 at(double t) const { return origin + t * dir; }
};

double distanceToCubeFaces(const dvec3& p) {
  return std::min({p.x, p.y, p.z, 1 - p.x, 1 - p.y, 1 - p.z});
}

// The normal of a hit on P's surface at p: a step sigma along it is outside the solid, a step
// against it inside. sigma stays below half the distance to the cube's faces, where the solid
// may be cut (P is convex, so nothing else can be crossed), and far above the band; hits too close
// to a face for that are counted and skipped.
std::string checkSurfaceNormal(Solid s, const dvec3& p, const dvec3& n, double band,
                               RayStats& stats) {
  const double sigma = std::min(1e-2, 0.5 * distanceToCubeFaces(p));
  if (sigma < 10 * band) {
    ++stats.skippedNormals;
    return {};
  }
  if (classify(s, p + sigma * n, sigma / 4) != Side::Outside) return "step along normal inside";
  if (classify(s, p - sigma * n, sigma / 4) != Side::Inside) return "step against normal outside";
  return {};
}

// The normal of a hit at the entry point p: the axis normal of a cube face that p lies on and
// that the ray crosses inward; a step along it leaves the cube.
std::string checkEntryNormal(Solid s, const dvec3& p, const dvec3& n, const dvec3& dir,
                             double band) {
  int axis = 0;
  for (int i = 1; i < 3; ++i) axis = std::abs(n[i]) > std::abs(n[axis]) ? i : axis;
  dvec3 face(0);
  face[axis] = n[axis] > 0 ? 1 : -1;
  if (n != face) return "entry normal is not a face normal";
  if (std::abs(p[axis] - (n[axis] > 0 ? 1 : 0)) > band) return "entry point is not on its face";
  if (glm::dot(n, dir) >= 0) return "ray does not enter through the normal's face";
  if (classify(s, p + 1e-3 * n, 2.5e-4) != Side::Outside) return "step along normal inside";
  return {};
}

// Checks one ray; returns an empty string or what went wrong.
template <typename T>
std::string checkRay(Solid s, const Ray& ray, double band, RayStats& stats) {
  const Vec<T> origin(ray.origin), dir(ray.dir);
  const std::optional<Chord<T>> chord = clipToCube(origin, dir);
  if (!chord) return {};
  const std::optional<nut::SolidHit<T>> hit =
      nut::intersectSolid<T>(s, origin, dir, chord->tEnter, chord->tExit);
  const RayPoints r{dvec3(origin), dvec3(dir)};
  const double tEnter = chord->tEnter, tExit = chord->tExit;
  constexpr int kSamples = 16;

  if (!hit) {
    ++stats.misses;
    for (int j = 0; j <= kSamples; ++j) {
      const double t = tEnter + (tExit - tEnter) * j / kSamples;
      if (classify(s, r.at(t), band) == Side::Inside) return "missed, but inside at sample " +
                                                              std::to_string(j);
    }
    return {};
  }

  const double t = hit->t;
  const dvec3 n(hit->normal);
  if (!std::isfinite(t) || !std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
    return "NaN or infinity in the hit";
  }
  if (t < tEnter || t > tExit) return "hit outside [tEnter, tExit]";
  if (std::abs(glm::length(n) - 1) > kUnitTolerance<T>) return "normal not unit length";

  const dvec3 p = r.at(t);
  if ((tExit - tEnter) * glm::length(r.dir) < band) {
    // The ray only touches the cube (an edge or corner): no face was crossed, no step is inside.
    ++stats.touches;
    return classify(s, p, band) == Side::Outside ? "touching hit is outside" : "";
  }
  const double nudge = 0.25 * band / glm::length(r.dir);
  if (classify(s, r.at(t + nudge), band) == Side::Outside) return "hit point is outside";
  for (int j = 0; j < kSamples && t > tEnter; ++j) {
    const double before = tEnter + (t - tEnter) * j / kSamples;
    if (classify(s, r.at(before), band) == Side::Inside) {
      return "inside before the hit at sample " + std::to_string(j);
    }
  }

  if (t == tEnter && glm::dot(n, r.dir) >= 0) return "hit at tEnter with a normal along the ray";
  if (t == tEnter && tEnter == 0 && insideClosedCube(r.origin)) {
    // The ray starts in the solid and crosses no face; -dir inside the cube, on its surface the
    // face rule may pick any face the ray moves into.
    ++stats.entryHits;
    const bool minusDir = glm::length(n + glm::normalize(r.dir)) <= 1e-6;
    return insideOpenCube(r.origin) && !minusDir ? "normal inside the cube is not -dir" : "";
  }
  if (classify(s, p, band) != Side::Band) return "hit point is not on a surface";
  if (t == tEnter) {
    ++stats.entryHits;
    return checkEntryNormal(s, p, n, r.dir, band);
  }
  ++stats.surfaceHits;
  // A tangent float hit may be off by sqrt(epsilon) along the ray, tilting its normal as much.
  if (glm::dot(n, glm::normalize(r.dir)) > 1e-3) return "ray leaves through the hit's surface";
  return checkSurfaceNormal(s, p, n, band, stats);
}

template <typename T>
void checkRays(Solid s, const std::vector<Ray>& rays, RayStats& stats, double band = kBand<T>) {
  int failures = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const std::string error = checkRay<T>(s, rays[i], band, stats);
    if (error.empty()) continue;
    if (++failures <= 5) {
      const Ray& ray = rays[i];
      ADD_FAILURE() << (sizeof(T) == 4 ? "float" : "double") << " ray " << i << " origin ("
                    << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir ("
                    << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << "): " << error;
    }
  }
  EXPECT_EQ(failures, 0) << (sizeof(T) == 4 ? "float" : "double") << " failures in total";
}

// Rays through the cube, not normalised: from outside towards random points, from inside in
// random directions, with direction components set to 0 (axis- and face-parallel rays), and
// aimed at points on the cube's faces, edges and corners.
std::vector<Ray> randomRays(std::uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  const auto direction = [&] {
    return glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)));
  };
  const auto scale = [&] { return std::exp(6 * unit(rng) - 3); };
  const dvec3 centre(0.5);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    dvec3 target(unit(rng), unit(rng), unit(rng));
    switch (i % 4) {
      case 0: {
        const dvec3 origin = centre + 2.5 * direction();
        rays.push_back({origin, (target - origin) * scale()});
        break;
      }
      case 1:
        rays.push_back({target, direction() * scale()});
        break;
      case 2: {
        dvec3 dir = direction();
        const int keep = static_cast<int>(unit(rng) * 3);  // this axis is never zeroed
        for (int a = 0; a < 3; ++a) {
          if (a != keep && unit(rng) < 0.5) dir[a] = 0;
        }
        dir = glm::normalize(dir);
        rays.push_back({target - 2.0 * dir, dir * scale()});
        break;
      }
      default: {
        for (int a = 0; a < 3; ++a) {
          if (unit(rng) < 0.5) target[a] = unit(rng) < 0.5 ? 0.0 : 1.0;
        }
        const dvec3 dir = direction();
        rays.push_back({target - 2.0 * dir, dir * scale()});
        break;
      }
    }
  }
  return rays;
}

// Every direction with components in {-1, 0, 1}, through every point of {0, 0.5, 1}^3: rays
// along axes, along faces and edges, through corners, and along the wedges' and pyramids' slopes;
// plus the same directions starting at those points. Then all of them again with each zero
// component replaced by 1e-30, whose square underflows in float.
std::vector<Ray> latticeRays() {
  std::vector<Ray> rays;
  const double steps[] = {0.0, 0.5, 1.0};
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const dvec3 dir(dx, dy, dz);
        for (double x : steps) {
          for (double y : steps) {
            for (double z : steps) {
              rays.push_back({dvec3(x, y, z) - 2.0 * dir, dir});
              rays.push_back({dvec3(x, y, z), 0.5 * dir});
            }
          }
        }
      }
    }
  }
  const std::size_t exact = rays.size();
  for (std::size_t i = 0; i < exact; ++i) {
    Ray ray = rays[i];
    for (int a = 0; a < 3; ++a) ray.dir[a] = ray.dir[a] == 0 ? 1e-30 : ray.dir[a];
    rays.push_back(ray);
  }
  return rays;
}

TEST_P(EverySolid, RandomRaysAgreeWithInsideTest) {
  const std::vector<Ray> rays = randomRays(42u + static_cast<unsigned>(GetParam()), 4000);
  RayStats doubles, floats;
  checkRays<double>(solid(), rays, doubles);
  checkRays<float>(solid(), rays, floats);
  // Guard against a vacuous pass: each kind of outcome must occur often.
  for (const RayStats& stats : {doubles, floats}) {
    EXPECT_GT(stats.entryHits, 100);
    if (solid() != nut::makeSolid(SolidGroup::Box, 0)) {
      EXPECT_GT(stats.surfaceHits, 100);
      EXPECT_GT(stats.misses, 100);
      EXPECT_LT(stats.skippedNormals, stats.surfaceHits / 10);
    }
  }
}

TEST_P(EverySolid, AxisEdgeAndCornerRaysAreFinite) {
  const std::vector<Ray> rays = latticeRays();
  RayStats doubles, floats;
  checkRays<double>(solid(), rays, doubles);
  checkRays<float>(solid(), rays, floats);
}

TEST_P(EverySolid, FarOriginKeepsFloatPrecision) {
  // Float rays from 1000 cell sizes away (a camera 10 m from a 1 cm cell): the error grows
  // linearly with the distance, here to 1e-6 * distance, about 16 ulps of the origin. Solving
  // from the origin with the textbook discriminant b^2 - a c misses quadrics by more than 0.1.
  constexpr double kDistance = 1000;
  std::vector<Ray> rays = randomRays(7u + static_cast<unsigned>(GetParam()), 2000);
  for (Ray& ray : rays) ray.origin -= kDistance * glm::normalize(ray.dir);
  RayStats stats;
  checkRays<float>(solid(), rays, stats, 1e-6 * kDistance);
}

INSTANTIATE_TEST_SUITE_P(All, EverySolid, ::testing::Range(0, nut::kSolidCount),
                         [](const ::testing::TestParamInfo<int>& param) {
                           std::string name = nut::solidName(solidAt(param.param));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// ---------------------------------------------------------------------------------------------
// Hand-computed hits

TEST(IntersectSolid, WedgeSlope) {
  // From (0.5, 2, 2) along (0, -1, -1): enters the cube at t = 1, meets y + z = 1 at t = 1.5.
  const auto hit = nut::intersectSolid<double>(named("wedge-x-c0"), {0.5, 2, 2}, {0, -1, -1}, 1, 2);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 1.5);
  EXPECT_NEAR(glm::distance(hit->normal, dvec3(0, 1, 1) / std::sqrt(2.0)), 0, 1e-15);
}

TEST(IntersectSolid, OctantAndItsInverse) {
  // Down the line x = y = 0.5: enters at z = 1 (t = 2), meets the sphere at z = sqrt(0.5).
  const dvec3 origin(0.5, 0.5, 3), dir(0, 0, -1);
  const auto octant = nut::intersectSolid<double>(named("octant-c0"), origin, dir, 2, 3);
  ASSERT_TRUE(octant);
  EXPECT_NEAR(octant->t, 3 - std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(glm::distance(octant->normal, dvec3(0.5, 0.5, std::sqrt(0.5))), 0, 1e-15);
  // The inverse octant holds the entry point (0.5, 0.5, 1): the hit is the top face.
  const auto inverse = nut::intersectSolid<double>(named("inverse-octant-c0"), origin, dir, 2, 3);
  ASSERT_TRUE(inverse);
  EXPECT_EQ(inverse->t, 2.0);
  EXPECT_EQ(inverse->normal, dvec3(0, 0, 1));

  // Up the line x = y = 0.2 from inside the ball: leaves it at z = sqrt(0.92).
  const auto up =
      nut::intersectSolid<double>(named("inverse-octant-c0"), {0.2, 0.2, -1}, {0, 0, 1}, 1, 2);
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->t, 1 + std::sqrt(0.92), 1e-15);
  EXPECT_NEAR(glm::distance(up->normal, -dvec3(0.2, 0.2, std::sqrt(0.92))), 0, 1e-15);
}

TEST(IntersectSolid, RayAlongCylinderAxis) {
  // Parallel to the axis of quarter-cylinder-z-c0 (x^2 + y^2 <= 1): all in or all out.
  const Solid cylinder = named("quarter-cylinder-z-c0");
  const Solid inverse = named("inverse-quarter-cylinder-z-c0");
  const auto in = nut::intersectSolid<float>(cylinder, {0.3f, 0.3f, -1}, {0, 0, 1}, 1, 2);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->t, 1.0f);
  EXPECT_EQ(in->normal, glm::vec3(0, 0, -1));
  EXPECT_FALSE(nut::intersectSolid<float>(inverse, {0.3f, 0.3f, -1}, {0, 0, 1}, 1, 2));

  EXPECT_FALSE(nut::intersectSolid<float>(cylinder, {0.9f, 0.9f, -1}, {0, 0, 2}, 0.5f, 1));
  const auto out = nut::intersectSolid<float>(inverse, {0.9f, 0.9f, -1}, {0, 0, 2}, 0.5f, 1);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->t, 0.5f);
  EXPECT_EQ(out->normal, glm::vec3(0, 0, -1));
}

TEST(IntersectSolid, OriginInsideGivesMinusDir) {
  const auto hit = nut::intersectSolid<double>(named("box"), {0.5, 0.5, 0.5}, {0, 3, 4}, 0, 0.1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 0.0);
  EXPECT_NEAR(glm::distance(hit->normal, dvec3(0, -0.6, -0.8)), 0, 1e-15);
}

TEST(IntersectSolid, EmptyChordMisses) {
  EXPECT_FALSE(nut::intersectSolid<double>(named("box"), {0.5, 0.5, 0.5}, {1, 0, 0}, 1, 0.5));
  EXPECT_FALSE(nut::intersectSolid<double>(named("inverse-octant-c0"), {0.9, 0.9, 0.9},
                                           {1, 0, 0}, 1, 0.5));
}

// rotateSolid against the rotation itself, at random points (not the grid the table is built
// from): a point is inside s exactly when its rotated image is inside the rotated solid.
TEST(RotateSolid, HoldsTheRotatedPointsOfEverySolidUnderEveryRotation) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int r = 0; r < nut::format::kCubeRotationCount; ++r) {
    const glm::dmat3 m(nut::cubeRotationMatrix(r));
    for (int i = 0; i < nut::kSolidCount; ++i) {
      const Solid s{static_cast<std::uint8_t>(i)};
      const Solid rotated = nut::rotateSolid(s, r);
      EXPECT_EQ(nut::solidGroup(rotated), nut::solidGroup(s));
      if (r == 0) {
        EXPECT_EQ(rotated, s);
      }
      int mismatches = 0;
      for (int k = 0; k < 2000; ++k) {
        const dvec3 p(unit(rng), unit(rng), unit(rng));
        mismatches += nut::solidContains(s, p) != nut::solidContains(rotated, m * (p - 0.5) + 0.5);
      }
      EXPECT_EQ(mismatches, 0) << nut::solidName(s) << " under rotation " << r;
    }
  }
}

// Turning by A then by B is turning by B A.
TEST(RotateSolid, ComposesLikeTheMatrices) {
  for (int a = 0; a < nut::format::kCubeRotationCount; ++a)
    for (int b = 0; b < nut::format::kCubeRotationCount; ++b) {
      const auto product = nut::cubeRotationMatrix(b) * nut::cubeRotationMatrix(a);
      int ba = 0;
      while (nut::cubeRotationMatrix(ba) != product) ++ba;
      for (int i = 0; i < nut::kSolidCount; ++i) {
        const Solid s{static_cast<std::uint8_t>(i)};
        EXPECT_EQ(nut::rotateSolid(nut::rotateSolid(s, a), b), nut::rotateSolid(s, ba));
      }
    }
}

}  // namespace

// solidCoverage against the inside test: for every solid and every box whose corners lie on the
// quarter lattice of the unit cube, "all" means every sample point of the box is inside, "none"
// that every point strictly inside the box is outside, and "part" that the samples find both.
TEST(SolidCoverage, AgreesWithPointsOfEveryLatticeBox) {
  constexpr int kSamples = 9;  // per axis, across the box, faces included
  for (int index = 0; index < nut::kSolidCount; ++index) {
    const nut::Solid s{static_cast<std::uint8_t>(index)};
    int counts[3] = {0, 0, 0};
    for (int box = 0; box < 1000; ++box) {
      // Box `box`: per axis one of the 10 intervals [i/4, j/4], i < j.
      glm::dvec3 lo, hi;
      for (int a = 0, code = box; a < 3; ++a, code /= 10) {
        int k = code % 10, i = 0;
        while (k >= 4 - i) k -= 4 - i++;
        lo[a] = i / 4.0;
        hi[a] = (i + 1 + k) / 4.0;
      }
      const nut::Coverage coverage = nut::solidCoverage(s, lo, hi);
      ++counts[static_cast<int>(coverage)];
      bool anyIn = false, anyOut = false, anyInStrictly = false;
      for (int z = 0; z < kSamples; ++z)
        for (int y = 0; y < kSamples; ++y)
          for (int x = 0; x < kSamples; ++x) {
            const glm::dvec3 t = glm::dvec3(x, y, z) / double(kSamples - 1);
            const glm::dvec3 p = lo + t * (hi - lo);
            const bool in = nut::solidContains(s, p);
            anyIn |= in;
            anyOut |= !in;
            const glm::dvec3 inner = lo + (0.001 + 0.998 * t) * (hi - lo);
            anyInStrictly |= nut::solidContains(s, inner);
          }
      const std::string where = nut::solidName(s) + " box " + std::to_string(box);
      if (coverage == nut::Coverage::All) {
        EXPECT_FALSE(anyOut) << where;
      } else if (coverage == nut::Coverage::None) {
        EXPECT_FALSE(anyInStrictly) << where;
      } else {
        EXPECT_TRUE(anyIn && anyOut) << where;
      }
    }
    // The box solid covers every box; the others have boxes of all three kinds.
    if (index == 0) {
      EXPECT_EQ(counts[static_cast<int>(nut::Coverage::All)], 1000);
    } else {
      for (int c = 0; c < 3; ++c) EXPECT_GT(counts[c], 0) << nut::solidName(s) << " coverage " << c;
    }
  }
}
