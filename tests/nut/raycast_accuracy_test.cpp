// Accuracy of the float ray caster (raycast.hpp, over the compiled image) against the exact path
// (exact_path.hpp, double precision over the model), on seeded random hierarchies and random rays
// from outside the root box aimed at random points inside it. The root sits at a city-sized world
// offset, as in a real scene.
//
// Exact lookup: the caster must give the exact answer up to float rounding: hit or miss, and the
// distance within kToleranceUlps float ulps of the ray's coordinate scale over the cosine of the
// incidence angle (exactTolerance); the shading test also compares normals and colours. Where it
// does not, the ray counts as grazing only if the caster's answer is the exact answer of a nearby
// ray (backward error): the ray moved sideways by that tolerance, or with solids thinner than it
// along the ray ignored (the flat faces of inverse cylinders and octants touch their solid only
// along a tangent). Any other disagreement is a failure and prints the ray.
//
// Heuristic lookup: the boundaries of block B move by at most delta_a = D_a / (512 M_a) along its
// axis a (docs/FORMAT.md). The content of a cell is placed from the cell's minimum corner, so the
// hit surface moves with the boundaries of every block from the root down to its own, and the hit
// distance by at most the bound of ExactSurface (plus the exact-lookup tolerance). Rays that pass
// within that distance of an edge may meet another face or none; they are counted, and their
// fraction is bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include <nut/exact_path.hpp>
#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/raycast.hpp>

#include "random_hierarchy.hpp"
#include "ray_printing.hpp"

namespace nut {
namespace {

constexpr std::uint64_t kSeeds = 500;
constexpr int kRaysPerSeed = 400;
const glm::dvec3 kWorldOrigin{1.0e6 + 0.3, 12.5, -7.0e5 + 0.7};
constexpr double kFloatEpsilon = 1.0 / (1 << 23);  // float ulp at 1
// Exact-lookup tolerance in float ulps of the ray's coordinate scale (measured worst: 3.3).
constexpr double kToleranceUlps = 8;

// One random hierarchy as both renderers see it.
struct Scene {
  std::uint64_t seed = 0;
  Hierarchy model;                // quantized: exactly what the image encodes
  Image image;
  std::vector<glm::dvec3> delta;  // per block: the heuristic boundary error bound per axis, metres
};

std::optional<Scene> makeScene(std::uint64_t seed) {
  const Hierarchy h = testing::randomHierarchy(seed);
  auto image = compile(h);
  if (!image.ok()) {
    ADD_FAILURE() << "seed " << seed << ": " << image.error().message;
    return std::nullopt;
  }
  Scene s{seed, quantized(h), std::move(*image), {}};
  const HniView view(s.image);
  const FileRecord file = view.fileRecord();
  for (std::size_t b = 0; b < s.model.blocks.size(); ++b) {
    const BlockHeader header = view.header(view.blockAddress(file, static_cast<int>(b)));
    glm::dvec3 d;
    for (int a = 0; a < 3; ++a)
      d[a] = header.sizeUnits[a] * format::kMetresPerUnit / (512.0 * header.metaPixels[a]);
    s.delta.push_back(d);
  }
  return s;
}

struct Ray {
  int index = 0;
  glm::dvec3 origin{0.0}, dir{0.0};
};

// A ray from a random point 1.2 to 4 bounding radii from the root box's centre towards a random
// point inside the box.
Ray randomRay(const Hierarchy& h, std::mt19937_64& rng, int index) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const glm::dvec3 size = h.blocks[h.root].sizeM();
  const double radius = 0.5 * glm::length(size);
  const double z = 2 * unit(rng) - 1, phi = 2 * std::numbers::pi * unit(rng);
  const glm::dvec3 away{std::sqrt(1 - z * z) * std::cos(phi), z, std::sqrt(1 - z * z) * std::sin(phi)};
  const glm::dvec3 from = 0.5 * size + radius * (1.2 + 2.8 * unit(rng)) * away;
  const glm::dvec3 to = size * glm::dvec3(unit(rng), unit(rng), unit(rng));
  return {index, kWorldOrigin + from, glm::normalize(to - from)};
}

// The size of the coordinates the float caster computes with for this ray (relative to the root):
// its rounding errors in positions are a few ulps of this.
double coordinateScale(const Scene& s, const Ray& ray) {
  return glm::length(ray.origin - kWorldOrigin) + glm::length(s.model.blocks[s.model.root].sizeM());
}

// The exact-lookup distance tolerance: kToleranceUlps of the coordinate scale, grown by 1 / cos of
// the incidence angle (a position error across the surface moves the hit along the ray that much).
double exactTolerance(const Scene& s, const Ray& ray, const RayResult& exact) {
  const double cosine = std::max(std::abs(glm::dot(exact.normal, ray.dir)), 1e-3);
  return kToleranceUlps * kFloatEpsilon * coordinateScale(s, ray) / cosine;
}

std::string describe(const Scene& s, const Ray& ray, const RayResult& exact, const RayResult& caster) {
  const auto vec = [](const glm::dvec3& v) { return testing::describe(v); };
  const auto result = [](const RayResult& r) { return testing::describe(r); };
  return "seed " + std::to_string(s.seed) + " ray " + std::to_string(ray.index) + " origin " +
         vec(ray.origin) + " dir " + vec(ray.dir) + " (root origin " + vec(kWorldOrigin) +
         ")\n    exact:  " + result(exact) + "\n    caster: " + result(caster);
}

RayCastOptions options(Lookup lookup) {
  RayCastOptions o;
  o.lookup = lookup;
  o.maxIterations = 1 << 20;  // the accuracy tests are not about the cap
  return o;
}

// What two answers must share.
enum class Compare {
  Distance,  // hit or miss, and the distance within exactTolerance
  Shading,   // that, the normal within 0.01 rad and every colour channel within 3
};

bool agrees(const Scene& s, const Ray& ray, const RayResult& exact, const RayResult& caster, Compare what) {
  if (exact.hit != caster.hit) return false;
  if (exact.hit && std::abs(exact.distanceM - caster.distanceM) > exactTolerance(s, ray, exact)) return false;
  if (what == Compare::Distance) return true;
  // Near the tangent between a flat face and a curved solid the normal turns fast (a position error
  // e at curvature radius r turns it by about sqrt(2 e / r)); 0.01 rad changes a colour by at most
  // 255 * 0.65 * 0.01 = 1.7, plus 1 for rounding.
  if (exact.hit && glm::dot(exact.normal, caster.normal) < std::cos(0.01)) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if (std::abs(exact.colour[i] - caster.colour[i]) > 3) return false;
  return true;
}

// Whether the caster's answer is the exact answer of a ray within float precision of this one:
// moved sideways by the tolerance (16 directions around the ray, two lengths), or with solids
// thinner than the tolerance along the ray ignored (slivers under the flat faces of inverse solids).
bool nearbyRayAgrees(const Scene& s, const Ray& ray, const RayResult& caster, Compare what) {
  const double shift = kToleranceUlps * kFloatEpsilon * coordinateScale(s, ray);
  const RayResult thick = traceExact(s.model, kWorldOrigin, ray.origin, ray.dir, {.minThicknessM = shift});
  if (agrees(s, ray, thick, caster, what)) return true;
  const glm::dvec3 helper = std::abs(ray.dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(ray.dir, helper)), v = glm::cross(ray.dir, u);
  for (const double length : {shift, 0.25 * shift}) {
    for (int k = 0; k < 16; ++k) {
      const double angle = 2 * std::numbers::pi * k / 16;
      Ray moved = ray;
      moved.origin += length * (std::cos(angle) * u + std::sin(angle) * v);
      const RayResult exact = traceExact(s.model, kWorldOrigin, moved.origin, moved.dir);
      if (agrees(s, moved, exact, caster, what)) return true;
    }
  }
  return false;
}

// Calls f(scene, caster, ray) for every ray of every seed.
template <typename F>
void forEachRay(F&& f) {
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const auto scene = makeScene(seed);
    if (!scene) continue;
    const HniRayCaster caster(scene->image, kWorldOrigin);
    std::mt19937_64 rng(seed);
    for (int i = 0; i < kRaysPerSeed; ++i) f(*scene, caster, randomRay(scene->model, rng, i));
  }
}

// Compares the caster in exact lookup with the exact path; `what` says how much must agree.
void compareExactLookup(Compare what) {
  long long rays = 0, hits = 0, grazing = 0, failures = 0, capped = 0;
  double worstUlps = 0;  // |distance error| * cos / (float ulp of the coordinate scale), agreeing hits
  std::string worstRay, grazingExample;
  forEachRay([&](const Scene& s, const HniRayCaster& caster, const Ray& ray) {
    const RayResult exact = traceExact(s.model, kWorldOrigin, ray.origin, ray.dir);
    const RayResult cast = caster.trace(ray.origin, ray.dir, 1e-3, options(Lookup::Exact));
    if (exact.capped || cast.capped) {
      ++capped;
      return;
    }
    ++rays;
    if (agrees(s, ray, exact, cast, what)) {
      if (!exact.hit) return;
      ++hits;
      const double cosine = std::max(std::abs(glm::dot(exact.normal, ray.dir)), 1e-3);
      const double ulps =
          std::abs(exact.distanceM - cast.distanceM) * cosine / (kFloatEpsilon * coordinateScale(s, ray));
      if (ulps > worstUlps) {
        worstUlps = ulps;
        worstRay = describe(s, ray, exact, cast);
      }
    } else if (nearbyRayAgrees(s, ray, cast, what)) {
      if (grazing++ == 0) grazingExample = describe(s, ray, exact, cast);
    } else if (++failures <= 10) {
      ADD_FAILURE() << "the caster disagrees with the exact path:\n  " << describe(s, ray, exact, cast);
    }
  });
  std::printf("exact lookup: %lld rays, %lld agreeing hits; %lld grazing (%.3g %%), %lld failures, "
              "%lld capped\n  worst distance error of an agreeing hit: %.3g float ulps of the coordinate "
              "scale / cos\n  %s\n"
              "  first grazing ray: %s\n",
              rays, hits, grazing, 100.0 * grazing / std::max(rays, 1LL), failures, capped, worstUlps,
              worstRay.c_str(), grazingExample.c_str());
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(capped, 0);
  EXPECT_LE(grazing, rays / 2000) << "more than 0.05 % of the rays graze an edge";
}

TEST(RaycastAccuracy, ExactLookupHitsAndDistancesMatchTheExactPath) { compareExactLookup(Compare::Distance); }

TEST(RaycastAccuracy, ExactLookupNormalsAndColoursMatchTheExactPath) { compareExactLookup(Compare::Shading); }

// The heuristic bound for one exact hit (exact_path.hpp): sum over the blocks from the root to the
// one whose surface was hit of sum_a |n_a| delta_a, over |n . d|, plus the exact-lookup tolerance.
double heuristicBound(const Scene& s, const Ray& ray, const RayResult& exact, const ExactSurface& surface) {
  double displacement = 0;
  for (const ExactSurface::Level& level : surface.path)
    for (int a = 0; a < 3; ++a) displacement += std::abs(level.normal[a]) * s.delta[level.block][a];
  const double cosine = std::max(std::abs(glm::dot(exact.normal, ray.dir)), 1e-3);
  return displacement / cosine + exactTolerance(s, ray, exact);
}

TEST(RaycastAccuracy, HeuristicLookupStaysWithinTheFormatBound) {
  long long rays = 0, hits = 0, beyond = 0, hitOrMiss = 0, capped = 0;
  double worstWithin = 0, worstBeyond = 0;  // |distance error| / bound
  std::string worstWithinRay, worstBeyondRay, hitOrMissRay;
  forEachRay([&](const Scene& s, const HniRayCaster& caster, const Ray& ray) {
    ExactSurface surface;
    const RayResult exact = traceExact(s.model, kWorldOrigin, ray.origin, ray.dir, {.surface = &surface});
    const RayResult cast = caster.trace(ray.origin, ray.dir, 1e-3, options(Lookup::Heuristic));
    if (exact.capped || cast.capped) {
      ++capped;
      return;
    }
    ++rays;
    if (exact.hit != cast.hit) {
      if (hitOrMiss++ == 0) hitOrMissRay = describe(s, ray, exact, cast);
      return;
    }
    if (!exact.hit) return;
    ++hits;
    const double ratio = std::abs(exact.distanceM - cast.distanceM) / heuristicBound(s, ray, exact, surface);
    double& worst = ratio <= 1 ? worstWithin : worstBeyond;
    if (ratio > 1) ++beyond;
    if (ratio > worst) {
      worst = ratio;
      (ratio <= 1 ? worstWithinRay : worstBeyondRay) = describe(s, ray, exact, cast);
    }
  });
  const long long exceptions = beyond + hitOrMiss;
  std::printf("heuristic lookup: %lld rays, %lld hits; exceptions: %lld hits beyond the bound and "
              "%lld hit/miss disagreements (%.3g %% of the rays), %lld capped\n"
              "  worst error within the bound: %.3g of it\n  %s\n  worst beyond it: %.3g of it\n  %s\n"
              "  first hit/miss disagreement:\n  %s\n",
              rays, hits, beyond, hitOrMiss, 100.0 * exceptions / std::max(rays, 1LL), capped, worstWithin,
              worstWithinRay.c_str(), worstBeyond, worstBeyondRay.c_str(), hitOrMissRay.c_str());
  EXPECT_EQ(capped, 0);
  EXPECT_LE(exceptions, rays / 200) << "more than 0.5 % of the rays cross an edge the heuristic moved";
}

// Minimal scenes for the two disagreements the random rays found, so that each is checked on its
// own: the answers of the exact path there are also worked out by hand in exact_path_test.cpp.

// One opaque box cell at the bottom of a 1 x 2 x 1 m block; the ray enters the block's +z face
// `below` metres under the edge y = 1 and leaves the box through its top y = 1 after a short way.
Hierarchy boxUnderEmptyCell() {
  Hierarchy h;
  h.materials.push_back({200, 100, 50, 255, 0});
  Block b = Block::fromSizes({{{1.0}, {1.0, 1.0}, {1.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  h.addBlock(b);
  return h;
}

TEST(RaycastAccuracy, EnteringABlockJustBelowAnEdgeHitsTheCellThere) {
  const Hierarchy h = boxUnderEmptyCell();
  const auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniRayCaster caster(*image, kWorldOrigin);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.1, 0.75, -0.66));
  // 5 um below the edge is 40 float ulps of the 1 m block: well within float precision.
  for (const double below : {1e-3, 1e-4, 2e-5, 5e-6}) {
    const Ray ray{0, kWorldOrigin + glm::dvec3(0.5, 1.0 - below, 1.0) - 0.28 * dir, dir};
    const RayResult exact = traceExact(h, kWorldOrigin, ray.origin, ray.dir);
    const RayResult cast = caster.trace(ray.origin, ray.dir, 1e-3, options(Lookup::Exact));
    ASSERT_TRUE(exact.hit);
    EXPECT_NEAR(exact.distanceM, 0.28, 1e-9);  // the ray origin itself is rounded near 1e6 m
    EXPECT_TRUE(cast.hit) << below << " m below the edge";
    EXPECT_NEAR(cast.distanceM, 0.28, 1e-6) << below << " m below the edge";
  }
}

TEST(RaycastAccuracy, ClippedSolidIsShadedWithTheClipFaceNormal) {
  // A 5 m box block in a 2 m cell: from +x the ray meets the cut at the cell face x = 2.
  Hierarchy h;
  h.materials.push_back({200, 100, 50, 255, 0});
  Block root = Block::fromSizes({{{2.0, 2.0}, {2.0}, {2.0}}});
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {false, false, false}});
  root.cell(0, 0, 0) = Cell::redirect(0);
  h.addBlock(root);
  Block big = Block::fromSizes({{{5.0}, {2.0}, {2.0}}});
  big.cell(0, 0, 0) = Cell::box(0);
  h.addBlock(big);
  const auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniRayCaster caster(*image, kWorldOrigin);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(-1.0, 0.1, 0.0));
  const glm::dvec3 origin = kWorldOrigin + glm::dvec3(2.0, 1.0, 1.0) - 8.0 * dir;
  const RayResult exact = traceExact(h, kWorldOrigin, origin, dir);
  const RayResult cast = caster.trace(origin, dir, 1e-3, options(Lookup::Exact));
  ASSERT_TRUE(exact.hit && cast.hit);
  EXPECT_EQ(exact.normal, glm::dvec3(1, 0, 0));
  EXPECT_NEAR(cast.distanceM, 8.0, 1e-5);
  EXPECT_NEAR(glm::dot(cast.normal, exact.normal), 1.0, 1e-6);
  EXPECT_EQ(cast.colour, exact.colour);
}

}  // namespace
}  // namespace nut
