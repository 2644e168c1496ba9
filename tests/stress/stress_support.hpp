// What the stress tests of the float ray caster share: a compiled scene (the image the caster
// reads, and the models the exact path reads), random rays, and the judgement of the caster's
// answers against the exact path's, with the tolerances of raycast_accuracy_test.cpp.
//
// Exact lookup is compared with the exact path on the model the image encodes (quantized(h)):
// hit or miss as the exact path, the distance within kToleranceUlps float ulps of the ray's
// coordinate scale over |n . d| (floored at Tolerance::minCosine), and for Compare::Shading the
// normal within 0.01 rad and every colour channel within 3. Otherwise the answer is accepted only
// as the exact answer of a nearby ray (backward error): the ray moved sideways or along itself by
// that position tolerance, with solids thinner than it ignored, or with a solid that it only
// touches (along an edge, or lying in the plane of a face) skipped or met. Anything else is a
// failure and prints the ray with 17 digits: scene, origin, direction, both answers.
//
// Heuristic lookup is judged the same way against the exact path on the *heuristic model*: the
// same hierarchy with every interior boundary where the heuristic lookup puts it,
// (k + f / 256) D / M (docs/FORMAT.md), read back from the image. That is the scene the heuristic
// caster draws, so it must match it to float precision too. How far that scene is from the true
// one is the format's heuristic error: each answer is also measured against the format's bound
// around the true model's (raycast_accuracy_test.cpp: the boundaries of block B move by at most
// D_a / (512 M_a), and the hit by at most the ExactSurface bound), and the rays beyond it, which
// pass near an edge the heuristic moved, are counted and reported.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/exact_path.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>

namespace nut::stress {

inline constexpr double kFloatEpsilon = 1.0 / (1 << 23);  // float ulp at 1
inline constexpr double kToleranceUlps = 8;                // as raycast_accuracy_test.cpp
inline constexpr int kNoCap = 1 << 20;                     // iteration cap of the accuracy checks

struct Ray {
  long long index = 0;
  glm::dvec3 origin{0.0}, dir{0.0};  // world metres; dir has length 1
};

// The ray from `from` through `to`.
Ray rayThrough(long long index, const glm::dvec3& from, const glm::dvec3& to);

// What the exact path says about a ray, with the surface it hit.
struct Reference {
  RayResult result;
  ExactSurface surface;
};

// A hierarchy as both renderers see it. Not movable: the caster keeps a reference to the image.
// Every ray cast() traces (up to kPacketCheckRays) is traced again by the packet caster
// (HniRayCaster::traceMany) when the scene is destroyed, in batches of every ray cast with the same
// lookup and cap; each answer must be the one-ray caster's to the bit, or the test fails naming
// the ray. So every stress test checks the packet path on its own scenes and rays too.
inline constexpr std::size_t kPacketCheckRays = 1000000;

struct Scene {
  std::string name;
  Hierarchy model;                 // quantized(h): exactly what the image encodes
  Hierarchy heuristicModel;        // model with the boundaries where the heuristic lookup puts them
  Image image;
  glm::dvec3 origin{0.0};          // world position of the root block's minimum corner
  std::vector<glm::dvec3> delta;   // per block: the heuristic boundary error bound per axis, metres
  std::unique_ptr<HniRayCaster> caster;

  Scene() = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  ~Scene();

  glm::dvec3 rootSize() const { return model.blocks[model.root].sizeM(); }
  glm::dvec3 toWorld(const glm::dvec3& local) const { return origin + local; }
  // The size of the coordinates the float caster computes with for this ray.
  double coordinateScale(const Ray& ray) const;
  // The float caster's position tolerance for this ray (metres).
  double positionTolerance(const Ray& ray) const;

  // The model whose exact answers the caster in this lookup mode must reproduce.
  const Hierarchy& modelFor(Lookup lookup) const { return lookup == Lookup::Exact ? model : heuristicModel; }
  RayResult cast(const Ray& ray, Lookup lookup, int maxIterations = kNoCap) const;
  Reference exact(const Ray& ray, Lookup lookup = Lookup::Exact, const ExactOptions& options = {}) const;

  // A ray from a random point 1.2 to 4 bounding radii from the root box's centre towards `target`.
  Ray rayFromOutside(std::mt19937_64& rng, const glm::dvec3& target, long long index) const;

 private:
  struct Cast {
    Ray ray;
    Lookup lookup;
    int maxIterations;
    RayResult result;
  };
  mutable std::vector<Cast> casts_;  // what cast() answered, for the packet check
  void expectPacketsAgree() const;
};

// Compiles h (a test failure naming the scene when it does not compile; nullptr then).
std::unique_ptr<Scene> makeScene(const std::string& name, const Hierarchy& h, const glm::dvec3& origin);

enum class Compare {
  Distance,  // hit or miss, and the distance
  Shading,   // that, the normal and the colour
};

struct Tolerance {
  Compare compare = Compare::Shading;
  // |n . d| is floored at this in the distance tolerance, as in raycast_accuracy_test.cpp. Tests of
  // deliberately grazing rays lower it: for them the backward error |error| |n . d| (the sideways
  // shift of the ray that explains the answer) is what float precision bounds.
  double minCosine = 1e-3;
};

// The distance tolerance for one exact answer: the position tolerance over |n . d|.
double exactTolerance(const Scene& s, const Ray& ray, const RayResult& exact, const Tolerance& tolerance = {});
// The format's heuristic bound for one hit of the true model (exact_path.hpp): sum over the blocks
// from the root to the one whose surface was hit of sum_a |n_a| delta_a, over |n . d|, plus the
// exact tolerance.
double heuristicBound(const Scene& s, const Ray& ray, const Reference& truth, const Tolerance& tolerance = {});

// Judges the caster's answers in one lookup mode over many rays, keeping the worst error and the
// first failures, and reports them.
class Tally {
 public:
  Tally(std::string label, Lookup lookup) : label_(std::move(label)), lookup_(lookup) {}

  // Judges the caster's answer against `reference`, the exact path on s.modelFor(lookup); in
  // heuristic lookup also measures it against the format's bound around `truth`, the exact path
  // on the true model.
  void judge(const Scene& s, const Ray& ray, const Reference& reference, const Reference& truth,
             const RayResult& cast, const Tolerance& tolerance);
  // Prints the summary and fails the test if any ray failed.
  void report() const;

  // The worst distance error of an agreeing hit, in float ulps of the coordinate scale times |n . d|.
  double worst() const { return worst_; }

 private:
  bool nearbyRayAgrees(const Scene& s, const Ray& ray, const RayResult& cast, const Tolerance& tolerance) const;
  void measureFormatBound(const Scene& s, const Ray& ray, const Reference& truth, const RayResult& cast,
                          const Tolerance& tolerance);

  std::string label_;
  Lookup lookup_;
  long long rays_ = 0, hits_ = 0, nearby_ = 0, failures_ = 0, capped_ = 0;
  double worst_ = 0;  // float ulps of the coordinate scale, times |n . d|
  std::string worstRay_, firstNearby_;
  long long beyondBound_ = 0, hitOrMiss_ = 0;
  double worstWithinBound_ = 0;  // fraction of the format's bound
  std::string firstBeyond_;
};

// Both lookup modes over the same rays.
class Comparison {
 public:
  explicit Comparison(const std::string& label)
      : exact_(label + ", exact lookup", Lookup::Exact), heuristic_(label + ", heuristic lookup", Lookup::Heuristic) {}
  // Traces the ray with the caster in both modes and with the exact path on both models, and
  // judges; returns the exact path's answer on the true model.
  Reference check(const Scene& s, const Ray& ray, const Tolerance& tolerance = {});
  void report() const {
    exact_.report();
    heuristic_.report();
  }
  const Tally& exactLookup() const { return exact_; }
  const Tally& heuristicLookup() const { return heuristic_; }

 private:
  Tally exact_, heuristic_;
};

std::string describe(const Scene& s, const Ray& ray, const RayResult& exact, const RayResult& cast, Lookup lookup);
std::string lookupName(Lookup lookup);

double uniform(std::mt19937_64& rng, double lo, double hi);
// A uniformly random unit vector.
glm::dvec3 randomDirection(std::mt19937_64& rng);

}  // namespace nut::stress
