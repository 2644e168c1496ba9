// Solid conversion, occupancy: which cells are inside (closed lines by counting, the rest by
// generalized winding numbers), wedges where slopes run corner to corner, and the trimming of
// box cells that the complementary mesh cuts (converter/solid.hpp, steps 2 and 3).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <span>
#include <unordered_map>

#include <glm/geometric.hpp>

#include <nut/units.hpp>

#include "parallel.hpp"
#include "solid_builder.hpp"

namespace nut::converter::solid {

namespace {

// The lines of cell centres along the sweep axis s (the grid's longest), one per column: the
// cell centres (cb, cc) of the other two axes b and c.
struct Sweep {
  int s, b, c;
  std::vector<double> cs, cb, cc;  // cell centres along s, b and c
  double eps;                      // crossings closer than this along a line are at one position
  std::size_t columns() const { return cb.size() * cc.size(); }
};

Sweep sweepOf(const Builder& builder) {
  const auto& n = builder.n;
  const int s = static_cast<int>(std::max_element(n.begin(), n.end()) - n.begin());
  const auto centres = [&](int a) {
    std::vector<double> out;
    const auto& bd = builder.bounds[static_cast<std::size_t>(a)];
    for (std::size_t i = 0; i + 1 < bd.size(); ++i) out.push_back(0.5 * (bd[i] + bd[i + 1]));
    return out;
  };
  const int b = (s + 1) % 3, c = (s + 2) % 3;
  const dvec3& size = builder.size;
  return {s, b, c, centres(s), centres(b), centres(c), 1e-9 * std::max({size.x, size.y, size.z, 1.0})};
}

// A triangle of the surface the lines cross (grid frame).
struct SweptTriangle {
  dvec3 a, b, c;
  double normalS;  // the normal's component along the sweep axis (any length)
  std::uint16_t material;
};

// The faces of the mesh, or of the whole building's surface when the mesh is a part of it.
std::vector<SweptTriangle> sweptSurface(const Builder& builder, int s) {
  std::vector<SweptTriangle> surface;
  if (builder.options.enclosing) {
    const TriangleMesh& whole = *builder.options.enclosing;
    const dvec3& origin = builder.origin;
    for (std::size_t t = 0; t < whole.triangles.size(); ++t) {
      const auto& tri = whole.triangles[t];
      const dvec3 A = whole.positions[tri[0]] - origin, B = whole.positions[tri[1]] - origin,
                  C = whole.positions[tri[2]] - origin;
      const dvec3 normal = glm::cross(B - A, C - A);
      if (glm::dot(normal, normal) > 0) surface.push_back({A, B, C, normal[s], whole.triangleMaterial[t]});
    }
  } else {
    for (std::uint32_t f = 0; f < builder.faces.size(); ++f)
      if (builder.faces[f].area > 0)
        surface.push_back({builder.corner(f, 0), builder.corner(f, 1), builder.corner(f, 2),
                           builder.faces[f].areaVector[s], builder.mesh.triangleMaterial[f]});
  }
  return surface;
}

struct Crossing {
  std::uint32_t column;
  std::uint32_t face;
  double at;
  int sign;  // +1 entry, -1 exit, 0 seen edge-on (only splits runs)
};

// Every column's crossings, grouped by column: column k's are sorted[start[k]] to
// sorted[start[k + 1]], in no order yet.
struct ColumnCrossings {
  std::vector<std::size_t> start;
  std::vector<Crossing> sorted;
};

// Crossings of every face with every column line it may touch (inclusive: a crossing found twice
// is merged later, one missed would be wrong), grouped by a counting sort.
ColumnCrossings crossColumns(const std::vector<SweptTriangle>& surface, const Sweep& sweep) {
  const int s = sweep.s, b = sweep.b, c = sweep.c;
  const auto &cb = sweep.cb, &cc = sweep.cc;
  const double eps = sweep.eps;
  std::vector<Crossing> crossings;
  for (std::uint32_t f = 0; f < surface.size(); ++f) {
    const dvec3 A = surface[f].a, B = surface[f].b, C = surface[f].c;
    const double bmin = std::min({A[b], B[b], C[b]}) - eps, bmax = std::max({A[b], B[b], C[b]}) + eps;
    const double cmin = std::min({A[c], B[c], C[c]}) - eps, cmax = std::max({A[c], B[c], C[c]}) + eps;
    const auto j0 = static_cast<std::size_t>(std::lower_bound(cb.begin(), cb.end(), bmin) - cb.begin());
    const auto j1 = static_cast<std::size_t>(std::upper_bound(cb.begin(), cb.end(), bmax) - cb.begin());
    const auto k0 = static_cast<std::size_t>(std::lower_bound(cc.begin(), cc.end(), cmin) - cc.begin());
    const auto k1 = static_cast<std::size_t>(std::upper_bound(cc.begin(), cc.end(), cmax) - cc.begin());
    const dvec2 a2(A[b], A[c]), b2(B[b], B[c]), c2(C[b], C[c]);
    const double det = (b2.x - a2.x) * (c2.y - a2.y) - (b2.y - a2.y) * (c2.x - a2.x);
    const double scale = glm::length(b2 - a2) + glm::length(c2 - a2) + glm::length(c2 - b2);
    const bool edgeOn = std::abs(det) <= 1e-12 * scale * scale;
    const int sign = surface[f].normalS < 0 ? +1 : -1;
    const double sMin = std::min({A[s], B[s], C[s]}), sMax = std::max({A[s], B[s], C[s]});
    const double margin = 1e-9;
    for (std::size_t k = k0; k < k1; ++k)
      for (std::size_t j = j0; j < j1; ++j) {
        const dvec2 q(cb[j], cc[k]);
        const auto column = static_cast<std::uint32_t>(j + cb.size() * k);
        if (edgeOn) {
          // The line may run inside the face: split the runs at both its ends.
          crossings.push_back({column, f, sMin, 0});
          crossings.push_back({column, f, sMax, 0});
          continue;
        }
        const double l1 = ((q.x - a2.x) * (c2.y - a2.y) - (q.y - a2.y) * (c2.x - a2.x)) / det;
        const double l2 = ((b2.x - a2.x) * (q.y - a2.y) - (b2.y - a2.y) * (q.x - a2.x)) / det;
        if (l1 < -margin || l2 < -margin || l1 + l2 > 1 + margin) continue;
        crossings.push_back({column, f, A[s] + l1 * (B[s] - A[s]) + l2 * (C[s] - A[s]), sign});
      }
  }
  ColumnCrossings out;
  out.start.assign(sweep.columns() + 1, 0);
  for (const Crossing& x : crossings) ++out.start[x.column + 1];
  std::partial_sum(out.start.begin(), out.start.end(), out.start.begin());
  out.sorted.resize(crossings.size());
  std::vector<std::size_t> fillAt(out.start.begin(), out.start.end() - 1);
  for (const Crossing& x : crossings) out.sorted[fillAt[x.column]++] = x;
  return out;
}

// A column's crossings (sorted along the line) merged by position into events (position, change
// of the count): at most one entry and one exit at each. Returns whether the count is the winding
// number on this line: the surface is closed, and the count never drops below zero and ends at
// zero.
bool mergeCrossings(std::span<const Crossing> crossings, double eps, bool closedSurface,
                    std::vector<std::pair<double, int>>& events) {
  events.clear();
  bool closed = closedSurface;
  int running = 0;
  for (auto it = crossings.begin(); it != crossings.end();) {
    auto group = it;
    bool entry = false, exit = false;
    while (group != crossings.end() && group->at - it->at <= eps) {
      entry = entry || group->sign > 0;
      exit = exit || group->sign < 0;
      ++group;
    }
    const int change = (entry ? 1 : 0) - (exit ? 1 : 0);
    events.emplace_back(it->at, change);
    running += change;
    closed = closed && running >= 0;
    it = group;
  }
  return closed && running == 0;
}

// Whether a cell centre q is inside by the winding number; on or next to a surface (w between
// the ambiguity bounds), by the mean with four samples a quarter cell away across the column.
bool insideByWinding(const LazyWinding& winding, const dvec3& origin, const Sweep& sweep, const dvec3& q,
                     const dvec3& half, bool& wasAmbiguous) {
  const double w = winding(q + origin);
  if (w < kAmbiguousLow || w > kAmbiguousHigh) return w >= kInside;
  wasAmbiguous = true;
  double sum = w;
  for (int d = 0; d < 4; ++d) {
    dvec3 o = q;
    o[sweep.b] += (d & 1 ? 0.5 : -0.5) * half[sweep.b];
    o[sweep.c] += (d & 2 ? 0.5 : -0.5) * half[sweep.c];
    sum += winding(o + origin);
  }
  return sum / 5.0 >= kInside;
}

struct SweepCounts {
  long long evaluations = 0, ambiguous = 0, windingColumns = 0;
};

// Classifies the cells of one column still unclassified and sets every cell's hint.
// `crossings` are the column's, sorted along the line; `events` them merged.
void classifyColumn(Builder& builder, const LazyWinding& winding, const Sweep& sweep, std::size_t column,
                    std::span<const Crossing> crossings, const std::vector<std::pair<double, int>>& events,
                    const std::vector<SweptTriangle>& surface, bool closed, SweepCounts& counts) {
  const int s = sweep.s, b = sweep.b, c = sweep.c;
  const double eps = sweep.eps;
  const std::size_t j = column % sweep.cb.size(), k = column / sweep.cb.size();
  std::array<int, 3> cell{};
  cell[static_cast<std::size_t>(b)] = static_cast<int>(j);
  cell[static_cast<std::size_t>(c)] = static_cast<int>(k);
  const auto& bb = builder.bounds[static_cast<std::size_t>(b)];
  const auto& bc = builder.bounds[static_cast<std::size_t>(c)];
  const auto& bs = builder.bounds[static_cast<std::size_t>(s)];
  auto next = crossings.begin();
  std::size_t event = 0;
  int count = 0;
  bool known = false, solid = false;
  if (!closed) ++counts.windingColumns;
  for (std::size_t i = 0; i < sweep.cs.size(); ++i) {
    const double centre = sweep.cs[i];
    bool crossed = false;
    while (event < events.size() && events[event].first < centre - eps) {
      count += events[event++].second;
      crossed = true;
    }
    while (next != crossings.end() && next->at < centre) ++next;
    cell[static_cast<std::size_t>(s)] = static_cast<int>(i);
    const std::size_t id = builder.index(cell);
    // The nearest face along the column (behind, else ahead) lends its material.
    if (next != crossings.begin())
      builder.hint[id] = surface[(next - 1)->face].material;
    else if (next != crossings.end())
      builder.hint[id] = surface[next->face].material;
    // A face through the centre itself leaves the count undecided for this cell.
    const bool onSurface = event < events.size() && events[event].first <= centre + eps;
    std::int8_t& shape = builder.shape[id];
    if (shape != Builder::kUnclassified) {
      // A wedge's or a round piece's cell, decided already: the next cell of its run is
      // evaluated afresh, since a crossing may lie between.
      known = false;
      continue;
    }
    if (closed && !onSurface) {
      shape = count > 0 ? 0 : -1;
      continue;
    }
    if (!known || crossed || onSurface) {
      dvec3 q, half;
      q[s] = centre;
      q[b] = sweep.cb[j];
      q[c] = sweep.cc[k];
      half[s] = 0.5 * (bs[i + 1] - bs[i]);
      half[b] = 0.5 * (bb[j + 1] - bb[j]);
      half[c] = 0.5 * (bc[k + 1] - bc[k]);
      bool wasAmbiguous = false;
      solid = insideByWinding(winding, builder.origin, sweep, q, half, wasAmbiguous);
      ++counts.evaluations;
      counts.ambiguous += wasAmbiguous;
      // A value decided for a centre on a surface holds for this cell only.
      known = !wasAmbiguous && !onSurface;
    }
    shape = solid ? 0 : -1;
  }
}

}  // namespace

// Occupancy of every cell centre that fitWedges and fitQuadrics left (step 3 of solid.hpp), and
// every cell's material hint (a wedge's or round piece's: its surface's). Each column of cells
// along the sweep axis s is a line; its crossings with the faces are gathered and, moving along +s,
// a face whose normal points against the line is an entry (+1) and one along it an exit (-1).
// Crossings at one position (the line through an edge or a vertex shared by several faces) count
// once per direction, so an edge is never counted twice. On a closed surface
// (MeshCheck::closedSurface), where the running count never drops below zero and ends at zero, the
// count is the winding number itself. Any other column (it met faces turned the wrong way) and
// every column of an open surface is decided by the generalized winding number, evaluated once per
// run of cells between two crossings: an open surface's winding number is not a count of crossings,
// even on a line that crosses none of its open parts (walls standing on a base plate make the room
// inside them solid; a line under a gable's overhanging roof crosses both pitches with air between
// them). The crossings of a part of a building (SolidOptions::enclosing) are those of the whole
// building's surface, whose winding number decides the cells.
void Builder::classify(const LazyWinding& winding) {
  const Sweep sweep = sweepOf(*this);
  stats.sweepAxis = sweep.s;
  const std::vector<SweptTriangle> surface = sweptSurface(*this, sweep.s);
  ColumnCrossings crossings = crossColumns(surface, sweep);
  std::atomic<long long> evaluations{0}, ambiguous{0}, windingColumns{0};
  parallelFor(
      sweep.columns(), 64, options.threads,
      [&](std::size_t begin, std::size_t end) {
        SweepCounts counts;
        std::vector<std::pair<double, int>> events;
        for (std::size_t column = begin; column < end; ++column) {
          const auto first = crossings.sorted.begin() + static_cast<std::ptrdiff_t>(crossings.start[column]);
          const auto last = crossings.sorted.begin() + static_cast<std::ptrdiff_t>(crossings.start[column + 1]);
          std::sort(first, last, [](const Crossing& x, const Crossing& y) { return x.at < y.at; });
          const std::span<const Crossing> line(first, last);
          const bool closed = mergeCrossings(line, sweep.eps, options.closedSurface, events);
          classifyColumn(*this, winding, sweep, column, line, events, surface, closed, counts);
        }
        evaluations += counts.evaluations;
        ambiguous += counts.ambiguous;
        windingColumns += counts.windingColumns;
      },
      options.progress);
  // Cells of wedges and round pieces take the material of the surface they show.
  for (const Share& share : wedgeShares) hint[share.cell] = share.material;
  stats.windingEvaluations = evaluations;
  stats.ambiguousCells = ambiguous;
  stats.windingColumns = windingColumns;
  stats.columns = static_cast<long long>(sweep.columns());
}

namespace {

// The cells (u, e) a slope's faces may reach: i0..i1 along u, k0..k1 along its extrusion axis e.
struct SlopeRange {
  int i0, i1, k0, k1;
  int columns() const { return std::max(i1 - i0 + 1, 0); }
  int rows() const { return std::max(k1 - k0 + 1, 0); }
};

// How much of each cell (u, e) of the range the plane's faces cover, projected onto (u, e).
class SlopeCover {
 public:
  SlopeCover(const Builder& b, const SlopePlane& plane, const SlopeRange& range)
      : U_(b.bounds[static_cast<std::size_t>(kU[plane.e])]),
        E_(b.bounds[static_cast<std::size_t>(plane.e)]),
        range_(range),
        tol_(b.tol),
        area_(static_cast<std::size_t>(range.columns() * range.rows()), 0.0) {
    const int u = kU[plane.e], e = plane.e;
    for (const std::uint32_t f : plane.faces) {
      Polygon2 tri;
      tri.n = 3;
      for (int c = 0; c < 3; ++c) tri.p[static_cast<std::size_t>(c)] = dvec2(b.corner(f, c)[u], b.corner(f, c)[e]);
      const auto lowest = [&](int axis) { return std::min({tri.p[0][axis], tri.p[1][axis], tri.p[2][axis]}); };
      const auto highest = [&](int axis) { return std::max({tri.p[0][axis], tri.p[1][axis], tri.p[2][axis]}); };
      const int a0 = std::max(range.i0, cellOf(U_, lowest(0))), a1 = std::min(range.i1, cellOf(U_, highest(0)));
      const int b0 = std::max(range.k0, cellOf(E_, lowest(1))), b1 = std::min(range.k1, cellOf(E_, highest(1)));
      for (int i = a0; i <= a1; ++i) {
        Polygon2 strip = tri;
        clipAxis(strip, 0, U_[static_cast<std::size_t>(i)], false);
        clipAxis(strip, 0, U_[static_cast<std::size_t>(i + 1)], true);
        for (int k = b0; k <= b1 && strip.n >= 3; ++k) {
          Polygon2 piece = strip;
          clipAxis(piece, 1, E_[static_cast<std::size_t>(k)], false);
          clipAxis(piece, 1, E_[static_cast<std::size_t>(k + 1)], true);
          if (piece.n >= 3) area_[at(i, k)] += polygonArea(piece);
        }
      }
    }
  }

  // 1: covered whole (but for strips within the tolerance of its sides), 0: not at all, -1: partly.
  int coverage(int i, int k) const {
    const double du = U_[static_cast<std::size_t>(i + 1)] - U_[static_cast<std::size_t>(i)];
    const double de = E_[static_cast<std::size_t>(k + 1)] - E_[static_cast<std::size_t>(k)];
    const double c = area_[at(i, k)], slack = tol_ * (du + de);
    return du * de - c <= slack ? 1 : c <= slack ? 0 : -1;
  }

 private:
  std::size_t at(int i, int k) const {
    return static_cast<std::size_t>((i - range_.i0) * range_.rows() + (k - range_.k0));
  }

  const std::vector<double>& U_;
  const std::vector<double>& E_;
  SlopeRange range_;
  double tol_;
  std::vector<double> area_;
};

// What fitting wedges along a slope found, cell by cell.
struct WedgeFit {
  int good = 0, bad = 0;
  double goodArea = 0, badArea = 0;        // the cells' cross-sections (u, e)
  std::vector<std::array<int, 2>> missed;  // cells (u, e) with no wedge, e = -1 for a whole column
  // Of those, the slope's own failures: all but the cells its outline cuts (hips, valleys).
  std::vector<std::array<int, 2>> ownFailures;

  void pass(double area) {
    ++good;
    goodArea += area;
  }
  void fail(double area) {
    ++bad;
    badArea += area;
  }
  bool givenUp() const { return bad > good + kWedgeGiveUp; }
};

// Fits the cells of column i (along u) of a slope: where the slope runs through a row of cells
// corner to corner, each cell its faces cover becomes a wedge, a box or empty by the winding
// number at its two halves' centroids; a column off the diagonal fails whole where the faces
// reach it.
void fitWedgeColumn(Builder& b, const SlopePlane& plane, const SlopeRange& range, const SlopeCover& cover, int i,
                    const LazyWinding& winding, WedgeFit& fit) {
  const int e = plane.e, u = kU[e], v = kV[e];
  const auto& U = b.bounds[static_cast<std::size_t>(u)];
  const auto& V = b.bounds[static_cast<std::size_t>(v)];
  const auto& E = b.bounds[static_cast<std::size_t>(e)];
  const double tol = b.tol;
  const int k0 = range.k0, k1 = range.k1;
  const double ua = U[static_cast<std::size_t>(i)], ub = U[static_cast<std::size_t>(i + 1)];
  const double va = plane.vAt(ua), vb = plane.vAt(ub);
  const int j = nearestBoundary(V, std::min(va, vb));
  if (ua < plane.uMin() - tol || ub > plane.uMax() + tol || j + 1 >= static_cast<int>(V.size()) ||
      std::abs(V[static_cast<std::size_t>(j)] - std::min(va, vb)) > tol ||
      std::abs(V[static_cast<std::size_t>(j + 1)] - std::max(va, vb)) > tol) {
    bool reached = false;
    for (int k = k0; k <= k1 && !reached; ++k) reached = cover.coverage(i, k) != 0;
    if (!reached) return;
    // Cut off the diagonal: centre classification stands, for every cell along e.
    fit.missed.push_back({i, -1});
    fit.ownFailures.push_back({i, -1});
    fit.bad += k1 - k0 + 1;
    fit.badArea += (ub - ua) * (E[static_cast<std::size_t>(k1 + 1)] - E[static_cast<std::size_t>(k0)]);
    return;
  }
  // The two corners off the diagonal: rising diagonal leaves (1,0) and (0,1), falling (0,0) and (1,1).
  const bool rising = vb > va;
  const std::array<std::array<int, 2>, 2> offCorners = rising ? std::array<std::array<int, 2>, 2>{{{1, 0}, {0, 1}}}
                                                              : std::array<std::array<int, 2>, 2>{{{0, 0}, {1, 1}}};
  const double vlo = V[static_cast<std::size_t>(j)], vhi = V[static_cast<std::size_t>(j + 1)];
  for (int k = k0; k <= k1 && !fit.givenUp(); ++k) {
    const double ea = E[static_cast<std::size_t>(k)], eb = E[static_cast<std::size_t>(k + 1)];
    const double crossSection = (ub - ua) * (eb - ea);
    if (ea < plane.e0 - tol || eb > plane.e1 + tol) {
      fit.missed.push_back({i, k});
      fit.ownFailures.push_back({i, k});
      fit.fail(crossSection);
      continue;
    }
    if (const int covered = cover.coverage(i, k); covered <= 0) {
      if (covered < 0) {
        fit.missed.push_back({i, k});
        fit.fail(crossSection);
      }
      continue;
    }
    std::array<bool, 2> in{};
    for (int h = 0; h < 2; ++h) {
      // Centroid of the half holding the off-diagonal corner h: (corner + two diagonal ends) / 3.
      const std::array<int, 2> oc = offCorners[static_cast<std::size_t>(h)];
      const double cu = oc[0] ? ub : ua, cv = oc[1] ? vhi : vlo;
      dvec3 q;
      q[e] = 0.5 * (ea + eb);
      q[u] = (cu + ua + ub) / 3.0;
      q[v] = (cv + vlo + vhi) / 3.0;
      in[static_cast<std::size_t>(h)] = winding(q + b.origin) >= kInside;
    }
    std::array<int, 3> cell{};
    cell[static_cast<std::size_t>(e)] = k;
    cell[static_cast<std::size_t>(u)] = i;
    cell[static_cast<std::size_t>(v)] = j;
    std::int8_t& sh = b.shape[b.index(cell)];
    if (in[0] == in[1]) {
      // Solid on both sides: the slope is hidden here (a chimney through the roof). Empty on
      // both: the slope is missing from the solid, so the mesh must show it.
      sh = in[0] ? 0 : -1;
      if (in[0]) {
        fit.pass(crossSection);
      } else {
        fit.missed.push_back({i, k});
        fit.ownFailures.push_back({i, k});
        fit.fail(crossSection);
      }
      continue;
    }
    const std::array<int, 2> oc = offCorners[in[0] ? 0 : 1];
    sh = static_cast<std::int8_t>(makeSolid(SolidGroup::Wedge, e * 4 + oc[0] + 2 * oc[1]).index);
    b.wedgeShares.push_back({b.index(cell), plane.material, 6, (eb - ea) * std::hypot(ub - ua, vhi - vlo)});
    fit.pass(crossSection);
  }
}

}  // namespace

// Cells a slope runs through corner to corner become wedges (or stay boxes / empty when both
// halves are solid / empty); a slope shown entirely by wedges leaves the complementary mesh.
// A cell becomes a wedge of a plane only where the plane's faces cover its whole extent in (u, e)
// (its cross-section along the free axis v): where the plane's outline cuts through the cell
// diagonally (a hip, a valley, the slanted side of a triangular slope), the surface there is
// partly another plane's, with a crease (solid = y' <= min or max of two planes) that no solid
// has, and a wedge of either plane would fill or cut away the other's part. Such a cell is left as
// the occupancy step classified it and counts as failed, as does a cell where both halves came
// out empty (an overhanging eave's sheet); the part of each face over a failed cell goes to the
// complementary mesh (meshPieces), and trimCutCells keeps the cell solid only if it is inside
// all over. Cells the faces do not reach at all (the rest of the plane's bounding box: beyond a
// hip, a chimney's hole) are none of the plane's business. Returns whether every slope
// closeSlopes accepted came out as wedges.
bool Builder::fitWedges(const LazyWinding& winding) {
  bool all = true;
  wedgeShares.clear();
  for (SlopePlane& plane : slopes) {
    if (!plane.represented) continue;  // rejected by closeSlopes
    const int e = plane.e;
    const auto& U = bounds[static_cast<std::size_t>(kU[e])];
    const auto& E = bounds[static_cast<std::size_t>(e)];
    const SlopeRange range{cellOf(U, plane.uMin() + tol), cellOf(U, plane.uMax() - tol), cellOf(E, plane.e0 + tol),
                           cellOf(E, plane.e1 - tol)};
    const SlopeCover cover(*this, plane, range);
    WedgeFit fit;
    plane.meshRegions.clear();
    for (int i = range.i0; i <= range.i1 && !fit.givenUp(); ++i)
      fitWedgeColumn(*this, plane, range, cover, i, winding, fit);
    // Mostly wedges, by count of cells and by their cross-section: the slope stays, the parts of
    // its faces over failed cells go to the complementary mesh. Mostly failed: its boundaries
    // were added for nothing. (A car park ramp, a slab thinner than the cells it crosses, fails
    // in a few wide cells between many narrow wedges: more than half of its cross-section.)
    plane.represented = fit.good > 0 && !fit.givenUp() &&
                        (options.partialWedges ? fit.bad <= fit.good && fit.badArea <= fit.goodArea : fit.bad == 0);
    // The faces over those cells go to the mesh as few pieces: cells joined into rectangles.
    constexpr double kAll = std::numeric_limits<double>::infinity();
    const auto regionsOf = [&](const std::vector<std::array<int, 2>>& cells) {
      std::vector<SlopePlane::Region> regions;
      for (const CellRectangle& r : joinCells(cells))
        regions.push_back({U[static_cast<std::size_t>(r.i0)], U[static_cast<std::size_t>(r.i1 + 1)],
                           r.j0 < 0 ? -kAll : E[static_cast<std::size_t>(r.j0)],
                           r.j0 < 0 ? kAll : E[static_cast<std::size_t>(r.j1 + 1)]});
      return regions;
    };
    // A slope whose own failures (an eave or overhang with no inside, columns off its diagonal)
    // would leave the mesh more triangles than its faces have is cheaper shown by the mesh
    // whole: an overhanging roof of a few large triangles, as most LoD2 roofs are. Cells its
    // outline cuts (hips, valleys) do not count: they are what a roof of several slopes costs
    // wherever its faces end, and counting them would give every hip roof to the mesh.
    if (plane.represented && !fit.ownFailures.empty()) {
      const std::vector<SlopePlane::Region> regions = regionsOf(fit.ownFailures);
      std::size_t triangles = 0;
      for (const std::uint32_t f : plane.faces)
        for (const MeshPiece& piece : piecesOver(f, regions)) triangles += static_cast<std::size_t>(piece.n - 2);
      plane.represented = triangles <= plane.faces.size();
    }
    if (plane.represented) plane.meshRegions = regionsOf(fit.missed);
    stats.slopesAsWedges += plane.represented;
    all = all && plane.represented;
  }
  return all;
}

std::vector<Builder::MeshPiece> Builder::meshPieces(std::uint32_t f) const {
  const Face& face = faces[f];
  if (face.kind != FaceKind::Slope) return {};
  const SlopePlane& plane = slopes[static_cast<std::size_t>(face.group)];
  if (!plane.represented) return {};
  return piecesOver(f, plane.meshRegions);
}

std::vector<Builder::MeshPiece> Builder::piecesOver(std::uint32_t f,
                                                    const std::vector<SlopePlane::Region>& regions) const {
  std::vector<MeshPiece> out;
  const Face& face = faces[f];
  if (face.area <= 0 || regions.empty()) return out;
  const SlopePlane& plane = slopes[static_cast<std::size_t>(face.group)];
  const int e = plane.e, u = kU[e], v = kV[e];
  const dvec3 P[3] = {corner(f, 0), corner(f, 1), corner(f, 2)};
  Polygon2 tri;
  tri.n = 3;
  for (std::size_t c = 0; c < 3; ++c) tri.p[c] = dvec2(P[c][u], P[c][e]);
  const double projected = polygonArea(tri);
  if (projected <= 0) return out;
  const double uLo = std::min({P[0][u], P[1][u], P[2][u]}), uHi = std::max({P[0][u], P[1][u], P[2][u]});
  const double eLo = std::min({P[0][e], P[1][e], P[2][e]}), eHi = std::max({P[0][e], P[1][e], P[2][e]});
  // The face's own plane lifts the pieces back to 3D (its normal is off v by more than the angle tolerance).
  const dvec3 normal = face.areaVector / face.area;
  const double d = glm::dot(normal, P[0]);
  for (const SlopePlane::Region& r : regions) {
    if (r.u1 <= uLo || r.u0 >= uHi || r.e1 <= eLo || r.e0 >= eHi) continue;
    Polygon2 piece = tri;
    clipAxis(piece, 0, r.u0, false);
    clipAxis(piece, 0, r.u1, true);
    clipAxis(piece, 1, r.e0, false);
    clipAxis(piece, 1, r.e1, true);
    MeshPiece m;
    m.area = polygonArea(piece) / projected * face.area;
    if (piece.n < 3 || m.area <= kMinPieceAreaM2) continue;  // a clipping sliver
    for (int c = 0; c < piece.n; ++c) {
      // A corner on a cell's side comes out of clipping twice, or nearly: once is enough.
      const dvec2 at = piece.p[static_cast<std::size_t>(c)];
      const dvec3& last = m.p[static_cast<std::size_t>(std::max(m.n - 1, 0))];
      if (m.n > 0 && glm::length(at - dvec2(last[u], last[e])) <= 1e-9) continue;
      dvec3& q = m.p[static_cast<std::size_t>(m.n++)];
      q[u] = at.x;
      q[e] = at.y;
      q[v] = (d - normal[u] * q[u] - normal[e] * q[e]) / normal[v];
    }
    while (m.n > 1 && glm::length(m.p[static_cast<std::size_t>(m.n - 1)] - m.p[0]) <= 1e-9) --m.n;
    if (m.n >= 3) out.push_back(m);
  }
  return out;
}

// Whether the complementary mesh shows face f whole: it is neither axis-aligned nor part of a
// slope shown by wedges (whose faces the mesh shows only over failed cells: meshPieces) nor of a
// piece shown by quadric cells.
bool Builder::shownByMesh(std::uint32_t f) const {
  const Face& face = faces[f];
  if (face.kind == FaceKind::General) return true;
  if (face.kind == FaceKind::Aligned) return false;
  if (face.kind == FaceKind::Quadric) return !quadrics[static_cast<std::size_t>(face.group)].represented;
  return !slopes[static_cast<std::size_t>(face.group)].represented;
}

// Separating-axis test of a triangle against an axis-aligned box (Akenine-Moeller 2001): the 3
// box axes, the triangle normal and the 9 edge cross products.
bool triangleOverlapsBox(dvec3 a, dvec3 b, dvec3 c, const dvec3& centre, const dvec3& half) {
  a -= centre;
  b -= centre;
  c -= centre;
  const dvec3 edges[3] = {b - a, c - b, a - c};
  const auto separated = [&](const dvec3& axis) {
    const double pa = glm::dot(a, axis), pb = glm::dot(b, axis), pc = glm::dot(c, axis);
    const double r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    return std::min({pa, pb, pc}) > r || std::max({pa, pb, pc}) < -r;
  };
  for (int i = 0; i < 3; ++i) {
    dvec3 axis(0.0);
    axis[i] = 1;
    if (separated(axis)) return false;
  }
  if (separated(glm::cross(edges[0], edges[1]))) return false;
  for (const dvec3& e : edges)
    for (int i = 0; i < 3; ++i) {
      dvec3 unit(0.0);
      unit[i] = 1;
      const dvec3 axis = glm::cross(e, unit);
      if (glm::dot(axis, axis) > 0 && separated(axis)) return false;
    }
  return true;
}

namespace {

// Grows `extent` by the part of triangle abc inside the box [lo, hi] (Sutherland-Hodgman against
// its six sides).
void growByClippedTriangle(Builder::CutExtent& extent, const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& lo,
                           const dvec3& hi) {
  std::array<dvec3, 9> poly{a, b, c}, next{};
  int n = 3;
  for (int side = 0; side < 6 && n > 0; ++side) {
    const int axis = side / 2;
    const bool below = side % 2 == 1;
    const double bound = below ? hi[axis] : lo[axis];
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const dvec3& p = poly[static_cast<std::size_t>(i)];
      const dvec3& q = poly[static_cast<std::size_t>(i + 1 == n ? 0 : i + 1)];
      const bool pin = below ? p[axis] <= bound : p[axis] >= bound;
      const bool qin = below ? q[axis] <= bound : q[axis] >= bound;
      if (pin) next[static_cast<std::size_t>(m++)] = p;
      if (pin != qin) {
        dvec3 x = p + (bound - p[axis]) / (q[axis] - p[axis]) * (q - p);
        x[axis] = bound;
        next[static_cast<std::size_t>(m++)] = x;
      }
    }
    poly = next;
    n = m;
  }
  for (int i = 0; i < n; ++i) {
    extent.lo = glm::min(extent.lo, poly[static_cast<std::size_t>(i)]);
    extent.hi = glm::max(extent.hi, poly[static_cast<std::size_t>(i)]);
  }
}

// Inside at the corners of box [lo, hi] (grid frame), each inset a little: on the box's own faces
// the winding number of a face lying there would be ambiguous, and a face may lie up to a
// tolerance off its boundary.
bool insideAllOver(const LazyWinding& winding, const dvec3& origin, double tol, const dvec3& lo, const dvec3& hi) {
  for (int sample = 0; sample < 8; ++sample) {
    dvec3 q;
    for (int ax = 0; ax < 3; ++ax) {
      const double inset = std::min(kCornerInset * (hi[ax] - lo[ax]), kCornerInsetTolerances * tol);
      q[ax] = (sample >> ax) & 1 ? hi[ax] - inset : lo[ax] + inset;
    }
    if (winding(q + origin) < kInside) return false;
  }
  return true;
}

}  // namespace

// Box cells that a face of the complementary mesh cuts stay solid only when they are inside all
// over (all eight corners): a cell half above a roof the grid could not follow would poke through
// it, while a missing part under the roof is hidden by the roof mesh, and the cell's own faces
// that go missing with it are empty on both sides and so move to the mesh as well. The cells
// emptied are kept in `trimmed` with the extent of what cuts them, for proposeTrimSplits.
void Builder::trimCutCells(const LazyWinding& winding) {
  std::unordered_map<std::size_t, CutExtent> cut;
  const auto markCut = [&](const dvec3& a, const dvec3& b, const dvec3& c) {
    std::array<int, 3> lo{}, hi{};
    for (int ax = 0; ax < 3; ++ax) {
      const auto& B = bounds[static_cast<std::size_t>(ax)];
      lo[static_cast<std::size_t>(ax)] = cellOf(B, std::min({a[ax], b[ax], c[ax]}));
      hi[static_cast<std::size_t>(ax)] = cellOf(B, std::max({a[ax], b[ax], c[ax]}));
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t id = index(x, y, z);
          if (shape[id] != 0 || subPiece[id] >= 0) continue;  // a sub-block's cell shows S, not its shape
          dvec3 cellLo, cellHi;
          cellBox(id, cellLo, cellHi);
          // Shrunk a little: a face lying on the cell's side does not cut it.
          const dvec3 half = 0.5 * (cellHi - cellLo) - dvec3(1e-6);
          if (glm::all(glm::greaterThan(half, dvec3(0.0))) &&
              triangleOverlapsBox(a, b, c, 0.5 * (cellLo + cellHi), half))
            growByClippedTriangle(cut[id], a, b, c, cellLo, cellHi);
        }
  };
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].area <= 0) continue;
    if (shownByMesh(f)) {
      markCut(corner(f, 0), corner(f, 1), corner(f, 2));
      continue;
    }
    // A slope face's parts over cells where its plane made no wedge (a hip's crease, an eave).
    for (const MeshPiece& piece : meshPieces(f))
      for (int m = 1; m + 1 < piece.n; ++m)
        markCut(piece.p[0], piece.p[static_cast<std::size_t>(m)], piece.p[static_cast<std::size_t>(m + 1)]);
  }
  trimmed.clear();
  if (cut.empty()) return;
  // Each cut cell's samples are independent of every other cell's result, so the cells are
  // shared among the threads; a cell is only ever emptied, by the thread that owns it.
  std::vector<std::size_t> cutCells;
  for (const auto& entry : cut) cutCells.push_back(entry.first);
  std::sort(cutCells.begin(), cutCells.end());
  std::vector<std::uint8_t> emptied(cutCells.size(), 0);
  parallelFor(
      cutCells.size(), 16, options.threads,
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          dvec3 lo, hi;
          cellBox(cutCells[i], lo, hi);
          if (insideAllOver(winding, origin, tol, lo, hi)) continue;
          shape[cutCells[i]] = -1;
          emptied[i] = 1;
        }
      },
      options.progress);
  for (std::size_t i = 0; i < cutCells.size(); ++i)
    if (emptied[i]) trimmed.emplace(cutCells[i], cut.at(cutCells[i]));
  stats.trimmedCells += static_cast<long long>(trimmed.size());
}

// A trimmed cell may still be solid all over on one side of what cuts it: the body of a house
// under a roof left to the mesh, when no face of the house ends at its eaves, is one cell up to
// the ridge, and trimming it sends every wall to the mesh. For each trimmed cell, the largest part
// beyond the extent of the cutting surface along one axis that is at least kTrimSplitShare of the
// cell and inside at its corners is a candidate; what it is worth is the surface of axis-aligned
// faces on its sides that went to the mesh with the cell (`lost`, per side; a side along the
// split counts the part's share of it). Candidates on one side, each within kTrimSplitReach
// tolerances of the next, are one boundary, placed at the one that keeps the least (the others'
// parts are solid there too), and proposed when together they are worth kTrimSplitShareOfSurface
// of the mesh's surface: a boundary runs across the whole grid and must pay for itself.
std::array<std::vector<double>, 3> Builder::proposeTrimSplits(const std::vector<Share>& lost,
                                                              const LazyWinding& winding) const {
  std::array<std::vector<double>, 3> proposals;
  if (lost.empty()) return proposals;
  // What each trimmed cell lost, per side (Share::side), in the order of the cells.
  std::map<std::size_t, std::array<double, 6>> lostBySide;
  for (const Share& s : lost) lostBySide[s.cell][s.side] += s.area;
  const std::vector<std::pair<std::size_t, std::array<double, 6>>> cells(lostBySide.begin(), lostBySide.end());
  struct Candidate {
    double at, worth;
    bool below;  // the part kept is on the - side of `at`
  };
  std::vector<std::optional<std::pair<int, Candidate>>> best(cells.size());
  parallelFor(cells.size(), 16, options.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto& [cell, sides] = cells[i];
      const CutExtent& cutBy = trimmed.at(cell);
      dvec3 lo, hi;
      cellBox(cell, lo, hi);
      for (int ax = 0; ax < 3; ++ax)
        for (const bool below : {true, false}) {
          // Snapped away from the cutting surface: boundaries are whole millimetres, and one
          // rounded into that surface would leave the part cut, and trimmed again.
          const double units = (below ? cutBy.lo[ax] : cutBy.hi[ax]) / format::kMetresPerUnit;
          const double at = toMetres(static_cast<std::int64_t>(below ? std::floor(units) : std::ceil(units)));
          const double share = (below ? at - lo[ax] : hi[ax] - at) / (hi[ax] - lo[ax]);
          if (share < kTrimSplitShare || hasBoundaryNear(bounds[static_cast<std::size_t>(ax)], at, tol)) continue;
          double worth = 0;
          for (int side = 0; side < 6; ++side)
            worth += side / 2 != ax             ? share * sides[static_cast<std::size_t>(side)]
                     : (side % 2 == 0) == below ? sides[static_cast<std::size_t>(side)]
                                                : 0.0;
          if (best[i] && worth <= best[i]->second.worth) continue;
          dvec3 partLo = lo, partHi = hi;
          (below ? partHi : partLo)[ax] = at;
          if (insideAllOver(winding, origin, tol, partLo, partHi)) best[i] = {ax, Candidate{at, worth, below}};
        }
    }
  });
  std::array<std::vector<Candidate>, 3> byAxis;
  for (const auto& b : best)
    if (b) byAxis[static_cast<std::size_t>(b->first)].push_back(b->second);
  for (int ax = 0; ax < 3; ++ax) {
    auto& list = byAxis[static_cast<std::size_t>(ax)];
    std::sort(list.begin(), list.end(),
              [](const Candidate& x, const Candidate& y) { return x.below != y.below ? x.below : x.at < y.at; });
    for (std::size_t first = 0; first < list.size();) {
      std::size_t last = first;
      double worth = list[first].worth;
      while (last + 1 < list.size() && list[last + 1].below == list[first].below &&
             list[last + 1].at - list[last].at <= kTrimSplitReach * tol)
        worth += list[++last].worth;
      if (worth >= kTrimSplitShareOfSurface * stats.areaM2)
        proposals[static_cast<std::size_t>(ax)].push_back(list[first].below ? list[first].at : list[last].at);
      first = last + 1;
    }
  }
  return proposals;
}

}  // namespace nut::converter::solid
