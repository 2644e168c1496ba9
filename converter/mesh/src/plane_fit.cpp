// Plane cells from the complementary mesh (converter/plane_fit.hpp): the complementary faces
// clustered into planes once for the whole building, so that every cell a plane crosses cuts the
// same plane; then per cell the planes and faces that cross it, the surface check, the winding
// check, and the faces' parts in the cells made plane cells taken out of the complementary mesh.
#include <converter/plane_fit.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/winding.hpp>

#include "plane_clusters.hpp"

namespace nut::converter {

namespace {

using glm::dvec3;
using Polygon = std::vector<dvec3>;

// The complementary mesh is not fitted above this many triangles: the clustering compares each
// triangle with every plane so far.
constexpr std::size_t kMaxTriangles = 20000;
// Nor when its triangles cross more cells than this in all (a mesh of large faces over a fine grid).
constexpr std::size_t kMaxCrossings = 2'000'000;
// Sample points per axis in a cell for the winding check, and how many must be far enough from
// the planes to count.
constexpr std::array<double, 3> kSampleAt{0.15, 0.5, 0.85};
constexpr int kMinSamples = 4;

// The part of a convex polygon with dot(n, p) <= d (below) or >= d.
Polygon clip(const Polygon& in, const dvec3& n, double d, bool below) {
  Polygon out;
  const double sign = below ? 1.0 : -1.0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const dvec3& a = in[i];
    const dvec3& b = in[(i + 1) % in.size()];
    const double da = sign * (glm::dot(n, a) - d), db = sign * (glm::dot(n, b) - d);
    if (da <= 0) out.push_back(a);
    if ((da <= 0) != (db <= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

double area(const Polygon& p) {
  dvec3 n(0.0);
  for (std::size_t i = 1; i + 1 < p.size(); ++i) n += glm::cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * glm::length(n);
}

double perimeter(const Polygon& p) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += glm::length(p[(i + 1) % p.size()] - p[i]);
  return sum;
}

struct Box {
  dvec3 lo, hi;
};

Polygon clipToBox(Polygon p, const Box& box) {
  for (int a = 0; a < 3 && p.size() >= 3; ++a) {
    dvec3 e(0.0);
    e[a] = 1.0;
    p = clip(p, e, box.hi[a], true);
    if (p.size() >= 3) p = clip(p, e, box.lo[a], false);
  }
  return p.size() >= 3 ? p : Polygon{};
}

using Plane = ClusterPlane;  // outward: the solid is dot(normal, p) <= offset

// A complementary triangle's part in one cell: on a plane of the cut, or on a side of the cell's
// box (an axis-aligned face the grid left to the mesh, which the plane cell's box shows).
struct Crossing {
  std::uint32_t triangle;
  double area;
  int side = -1;  // 2 * axis + (1 on the + side) for a face on the box, else -1
  // Narrower than the tolerance (a triangle along the cell's edge, a boundary snapped to
  // millimetres beside the triangle's): the cell need not show it, but the triangle leaves the
  // mesh only if the cell fits.
  bool narrow = false;
};

class Fitter {
 public:
  Fitter(SolidGrid& grid, const TriangleMesh& inside, const SolidOptions& options)
      : grid_(grid),
        winding_(inside.positions, inside.triangles),
        tol_(options.toleranceM),
        cosAngle_(std::cos(options.angleToleranceDeg * std::numbers::pi / 180.0)) {}

  PlaneFitStats run() {
    const TriangleMesh& m = grid_.complement;
    if (m.triangles.empty() || m.triangles.size() > kMaxTriangles) return stats_;
    std::vector<double> areas(m.triangles.size());
    for (std::size_t t = 0; t < areas.size(); ++t) areas[t] = area(polygonOf(t));
    std::vector<std::array<dvec3, 3>> corners(m.triangles.size());
    for (std::size_t t = 0; t < corners.size(); ++t) {
      const auto& tri = m.triangles[t];
      corners[t] = {m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]};
    }
    const std::vector<int> planeOf = clusterPlanes(corners, cosAngle_, tol_, planes_);
    if (!collectCrossings(areas)) return stats_;
    std::map<std::size_t, Fit> fitted;
    for (const auto& [cell, crossings] : crossings_) {
      ++stats_.candidateCells;
      if (auto fit = fitCell(cell, crossings, planeOf)) fitted.emplace(cell, *fit);
    }
    // A triangle's parts in the cells that fit leave the mesh; the rest stays, as the triangle
    // whole when no part leaves, else as polygons that end where the plane cells beside them
    // begin, on the same plane (stayingParts).
    // A triangle partly outside every cell (beyond the grid by more than the tolerance) stays
    // whole, and the cells it crosses are not taken.
    // A narrow part neither needs its cell to fit nor keeps the triangle from leaving, unless all
    // of its triangle is narrow (a sliver): that leaves only where every cell it touches fits.
    std::vector<bool> sliver(m.triangles.size(), true), outside(m.triangles.size(), false);
    std::vector<double> inCells(m.triangles.size(), 0.0);
    for (const auto& [cell, crossings] : crossings_)
      for (const Crossing& x : crossings) {
        sliver[x.triangle] = sliver[x.triangle] && x.narrow;
        inCells[x.triangle] += x.area;
      }
    for (std::size_t t = 0; t < outside.size(); ++t)
      outside[t] = inCells[t] < areas[t] - tol_ * perimeter(polygonOf(t));
    for (auto it = fitted.begin(); it != fitted.end();) {
      const auto& crossings = crossings_.at(it->first);
      const bool blocked = std::any_of(crossings.begin(), crossings.end(),
                                       [&](const Crossing& x) { return !x.narrow && outside[x.triangle]; });
      it = blocked ? fitted.erase(it) : std::next(it);
    }
    // Per triangle: 0 no part leaves, 1 every part leaves, 2 some do (cut into the rest).
    std::vector<int> leaving(m.triangles.size(), -1);
    for (const auto& [cell, crossings] : crossings_)
      for (const Crossing& x : crossings) {
        if (x.narrow && !sliver[x.triangle]) continue;
        const int here = fitted.count(cell) ? 1 : 0;
        int& l = leaving[x.triangle];
        l = l < 0 ? here : (l == here ? l : 2);
      }
    for (std::size_t t = 0; t < leaving.size(); ++t)
      if (outside[t] || leaving[t] < 0 || (sliver[t] && leaving[t] == 2)) leaving[t] = 0;
    // The leaving parts in boxes that showed them already (faces given to the mesh whole).
    for (const auto& [cell, crossings] : crossings_)
      for (const Crossing& x : crossings)
        if (leaving[x.triangle] != 0 && fitted.count(cell) && grid_.block.cells[cell].kind == CellKind::Solid)
          stats_.drawnTwiceM2 += x.area;
    for (const auto& [cell, fit] : fitted) {
      if (fit.keepsCell) continue;
      const auto [it, added] = cutIndex_.try_emplace(fit.key, static_cast<std::uint32_t>(grid_.block.cuts.size()));
      if (added) grid_.block.cuts.push_back(fit.cut);
      grid_.block.cells[cell] = Cell::planeCell(it->second, fit.material);
      ++stats_.planeCells;
      stats_.twoPlaneCells += fit.cut.planeCount() == 2;
    }
    removeLeaving(leaving, fitted);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) stats_.complementLeftM2 += area(polygonOf(t));
    return stats_;
  }

 private:
  Polygon polygonOf(std::size_t t) const {
    const auto& tri = grid_.complement.triangles[t];
    return {grid_.complement.positions[tri[0]], grid_.complement.positions[tri[1]], grid_.complement.positions[tri[2]]};
  }

  // The cell's box in world coordinates.
  Box boxOf(std::size_t cell) const {
    const Block& b = grid_.block;
    const int nx = b.cellCount(0), ny = b.cellCount(1);
    const std::array<int, 3> c{static_cast<int>(cell % static_cast<std::size_t>(nx)),
                               static_cast<int>(cell / static_cast<std::size_t>(nx) % static_cast<std::size_t>(ny)),
                               static_cast<int>(cell / (static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)))};
    Box box;
    for (int a = 0; a < 3; ++a) {
      const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
      box.lo[a] = grid_.originM[a] + bounds[static_cast<std::size_t>(c[static_cast<std::size_t>(a)])];
      box.hi[a] = grid_.originM[a] + bounds[static_cast<std::size_t>(c[static_cast<std::size_t>(a)] + 1)];
    }
    return box;
  }

  // Where an axis-aligned triangle lies on a grid boundary (its corners within the tolerance of
  // it): the side of the cell behind it (against its normal, where the solid is) and that cell's
  // layer along the axis, -1 when the boundary is the grid's own outside. {-1, -1} for any other.
  std::pair<int, int> boxSideOf(const Polygon& tri) const {
    const dvec3 n = glm::normalize(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
    for (int a = 0; a < 3; ++a) {
      if (std::abs(n[a]) < cosAngle_) continue;
      const auto& bounds = grid_.block.boundsM[static_cast<std::size_t>(a)];
      const double at = (tri[0][a] + tri[1][a] + tri[2][a]) / 3.0 - grid_.originM[a];
      const auto k = static_cast<int>(std::lower_bound(bounds.begin(), bounds.end(), at - tol_) - bounds.begin());
      if (k >= static_cast<int>(bounds.size())) return {-1, -1};
      for (const dvec3& q : tri)
        if (std::abs(q[a] - grid_.originM[a] - bounds[static_cast<std::size_t>(k)]) > tol_) return {-1, -1};
      // The normal points out of the solid: the cell behind a +a face ends at the boundary.
      const int layer = n[a] > 0 ? k - 1 : (k < grid_.block.cellCount(a) ? k : -1);
      return {2 * a + (n[a] > 0 ? 1 : 0), layer};
    }
    return {-1, -1};
  }

  // Every triangle's parts in the cells its bounding box meets.
  bool collectCrossings(const std::vector<double>& areas) {
    const TriangleMesh& m = grid_.complement;
    const Block& b = grid_.block;
    std::size_t total = 0;
    snapped_.resize(m.triangles.size());
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      if (areas[t] <= 0) continue;
      Polygon& tri = snapped_[t] = polygonOf(t);
      std::array<int, 3> first{}, last{};
      const auto [side, layer] = boxSideOf(tri);
      if (side >= 0 && layer < 0) continue;  // on the grid's outside: no cell behind it
      if (side >= 0) {
        // Laid onto the boundary it lies within the tolerance of, so that clipping keeps it.
        const int a = side / 2;
        const double at = grid_.originM[a] + b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(layer + side % 2)];
        for (dvec3& q : tri) q[a] = at;
      }
      for (int a = 0; a < 3; ++a) {
        const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
        const double lo = std::min({tri[0][a], tri[1][a], tri[2][a]}) - grid_.originM[a];
        const double hi = std::max({tri[0][a], tri[1][a], tri[2][a]}) - grid_.originM[a];
        const auto cellAt = [&](double x) {
          const int i = static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), x) - bounds.begin()) - 1;
          return std::clamp(i, 0, b.cellCount(a) - 1);
        };
        first[static_cast<std::size_t>(a)] = cellAt(lo);
        last[static_cast<std::size_t>(a)] = cellAt(hi);
      }
      if (side >= 0) first[static_cast<std::size_t>(side / 2)] = last[static_cast<std::size_t>(side / 2)] = layer;
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
          for (int x = first[0]; x <= last[0]; ++x) {
            if (++total > kMaxCrossings) return false;
            const std::size_t cell = b.cellIndex(x, y, z);
            // A narrow part's area is below half the tolerance times its perimeter.
            const Polygon piece = clipToBox(tri, boxOf(cell));
            const double part = area(piece);
            if (part > 0) crossings_[cell].push_back({t, part, side, part <= 0.5 * tol_ * perimeter(piece)});
          }
    }
    return true;
  }

  // The surface of the cut on plane k in the box: the box's section by the plane, kept on the
  // side of the other plane that the combination shows.
  double cutSurface(const Box& box, const PlaneCut& cut, const std::array<Plane, 2>& world, int k,
                    double& outline) const {
    const Plane& p = world[static_cast<std::size_t>(k)];
    const dvec3 centre = 0.5 * (box.lo + box.hi);
    const dvec3 onPlane = centre - (glm::dot(p.normal, centre) - p.offset) * p.normal;
    const dvec3 helper = std::abs(p.normal.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 u = glm::normalize(glm::cross(p.normal, helper)), v = glm::cross(p.normal, u);
    const double reach = 2.0 * glm::length(box.hi - box.lo);
    Polygon section = clipToBox({onPlane - reach * u - reach * v, onPlane + reach * u - reach * v,
                                 onPlane + reach * u + reach * v, onPlane - reach * u + reach * v},
                                box);
    if (cut.combine != PlaneCombine::One && section.size() >= 3) {
      const Plane& other = world[static_cast<std::size_t>(1 - k)];
      section = clip(section, other.normal, other.offset, cut.combine == PlaneCombine::Both);
    }
    outline = section.size() >= 3 ? perimeter(section) : 0.0;
    return section.size() >= 3 ? area(section) : 0.0;
  }

  // Whether the cut shows what the faces and the winding number say of the cell.
  bool cutFits(const Box& box, const PlaneCut& cut, const std::array<Plane, 2>& world,
               const std::array<double, 2>& faceArea) const {
    for (int k = 0; k < cut.planeCount(); ++k) {
      double outline = 0;
      const double surface = cutSurface(box, cut, world, k, outline);
      if (std::abs(surface - faceArea[static_cast<std::size_t>(k)]) > tol_ * outline) return false;
    }
    int samples = 0;
    for (const double fx : kSampleAt)
      for (const double fy : kSampleAt)
        for (const double fz : kSampleAt) {
          const dvec3 q = box.lo + dvec3(fx, fy, fz) * (box.hi - box.lo);
          bool far = true;
          for (int k = 0; k < cut.planeCount(); ++k) {
            const Plane& p = world[static_cast<std::size_t>(k)];
            far = far && std::abs(glm::dot(p.normal, q) - p.offset) > 2 * tol_;
          }
          if (!far) continue;
          if (cutContains(cut, q - grid_.originM) != (winding_(q) >= 0.5)) return false;
          ++samples;
        }
    return samples >= kMinSamples;
  }

  // The area of side `side` of the box that lies inside the cut, and the side's perimeter.
  double sideInside(const Box& box, const std::array<Plane, 2>& world, PlaneCombine combine, int side,
                    double& outline) const {
    const int a = side / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    dvec3 q = box.lo;
    q[a] = side % 2 ? box.hi[a] : box.lo[a];
    Polygon rect(4, q);
    rect[1][u] = rect[2][u] = box.hi[u];
    rect[2][v] = rect[3][v] = box.hi[v];
    outline = perimeter(rect);
    const auto inside = [&](std::initializer_list<int> planes) {
      Polygon p = rect;
      for (const int k : planes)
        if (p.size() >= 3)
          p = clip(p, world[static_cast<std::size_t>(k)].normal, world[static_cast<std::size_t>(k)].offset, true);
      return p.size() >= 3 ? area(p) : 0.0;
    };
    switch (combine) {
      case PlaneCombine::One: return inside({0});
      case PlaneCombine::Both: return inside({0, 1});
      case PlaneCombine::Either: return inside({0}) + inside({1}) - inside({0, 1});
    }
    return 0.0;
  }

  // Plane indices (-1: none), combination and surface materials (kCellMaterial: the cell's): equal
  // keys are one cut of the block.
  static constexpr int kCellMaterial = -1;
  using CutKey = std::tuple<int, int, PlaneCombine, int, int>;

  // A cell's plane cut, the planes it uses and its material.
  struct Fit {
    PlaneCut cut;
    CutKey key;
    std::uint16_t material = 0;
    bool keepsCell = false;  // a box whose sides show the faces: nothing changes
  };

  std::optional<Fit> fitCell(std::size_t cell, const std::vector<Crossing>& crossings,
                             const std::vector<int>& planeOf) const {
    const std::vector<std::uint16_t>& materialOf = grid_.complement.triangleMaterial;
    std::optional<std::uint16_t> boxMaterial;
    std::array<std::optional<std::uint16_t>, 2> planeMaterial;
    const auto agrees = [](std::optional<std::uint16_t>& shared, std::uint16_t m) {
      if (!shared) shared = m;
      return *shared == m;
    };
    // Empty cells (what the occupancy makes of most cells a face cuts) and boxes, which keep
    // their material on the box's sides.
    const Cell& c = grid_.block.cells[cell];
    if (c.kind == CellKind::Solid && c.solid.index == 0)
      boxMaterial = c.material;
    else if (c.kind != CellKind::Empty)
      return std::nullopt;
    std::vector<int> ids;
    std::array<double, 2> faceArea{0, 0};
    std::array<double, 6> sideArea{};
    for (const Crossing& x : crossings) {
      if (x.narrow) continue;
      if (x.side >= 0) {
        if (!agrees(boxMaterial, materialOf[x.triangle])) return std::nullopt;
        sideArea[static_cast<std::size_t>(x.side)] += x.area;
        continue;
      }
      const int id = planeOf[x.triangle];
      auto it = std::find(ids.begin(), ids.end(), id);
      if (it == ids.end()) {
        if (ids.size() == 2) return std::nullopt;
        it = ids.insert(ids.end(), id);
      }
      const auto k = static_cast<std::size_t>(it - ids.begin());
      if (!agrees(planeMaterial[k], materialOf[x.triangle])) return std::nullopt;
      faceArea[k] += x.area;
    }
    // A box whose sides show all the faces crossing it (faces the grid gave the mesh whole, as
    // they reach beyond it) stays as it is; they may leave the mesh if their other cells fit.
    if (ids.empty()) return c.kind == CellKind::Solid ? std::optional<Fit>(Fit{.keepsCell = true}) : std::nullopt;
    // The box's sides show the cell's material (the first plane's when no face lies on them), each
    // plane its own where that differs (a roof over walls).
    const std::uint16_t material = boxMaterial.value_or(*planeMaterial[0]);
    std::array<std::optional<std::uint16_t>, 2> surfaceMaterials;
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (*planeMaterial[k] != material) surfaceMaterials[k] = planeMaterial[k];
    std::array<Plane, 2> world{planes_[static_cast<std::size_t>(ids[0])],
                               planes_[static_cast<std::size_t>(ids.size() > 1 ? ids[1] : ids[0])]};
    const Box box = boxOf(cell);
    for (const PlaneCombine combine : ids.size() == 1
                                          ? std::vector<PlaneCombine>{PlaneCombine::One}
                                          : std::vector<PlaneCombine>{PlaneCombine::Both, PlaneCombine::Either}) {
      // The faces on the box's sides lie where the cut leaves the side solid.
      bool sidesFit = true;
      for (int side = 0; side < 6 && sidesFit; ++side) {
        double outline = 0;
        const double inside = sideInside(box, world, combine, side, outline);
        sidesFit = sideArea[static_cast<std::size_t>(side)] <= inside + tol_ * outline;
      }
      if (!sidesFit) continue;
      PlaneCut cut;
      cut.combine = combine;
      cut.surfaceMaterials = surfaceMaterials;
      for (std::size_t k = 0; k < 2; ++k)
        cut.planes[k] = k < ids.size()
                            ? CutPlane{world[k].normal, world[k].offset - glm::dot(world[k].normal, grid_.originM)}
                            : CutPlane{};
      if (cutFits(box, cut, world, faceArea))
        return Fit{cut,
                   {ids[0], ids.size() > 1 ? ids[1] : -1, combine, surfaceMaterials[0].value_or(kCellMaterial),
                    surfaceMaterials[1].value_or(kCellMaterial)},
                   material};
    }
    return std::nullopt;
  }

  // What stays of a triangle that leaves in part: its parts in the cells that did not fit, or the
  // triangle less the boxes of the cells that did, whichever takes fewer triangles. Convex
  // polygons either way, none reaching into a cell that fits.
  std::vector<Polygon> stayingParts(std::size_t t, const std::vector<std::size_t>& unfit,
                                    const std::vector<std::size_t>& fit) const {
    std::vector<Polygon> inCells, outsideBoxes{snapped_[t]};
    for (const std::size_t cell : unfit)
      if (Polygon piece = clipToBox(snapped_[t], boxOf(cell)); area(piece) > 0) inCells.push_back(std::move(piece));
    const auto triangles = [](const std::vector<Polygon>& parts) {
      std::size_t n = 0;
      for (const Polygon& p : parts) n += p.size() - 2;
      return n;
    };
    // Each box subtracted may split a part in up to six: given up once it has more parts than
    // the cells' pieces have triangles.
    for (const std::size_t cell : fit) {
      const Box box = boxOf(cell);
      std::vector<Polygon> next;
      for (const Polygon& p : outsideBoxes) subtractBox(p, box, next);
      outsideBoxes = std::move(next);
      if (outsideBoxes.size() > triangles(inCells)) return inCells;
    }
    return triangles(outsideBoxes) < triangles(inCells) ? outsideBoxes : inCells;
  }

  // The parts of convex polygon p outside the box, as convex polygons appended to `out`: for each
  // side in turn, what lies beyond it and within the sides before.
  static void subtractBox(Polygon p, const Box& box, std::vector<Polygon>& out) {
    for (int a = 0; a < 3 && p.size() >= 3; ++a)
      for (const bool upper : {false, true}) {
        if (p.size() < 3) break;
        dvec3 e(0.0);
        e[a] = 1.0;
        const double at = upper ? box.hi[a] : box.lo[a];
        if (Polygon beyond = clip(p, e, at, !upper); beyond.size() >= 3 && area(beyond) > 0)
          out.push_back(std::move(beyond));
        p = clip(p, e, at, upper);
      }
  }

  // The complementary mesh without the triangles that left it, and with the triangles that left
  // in part as what stays of them (stayingParts), each part a fan of triangles. A triangle that
  // crosses no cell (it has no part of positive area in any) stays.
  void removeLeaving(const std::vector<int>& leaving, const std::map<std::size_t, Fit>& fitted) {
    TriangleMesh& m = grid_.complement;
    std::vector<std::vector<std::size_t>> unfit(m.triangles.size()), fit(m.triangles.size());
    for (const auto& [cell, crossings] : crossings_)
      for (const Crossing& x : crossings) (fitted.count(cell) ? fit : unfit)[x.triangle].push_back(cell);
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint16_t> materials;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      if (leaving[t] == 0) {
        triangles.push_back(m.triangles[t]);
        materials.push_back(m.triangleMaterial[t]);
      }
      if (leaving[t] != 2) continue;
      for (const Polygon& piece : stayingParts(t, unfit[t], fit[t])) {
        const auto first = static_cast<std::uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), piece.begin(), piece.end());
        for (std::uint32_t k = 1; k + 1 < piece.size(); ++k) {
          triangles.push_back({first, first + k, first + k + 1});
          materials.push_back(m.triangleMaterial[t]);
        }
      }
    }
    m.triangles = std::move(triangles);
    m.triangleMaterial = std::move(materials);
  }

  SolidGrid& grid_;
  WindingNumber winding_;
  double tol_, cosAngle_;
  std::vector<Plane> planes_;
  std::map<std::size_t, std::vector<Crossing>> crossings_;  // per cell index, in index order
  std::vector<Polygon> snapped_;  // per triangle, as clipped into cells (laid onto its boundary)
  std::map<CutKey, std::uint32_t> cutIndex_;
  PlaneFitStats stats_;
};

}  // namespace

PlaneFitStats fitPlaneCells(SolidGrid& grid, const TriangleMesh& inside, const SolidOptions& options) {
  return Fitter(grid, inside, options).run();
}

}  // namespace nut::converter
