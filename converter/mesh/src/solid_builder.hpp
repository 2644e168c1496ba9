// converter/mesh/src/solid_builder.hpp — what the steps of solid conversion share (solid.hpp
// describes the steps): the per-face and per-slope records, the grid helpers, and Builder, which
// holds the state; solid_grid.cpp (planes, slopes, boundaries, the driver), solid_occupancy.cpp
// (occupancy, wedges, trimming), quadrics.cpp (quarter cylinders, sphere octants, and fitting
// every such piece to cells or a sub-block), corner_slopes.cpp (corner slopes as pyramids) and
// solid_materials.cpp (materials, complementary mesh) implement it.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <converter/solid.hpp>
#include <converter/winding.hpp>

namespace nut::converter::solid {

using glm::dvec2;
using glm::dvec3;

// The other two axes of an extrusion axis in the solids' cyclic order ((y,z), (z,x), (x,y)).
constexpr int kU[3] = {1, 2, 0};
constexpr int kV[3] = {2, 0, 1};

// w at or above this is inside (signed: the mesh check turned the mesh outwards, and outside an
// open mesh w can reach -1/2); between the ambiguity bounds the cell is sampled again.
constexpr double kInside = 0.5;
constexpr double kAmbiguousLow = 0.3, kAmbiguousHigh = 0.7;
// Clipped pieces of faces smaller than this (1 mm^2) are numerical slivers.
constexpr double kMinPieceAreaM2 = 1e-6;
// Faces whose material differs from their cell's on more than this share of the grid's surface
// make the grid be built again with boundaries that separate them.
constexpr double kConflictShareForRebuild = 0.001;
// A side of a cell whose material is not the cell's counts as a conflict when it is this share of
// the cell's faces (a small trim on a big cell is not worth a boundary across the whole grid)...
constexpr double kConflictShareOfCell = 0.15;
// ...or this share of the mesh's surface, however big the cell (a gable end under a long pitch),
// alone or summed over the conflicts one boundary would separate (the ends of a gable's wedges).
constexpr double kConflictShareOfSurface = 0.005;
// A line where coplanar faces of two materials meet gets a boundary when the strip it would
// colour wrongly is at least this share of the surface (Builder::addMaterialEdges).
constexpr double kMaterialEdgeShareOfSurface = 0.0005;
// Builds of the grid whose occupancy is computed, at most (see buildSolidGrid).
constexpr int kAttempts = 3;
// How many boundaries slope closure may add per axis.
constexpr std::size_t kMaxSlopeBoundariesPerAxis = 128;
// Slopes (and corner slopes) with less than this share of the mesh's area are left to the
// complementary mesh.
constexpr double kMinSlopeShare = 0.002;
// fitWedges gives a slope up once this many more of its cells failed than became wedges.
constexpr int kWedgeGiveUp = 16;
// A hip or valley is cut into this many steps at most, each at least kCreaseMinStep tolerances
// long along e and across it (findCreasePoints, solid_grid.cpp): its crease cells then hold about
// a quarter of the surface of the box around it, and it adds at most three boundaries per axis.
constexpr int kCreaseSteps = 4;
constexpr double kCreaseMinStep = 8;
// trimCutCells samples a cut cell at its corners, this far inside (a share of the cell's size,
// at most this many tolerances): on the cell's own faces the winding number of a face lying
// there would be ambiguous, and a face may lie up to a tolerance off its boundary. More would
// let a tall cell poke through a roof (2 % of an 11.7 m storey hid a wall top 17 cm above it).
constexpr double kCornerInset = 0.02, kCornerInsetTolerances = 2.0;
// A cell trimCutCells empties proposes a boundary that splits off the part of it on one side of
// what cuts it when that part is solid and at least this share of the cell (along the split axis)...
constexpr double kTrimSplitShare = 0.25;
// ...and when the parts one such boundary keeps have at least this share of the mesh's surface.
constexpr double kTrimSplitShareOfSurface = 0.02;
// Proposed splits this many tolerances apart are one (Builder::proposeTrimSplits).
constexpr double kTrimSplitReach = 10;
// Weight of a face that faces into the solid it bounds, against faces that face out.
constexpr double kInnerFaceWeight = 0.01;

// Rounds of slope closure.
constexpr int kSlopeRounds = 6;

enum class FaceKind : std::uint8_t { Aligned, Slope, Quadric, General };

struct Face {
  dvec3 areaVector{0.0};  // half the cross product: area times unit normal
  double area = 0;
  FaceKind kind = FaceKind::General;
  int axis = 0;           // Aligned: the normal's axis; Slope, Quadric: the extrusion axis
  int group = -1;         // Aligned: cluster (later boundary) index; Slope: plane index; Quadric: piece
};

struct SlopePlane {
  int e = 0;               // extrusion axis; the plane is n . (p_u, p_v) = offset
  dvec2 n{0.0};            // unit normal in (u, v)
  double offset = 0;
  double s0 = 0, s1 = 0;   // extent along t = (-n.v, n.u)
  double e0 = 0, e1 = 0;   // extent along e
  double area = 0;
  std::uint16_t material = 0;
  std::vector<std::uint32_t> faces;
  bool represented = true;
  // Where fitWedges made no wedge, as rectangles [u0, u1] x [e0, e1] of its cross-section: cells
  // where it could not (a failed column spans all of e) and cells the plane's faces cover only
  // partly (its outline cuts through them: a hip, a valley). The parts of the plane's faces over
  // them go to the complementary mesh. Neighbouring cells are merged into one rectangle, so that
  // an eave strip along a roof is one piece of each face, not one per cell it crosses.
  struct Region {
    double u0, u1, e0, e1;
  };
  std::vector<Region> meshRegions;
  // Points along the hips and valleys it shares with slopes along other axes, a few per edge:
  // closeSlopes makes them boundaries, so that the cells such an edge cuts are one small cell per
  // step along it (findCreasePoints, solid_grid.cpp).
  std::vector<dvec3> creasePoints;

  dvec2 point(double s) const { return offset * n + s * dvec2(-n.y, n.x); }
  double vAt(double u) const { return (offset - n.x * u) / n.y; }
  double uAt(double v) const { return (offset - n.y * v) / n.x; }
  double uMin() const { return std::min(point(s0).x, point(s1).x); }
  double uMax() const { return std::max(point(s0).x, point(s1).x); }
  double vMin() const { return std::min(point(s0).y, point(s1).y); }
  double vMax() const { return std::max(point(s0).y, point(s1).y); }
};

// A quarter-round piece (quadrics.cpp): faces on a quarter of an elliptic cylinder whose axis
// is parallel to axis e, from one axis-aligned tangent direction to the next. Boundaries at the
// axis and at both tangent lines make the arc fill the cross-section of one cell, which becomes a
// QuarterCylinder (solid on the axis side, a round corner) or an InverseQuarterCylinder (a cove).
// Where boundaries from elsewhere cut that cross-section into several cells, the piece becomes a
// sub-block S of its own (one cell across, G0's layers along e) and every cell of its box in G0
// redirects to S. A sphere-octant piece (a quarter of a dome, e = z) is the same with a centre
// and radius along e as well: its box becomes one SphereOctant or InverseSphereOctant cell, or S
// of one cell that every cell of the box redirects to. A corner slope (corner_slopes.cpp, planar)
// is fitted like a sphere octant: its surface is the triangle through the three box corners next
// to the centre, and its box becomes one Pyramid or InversePyramid cell, or S of one cell.
struct QuadricPiece {
  int e = 0;                      // axis; (u, v) = (kU[e], kV[e])
  dvec2 centre{0.0};              // the axis in (u, v)
  dvec2 radius{0.0};              // along u and v
  std::array<int, 2> quadrant{};  // direction (+1 or -1) from the axis to the arc along u and v
  double e0 = 0, e1 = 0;          // extent along e
  // A sphere octant's direction (+1 or -1) from its centre to its pole along e, the centre being
  // at e0 or e1 and the radius e1 - e0; 0 for a quarter cylinder.
  int eSign = 0;
  // A corner slope: the plane through the box corners next to the centre (eSign != 0 too).
  bool planar = false;
  double area = 0;
  std::uint16_t material = 0;
  std::vector<std::uint32_t> faces;
  bool represented = true;        // false once its cells could not show it
  bool subBlock = false;          // shown by S (set by fitQuadrics)
  std::array<int, 3> lo{}, hi{};  // its box's cells in G0 (hi exclusive), when represented
  std::vector<std::int8_t> layers;  // the solid of each layer of its box along e (an octant: one)

  bool octant() const { return eSign != 0; }
  // A corner-centred piece (sphere octant, corner slope) spanning the box [lo, hi] along e = z.
  void spanBox(const dvec3& boxLo, const dvec3& boxHi, double pieceArea) {
    e = 2;
    radius = dvec2(boxHi.x - boxLo.x, boxHi.y - boxLo.y);
    e0 = boxLo.z;
    e1 = boxHi.z;
    area = pieceArea;
  }
  // Its centre at the box corner behind the normal (side = +1) or in front of it (side = -1).
  void centreAtCorner(const dvec3& normal, int side, const dvec3& boxLo, const dvec3& boxHi) {
    quadrant = {normal.x > 0 ? side : -side, normal.y > 0 ? side : -side};
    eSign = normal.z > 0 ? side : -side;
    centre = dvec2(quadrant[0] > 0 ? boxLo.x : boxHi.x, quadrant[1] > 0 ? boxLo.y : boxHi.y);
  }
  // The largest radius: rho's error times this is a distance.
  double reach() const { return std::max({radius.x, radius.y, octant() ? e1 - e0 : 0.0}); }
  // Distance of x (grid frame) from the axis or centre, in units of the radius: 1 on the surface
  // (a corner slope: the sum of the distances along the axes, each in units of the box's size).
  double rho(const dvec3& x) const {
    const double du = (x[kU[e]] - centre.x) / radius.x, dv = (x[kV[e]] - centre.y) / radius.y;
    const double de = octant() ? (x[e] - (eSign > 0 ? e0 : e1)) / (e1 - e0) : 0.0;
    if (planar) return std::abs(du) + std::abs(dv) + std::abs(de);
    return std::sqrt(du * du + dv * dv + de * de);
  }
  // The curved surface's unit normal at x (grid frame; up to sign): rho's gradient direction.
  dvec3 normalAt(const dvec3& x) const {
    dvec3 g(0.0);
    g[kU[e]] = (x[kU[e]] - centre.x) / (radius.x * radius.x);
    g[kV[e]] = (x[kV[e]] - centre.y) / (radius.y * radius.y);
    if (octant()) g[e] = (x[e] - (eSign > 0 ? e0 : e1)) / ((e1 - e0) * (e1 - e0));
    const double length = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
    return length > 0 ? g / length : g;
  }
  // A corner slope's rho per metre across its plane (the length of rho's gradient).
  double rhoPerMetre() const {
    return std::sqrt(1 / (radius.x * radius.x) + 1 / (radius.y * radius.y) + 1 / ((e1 - e0) * (e1 - e0)));
  }
  // Index into layers of the box's layer k along e.
  std::size_t layerOf(int k) const { return octant() ? 0 : static_cast<std::size_t>(k - lo[static_cast<std::size_t>(e)]); }
};

// Whether a quadric (or pyramid) group is solid on the axis's or centre's side of its surface.
inline bool convexQuadric(SolidGroup g) {
  return g == SolidGroup::QuarterCylinder || g == SolidGroup::SphereOctant || g == SolidGroup::Pyramid;
}

// Boundary helpers (solid_grid.cpp). Boundaries are sorted positions, metres from the origin.
// Index of the last boundary <= x (clamped to a cell index 0..n-1).
int cellOf(const std::vector<double>& bounds, double x);
// Index of the boundary nearest to x.
int nearestBoundary(const std::vector<double>& bounds, double x);
bool hasBoundaryNear(const std::vector<double>& bounds, double x, double tolerance);
// Sorted, millimetre-snapped positions at least 1 mm apart; 0 and size stay exact.
std::vector<double> tidy(std::vector<double> positions, double size);
// Whether boundary and position x, snapped, are within the tolerance, compared in whole
// millimetres: a position just the tolerance away (a centimetre from a boundary on a centimetre
// grid) must count the same whatever the rounding, since a building turned to its own frame (its
// origin elsewhere) must get the grid it gets upright.
bool snappedWithin(double boundary, double x, double tol);
// Inserts positions into one axis's boundaries unless a boundary lies within the tolerance.
void insertBoundaries(std::vector<double>& bounds, std::vector<double> positions, double size, double tol);

// A convex polygon in 2D and its clipping (solid_materials.cpp).
struct Polygon2 {
  std::array<dvec2, 12> p;
  int n = 0;
};
// Keeps the part with coordinate `axis` below (keepBelow) or above `bound` (Sutherland-Hodgman).
void clipAxis(Polygon2& poly, int axis, double bound, bool keepBelow);
double polygonArea(const Polygon2& poly);
// Cells i0..i1 by j0..j1 of a plane, and cells (i, j), sorted by i then j, joined into such
// rectangles: runs of consecutive j in one column, and a run continued by the same run in the
// next column (solid_materials.cpp).
struct CellRectangle {
  int i0, i1, j0, j1;
};
std::vector<CellRectangle> joinCells(const std::vector<std::array<int, 2>>& cells);

// Whether a triangle overlaps an axis-aligned box, by the separating-axis test (solid_occupancy.cpp).
bool triangleOverlapsBox(dvec3 a, dvec3 b, dvec3 c, const dvec3& centre, const dvec3& half);

// The winding-number tree, built on first use: a closed mesh without slopes never needs it.
class LazyWinding {
 public:
  explicit LazyWinding(const TriangleMesh& mesh) : mesh_(mesh) {}
  double operator()(const dvec3& q) const {
    std::call_once(once_, [this] {
      const auto start = std::chrono::steady_clock::now();
      tree_.emplace(mesh_.positions, mesh_.triangles);
      seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    return (*tree_)(q);
  }
  double buildSeconds() const { return seconds_; }

 private:
  const TriangleMesh& mesh_;
  mutable std::once_flag once_;
  mutable std::optional<WindingNumber> tree_;
  mutable double seconds_ = 0;
};

// Everything the steps share.
struct Builder {
  const TriangleMesh& mesh;
  const SolidOptions& options;
  double tol;
  dvec3 origin;
  std::vector<dvec3> p;  // positions relative to origin
  // Each triangle's corners as ids of distinct positions (weld.hpp): a mesh may repeat a vertex
  // on either side of a seam, and the pieces of quadrics and corner slopes join across it.
  std::vector<std::array<std::uint32_t, 3>> cornerIds;
  dvec3 size{0.0};
  std::vector<Face> faces;
  std::array<std::vector<double>, 3> clusterMeans;   // per axis
  std::array<std::vector<bool>, 3> clusterDrifts;    // per axis and cluster: a step of a drifting chain
  std::vector<SlopePlane> slopes;
  std::vector<QuadricPiece> quadrics;
  std::vector<std::pair<dvec3, dvec3>> bevelBoxes;  // boxes of pieces too coarsely faceted to fit
  std::array<std::vector<double>, 3> bounds;
  std::array<int, 3> n{};
  std::vector<std::int8_t> shape;        // per cell: -1 empty, else solid index (0 box, 1..12 wedge)
  std::vector<std::uint16_t> hint;       // per cell: material of the nearest face along the sweep
  // shape before anything decided the cell: fitWedges and fitQuadrics run first, and classify
  // fills the cells they left.
  static constexpr std::int8_t kUnclassified = -2;
  std::vector<int> subPiece;             // per cell: the quadric piece whose sub-block it shows, or -1
  SolidStats stats;

  Builder(const TriangleMesh& m, const SolidOptions& o) : mesh(m), options(o), tol(o.toleranceM) {}

  std::size_t index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(n[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(z));
  }
  std::size_t index(const std::array<int, 3>& c) const { return index(c[0], c[1], c[2]); }
  std::array<int, 3> cellAt(std::size_t id) const {
    const auto nx = static_cast<std::size_t>(n[0]), ny = static_cast<std::size_t>(n[1]);
    return {static_cast<int>(id % nx), static_cast<int>(id / nx % ny), static_cast<int>(id / (nx * ny))};
  }
  // The box of cell `id` (grid frame).
  void cellBox(std::size_t id, dvec3& lo, dvec3& hi) const {
    const std::array<int, 3> c = cellAt(id);
    for (int ax = 0; ax < 3; ++ax) {
      const auto& B = bounds[static_cast<std::size_t>(ax)];
      lo[ax] = B[static_cast<std::size_t>(c[static_cast<std::size_t>(ax)])];
      hi[ax] = B[static_cast<std::size_t>(c[static_cast<std::size_t>(ax)] + 1)];
    }
  }
  dvec3 corner(std::uint32_t face, int k) const { return p[mesh.triangles[face][static_cast<std::size_t>(k)]]; }

  // What a piece of faces spans: its bounding box, area, summed area vector and area per material.
  struct PieceSpan {
    dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    dvec3 areaVector{0.0};
    double area = 0;
    std::vector<double> materialArea;
  };
  PieceSpan spanOf(const std::vector<std::uint32_t>& members) const;
  bool facetsFollowSurface(const QuadricPiece& piece, const std::vector<std::uint32_t>& members, const PieceSpan& span);

  void analyseFaces();
  void findSlopes();
  void findQuadrics();
  void findSphereOctants();
  void findCornerSlopes();
  void keepPiece(QuadricPiece piece, std::vector<std::uint32_t> members, const std::vector<double>& materialArea);
  void findMaterialEdges();
  void buildBounds();
  void addMaterialEdges();
  void addQuadricBounds();
  void closeSlopes();
  // Occupancy of the cells still kUnclassified, and every cell's hint.
  void classify(const LazyWinding& winding);
  bool fitWedges(const LazyWinding& winding);
  bool fitQuadrics(const LazyWinding& winding);
  bool subBlockFits(int piece, const LazyWinding& winding) const;
  // Whether the cell is solid at all the points (grid frame) on or in it: a cell showing a
  // sub-block is solid where S is (within the tolerance), any other where its shape is.
  bool solidAt(std::size_t cell, std::span<const dvec3> points) const;
  void trimCutCells(const LazyWinding& winding);
  bool shownByMesh(std::uint32_t face) const;
  // The parts of slope face f over cells where its plane made no wedge (SlopePlane::meshRegions),
  // which the complementary mesh shows: convex polygons in the grid frame (solid_occupancy.cpp).
  struct MeshPiece {
    std::array<dvec3, 12> p;
    int n = 0;
    double area = 0;
  };
  std::vector<MeshPiece> meshPieces(std::uint32_t face) const;
  // The same over any rectangles of its plane's cross-section.
  std::vector<MeshPiece> piecesOver(std::uint32_t face, const std::vector<SlopePlane::Region>& regions) const;
  struct Share {
    std::size_t cell;
    std::uint16_t material;
    std::uint8_t side;  // 2 * axis + (1 on the + side); 6 for a wedge's slope or a curved face
    double area;
  };
  std::vector<Share> wedgeShares;  // filled by fitWedges and fitQuadrics
  std::vector<Share> computeShares(TriangleMesh& complement, SolidStats& area, std::vector<Share>& lost);
  // Cells trimCutCells emptied, and the extent of the surface that cuts each (inside the cell).
  struct CutExtent {
    dvec3 lo{std::numeric_limits<double>::infinity()};
    dvec3 hi{-std::numeric_limits<double>::infinity()};
  };
  std::unordered_map<std::size_t, CutExtent> trimmed;
  // Boundaries that would keep the solid part of a trimmed cell, for the next build of the grid
  // (solid_occupancy.cpp); `lost`: computeShares's pieces of axis-aligned faces that went to the
  // mesh because a trimmed cell beside them was emptied.
  std::array<std::vector<double>, 3> proposeTrimSplits(const std::vector<Share>& lost, const LazyWinding& winding) const;
  // Boundaries at the corners of the planes of the faces the mesh shows (plane_corners.cpp).
  std::array<std::vector<double>, 3> proposePlaneCorners() const;
  std::array<std::vector<double>, 3> materialConflicts(const std::vector<Share>& shares, double& conflictArea) const;
  void assignMaterials(Block& block, std::vector<Block>& subBlocks, const std::vector<Share>& shares);
  std::array<std::vector<double>, 3> extraBounds;  // from material conflicts, trimmed cells and plane corners
  struct MaterialLine {
    double at;      // the coordinate along the axis it is a line of constant value of
    double length;  // shared by the two materials
  };
  std::array<std::vector<MaterialLine>, 3> materialLines;  // findMaterialEdges
};


}  // namespace nut::converter::solid
