// The comparison machinery of the stress tests (stress_support.hpp).
#include "stress_support.hpp"

#include "../ray_printing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <sstream>

#include <glm/geometric.hpp>

#include <nut/format.hpp>
#include <nut/hni.hpp>
#include <nut/hni_view.hpp>

namespace nut::stress {

Ray rayThrough(long long index, const glm::dvec3& from, const glm::dvec3& to) {
  return {index, from, glm::normalize(to - from)};
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

glm::dvec3 randomDirection(std::mt19937_64& rng) {
  const double z = uniform(rng, -1, 1), phi = uniform(rng, 0, 2 * std::numbers::pi);
  const double r = std::sqrt(1 - z * z);
  return {r * std::cos(phi), z, r * std::sin(phi)};
}

std::unique_ptr<Scene> makeScene(const std::string& name, const Hierarchy& h, const glm::dvec3& origin) {
  auto image = compile(h);
  if (!image.ok()) {
    ADD_FAILURE() << name << ": " << image.error().message;
    return nullptr;
  }
  auto s = std::make_unique<Scene>();
  s->name = name;
  s->model = quantized(h);
  s->heuristicModel = s->model;
  s->image = std::move(*image);
  s->origin = origin;
  const HniView view(s->image);
  const FileRecord file = view.fileRecord();
  for (std::size_t b = 0; b < s->model.blocks.size(); ++b) {
    const BlockHeader header = view.header(view.blockAddress(file, static_cast<int>(b)));
    glm::dvec3 delta;
    for (int a = 0; a < 3; ++a) {
      const int pixels = header.metaPixels[a];
      const double size = header.sizeUnits[a];
      delta[a] = size * format::kMetresPerUnit / (512.0 * pixels);
      // The heuristic position of boundary m is (k + f / 256) D / M, k the pixel that holds it:
      // the pixels with f != 0, in order.
      const AxisView axis = view.axis(header, a);
      std::vector<double>& bounds = s->heuristicModel.blocks[b].boundsM[a];
      std::size_t m = 1;
      for (int k = 0; k < pixels; ++k) {
        const int f = axis.meta[4 * k + 1];
        if (f == 0) continue;
        if (m + 1 >= bounds.size()) break;
        bounds[m++] = (256.0 * k + f) * size / (256.0 * pixels) * format::kMetresPerUnit;
      }
      if (m + 1 != bounds.size()) ADD_FAILURE() << name << ": block " << b << " axis " << a << " holds too few boundaries";
      for (std::size_t i = 0; i < bounds.size(); ++i)
        if (std::abs(bounds[i] - s->model.blocks[b].boundsM[a][i]) > delta[a] + 1e-12)
          ADD_FAILURE() << name << ": block " << b << " axis " << a << " boundary " << i
                        << " moves beyond the format's bound";
    }
    s->delta.push_back(delta);
  }
  s->caster = std::make_unique<HniRayCaster>(s->image, origin);
  return s;
}

double Scene::coordinateScale(const Ray& ray) const {
  return glm::length(ray.origin - origin) + glm::length(rootSize());
}

double Scene::positionTolerance(const Ray& ray) const {
  return kToleranceUlps * kFloatEpsilon * coordinateScale(ray);
}

RayResult Scene::cast(const Ray& ray, Lookup lookup, int maxIterations) const {
  RayCastOptions o;
  o.lookup = lookup;
  o.maxIterations = maxIterations;
  const RayResult result = caster->trace(ray.origin, ray.dir, 1e-3, o);
  if (casts_.size() < kPacketCheckRays) casts_.push_back({ray, lookup, maxIterations, result});
  return result;
}

Scene::~Scene() { expectPacketsAgree(); }

void Scene::expectPacketsAgree() const {
  std::map<std::pair<Lookup, int>, std::vector<const Cast*>> batches;
  for (const Cast& c : casts_) batches[{c.lookup, c.maxIterations}].push_back(&c);
  int failures = 0;
  for (const auto& [key, batch] : batches) {
    std::vector<glm::dvec3> origins, directions;
    for (const Cast* c : batch) origins.push_back(c->ray.origin), directions.push_back(c->ray.dir);
    RayCastOptions o;
    o.lookup = key.first;
    o.maxIterations = key.second;
    std::vector<RayResult> packets(batch.size());
    caster->traceMany(origins, directions, 1e-3, o, packets);
    for (std::size_t i = 0; i < batch.size() && failures < 5; ++i) {
      const RayResult& one = batch[i]->result;
      const RayResult& packet = packets[i];
      const bool same = one.hit == packet.hit && std::memcmp(&one.distanceM, &packet.distanceM, sizeof(double)) == 0 &&
                        std::memcmp(&one.normal, &packet.normal, sizeof one.normal) == 0 &&
                        one.colour == packet.colour && one.iterations == packet.iterations &&
                        one.capped == packet.capped;
      if (same) continue;
      ++failures;
      ADD_FAILURE() << name << ", " << lookupName(key.first)
                    << ": the packet caster differs from the one-ray caster on ray " << batch[i]->ray.index << " from "
                    << nut::testing::describe(batch[i]->ray.origin) << " along "
                    << nut::testing::describe(batch[i]->ray.dir) << "; one ray: " << nut::testing::describe(one)
                    << "; packet: " << nut::testing::describe(packet);
    }
  }
}

Reference Scene::exact(const Ray& ray, Lookup lookup, const ExactOptions& options) const {
  Reference r;
  ExactOptions o = options;
  o.surface = &r.surface;
  r.result = traceExact(modelFor(lookup), origin, ray.origin, ray.dir, o);
  return r;
}

Ray Scene::rayFromOutside(std::mt19937_64& rng, const glm::dvec3& target, long long index) const {
  const glm::dvec3 size = rootSize();
  const double radius = 0.5 * glm::length(size);
  const glm::dvec3 from = toWorld(0.5 * size) + radius * uniform(rng, 1.2, 4.0) * randomDirection(rng);
  return rayThrough(index, from, target);
}

namespace {

// |n . d| of the exact hit, floored as the tolerance says.
double cosine(const RayResult& exact, const Ray& ray, const Tolerance& tolerance) {
  return std::max(std::abs(glm::dot(exact.normal, ray.dir)), std::max(tolerance.minCosine, 1e-12));
}

bool sameShading(const RayResult& exact, const RayResult& cast) {
  // Near the tangent between a flat face and a curved solid the normal turns fast; 0.01 rad changes
  // a colour by at most 255 * 0.65 * 0.01 = 1.7, plus 1 for rounding (as raycast_accuracy_test).
  if (exact.hit && glm::dot(exact.normal, cast.normal) < std::cos(0.01)) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if (std::abs(exact.colour[i] - cast.colour[i]) > 3) return false;
  return true;
}

// Whether the caster's answer is within tolerance of this exact answer. `shift` is how far along
// itself the exact ray was moved (its distances are shifted back by it).
bool withinTolerance(const Scene& s, const Ray& ray, const RayResult& exact, double shift, const RayResult& cast,
                     const Tolerance& tolerance) {
  if (exact.capped || cast.capped) return exact.capped == cast.capped;
  if (exact.hit != cast.hit) return false;
  if (exact.hit && std::abs(exact.distanceM + shift - cast.distanceM) > exactTolerance(s, ray, exact, tolerance))
    return false;
  return tolerance.compare == Compare::Distance || sameShading(exact, cast);
}

}  // namespace

double exactTolerance(const Scene& s, const Ray& ray, const RayResult& exact, const Tolerance& tolerance) {
  return s.positionTolerance(ray) / cosine(exact, ray, tolerance);
}

double heuristicBound(const Scene& s, const Ray& ray, const Reference& truth, const Tolerance& tolerance) {
  double displacement = 0;
  for (const ExactSurface::Level& level : truth.surface.path)
    for (int a = 0; a < 3; ++a) displacement += std::abs(level.normal[a]) * s.delta[level.block][a];
  return displacement / cosine(truth.result, ray, tolerance) + exactTolerance(s, ray, truth.result, tolerance);
}

std::string lookupName(Lookup lookup) { return lookup == Lookup::Exact ? "exact" : "heuristic"; }

std::string describe(const Scene& s, const Ray& ray, const RayResult& exact, const RayResult& cast, Lookup lookup) {
  const auto vec = [](const glm::dvec3& v) { return testing::describe(v); };
  const auto result = [](const RayResult& r) { return testing::describe(r); };
  return "scene \"" + s.name + "\" (root origin " + vec(s.origin) + "), " + lookupName(lookup) + " lookup, ray " +
         std::to_string(ray.index) + "\n    origin " + vec(ray.origin) + " dir " + vec(ray.dir) +
         "\n    exact:  " + result(exact) + "\n    caster: " + result(cast);
}

bool Tally::nearbyRayAgrees(const Scene& s, const Ray& ray, const RayResult& cast, const Tolerance& tolerance) const {
  const double shift = s.positionTolerance(ray);
  if (withinTolerance(s, ray, s.exact(ray, lookup_, {.minThicknessM = shift}).result, 0.0, cast, tolerance)) return true;
  // Solids that the ray only touches, along an edge or in the plane of a face, are decided by
  // rounding, and minThicknessM does not see all of them. Skip those the exact ray meets by
  // restarting it just past each (if the solid was thicker, the restarted ray starts inside it and
  // meets it at 0), and accept a hit of the caster on one that the exact ray skipped if its point
  // lies on the model's surface: a short probe back along its normal, from there or a tolerance
  // to a side, meets it, with that normal and (lit the same way) that colour.
  const auto onSurface = [&] {
    const glm::dvec3 point = ray.origin + cast.distanceM * ray.dir;
    for (const glm::dvec3& side : {glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0),
                                   glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)}) {
      const Ray probe{ray.index, point + shift * (2.0 * cast.normal + side), -cast.normal};
      const RayResult surface = s.exact(probe, lookup_).result;
      if (surface.hit && surface.distanceM <= 4 * shift &&
          (tolerance.compare == Compare::Distance || sameShading(surface, cast)))
        return true;
    }
    return false;
  };
  double skipped = 0;
  for (int skips = 0; skips < 4; ++skips) {
    Ray past = ray;
    past.origin += skipped * ray.dir;
    const RayResult exact = s.exact(past, lookup_).result;
    if (skips > 0 && withinTolerance(s, past, exact, skipped, cast, tolerance)) return true;
    if (cast.hit && (!exact.hit || skipped + exact.distanceM >= cast.distanceM - shift) && onSurface()) return true;
    if (!exact.hit || (skips > 0 && exact.distanceM == 0)) break;
    skipped += exact.distanceM + shift;
  }
  // Along itself: a ray starting on a boundary belongs to the cell on either side.
  for (const double along : {-shift, shift}) {
    Ray moved = ray;
    moved.origin += along * ray.dir;
    if (withinTolerance(s, moved, s.exact(moved, lookup_).result, along, cast, tolerance)) return true;
  }
  const glm::dvec3 helper = std::abs(ray.dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(ray.dir, helper)), v = glm::cross(ray.dir, u);
  for (const double length : {shift, 0.25 * shift}) {
    for (int k = 0; k < 16; ++k) {
      // Exact zeros at the quarter turns: a ray on a block's face must stay on it.
      const double angle = 2 * std::numbers::pi * k / 16;
      const double cu = k % 8 == 4 ? 0.0 : std::cos(angle), cv = k % 8 == 0 ? 0.0 : std::sin(angle);
      Ray moved = ray;
      moved.origin += length * (cu * u + cv * v);
      if (withinTolerance(s, moved, s.exact(moved, lookup_).result, 0.0, cast, tolerance)) return true;
    }
  }
  return false;
}

void Tally::measureFormatBound(const Scene& s, const Ray& ray, const Reference& truth, const RayResult& cast,
                               const Tolerance& tolerance) {
  const RayResult& t = truth.result;
  if (t.capped || cast.capped) return;
  double ratio = 0;
  if (t.hit != cast.hit) {
    ++hitOrMiss_;
  } else if (t.hit) {
    ratio = std::abs(t.distanceM - cast.distanceM) / heuristicBound(s, ray, truth, {.minCosine = tolerance.minCosine});
    if (ratio <= 1) {
      worstWithinBound_ = std::max(worstWithinBound_, ratio);
      return;
    }
    ++beyondBound_;
  } else {
    return;
  }
  if (beyondBound_ + hitOrMiss_ == 1) firstBeyond_ = describe(s, ray, t, cast, lookup_);
}

void Tally::judge(const Scene& s, const Ray& ray, const Reference& reference, const Reference& truth,
                  const RayResult& cast, const Tolerance& tolerance) {
  ++rays_;
  const RayResult& e = reference.result;
  if (e.capped || cast.capped) ++capped_;
  if (lookup_ == Lookup::Heuristic) measureFormatBound(s, ray, truth, cast, tolerance);
  if (withinTolerance(s, ray, e, 0.0, cast, tolerance)) {
    if (!e.hit) return;
    ++hits_;
    const double ulps = std::abs(e.distanceM - cast.distanceM) * cosine(e, ray, tolerance) /
                        (kFloatEpsilon * s.coordinateScale(ray));
    if (ulps > worst_) {
      worst_ = ulps;
      worstRay_ = describe(s, ray, e, cast, lookup_);
    }
  } else if (nearbyRayAgrees(s, ray, cast, tolerance)) {
    if (nearby_++ == 0) firstNearby_ = describe(s, ray, e, cast, lookup_);
  } else if (++failures_ <= 10) {
    ADD_FAILURE() << label_ << ": the caster disagrees with the exact path on the "
                  << (lookup_ == Lookup::Exact ? "model" : "heuristic model") << ":\n  "
                  << describe(s, ray, e, cast, lookup_);
  }
}

void Tally::report() const {
  const auto percent = [&](long long n) { return 100.0 * static_cast<double>(n) / static_cast<double>(std::max(rays_, 1LL)); };
  std::printf("%s: %lld rays, %lld agreeing hits, %lld capped; %lld answers of a nearby ray (%.3g %%), %lld failures\n"
              "  worst distance error of an agreeing hit: %.3g float ulps of the coordinate scale (x |n.d|)\n    %s\n",
              label_.c_str(), rays_, hits_, capped_, nearby_, percent(nearby_), failures_, worst_, worstRay_.c_str());
  if (nearby_ > 0) std::printf("  first answer of a nearby ray:\n    %s\n", firstNearby_.c_str());
  if (lookup_ == Lookup::Heuristic) {
    std::printf("  against the true model: worst hit within the format's bound at %.3g of it; beyond it (near edges "
                "the heuristic moved): %lld hits and %lld hit/miss (%.3g %% of the rays)\n",
                worstWithinBound_, beyondBound_, hitOrMiss_, percent(beyondBound_ + hitOrMiss_));
    if (beyondBound_ + hitOrMiss_ > 0) std::printf("  first of those:\n    %s\n", firstBeyond_.c_str());
  }
  EXPECT_EQ(failures_, 0) << label_;
}

Reference Comparison::check(const Scene& s, const Ray& ray, const Tolerance& tolerance) {
  const Reference truth = s.exact(ray, Lookup::Exact);
  exact_.judge(s, ray, truth, truth, s.cast(ray, Lookup::Exact), tolerance);
  heuristic_.judge(s, ray, s.exact(ray, Lookup::Heuristic), truth, s.cast(ray, Lookup::Heuristic), tolerance);
  return truth;
}

}  // namespace nut::stress
