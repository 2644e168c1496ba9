// Uncancelled edges matched along their supporting lines (closed_surface.hpp).
#include "closed_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace nut::converter {

namespace {

using glm::dvec3;

// A supporting line is keyed by its unit direction (sign fixed so that its largest component is
// positive) and its point nearest the first edge's start, both rounded to these steps. Collinear
// edges whose keys round apart make the surface count as open: the occupancy step then asks the
// winding number, slower but never wrong.
constexpr double kDirectionStep = 1e-6;
constexpr double kOffsetStepM = 1e-5;
// Positions along a line this close are one position (runs meeting end to end at a T-junction).
constexpr double kSamePlaceM = 1e-6;

// What an edge leaves uncancelled between its two vertices, placed on its supporting line:
// `weight` runs along the line's direction over [from, to].
struct Run {
  std::array<std::int64_t, 6> line;
  double from, to;
  int weight;
};

// v in whole steps, rounded to the nearest (inline, unlike std::llround: a mesh has many edges).
std::int64_t steps(double v, double step) {
  const double q = v / step;
  return static_cast<std::int64_t>(q < 0 ? q - 0.5 : q + 0.5);
}

Run runOnLine(const dvec3& a, const dvec3& b, int weight, const dvec3& corner) {
  dvec3 d = glm::normalize(b - a);
  int largest = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(d[k]) > std::abs(d[largest])) largest = k;
  if (d[largest] < 0) d = -d;
  const double ta = glm::dot(a - corner, d), tb = glm::dot(b - corner, d);
  const dvec3 nearest = (a - corner) - ta * d;
  Run run{};
  for (int k = 0; k < 3; ++k) {
    run.line[static_cast<std::size_t>(k)] = steps(d[k], kDirectionStep);
    run.line[static_cast<std::size_t>(k + 3)] = steps(nearest[k], kOffsetStepM);
  }
  run.from = std::min(ta, tb);
  run.to = std::max(ta, tb);
  run.weight = ta < tb ? weight : -weight;
  return run;
}

// Whether the runs of one line cancel everywhere along it (events: scratch space).
bool cancels(std::span<const Run> runs, std::vector<std::pair<double, int>>& events) {
  events.clear();
  for (const Run& r : runs) {
    events.emplace_back(r.from, r.weight);
    events.emplace_back(r.to, -r.weight);
  }
  std::sort(events.begin(), events.end());
  int sum = 0;
  for (std::size_t i = 0; i < events.size();) {
    const double at = events[i].first;
    for (; i < events.size() && events[i].first - at <= kSamePlaceM; ++i) sum += events[i].second;
    if (sum != 0 && i < events.size() && events[i].first - at > kSamePlaceM) return false;
  }
  return true;
}

}  // namespace

bool cancelAlongLines(std::span<const UncancelledEdge> edges) {
  if (edges.empty()) return true;
  std::vector<Run> runs;
  runs.reserve(edges.size());
  for (const UncancelledEdge& e : edges) runs.push_back(runOnLine(e.a, e.b, e.weight, edges.front().a));
  std::sort(runs.begin(), runs.end(), [](const Run& x, const Run& y) { return x.line < y.line; });
  std::vector<std::pair<double, int>> events;
  for (std::size_t i = 0; i < runs.size();) {
    std::size_t j = i;
    while (j < runs.size() && runs[j].line == runs[i].line) ++j;
    if (!cancels(std::span<const Run>(runs.data() + i, j - i), events)) return false;
    i = j;
  }
  return true;
}

}  // namespace nut::converter
