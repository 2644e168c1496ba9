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

struct Plane {
  dvec3 normal;   // unit, outward: the solid is dot(normal, p) <= offset
  double offset;  // world
};

// Triangles clustered into planes, largest first: a triangle joins the first plane whose normal is
// within the angle and which all its corners lie within the tolerance of. The plane is the first
// triangle's, so that every cell a plane crosses cuts exactly the same one.
std::vector<int> clusterPlanes(const TriangleMesh& m, const std::vector<double>& areas, double cosAngle, double tol,
                               std::vector<Plane>& planes) {
  std::vector<std::uint32_t> order(m.triangles.size());
  for (std::uint32_t t = 0; t < order.size(); ++t) order[t] = t;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return areas[a] > areas[b]; });
  std::vector<int> planeOf(m.triangles.size(), -1);
  for (const std::uint32_t t : order) {
    if (areas[t] <= 0) continue;
    const auto& tri = m.triangles[t];
    const dvec3 p0 = m.positions[tri[0]], p1 = m.positions[tri[1]], p2 = m.positions[tri[2]];
    const dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    for (std::size_t k = 0; k < planes.size() && planeOf[t] < 0; ++k) {
      const Plane& q = planes[k];
      if (glm::dot(q.normal, n) < cosAngle) continue;
      bool near = true;
      for (const dvec3& p : {p0, p1, p2}) near = near && std::abs(glm::dot(q.normal, p) - q.offset) <= tol;
      if (near) planeOf[t] = static_cast<int>(k);
    }
    if (planeOf[t] < 0) {
      planeOf[t] = static_cast<int>(planes.size());
      planes.push_back({n, glm::dot(n, p0)});
    }
  }
  return planeOf;
}

// A complementary triangle's part in one cell.
struct Crossing {
  std::uint32_t triangle;
  double area;
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
    const std::vector<int> planeOf = clusterPlanes(m, areas, cosAngle_, tol_, planes_);
    if (!collectCrossings(areas)) return stats_;
    std::map<std::size_t, Fit> fits;
    for (const auto& [cell, crossings] : crossings_) {
      ++stats_.candidateCells;
      if (auto fit = fitCell(cell, crossings, planeOf)) fits.emplace(cell, *fit);
    }
    // A triangle leaves the mesh only whole: every cell it crosses must fit, and every other
    // triangle crossing those cells leave too. Cutting faces around the cells that fit would leave
    // the mesh more triangles than it had.
    std::vector<bool> leaves(m.triangles.size(), true);
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [cell, crossings] : crossings_) {
        bool taken = fits.count(cell) > 0;
        for (const Crossing& x : crossings) taken = taken && leaves[x.triangle];
        if (taken) continue;
        for (const Crossing& x : crossings)
          if (leaves[x.triangle]) leaves[x.triangle] = false, changed = true;
      }
    }
    for (const auto& [cell, fit] : fits) {
      if (!leaves[crossings_.at(cell).front().triangle]) continue;
      const auto [it, added] = cutIndex_.try_emplace(fit.key, static_cast<std::uint32_t>(grid_.block.cuts.size()));
      if (added) grid_.block.cuts.push_back(fit.cut);
      grid_.block.cells[cell] = Cell::planeCell(it->second, fit.material);
      ++stats_.planeCells;
      stats_.twoPlaneCells += fit.cut.planeCount() == 2;
    }
    if (stats_.planeCells > 0) removeLeaving(leaves, areas);
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

  // Every triangle's parts in the cells its bounding box meets.
  bool collectCrossings(const std::vector<double>& areas) {
    const TriangleMesh& m = grid_.complement;
    const Block& b = grid_.block;
    std::size_t total = 0;
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      if (areas[t] <= 0) continue;
      const Polygon tri = polygonOf(t);
      std::array<int, 3> first{}, last{};
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
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
          for (int x = first[0]; x <= last[0]; ++x) {
            if (++total > kMaxCrossings) return false;
            const std::size_t cell = b.cellIndex(x, y, z);
            // A triangle that only touches the cell (within rounding, along an edge) does not cross it.
            const double part = area(clipToBox(tri, boxOf(cell)));
            if (part > tol_ * tol_) crossings_[cell].push_back({t, part});
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
      if (surface <= tol_ * outline || std::abs(surface - faceArea[static_cast<std::size_t>(k)]) > tol_ * outline)
        return false;
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

  // A cell's plane cut, the planes it uses and its material.
  struct Fit {
    PlaneCut cut;
    std::tuple<int, int, PlaneCombine> key;  // plane indices (-1: none) and combination
    std::uint16_t material;
  };

  std::optional<Fit> fitCell(std::size_t cell, const std::vector<Crossing>& crossings,
                             const std::vector<int>& planeOf) const {
    // Empty cells (what the occupancy makes of a cell a face cuts), and boxes of the faces'
    // material: a plane cell shows one material on its cut and on its box's faces alike.
    const Cell& c = grid_.block.cells[cell];
    const std::uint16_t material = grid_.complement.triangleMaterial[crossings.front().triangle];
    if (c.kind != CellKind::Empty && !(c.kind == CellKind::Solid && c.solid.index == 0 && c.material == material))
      return std::nullopt;
    std::vector<int> ids;
    std::array<double, 2> faceArea{0, 0};
    for (const Crossing& x : crossings) {
      if (grid_.complement.triangleMaterial[x.triangle] != material) return std::nullopt;
      const int id = planeOf[x.triangle];
      auto it = std::find(ids.begin(), ids.end(), id);
      if (it == ids.end()) {
        if (ids.size() == 2) return std::nullopt;
        it = ids.insert(ids.end(), id);
      }
      faceArea[static_cast<std::size_t>(it - ids.begin())] += x.area;
    }
    std::array<Plane, 2> world{planes_[static_cast<std::size_t>(ids[0])],
                               planes_[static_cast<std::size_t>(ids.size() > 1 ? ids[1] : ids[0])]};
    const Box box = boxOf(cell);
    for (const PlaneCombine combine : ids.size() == 1
                                          ? std::vector<PlaneCombine>{PlaneCombine::One}
                                          : std::vector<PlaneCombine>{PlaneCombine::Both, PlaneCombine::Either}) {
      PlaneCut cut;
      cut.combine = combine;
      for (std::size_t k = 0; k < 2; ++k)
        cut.planes[k] = k < ids.size()
                            ? CutPlane{world[k].normal, world[k].offset - glm::dot(world[k].normal, grid_.originM)}
                            : CutPlane{};
      if (cutFits(box, cut, world, faceArea))
        return Fit{cut, std::make_tuple(ids[0], ids.size() > 1 ? ids[1] : -1, combine), material};
    }
    return std::nullopt;
  }

  // The complementary mesh without the triangles that left it for plane cells. A triangle that
  // crosses no cell (its parts are all below the tolerance squared) stays.
  void removeLeaving(const std::vector<bool>& leaves, const std::vector<double>& areas) {
    std::vector<bool> crosses(leaves.size(), false);
    for (const auto& [cell, crossings] : crossings_)
      for (const Crossing& x : crossings) crosses[x.triangle] = true;
    TriangleMesh& m = grid_.complement;
    std::size_t kept = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      if (leaves[t] && crosses[t]) {
        stats_.areaM2 += areas[t];
        continue;
      }
      m.triangles[kept] = m.triangles[t];
      m.triangleMaterial[kept] = m.triangleMaterial[t];
      ++kept;
    }
    m.triangles.resize(kept);
    m.triangleMaterial.resize(kept);
  }

  SolidGrid& grid_;
  WindingNumber winding_;
  double tol_, cosAngle_;
  std::vector<Plane> planes_;
  std::map<std::size_t, std::vector<Crossing>> crossings_;  // per cell index, in index order
  std::map<std::tuple<int, int, PlaneCombine>, std::uint32_t> cutIndex_;
  PlaneFitStats stats_;
};

}  // namespace

PlaneFitStats fitPlaneCells(SolidGrid& grid, const TriangleMesh& inside, const SolidOptions& options) {
  return Fitter(grid, inside, options).run();
}

}  // namespace nut::converter
