// Closed surfaces (closed_surface.hpp): edges matched between their vertices, then what does
// not cancel there matched along supporting lines.
#include "closed_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace nut::converter::solid {

namespace {

using glm::dvec3;

// A supporting line is keyed by its unit direction (sign fixed so that its largest component is
// positive) and its point nearest the mesh's first vertex, both rounded to these steps. Collinear
// edges whose keys round apart make the surface count as open: the occupancy step then asks the
// winding number, slower but never wrong.
constexpr double kDirectionStep = 1e-6;
constexpr double kOffsetStepM = 1e-5;
// Positions along a line this close are one position (runs meeting end to end at a T-junction).
constexpr double kSamePlaceM = 1e-6;

// Positions at one place share an index: the first of them in lexicographic order.
std::vector<std::uint32_t> weldPositions(const std::vector<dvec3>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto less = [&](std::uint32_t a, std::uint32_t b) {
    const dvec3 &p = positions[a], &q = positions[b];
    return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> weld(positions.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    weld[order[i]] = i > 0 && !less(order[i - 1], order[i]) ? weld[order[i - 1]] : order[i];
  return weld;
}

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

bool isClosedSurface(const Mesh& mesh) {
  if (mesh.triangles.empty()) return false;
  const std::vector<std::uint32_t> weld = weldPositions(mesh.positions);

  // Every edge once per triangle that runs it, filed under its lower vertex as (higher vertex,
  // whether run low to high) packed into one integer (indices below 2^31).
  if (mesh.positions.size() >= (std::size_t{1} << 31)) return false;
  std::vector<std::uint32_t> start(mesh.positions.size() + 1, 0);
  const auto eachEdge = [&](auto&& use) {
    for (const auto& t : mesh.triangles)
      for (std::size_t k = 0; k < 3; ++k)
        if (const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]]; a != b) use(a, b);
  };
  eachEdge([&](std::uint32_t a, std::uint32_t b) { ++start[std::min(a, b) + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> uses(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    eachEdge([&](std::uint32_t a, std::uint32_t b) { uses[fill[std::min(a, b)]++] = std::max(a, b) << 1 | (a < b ? 1u : 0u); });
  }

  const dvec3 corner = mesh.positions[mesh.triangles[0][0]];
  std::vector<Run> runs;
  for (std::uint32_t low = 0; low < mesh.positions.size(); ++low) {
    const auto first = uses.begin() + start[low], last = uses.begin() + start[low + 1];
    std::sort(first, last);
    for (auto i = first; i != last;) {
      const std::uint32_t high = *i >> 1;
      int balance = 0;
      for (; i != last && *i >> 1 == high; ++i) balance += (*i & 1) ? 1 : -1;
      if (balance != 0) runs.push_back(runOnLine(mesh.positions[low], mesh.positions[high], balance, corner));
    }
  }

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

}  // namespace nut::converter::solid
