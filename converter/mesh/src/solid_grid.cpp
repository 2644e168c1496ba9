// Solid conversion, first steps and driver: faces sorted into axis-aligned, sloped and other,
// plane clustering, the grid's boundaries, slope closure, and buildSolidGrid (converter/solid.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <tuple>

#include <glm/geometric.hpp>

#include <nut/units.hpp>

#include "solid_builder.hpp"
#include "weld.hpp"

namespace nut::converter {
namespace solid {

// Index of the last boundary <= x (clamped to a cell index 0..n-1).
int cellOf(const std::vector<double>& bounds, double x) {
  const auto it = std::upper_bound(bounds.begin(), bounds.end(), x);
  const int i = static_cast<int>(it - bounds.begin()) - 1;
  return std::clamp(i, 0, static_cast<int>(bounds.size()) - 2);
}

// Index of the boundary nearest to x.
int nearestBoundary(const std::vector<double>& bounds, double x) {
  const auto it = std::lower_bound(bounds.begin(), bounds.end(), x);
  if (it == bounds.begin()) return 0;
  if (it == bounds.end()) return static_cast<int>(bounds.size()) - 1;
  const int i = static_cast<int>(it - bounds.begin());
  return x - bounds[static_cast<std::size_t>(i - 1)] <= bounds[static_cast<std::size_t>(i)] - x ? i - 1 : i;
}

bool hasBoundaryNear(const std::vector<double>& bounds, double x, double tolerance) {
  return std::abs(bounds[static_cast<std::size_t>(nearestBoundary(bounds, x))] - x) <= tolerance;
}

// Sorted, millimetre-snapped positions at least 1 mm apart; 0 and size stay exact.
std::vector<double> tidy(std::vector<double> positions, double size) {
  for (double& p : positions) p = std::clamp(snapToUnits(p), 0.0, size);
  positions.push_back(0.0);
  positions.push_back(size);
  std::sort(positions.begin(), positions.end());
  std::vector<double> out;
  for (double p : positions)
    if (out.empty() || p - out.back() >= 0.001 - 1e-9) out.push_back(p);
  if (out.back() != size) out.back() = size;  // the last one within 1 mm of size becomes size
  return out;
}

bool snappedWithin(double boundary, double x, double tol) {
  constexpr double kRoundingM = 1e-9;
  return std::abs(boundary - snapToUnits(x)) <= tol + kRoundingM;
}

// Inserts positions into one axis's boundaries unless a boundary lies within the tolerance (in
// whole millimetres: snappedWithin).
void insertBoundaries(std::vector<double>& bounds, std::vector<double> positions, double size, double tol) {
  for (double& p : positions) p = snapToUnits(p);
  std::sort(positions.begin(), positions.end());
  std::vector<double> merged = bounds;
  for (double p : positions)
    if (!snappedWithin(merged[static_cast<std::size_t>(nearestBoundary(merged, p))], p, tol)) {
      merged.push_back(p);
      std::sort(merged.begin(), merged.end());
    }
  bounds = tidy(std::move(merged), size);
}

namespace {

// Clusters weighted intervals [lo, hi] whose gaps are at most `tolerance`; returns each
// cluster's weighted mean of `centre` and sets cluster[i] for every item. A cluster that reaches
// the end of the axis (0 or size) within the tolerance sits there: a wall tilted by half a degree
// spans centimetres, and a boundary at its mean would leave a sliver of cells half in the wall.
//
// A cluster spanning more than twice the tolerance would put its surfaces up to half its span
// from its one boundary: a facade turned 0.5 degrees against the rest of a surveyed building
// drifts 7 cm over its 8 m, and its wall, frames and panes chain into one. Where such a cluster
// holds flat items (within the tolerance of their own plane: panes, frames, sills, the strips of
// a finely cut wall) at two places or more, each place becomes a step instead: the flat items'
// centres are grouped from the lowest, each group spanning at most twice the tolerance, at its
// weighted mean kept within the tolerance of both its ends; every item joins the step nearest its
// centre. The steps are marked in `drifts`: buildBounds keeps them apart, and computeShares
// places a tilted face's pieces at the steps they reach. A chain of tilted faces alone (a
// surveyed wall of two triangles) keeps one boundary, since a step per face would not follow it
// better.
struct Interval {
  double lo, hi, centre, weight;
  std::uint32_t item;
};
std::vector<double> clusterIntervals(std::vector<Interval> items, double tolerance, double size,
                                     std::vector<int>& cluster, std::vector<bool>& drifts) {
  std::sort(items.begin(), items.end(), [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  std::vector<double> means;
  const auto atEnds = [&](double lo, double hi, double mean) {
    return lo <= tolerance ? 0.0 : hi >= size - tolerance ? size : mean;
  };
  const auto close = [&](std::span<Interval> members, double lo, double hi) {
    const auto merged = [&] {
      double sum = 0, weight = 0;
      for (const Interval& it : members) {
        sum += it.weight * it.centre;
        weight += it.weight;
        cluster[it.item] = static_cast<int>(means.size());
      }
      means.push_back(atEnds(lo, hi, sum / weight));
      drifts.push_back(false);
    };
    if (hi - lo <= 2 * tolerance) {
      merged();
      return;
    }
    const auto flat = [&](const Interval& it) { return it.hi - it.lo <= tolerance; };
    std::vector<double> steps;
    std::sort(members.begin(), members.end(), [](const Interval& a, const Interval& b) { return a.centre < b.centre; });
    for (std::size_t i = 0; i < members.size();) {
      if (!flat(members[i])) {
        ++i;
        continue;
      }
      double sum = 0, weight = 0, last = members[i].centre;
      std::size_t j = i;
      for (; j < members.size() && members[j].centre <= members[i].centre + 2 * tolerance; ++j)
        if (flat(members[j])) {
          sum += members[j].weight * members[j].centre;
          weight += members[j].weight;
          last = members[j].centre;
        }
      steps.push_back(std::clamp(sum / weight, last - tolerance, members[i].centre + tolerance));
      i = j;
    }
    if (steps.size() < 2) {
      merged();
      return;
    }
    const auto base = static_cast<int>(means.size());
    for (const Interval& it : members) cluster[it.item] = base + nearestBoundary(steps, it.centre);
    for (double step : steps) {
      means.push_back(atEnds(step - tolerance, step + tolerance, step));
      drifts.push_back(true);
    }
  };
  std::size_t first = 0;
  double lo = 0, reach = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > first && items[i].lo > reach + tolerance) {
      close(std::span(items).subspan(first, i - first), lo, reach);
      first = i;
    }
    if (i == first) {
      lo = items[i].lo;
      reach = items[i].hi;
    }
    reach = std::max(reach, items[i].hi);
  }
  if (first < items.size()) close(std::span(items).subspan(first), lo, reach);
  return means;
}

// Merges candidate positions closer than `tolerance` (weighted mean; 0 and size win) and tidies.
std::vector<double> mergePositions(std::vector<std::pair<double, double>> candidates, double size, double tolerance) {
  candidates.emplace_back(0.0, std::numeric_limits<double>::infinity());
  candidates.emplace_back(size, std::numeric_limits<double>::infinity());
  std::sort(candidates.begin(), candidates.end());
  std::vector<double> out;
  std::size_t i = 0;
  while (i < candidates.size()) {
    std::size_t j = i + 1;
    while (j < candidates.size() && candidates[j].first - candidates[j - 1].first <= tolerance) ++j;
    double sum = 0, weight = 0, fixed = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = i; k < j; ++k) {
      if (std::isinf(candidates[k].second)) fixed = candidates[k].first;
      sum += candidates[k].second * candidates[k].first;
      weight += candidates[k].second;
    }
    out.push_back(!std::isnan(fixed) ? fixed : weight > 0 ? sum / weight : candidates[i].first);
    i = j;
  }
  return tidy(std::move(out), size);
}

// The slopes' crease points (SlopePlane::creasePoints). A crease is an edge that a face of one
// slope shares with a face of a slope along another axis (matched by position) and that runs
// diagonally across the first slope's (s, e) coordinates, beyond the tolerance both ways: a hip
// (solid = y' <= min of the two planes) or a valley (max). The cells such an edge passes through
// are covered by each plane only partly, so fitWedges cannot make them wedges of either. Points
// that cut the edge into equal steps (kCreaseSteps at most, each kCreaseMinStep tolerances long at
// least) become boundaries on all three axes; the edge's ends are the slopes' ends already. Then
// the crease passes through one small cell per step, a staircase, while the cells beside it are
// covered whole and become wedges; the slope across the crease has the same edge and points. An
// edge shared with a slope along the same axis (the diagonal of a quad split into two triangles
// that are not quite coplanar) or with anything else is no crease.
void findCreasePoints(std::vector<SlopePlane>& slopes, const std::vector<std::array<dvec3, 3>>& corners, double tol) {
  using Key = std::array<double, 6>;
  struct Edge {
    Key key;
    std::size_t plane;
  };
  std::vector<Edge> edges;
  for (std::size_t id = 0; id < slopes.size(); ++id)
    for (const std::uint32_t f : slopes[id].faces)
      for (int k = 0; k < 3; ++k) {
        dvec3 a = corners[f][static_cast<std::size_t>(k)], b = corners[f][static_cast<std::size_t>((k + 1) % 3)];
        if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
        edges.push_back({{a.x, a.y, a.z, b.x, b.y, b.z}, id});
      }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return x.key != y.key ? x.key < y.key : x.plane < y.plane; });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    const dvec3 a(edges[i].key[0], edges[i].key[1], edges[i].key[2]),
        b(edges[i].key[3], edges[i].key[4], edges[i].key[5]);
    // Exactly two faces, of slopes along different axes.
    if (j == i + 2 && slopes[edges[i].plane].e != slopes[edges[i + 1].plane].e)
      for (std::size_t m = i; m < j; ++m) {
        SlopePlane& plane = slopes[edges[m].plane];
        const int e = plane.e, u = kU[e], v = kV[e];
        const dvec2 t(-plane.n.y, plane.n.x);
        const double ds = glm::dot(t, dvec2(b[u] - a[u], b[v] - a[v])), de = b[e] - a[e];
        if (std::abs(ds) <= tol || std::abs(de) <= tol) continue;  // along or across the slope
        const int steps = std::clamp(static_cast<int>(std::min(std::abs(ds), std::abs(de)) / (kCreaseMinStep * tol)), 1,
                                     kCreaseSteps);
        for (int k = 1; k < steps; ++k) plane.creasePoints.push_back(a + (static_cast<double>(k) / steps) * (b - a));
      }
    i = j;
  }
}

}  // namespace

void Builder::analyseFaces() {
  const double cosAligned = std::cos(options.angleToleranceDeg * std::numbers::pi / 180.0);
  const double sinAlong = std::sin(options.angleToleranceDeg * std::numbers::pi / 180.0);
  faces.resize(mesh.triangles.size());
  std::array<std::vector<Interval>, 3> intervals;
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    Face& face = faces[f];
    const dvec3 a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
    face.areaVector = 0.5 * glm::cross(b - a, c - a);
    face.area = glm::length(face.areaVector);
    stats.areaM2 += face.area;
    if (face.area <= 0) continue;
    const dvec3 normal = face.areaVector / face.area;
    const dvec3 absN = glm::abs(normal);
    const int major = absN.x >= absN.y && absN.x >= absN.z ? 0 : absN.y >= absN.z ? 1 : 2;
    if (absN[major] >= cosAligned) {
      face.kind = FaceKind::Aligned;
      face.axis = major;
      intervals[static_cast<std::size_t>(major)].push_back({std::min({a[major], b[major], c[major]}),
                                                            std::max({a[major], b[major], c[major]}),
                                                            (a[major] + b[major] + c[major]) / 3.0, face.area, f});
      continue;
    }
    for (int e = 0; e < 3; ++e)
      if (absN[e] <= sinAlong && absN[kU[e]] > sinAlong && absN[kV[e]] > sinAlong) {
        face.kind = FaceKind::Slope;
        face.axis = e;
      }
  }
  std::vector<int> cluster(faces.size(), -1);
  for (int a = 0; a < 3; ++a) {
    clusterMeans[static_cast<std::size_t>(a)] = clusterIntervals(intervals[static_cast<std::size_t>(a)], tol, size[a],
                                                                 cluster, clusterDrifts[static_cast<std::size_t>(a)]);
    stats.planes[static_cast<std::size_t>(a)] = static_cast<int>(clusterMeans[static_cast<std::size_t>(a)].size());
  }
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    if (faces[f].kind == FaceKind::Aligned) faces[f].group = cluster[f];
}

// Groups slope faces into planes: same extrusion axis, normals within the angle tolerance,
// offsets within the distance tolerance.
void Builder::findSlopes() {
  if (!options.wedges) {
    for (Face& f : faces)
      if (f.kind == FaceKind::Slope) f.kind = FaceKind::General;
    return;
  }
  struct Item {
    int e;
    double angle, offset;
    std::uint32_t face;
  };
  std::vector<Item> items;
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].kind != FaceKind::Slope) continue;
    const int e = faces[f].axis;
    const dvec2 n2 = glm::normalize(dvec2(faces[f].areaVector[kU[e]], faces[f].areaVector[kV[e]]));
    const dvec3 centre = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
    items.push_back({e, std::atan2(n2.y, n2.x), glm::dot(n2, dvec2(centre[kU[e]], centre[kV[e]])), f});
  }
  std::sort(items.begin(), items.end(),
            [](const Item& a, const Item& b) { return a.e != b.e ? a.e < b.e : a.angle < b.angle; });
  const double angleTol = options.angleToleranceDeg * std::numbers::pi / 180.0;
  std::size_t i = 0;
  while (i < items.size()) {
    std::size_t j = i + 1;
    while (j < items.size() && items[j].e == items[i].e && items[j].angle - items[j - 1].angle <= angleTol) ++j;
    std::sort(items.begin() + static_cast<std::ptrdiff_t>(i), items.begin() + static_cast<std::ptrdiff_t>(j),
              [](const Item& a, const Item& b) { return a.offset < b.offset; });
    std::size_t k = i;
    while (k < j) {
      std::size_t l = k + 1;
      while (l < j && items[l].offset - items[l - 1].offset <= tol) ++l;
      SlopePlane plane;
      plane.e = items[k].e;
      const int e = plane.e, u = kU[e], v = kV[e];
      dvec2 normalSum(0.0);
      std::vector<double> materialArea(mesh.materials.size(), 0.0);
      for (std::size_t m = k; m < l; ++m) {
        const Face& face = faces[items[m].face];
        normalSum += dvec2(face.areaVector[u], face.areaVector[v]);
        plane.area += face.area;
        plane.faces.push_back(items[m].face);
        materialArea[mesh.triangleMaterial[items[m].face]] += face.area;
      }
      plane.n = glm::normalize(normalSum);
      double offsetSum = 0;
      plane.s0 = plane.e0 = std::numeric_limits<double>::infinity();
      plane.s1 = plane.e1 = -std::numeric_limits<double>::infinity();
      const dvec2 t(-plane.n.y, plane.n.x);
      for (std::uint32_t f : plane.faces) {
        for (int c = 0; c < 3; ++c) {
          const dvec3 q = corner(f, c);
          const double s = glm::dot(t, dvec2(q[u], q[v]));
          plane.s0 = std::min(plane.s0, s);
          plane.s1 = std::max(plane.s1, s);
          plane.e0 = std::min(plane.e0, q[e]);
          plane.e1 = std::max(plane.e1, q[e]);
          offsetSum += faces[f].area / 3.0 * glm::dot(plane.n, dvec2(q[u], q[v]));
        }
      }
      plane.offset = offsetSum / plane.area;
      plane.material =
          static_cast<std::uint16_t>(std::max_element(materialArea.begin(), materialArea.end()) - materialArea.begin());
      const auto id = static_cast<int>(slopes.size());
      for (std::uint32_t f : plane.faces) faces[f].group = id;
      slopes.push_back(std::move(plane));
      k = l;
    }
    i = j;
  }
  stats.slopes = static_cast<int>(slopes.size());
  if (slopes.size() < 2) return;
  std::vector<std::array<dvec3, 3>> corners(faces.size());
  for (const SlopePlane& plane : slopes)
    for (const std::uint32_t f : plane.faces) corners[f] = {corner(f, 0), corner(f, 1), corner(f, 2)};
  findCreasePoints(slopes, corners, tol);
}

// Lines where axis-aligned faces of different materials meet in one plane (a roof flush with the
// wall tops around it, a painted band): no face lies across them, so no plane cluster puts a
// boundary there, and the cell the line crosses shows one material on both sides of it (the
// house's 0.3 m wall-top strip became 0.2 m, the next boundary in). An edge of such a face that
// runs along an axis lies on a line of constant coordinate c; where edges of two materials on one
// plane lie on one such line (within the tolerance), the line is kept with the length the two
// materials share on it (the smaller of their edge lengths). addMaterialEdges decides which get
// a boundary.
void Builder::findMaterialEdges() {
  struct Edge {
    int plane, group, axis;  // the faces' plane (axis, cluster) and the axis c held constant
    double at;               // c
    double length;
    std::uint16_t material;
  };
  std::vector<Edge> edges;
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    const Face& face = faces[f];
    if (face.kind != FaceKind::Aligned) continue;
    // The underside the building stands on is not seen.
    if (face.axis == 1 && std::max({corner(f, 0).y, corner(f, 1).y, corner(f, 2).y}) <= tol) continue;
    for (int k = 0; k < 3; ++k) {
      const dvec3 a = corner(f, k), b = corner(f, (k + 1) % 3);
      for (int c = 0; c < 3; ++c) {
        const int along = 3 - face.axis - c;
        if (c != face.axis && std::abs(a[c] - b[c]) <= tol && std::abs(a[along] - b[along]) > tol)
          edges.push_back(
              {face.axis, face.group, c, 0.5 * (a[c] + b[c]), std::abs(a[along] - b[along]), mesh.triangleMaterial[f]});
      }
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return std::tie(x.plane, x.group, x.axis, x.at) < std::tie(y.plane, y.group, y.axis, y.at);
  });
  std::map<std::uint16_t, double> lengthOf;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].plane == edges[i].plane && edges[j].group == edges[i].group &&
           edges[j].axis == edges[i].axis && edges[j].at - edges[j - 1].at <= tol)
      ++j;
    lengthOf.clear();
    double sum = 0;
    for (std::size_t k = i; k < j; ++k) {
      lengthOf[edges[k].material] += edges[k].length;
      sum += edges[k].at;
    }
    if (lengthOf.size() >= 2) {
      std::vector<double> lengths;
      for (const auto& [material, length] : lengthOf) lengths.push_back(length);
      std::sort(lengths.rbegin(), lengths.rend());
      materialLines[static_cast<std::size_t>(edges[i].axis)].push_back({sum / static_cast<double>(j - i), lengths[1]});
    }
    i = j;
  }
}

// A material line gets a boundary when the strip of faces it would otherwise colour wrongly (its
// shared length times its distance to the nearer boundary around it) is at least
// kMaterialEdgeShareOfSurface of the surface: the house's wall-top strip (0.1 m x 9.4 m a side,
// 0.11 % of its surface) does, a sliver of window glass in the side of the residential block's
// entrance (0.05 m x 1.2 m, 0.002 %) does not; each boundary cuts the whole grid, and the slopes it
// crosses add their own.
void Builder::addMaterialEdges() {
  for (int a = 0; a < 3; ++a) {
    std::vector<double> kept;
    const auto& B = bounds[static_cast<std::size_t>(a)];
    for (const MaterialLine& line : materialLines[static_cast<std::size_t>(a)]) {
      const auto next = std::upper_bound(B.begin(), B.end(), line.at);
      if (next == B.begin() || next == B.end()) continue;
      const double width = std::min(line.at - *(next - 1), *next - line.at);
      if (width > tol && width * line.length >= kMaterialEdgeShareOfSurface * stats.areaM2) kept.push_back(line.at);
    }
    stats.materialBoundaries += static_cast<long long>(kept.size());
    insertBoundaries(bounds[static_cast<std::size_t>(a)], kept, size[a], tol);
  }
}

void Builder::buildBounds() {
  for (int a = 0; a < 3; ++a) {
    std::vector<std::pair<double, double>> candidates;
    std::vector<double> weights(clusterMeans[static_cast<std::size_t>(a)].size(), 0.0);
    for (const Face& f : faces)
      if (f.kind == FaceKind::Aligned && f.axis == a) weights[static_cast<std::size_t>(f.group)] += f.area;
    std::vector<double> drifting;
    for (std::size_t c = 0; c < weights.size(); ++c)
      if (clusterDrifts[static_cast<std::size_t>(a)][c])
        drifting.push_back(clusterMeans[static_cast<std::size_t>(a)][c]);
      else
        candidates.emplace_back(clusterMeans[static_cast<std::size_t>(a)][c], weights[c]);
    bounds[static_cast<std::size_t>(a)] = mergePositions(std::move(candidates), size[a], tol);
    // A drifting cluster's steps are kept apart: merged as the others are, they would chain back
    // into one boundary.
    insertBoundaries(bounds[static_cast<std::size_t>(a)], std::move(drifting), size[a], tol);
    insertBoundaries(bounds[static_cast<std::size_t>(a)], extraBounds[static_cast<std::size_t>(a)], size[a], tol);
  }
}

namespace {

using Bounds = std::array<std::vector<double>, 3>;

// Slopes closed into a grid's boundaries, and those left out.
struct Closure {
  Bounds bounds;
  std::vector<std::size_t> accepted, rejected;
  int offDiagonal = 0;  // columns (u cells) of accepted slopes that do not run corner to corner
};

// Closes a builder's slopes, largest first, into its boundaries (Builder::closeSlopes).
class SlopeCloser {
 public:
  explicit SlopeCloser(const Builder& b)
      : b_(b), initial_{b.bounds[0].size(), b.bounds[1].size(), b.bounds[2].size()}, order_(b.slopes.size()) {
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    std::sort(order_.begin(), order_.end(),
              [&](std::size_t x, std::size_t y) { return b.slopes[x].area > b.slopes[y].area; });
  }

  // Every slope closed in turn (with its crease points where `creases` and they fit), each kept
  // only when its closure does not add too many boundaries.
  Closure closeAll(bool creases) const {
    Closure c;
    c.bounds = b_.bounds;
    for (std::size_t candidate : order_) {
      const SlopePlane& plane = b_.slopes[candidate];
      if (!plane.represented) continue;  // failed a previous attempt
      if (plane.area < kMinSlopeShare * b_.stats.areaM2) {
        c.rejected.push_back(candidate);  // a facet too small to pay for its boundaries
        continue;
      }
      c.accepted.push_back(candidate);
      auto trial = creases && !plane.creasePoints.empty() ? close(c, plane, true) : std::nullopt;
      if (!trial) trial = close(c, plane, false);
      if (!trial) {
        c.accepted.pop_back();
        c.rejected.push_back(candidate);
        continue;
      }
      c.bounds = std::move(*trial);
    }
    c.offDiagonal = offDiagonalColumns(c);
    return c;
  }

 private:
  // The boundaries with one more slope (the last of c.accepted) closed, or nothing when that adds
  // too many.
  std::optional<Bounds> close(const Closure& c, const SlopePlane& plane, bool creases) const {
    const double tol = b_.tol;
    const dvec3& size = b_.size;
    Bounds trial = c.bounds;
    const int u = kU[plane.e], v = kV[plane.e];
    insertBoundaries(trial[static_cast<std::size_t>(plane.e)], {plane.e0, plane.e1}, size[plane.e], tol);
    insertBoundaries(trial[static_cast<std::size_t>(u)], {plane.uMin(), plane.uMax()}, size[u], tol);
    insertBoundaries(trial[static_cast<std::size_t>(v)], {plane.vMin(), plane.vMax()}, size[v], tol);
    // What a lone slope would add: one boundary per boundary it crosses, plus its ends.
    std::size_t crossed = 4;
    for (double x : trial[static_cast<std::size_t>(u)]) crossed += x > plane.uMin() + tol && x < plane.uMax() - tol;
    for (double x : trial[static_cast<std::size_t>(v)]) crossed += x > plane.vMin() + tol && x < plane.vMax() - tol;
    const std::size_t own = creases ? addCreasePoints(trial, plane) : 0;
    const bool converged = closeCrossings(trial, c.accepted);
    std::size_t growth = 0;
    bool withinBudget = true;
    for (std::size_t a = 0; a < 3; ++a) {
      growth += trial[a].size() - c.bounds[a].size();
      withinBudget = withinBudget && trial[a].size() <= initial_[a] + kMaxSlopeBoundariesPerAxis;
    }
    if (growth > 2 * crossed + 8 + own || !withinBudget || (own > 0 && !converged)) return std::nullopt;
    return trial;
  }

  // Adds the plane's crease points, each on all three axes, and returns how many boundaries they
  // added. One that would land near a boundary but not on it (within half a step: a wall's plane
  // beside the eaves corner, another hip's step) is left out rather than make a sliver of cells;
  // the boundary there crosses the crease already.
  std::size_t addCreasePoints(Bounds& trial, const SlopePlane& plane) const {
    const double tol = b_.tol;
    std::size_t own = 0;
    for (const dvec3& q : plane.creasePoints) {
      bool clear = true;
      for (int a = 0; a < 3 && clear; ++a) {
        const auto& B = trial[static_cast<std::size_t>(a)];
        const double boundary = B[static_cast<std::size_t>(nearestBoundary(B, q[a]))];
        clear = snappedWithin(boundary, q[a], tol) || std::abs(boundary - q[a]) >= 0.5 * kCreaseMinStep * tol;
      }
      for (int a = 0; a < 3 && clear; ++a) {
        const std::size_t before = trial[static_cast<std::size_t>(a)].size();
        insertBoundaries(trial[static_cast<std::size_t>(a)], {q[a]}, b_.size[a], tol);
        own += trial[static_cast<std::size_t>(a)].size() - before;
      }
    }
    return own;
  }

  // Adds where each accepted slope crosses a boundary of the other axis of its cross-section,
  // round after round, since each addition may cross another slope. Returns whether the rounds
  // ended with nothing left to add.
  bool closeCrossings(Bounds& trial, const std::vector<std::size_t>& accepted) const {
    const double tol = b_.tol;
    for (int round = 0; round < kSlopeRounds; ++round) {
      Bounds added;
      for (std::size_t id : accepted) {
        const SlopePlane& sp = b_.slopes[id];
        const int su = kU[sp.e], sv = kV[sp.e];
        for (double bu : trial[static_cast<std::size_t>(su)])
          if (bu > sp.uMin() + tol && bu < sp.uMax() - tol) added[static_cast<std::size_t>(sv)].push_back(sp.vAt(bu));
        for (double bv : trial[static_cast<std::size_t>(sv)])
          if (bv > sp.vMin() + tol && bv < sp.vMax() - tol) added[static_cast<std::size_t>(su)].push_back(sp.uAt(bv));
      }
      bool any = false;
      for (int a = 0; a < 3; ++a) {
        const std::size_t before = trial[static_cast<std::size_t>(a)].size();
        insertBoundaries(trial[static_cast<std::size_t>(a)], std::move(added[static_cast<std::size_t>(a)]), b_.size[a],
                         tol);
        any = any || trial[static_cast<std::size_t>(a)].size() > before;
      }
      if (!any) return true;
    }
    return false;
  }

  // Columns of the accepted slopes whose ends are not within the tolerance of a pair of
  // neighbouring boundaries (fitWedges fails them whole).
  int offDiagonalColumns(const Closure& c) const {
    const double tol = b_.tol;
    int count = 0;
    for (const std::size_t id : c.accepted) {
      const SlopePlane& sp = b_.slopes[id];
      const auto& U = c.bounds[static_cast<std::size_t>(kU[sp.e])];
      const auto& V = c.bounds[static_cast<std::size_t>(kV[sp.e])];
      for (int i = cellOf(U, sp.uMin() + tol); i <= cellOf(U, sp.uMax() - tol); ++i) {
        const double va = sp.vAt(U[static_cast<std::size_t>(i)]), vb = sp.vAt(U[static_cast<std::size_t>(i + 1)]);
        const int j = nearestBoundary(V, std::min(va, vb));
        count += j + 1 >= static_cast<int>(V.size()) ||
                 std::abs(V[static_cast<std::size_t>(j)] - std::min(va, vb)) > tol ||
                 std::abs(V[static_cast<std::size_t>(j + 1)] - std::max(va, vb)) > tol;
      }
    }
    return count;
  }

  const Builder& b_;
  std::array<std::size_t, 3> initial_;  // boundaries per axis before any slope
  std::vector<std::size_t> order_;      // slopes, largest first
};

}  // namespace

// Adds, for each slope, its end lines and the boundaries where it crosses a boundary of the
// other axis of its cross-section, until every accepted slope runs through cells corner to corner.
// Slopes are taken largest first; one whose closure would add more boundaries than it crosses
// (parallel slopes feed each other: a ramp's top and bottom would cascade across its whole run)
// or push the grid past the budget is left to the complementary mesh.
//
// A slope's crease points (hips, valleys: SlopePlane::creasePoints) are added with it. They lie on
// the slope, so its own closure adds nothing for them, but they cross the other slopes too: they
// may add what they add themselves, and where the cascade beyond that is too large, or does not
// end within the rounds, the slope is closed without them (its cells along the crease are then
// larger, and more of it goes to the complementary mesh). More boundaries also make it likelier
// that one lands within the tolerance of a crossing and is merged with it, leaving a column of
// some slope off its diagonal (fitWedges fails it whole, a stripe of the wrong cells down a turned
// wall): so the slopes are closed both ways, and the crease points are kept only when they leave
// no slope rejected and no column off its diagonal that closing without them would not.
void Builder::closeSlopes() {
  if (slopes.empty()) return;
  const SlopeCloser closer(*this);
  Closure chosen = closer.closeAll(false);
  if (std::any_of(slopes.begin(), slopes.end(),
                  [](const SlopePlane& sp) { return sp.represented && !sp.creasePoints.empty(); })) {
    Closure creased = closer.closeAll(true);
    if (creased.rejected.size() <= chosen.rejected.size() && creased.offDiagonal <= chosen.offDiagonal)
      chosen = std::move(creased);
  }
  for (const std::size_t id : chosen.rejected) slopes[id].represented = false;
  for (std::size_t a = 0; a < 3; ++a)
    stats.slopeBoundaries += static_cast<long long>(chosen.bounds[a].size() - bounds[a].size());
  bounds = std::move(chosen.bounds);
}

}  // namespace solid

using namespace solid;

namespace {

// The mesh in the grid frame (its bounding box's minimum at the origin), and the grid's size,
// which an HNI must be able to hold.
Status placeMesh(Builder& builder) {
  const TriangleMesh& mesh = builder.mesh;
  const WorldBox box = mesh.bounds();
  builder.origin = box.min;
  builder.size = box.max - box.min;
  builder.p.reserve(mesh.positions.size());
  for (const dvec3& q : mesh.positions) builder.p.push_back(q - builder.origin);
  builder.cornerIds = weld(builder.p, mesh.triangles).triangles;
  // An HNI block spans at most a u24 of millimetres (16.8 km) per axis.
  const double maxSpanM = toMetres(format::kMaxLengthUnits);
  for (int a = 0; a < 3; ++a)
    if (!(builder.size[a] <= maxSpanM)) {
      char span[64];
      std::snprintf(span, sizeof span, "%.6g", builder.size[a]);
      return Error{mesh.name + ": the mesh spans " + span + " m along " + std::string(1, "xyz"[a]) +
                   ", more than an HNI holds (" + std::to_string(static_cast<int>(maxSpanM)) + " m)"};
    }
  for (int a = 0; a < 3; ++a)
    if (snapToUnits(builder.size[a]) < 0.001)
      return Error{mesh.name + ": the mesh is flat along " + std::string(1, "xyz"[a]) +
                   " (thinner than 1 mm), so it encloses no volume to convert"};
  for (int a = 0; a < 3; ++a) builder.size[a] = std::max(snapToUnits(builder.size[a]), 0.001);
  return Ok{};
}

// The cells of the boundaries just built, all unclassified; refused above SolidOptions::maxCells.
Status allocateCells(Builder& builder) {
  std::size_t cells = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    builder.n[a] = static_cast<int>(builder.bounds[a].size()) - 1;
    builder.stats.cells[a] = builder.n[a];
    cells *= static_cast<std::size_t>(builder.n[a]);
  }
  if (cells > builder.options.maxCells)
    return Error{builder.mesh.name + ": the grid would have " + std::to_string(builder.n[0]) + " x " +
                 std::to_string(builder.n[1]) + " x " + std::to_string(builder.n[2]) + " cells, more than " +
                 std::to_string(builder.options.maxCells) + "; raise --tolerance to merge nearby planes"};
  builder.shape.assign(cells, Builder::kUnclassified);
  builder.hint.assign(cells, 0);
  return Ok{};
}

// Proposed boundaries not yet there (nor within a tolerance of one another) go into the next
// build; `count` counts them. Returns whether there were any.
bool addBoundaries(Builder& builder, std::array<std::vector<double>, 3> proposals, long long& count) {
  bool added = false;
  for (std::size_t a = 0; a < 3; ++a) {
    auto& list = proposals[a];
    std::sort(list.begin(), list.end());
    std::vector<double> fresh;
    for (double p : list)
      if (!hasBoundaryNear(builder.bounds[a], p, builder.tol) && (fresh.empty() || p - fresh.back() > builder.tol))
        fresh.push_back(p);
    builder.extraBounds[a].insert(builder.extraBounds[a].end(), fresh.begin(), fresh.end());
    count += static_cast<long long>(fresh.size());
    added = added || !fresh.empty();
  }
  return added;
}

}  // namespace

Result<SolidGrid> buildSolidGrid(const TriangleMesh& mesh, const SolidOptions& asked) {
  if (mesh.triangles.empty()) return Error{mesh.name + ": no triangles to convert"};
  SolidOptions options = asked;
  if (options.enclosing) options.closedSurface = false;
  Builder builder(mesh, options);
  if (Status s = placeMesh(builder); !s) return s.error();

  using Clock = std::chrono::steady_clock;
  auto mark = Clock::now();
  const auto lap = [&mark] {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - mark).count();
    mark = now;
    return s;
  };
  builder.analyseFaces();
  builder.findQuadrics();       // before slopes: a quarter cylinder's faces are sloped too
  builder.findSphereOctants();  // a dome's faces near its quarters' seams may be sloped too
  builder.findCornerSlopes();   // planar faces sloped along three axes, the domes' taken
  builder.findSlopes();
  builder.findMaterialEdges();
  const LazyWinding winding(options.enclosing ? *options.enclosing : mesh);
  // The grid is built again when a slope did not come out as wedges or a quarter-round piece,
  // sphere octant or corner slope as its cells (its boundaries were added for nothing), cells show
  // faces of different materials (materialConflicts adds the boundaries that separate them) or
  // cells the complementary mesh cuts were emptied though most of them is solid
  // (proposeTrimSplits adds boundaries that keep that part). Slopes and pieces are judged by
  // winding numbers sampled in their own cells, before the occupancy of the rest, so a grid that
  // failed one is built again at once: its occupancy, which on a roof of many slopes tried and
  // given up is most of the conversion, is never computed, and such a build does not count
  // against kAttempts (each gives up at least one slope or piece for good).
  SolidGrid out;
  std::vector<Builder::Share> shares;
  for (int attempt = 0; attempt < kAttempts;) {
    builder.buildBounds();
    builder.addMaterialEdges();
    builder.addQuadricBounds();
    builder.stats.slopeBoundaries = 0;  // closeSlopes counts this attempt's
    builder.closeSlopes();
    if (Status s = allocateCells(builder); !s) return s.error();
    builder.stats.planesSeconds += lap();
    ++builder.stats.gridBuilds;
    builder.stats.slopesAsWedges = 0;
    bool fitted = builder.fitWedges(winding);
    fitted = builder.fitQuadrics(winding) && fitted;
    builder.stats.wedgesSeconds += lap();
    if (!fitted) continue;
    ++attempt;
    ++builder.stats.gridsClassified;
    builder.classify(winding);
    builder.stats.occupancySeconds += lap();
    builder.stats.trimmedCells = 0;
    builder.trimCutCells(winding);
    builder.stats.wedgesSeconds += lap();
    bool again = false;
    out.complement = TriangleMesh{};
    SolidStats area;
    std::vector<Builder::Share> lost;
    shares = builder.computeShares(out.complement, area, lost);
    builder.stats.nutAreaM2 = area.nutAreaM2;
    builder.stats.complementAreaM2 = area.complementAreaM2;
    builder.stats.hiddenAreaM2 = area.hiddenAreaM2;
    builder.stats.drawnTwiceAreaM2 = area.drawnTwiceAreaM2;
    double conflictArea = 0;
    auto conflicts = builder.materialConflicts(shares, conflictArea);
    builder.stats.conflictAreaM2 = conflictArea;
    if (attempt < kAttempts) {
      // Conflicts on a sliver of the surface are not worth another build of the grid.
      if (conflictArea > kConflictShareForRebuild * area.nutAreaM2)
        again = addBoundaries(builder, std::move(conflicts), builder.stats.materialBoundaries) || again;
      // Splits of trimmed cells are taken once: the cells they leave cut would propose splits of
      // their own, and so on down a roof.
      if (builder.stats.trimBoundaries == 0)
        again = addBoundaries(builder, builder.proposeTrimSplits(lost, winding), builder.stats.trimBoundaries) || again;
      // Plane corners are taken once too: the next build's mesh has the same planes.
      if (options.planeCells && options.closedSurface && builder.stats.planeBoundaries == 0)
        again = addBoundaries(builder, builder.proposePlaneCorners(), builder.stats.planeBoundaries) || again;
    }
    builder.stats.materialsSeconds += lap();
    if (!again) break;
  }
  builder.stats.treeSeconds = winding.buildSeconds();  // part of the step that needed it first

  out.originM = builder.origin;
  out.block.boundsM = builder.bounds;
  out.materials = mesh.materials;
  out.complement.name = mesh.name + " (complement)";
  out.complement.materials = mesh.materials;
  out.complement.materialNames = mesh.materialNames;
  builder.assignMaterials(out.block, out.subBlocks, shares);
  builder.stats.materialsSeconds += lap();
  out.stats = builder.stats;
  return out;
}

}  // namespace nut::converter
