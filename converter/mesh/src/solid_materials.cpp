// Solid conversion, materials: faces clipped against the cells they bound, each cell's material,
// the boundaries that separate faces of different materials, and the complementary mesh
// (converter/solid.hpp, step 4).
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <glm/geometric.hpp>

#include <converter/axis_order.hpp>
#include <nut/format.hpp>
#include <nut/units.hpp>

#include "parallel.hpp"
#include "solid_builder.hpp"
#include "weld.hpp"

namespace nut::converter::solid {

void clipAxis(Polygon2& poly, int axis, double bound, bool keepBelow) {
  // Called for every piece of every face: the sides are tested once per corner, and only the
  // corners kept are copied (a Polygon2 holds 12).
  std::array<bool, 12> in{};
  for (int i = 0; i < poly.n; ++i) {
    const double x = poly.p[static_cast<std::size_t>(i)][axis];
    in[static_cast<std::size_t>(i)] = keepBelow ? x <= bound : x >= bound;
  }
  std::array<dvec2, 12> out;
  int n = 0;
  for (int i = 0; i < poly.n; ++i) {
    const int next = i + 1 == poly.n ? 0 : i + 1;
    const dvec2 a = poly.p[static_cast<std::size_t>(i)], b = poly.p[static_cast<std::size_t>(next)];
    const bool ina = in[static_cast<std::size_t>(i)], inb = in[static_cast<std::size_t>(next)];
    if (ina) out[static_cast<std::size_t>(n++)] = a;
    if (ina != inb) {
      const double t = (bound - a[axis]) / (b[axis] - a[axis]);
      dvec2 c = a + t * (b - a);
      c[axis] = bound;
      out[static_cast<std::size_t>(n++)] = c;
    }
  }
  std::copy_n(out.begin(), n, poly.p.begin());
  poly.n = n;
}
double polygonArea(const Polygon2& poly) {
  double twice = 0;
  for (int i = 0; i < poly.n; ++i) {
    const dvec2 a = poly.p[static_cast<std::size_t>(i)], b = poly.p[static_cast<std::size_t>((i + 1) % poly.n)];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * std::abs(twice);
}

// Joins cells (i, j), sorted by i then j as the face loop finds them, into rectangles: runs of
// consecutive j in one column, and a run continued by the same run in the next column.
std::vector<CellRectangle> joinCells(const std::vector<std::array<int, 2>>& cells) {
  std::vector<CellRectangle> runs;
  for (const auto& [i, j] : cells) {
    if (!runs.empty() && runs.back().i0 == i && runs.back().j1 + 1 == j)
      ++runs.back().j1;
    else
      runs.push_back({i, i, j, j});
  }
  std::vector<CellRectangle> out;
  std::vector<std::size_t> open;  // rectangles of out that the previous column's runs extended
  for (std::size_t r = 0; r < runs.size();) {
    const int column = runs[r].i0;
    std::vector<std::size_t> extended;
    for (; r < runs.size() && runs[r].i0 == column; ++r) {
      const CellRectangle& run = runs[r];
      const auto same = std::find_if(open.begin(), open.end(), [&](std::size_t o) {
        return out[o].i1 + 1 == column && out[o].j0 == run.j0 && out[o].j1 == run.j1;
      });
      if (same != open.end()) {
        out[*same].i1 = column;
        extended.push_back(*same);
      } else {
        extended.push_back(out.size());
        out.push_back(run);
      }
    }
    open = std::move(extended);
  }
  return out;
}

namespace {

// What computeShares gathers from a run of faces; runs are joined in order afterwards, so that
// the result does not depend on the thread count.
struct ShareChunk {
  std::vector<Builder::Share> shares, lost;
  TriangleMesh complement;
  double nut = 0, complementArea = 0, hidden = 0, drawnTwice = 0;

  // A convex polygon in the grid frame, added to the complementary mesh (world frame) as a fan.
  void addToMesh(const dvec3* poly, int count, std::uint16_t material, const dvec3& origin) {
    const auto base = static_cast<std::uint32_t>(complement.positions.size());
    for (int i = 0; i < count; ++i) complement.positions.push_back(poly[i] + origin);
    for (std::uint32_t i = 1; i + 1 < static_cast<std::uint32_t>(count); ++i) {
      complement.triangles.push_back({base, base + i, base + i + 1});
      complement.triangleMaterial.push_back(material);
    }
  }
};

// An axis-aligned face seen along its axis a: its triangle in the (u, v) plane, and its own
// plane, which lifts clipped pieces back to 3D (where along a the surface really is, and the
// complementary mesh's corners).
struct FaceAlongAxis {
  int a, u, v;
  Polygon2 tri;
  dvec3 normal;
  double d;         // normal . x on the plane
  double trueArea;  // per projected area

  std::array<dvec3, 12> lift(const Polygon2& piece) const {
    std::array<dvec3, 12> corners{};
    for (int m = 0; m < piece.n; ++m) {
      dvec3& q = corners[static_cast<std::size_t>(m)];
      q[u] = piece.p[static_cast<std::size_t>(m)].x;
      q[v] = piece.p[static_cast<std::size_t>(m)].y;
      q[a] = (d - normal[u] * q[u] - normal[v] * q[v]) / normal[a];
    }
    return corners;
  }
};

// A face's piece over the cells (i, j) of its plane.
struct FacePiece {
  int i, j;
  const Polygon2& poly;
  double area;                    // true area
  std::array<dvec3, 12> corners;  // on the face's plane
  double surfaceLo, surfaceHi;    // where along the axis the piece is
};

// Calls f(piece) for each piece of the face over a cell of its plane, clipping a column strip
// first, then its rows: two clips per cell instead of four.
template <typename F>
void forEachPiece(const Builder& b, const FaceAlongAxis& face, F&& f) {
  const auto& U = b.bounds[static_cast<std::size_t>(face.u)];
  const auto& V = b.bounds[static_cast<std::size_t>(face.v)];
  const auto& p = face.tri.p;
  const int i0 = cellOf(U, std::min({p[0].x, p[1].x, p[2].x})), i1 = cellOf(U, std::max({p[0].x, p[1].x, p[2].x}));
  const int j0 = cellOf(V, std::min({p[0].y, p[1].y, p[2].y})), j1 = cellOf(V, std::max({p[0].y, p[1].y, p[2].y}));
  for (int i = i0; i <= i1; ++i) {
    Polygon2 strip = face.tri;
    if (i0 != i1) {
      clipAxis(strip, 0, U[static_cast<std::size_t>(i)], false);
      clipAxis(strip, 0, U[static_cast<std::size_t>(i + 1)], true);
      if (strip.n < 3) continue;
    }
    for (int j = j0; j <= j1; ++j) {
      Polygon2 poly = strip;
      if (j0 != j1) {
        clipAxis(poly, 1, V[static_cast<std::size_t>(j)], false);
        clipAxis(poly, 1, V[static_cast<std::size_t>(j + 1)], true);
        if (poly.n < 3) continue;
      }
      const double area = polygonArea(poly) * face.trueArea;
      if (area <= kMinPieceAreaM2) continue;  // a clipping sliver, not a piece of surface
      FacePiece piece{i,
                      j,
                      poly,
                      area,
                      face.lift(poly),
                      std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
      for (int m = 0; m < poly.n; ++m) {
        piece.surfaceLo = std::min(piece.surfaceLo, piece.corners[static_cast<std::size_t>(m)][face.a]);
        piece.surfaceHi = std::max(piece.surfaceHi, piece.corners[static_cast<std::size_t>(m)][face.a]);
      }
      f(piece);
    }
  }
}

// The cells on either side of a boundary under a piece, and whether each is solid there.
constexpr std::size_t kNoCell = std::numeric_limits<std::size_t>::max();
struct Sides {
  std::size_t lo, hi;  // the cells below and above the boundary (kNoCell: beyond the grid)
  bool solidLo, solidHi;
};

// The sides of boundary k of the face's axis under the piece. A cell showing a quarter-round
// sub-block covers the piece only where S is solid under all of it; where the arc crosses it, the
// other side's cell shows it.
Sides sidesAt(const Builder& b, const FaceAlongAxis& face, const FacePiece& piece, int k) {
  const auto a = static_cast<std::size_t>(face.a);
  std::array<int, 3> lo{}, hi{};
  lo[static_cast<std::size_t>(face.u)] = hi[static_cast<std::size_t>(face.u)] = piece.i;
  lo[static_cast<std::size_t>(face.v)] = hi[static_cast<std::size_t>(face.v)] = piece.j;
  lo[a] = k - 1;
  hi[a] = k;
  // The piece's corners moved onto the boundary matter only to a cell showing a sub-block (any
  // other is solid by its shape alone, Builder::solidAt); they are made for those alone.
  const auto solid = [&](std::size_t cell) {
    if (b.subPiece[cell] < 0) return b.solidAt(cell, {});
    std::array<dvec3, 12> onBoundary = piece.corners;
    for (int m = 0; m < piece.poly.n; ++m)
      onBoundary[static_cast<std::size_t>(m)][face.a] = b.bounds[a][static_cast<std::size_t>(k)];
    return b.solidAt(cell, std::span<const dvec3>(onBoundary.data(), static_cast<std::size_t>(piece.poly.n)));
  };
  Sides s{kNoCell, kNoCell, false, false};
  if (k > 0) s.lo = b.index(lo), s.solidLo = solid(s.lo);
  if (k < b.n[a]) s.hi = b.index(hi), s.solidHi = solid(s.hi);
  return s;
}

// The sides at boundary k, or where those are both empty or both solid, at the nearest boundary
// within the tolerance of the piece whose sides differ. A slightly tilted face spans more than
// one boundary of its axis, and the solid's face may be at another one (a wall 0.1 degree off
// over 10 m; the steps of a drifting facade); without this the face would take the colour of the
// cell's other faces (a ground plate's) with the true wall in the mesh a few millimetres away.
Sides sidesShowing(const Builder& b, const FaceAlongAxis& face, const FacePiece& piece, int k) {
  const auto& A = b.bounds[static_cast<std::size_t>(face.a)];
  Sides sides = sidesAt(b, face, piece, k);
  for (int step = 1; sides.solidLo == sides.solidHi; ++step) {
    bool inReach = false;
    for (int kk : {k - step, k + step}) {
      if (kk < 0 || kk > b.n[static_cast<std::size_t>(face.a)]) continue;
      const double at = A[static_cast<std::size_t>(kk)];
      if (at < piece.surfaceLo - b.tol || at > piece.surfaceHi + b.tol) continue;
      inReach = true;
      if (const Sides near = sidesAt(b, face, piece, kk); near.solidLo != near.solidHi) return near;
    }
    if (!inReach) break;
  }
  return sides;
}

// A face given to the complementary mesh whole.
void giveFaceToMesh(const Builder& b, std::uint32_t f, ShareChunk& out) {
  const Face& face = b.faces[f];
  const dvec3 tri3[3] = {b.corner(f, 0), b.corner(f, 1), b.corner(f, 2)};
  if (face.area > 0) out.addToMesh(tri3, 3, b.mesh.triangleMaterial[f], b.origin);
  out.complementArea += face.area;
}

// A slope's face, shown by wedges, or a quadric's curved face, shown by its cells or sub-block
// (fitWedges and fitQuadrics gave the cells their shares). A slope face's parts over cells where
// its plane made no wedge go to the mesh.
void shareSlopeOrCurvedFace(const Builder& b, std::uint32_t f, ShareChunk& out) {
  const Face& face = b.faces[f];
  double meshArea = 0;
  if (face.kind == FaceKind::Slope)
    for (const Builder::MeshPiece& piece : b.meshPieces(f)) {
      out.addToMesh(piece.p.data(), piece.n, b.mesh.triangleMaterial[f], b.origin);
      meshArea += piece.area;
    }
  out.complementArea += meshArea;
  out.nut += face.area - meshArea;
}

// An axis-aligned face, piece by piece over the cells of its plane.
void shareAxisAlignedFace(const Builder& b, std::uint32_t f, ShareChunk& out) {
  const Face& face = b.faces[f];
  const std::uint16_t material = b.mesh.triangleMaterial[f];
  const int a = face.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const auto& A = b.bounds[static_cast<std::size_t>(a)];
  const int clusterBoundary =
      nearestBoundary(A, b.clusterMeans[static_cast<std::size_t>(a)][static_cast<std::size_t>(face.group)]);
  const bool drifting = b.clusterDrifts[static_cast<std::size_t>(a)][static_cast<std::size_t>(face.group)];
  const dvec3 P0 = b.corner(f, 0), P1 = b.corner(f, 1), P2 = b.corner(f, 2);
  FaceAlongAxis along{a, u, v, {}, face.areaVector / face.area, 0, 0};
  along.tri.n = 3;
  along.tri.p[0] = {P0[u], P0[v]};
  along.tri.p[1] = {P1[u], P1[v]};
  along.tri.p[2] = {P2[u], P2[v]};
  const double projected = polygonArea(along.tri);
  if (projected <= 0) return;
  along.trueArea = face.area / projected;
  along.d = glm::dot(along.normal, P0);

  // Cells (i, j) whose piece the mesh must show.
  std::vector<std::array<int, 2>> uncovered;
  double uncoveredArea = 0, shownArea = 0;
  forEachPiece(b, along, [&](const FacePiece& piece) {
    // A face of a drifting chain (clusterIntervals) is cut across its steps: each piece starts at
    // the boundary nearest to where it is.
    const int k = drifting ? nearestBoundary(A, 0.5 * (piece.surfaceLo + piece.surfaceHi)) : clusterBoundary;
    const Sides sides = sidesShowing(b, along, piece, k);
    if (sides.solidLo != sides.solidHi) {
      // The face is on the +a side of the cell below it, on the -a side of the cell above. One
      // that faces into the solid is an inner face (the bottom of a dome standing on the roof):
      // it only counts where nothing else covers the cell.
      const bool facesOut = (along.normal[a] > 0) == sides.solidLo;
      out.shares.push_back({sides.solidLo ? sides.lo : sides.hi, material,
                            static_cast<std::uint8_t>(2 * a + (sides.solidLo ? 1 : 0)),
                            facesOut ? piece.area : kInnerFaceWeight * piece.area});
      out.nut += piece.area;
      shownArea += piece.area;
    } else if (!sides.solidLo) {
      // Empty on both sides: a thin sheet the mesh must show, or a strip thinner than the
      // tolerance left over where boundaries merged, which is within the tolerance already.
      double extent = 0;
      const auto& q = piece.poly.p;
      for (int m = 0; m < piece.poly.n; ++m)
        extent = std::max(
            extent, glm::length(q[static_cast<std::size_t>(m)] - q[static_cast<std::size_t>((m + 1) % piece.poly.n)]));
      if (piece.area < 0.5 * b.tol * extent) {
        out.nut += piece.area;
        return;
      }
      uncovered.push_back({piece.i, piece.j});
      uncoveredArea += piece.area;
      if (sides.lo != kNoCell && b.trimmed.contains(sides.lo))
        out.lost.push_back({sides.lo, material, static_cast<std::uint8_t>(2 * a + 1), piece.area});
      if (sides.hi != kNoCell && b.trimmed.contains(sides.hi))
        out.lost.push_back({sides.hi, material, static_cast<std::uint8_t>(2 * a), piece.area});
      out.complementArea += piece.area;
    } else {
      out.hidden += piece.area;  // solid on both sides: an inner face nobody sees
    }
  });
  if (uncovered.empty()) return;

  // The uncovered cells joined into rectangles (runs along v, then equal runs of neighbouring
  // columns), each clipped from the face once.
  const auto& U = b.bounds[static_cast<std::size_t>(u)];
  const auto& V = b.bounds[static_cast<std::size_t>(v)];
  std::vector<Polygon2> pieces;
  int pieceTriangles = 0;
  for (const CellRectangle& r : joinCells(uncovered)) {
    Polygon2 piece = along.tri;
    clipAxis(piece, 0, U[static_cast<std::size_t>(r.i0)], false);
    clipAxis(piece, 0, U[static_cast<std::size_t>(r.i1 + 1)], true);
    clipAxis(piece, 1, V[static_cast<std::size_t>(r.j0)], false);
    clipAxis(piece, 1, V[static_cast<std::size_t>(r.j1 + 1)], true);
    if (piece.n < 3) continue;
    pieces.push_back(piece);
    pieceTriangles += piece.n - 2;
  }
  // The face goes to the mesh whole when that takes fewer triangles than its pieces (a staircase
  // of cells under a roof left to the mesh cuts a gable into a dozen), or when most of it is
  // uncovered. Its covered part is then drawn twice, by its cells and by the face itself, in the
  // face's own material and within the tolerance of the cells' surface.
  if (pieceTriangles > 1 || 2 * uncoveredArea > face.area) {
    const dvec3 tri3[3] = {P0, P1, P2};
    out.addToMesh(tri3, 3, material, b.origin);
    out.drawnTwice += shownArea;
    return;
  }
  for (const Polygon2& piece : pieces) out.addToMesh(along.lift(piece).data(), piece.n, material, b.origin);
}

}  // namespace

// Clips every axis-aligned face against the cell faces it covers (step 4 of solid.hpp). Where
// exactly one side is solid, that cell gets a share of the face's area for the face's material
// on that side; wedges add their slope (fitWedges), quadric cells their curved face
// (fitQuadrics). The pieces that are empty on both sides go to `complement`, and the surface
// statistics are counted; those beside a trimmed cell are also listed in `lost`, as shares of
// that cell (what keeping part of it would win back: proposeTrimSplits).
std::vector<Builder::Share> Builder::computeShares(TriangleMesh& complement, SolidStats& area, std::vector<Share>& lost) {
  constexpr std::size_t kChunk = 4096;  // faces per task on the threads
  std::vector<ShareChunk> chunks((faces.size() + kChunk - 1) / kChunk);
  parallelFor(faces.size(), kChunk, options.threads, [&](std::size_t begin, std::size_t end) {
    ShareChunk& out = chunks[begin / kChunk];
    for (auto f = static_cast<std::uint32_t>(begin); f < end; ++f) {
      const FaceKind kind = faces[f].kind;
      if (shownByMesh(f))
        giveFaceToMesh(*this, f, out);
      else if (kind == FaceKind::Slope || kind == FaceKind::Quadric)
        shareSlopeOrCurvedFace(*this, f, out);
      else
        shareAxisAlignedFace(*this, f, out);
    }
  });
  std::vector<Share> shares = wedgeShares;
  lost.clear();
  for (ShareChunk& c : chunks) {
    shares.insert(shares.end(), c.shares.begin(), c.shares.end());
    lost.insert(lost.end(), c.lost.begin(), c.lost.end());
    const auto base = static_cast<std::uint32_t>(complement.positions.size());
    complement.positions.insert(complement.positions.end(), c.complement.positions.begin(),
                                c.complement.positions.end());
    for (const auto& t : c.complement.triangles)
      complement.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    complement.triangleMaterial.insert(complement.triangleMaterial.end(), c.complement.triangleMaterial.begin(),
                                       c.complement.triangleMaterial.end());
    area.nutAreaM2 += c.nut;
    area.complementAreaM2 += c.complementArea;
    area.hiddenAreaM2 += c.hidden;
    area.drawnTwiceAreaM2 += c.drawnTwice;
  }
  // Pieces of neighbouring cells and faces repeat their corners: each is stored once.
  Welded welded = weld(complement.positions, complement.triangles);
  complement.positions = std::move(welded.points);
  complement.triangles = std::move(welded.triangles);
  std::sort(shares.begin(), shares.end(), [](const Share& x, const Share& y) {
    return x.cell != y.cell ? x.cell < y.cell : x.side != y.side ? x.side < y.side : x.material < y.material;
  });
  return shares;
}

// A cell shows one material on all its faces. Where two of its faces carry different materials
// with a real share each (a slab with a deck on top and a concrete ceiling below, a gable end
// under a roof slope), a boundary is proposed that gives the smaller one a cell of its own: in
// the middle for opposite faces, a little inside the smaller face otherwise. Conflicts too small
// alone are proposed where, summed by place, they reach the surface share together.
std::array<std::vector<double>, 3> Builder::materialConflicts(const std::vector<Share>& shares,
                                                              double& conflictArea) const {
  conflictArea = 0;
  std::array<std::vector<double>, 3> proposals;
  // Conflicts too small on their own, by the place their boundary would go: a boundary that
  // separates many of them at once (the ends of all the wedges along a gable) pays together.
  struct Minor {
    double at, area;
  };
  std::array<std::vector<Minor>, 3> minor;
  const double inset = std::max(1.5 * tol, 0.002);
  for (std::size_t i = 0; i < shares.size();) {
    std::size_t j = i;
    // Dominant material and area per side (6 = a wedge's slope).
    std::array<double, 7> sideArea{};
    std::array<std::uint16_t, 7> sideMaterial{};
    double total = 0;
    while (j < shares.size() && shares[j].cell == shares[i].cell) {
      std::size_t k = j;
      double sum = 0;
      while (k < shares.size() && shares[k].cell == shares[j].cell && shares[k].side == shares[j].side &&
             shares[k].material == shares[j].material)
        sum += shares[k++].area;
      if (sum > sideArea[shares[j].side]) {
        sideArea[shares[j].side] = sum;
        sideMaterial[shares[j].side] = shares[j].material;
      }
      total += sum;
      j = k;
    }
    const std::size_t cell = shares[i].cell;
    i = j;
    const int best = static_cast<int>(std::max_element(sideArea.begin(), sideArea.end()) - sideArea.begin());
    std::array<int, 3> c{static_cast<int>(cell % static_cast<std::size_t>(n[0])),
                         static_cast<int>(cell / static_cast<std::size_t>(n[0]) % static_cast<std::size_t>(n[1])),
                         static_cast<int>(cell / (static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1])))};
    for (int side = 0; side < 6; ++side) {
      const double area = sideArea[static_cast<std::size_t>(side)];
      if (side == best || area <= 0 ||
          sideMaterial[static_cast<std::size_t>(side)] == sideMaterial[static_cast<std::size_t>(best)])
        continue;
      const int a = side / 2;
      const auto& B = bounds[static_cast<std::size_t>(a)];
      const double lo = B[static_cast<std::size_t>(c[static_cast<std::size_t>(a)])],
                   hi = B[static_cast<std::size_t>(c[static_cast<std::size_t>(a)] + 1)];
      if (hi - lo < 2 * inset) continue;
      const double at = best / 2 == a && best < 6 ? 0.5 * (lo + hi) : side % 2 ? hi - inset : lo + inset;
      if (area < kConflictShareOfCell * total && area < kConflictShareOfSurface * stats.areaM2) {
        minor[static_cast<std::size_t>(a)].push_back({at, area});
        continue;
      }
      conflictArea += area;
      proposals[static_cast<std::size_t>(a)].push_back(at);
    }
  }
  for (int a = 0; a < 3; ++a) {
    auto& list = minor[static_cast<std::size_t>(a)];
    std::sort(list.begin(), list.end(), [](const Minor& x, const Minor& y) { return x.at < y.at; });
    for (std::size_t i = 0; i < list.size();) {
      std::size_t j = i;
      double sum = 0;
      while (j < list.size() && list[j].at - list[i].at <= tol) sum += list[j++].area;
      if (sum >= kConflictShareOfSurface * stats.areaM2) {
        conflictArea += sum;
        proposals[static_cast<std::size_t>(a)].push_back(list[i].at);
      }
      i = j;
    }
  }
  return proposals;
}

namespace {

// Where a piece's sub-block S is shown from: S itself, or an earlier sub-block that is S turned
// (placed with rotation `cube` at offsetM in S's frame it shows S, as turnBlock defines).
struct SharedSubBlock {
  BlockId target = 0;
  int cube = 0;
  glm::dvec3 offsetM{0.0};
};

// The four round corners of a building, or the quarters of a dome or drum, are one S turned:
// they share one block (one header) and their records carry the turn.
SharedSubBlock shareTurned(std::vector<Block>& subBlocks, Block s) {
  for (std::size_t j = 0; j < subBlocks.size(); ++j) {
    if (subBlocks[j].cells.size() != s.cells.size()) continue;
    for (int cube = 0; cube < format::kCubeRotationCount; ++cube)
      if (TurnedBlock turned = turnBlock(s, cube); turned.block == subBlocks[j])
        return {static_cast<BlockId>(j), cube, turned.offsetM};
  }
  subBlocks.push_back(std::move(s));
  return {static_cast<BlockId>(subBlocks.size() - 1), 0, glm::dvec3(0.0)};
}

// What the shares decide: each cell's material (of largest area among its shares; the hint where
// it has none, or for a box open to the outside exposedBoxMaterials' where it has none but on its
// underside), and per quadric piece shown by a sub-block, the area of each material per layer
// of its box (layer * materials + material; empty when its cells have no shares).
struct MaterialChoice {
  std::vector<std::uint16_t> cell;
  std::vector<std::vector<double>> pieceLayerArea;
};

// The distance along the ray from `from` in direction `dir` (a unit axis) to triangle abc, or
// infinity (Moller-Trumbore).
double rayDistance(const dvec3& from, const dvec3& dir, const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 e1 = b - a, e2 = c - a, q = glm::cross(dir, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-15) return INFINITY;
  const dvec3 s = from - a;
  const double u = glm::dot(s, q) / det;
  if (u < 0 || u > 1) return INFINITY;
  const dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(dir, r) / det;
  if (v < 0 || u + v > 1) return INFINITY;
  const double t = glm::dot(e2, r) / det;
  return t > 0 ? t : INFINITY;
}

// A box cell with no face on its sides but the underside, which only a view from below sees, takes
// its column's hint or the underside's material: under a wall a little off the axes (left to the
// mesh, in front of the box) that is the ground plate, whose colour then shows where the wall
// drifts behind the box's side (a Zurich house in the ground's grey over a third of a wall). Such
// a box open to the outside across another side (an empty neighbour, the grid's edge) takes
// instead the material of the nearest face beyond those sides, seen from its centre. Every face is
// tried for every such box, up to kMaxExposedTests pairs; beyond that the materials stay.
constexpr double kMaxExposedTests = 2e7;
constexpr int kUnderside = 2;  // 2 * axis + 0: the side facing -y

void exposedBoxMaterials(const Builder& b, const std::vector<std::uint8_t>& seenFace,
                         std::vector<std::uint16_t>& material) {
  std::vector<std::pair<std::size_t, std::vector<int>>> exposed;  // cell, open sides
  for (std::size_t id = 0; id < b.shape.size(); ++id) {
    if (b.shape[id] != 0 || seenFace[id] || b.subPiece[id] >= 0) continue;
    const std::array<int, 3> c = b.cellAt(id);
    std::vector<int> open;
    for (int side = 0; side < 6; ++side) {
      if (side == kUnderside) continue;
      std::array<int, 3> n = c;
      n[static_cast<std::size_t>(side / 2)] += side % 2 ? 1 : -1;
      const bool outside =
          n[static_cast<std::size_t>(side / 2)] < 0 || n[static_cast<std::size_t>(side / 2)] >= b.n[side / 2];
      if (outside || b.shape[b.index(n)] < 0) open.push_back(side);
    }
    if (!open.empty()) exposed.emplace_back(id, std::move(open));
  }
  if (static_cast<double>(exposed.size()) * static_cast<double>(b.mesh.triangles.size()) > kMaxExposedTests) return;
  for (const auto& [id, open] : exposed) {
    dvec3 lo, hi;
    b.cellBox(id, lo, hi);
    const dvec3 centre = 0.5 * (lo + hi);
    double nearest = INFINITY;
    for (int side : open) {
      dvec3 dir(0.0);
      dir[side / 2] = side % 2 ? 1.0 : -1.0;
      for (std::uint32_t f = 0; f < b.mesh.triangles.size(); ++f) {
        const double t = rayDistance(centre, dir, b.corner(f, 0), b.corner(f, 1), b.corner(f, 2));
        if (t < nearest) {
          nearest = t;
          material[id] = b.mesh.triangleMaterial[f];
        }
      }
    }
  }
}

MaterialChoice chooseMaterials(const Builder& b, const std::vector<Builder::Share>& shares) {
  MaterialChoice choice{b.hint, std::vector<std::vector<double>>(b.quadrics.size())};
  std::vector<double> materialArea(b.mesh.materials.size(), 0.0);
  for (std::size_t i = 0; i < shares.size();) {
    std::size_t j = i;
    std::fill(materialArea.begin(), materialArea.end(), 0.0);
    while (j < shares.size() && shares[j].cell == shares[i].cell) {
      materialArea[shares[j].material] += shares[j].area;
      ++j;
    }
    choice.cell[shares[i].cell] =
        static_cast<std::uint16_t>(std::max_element(materialArea.begin(), materialArea.end()) - materialArea.begin());
    if (const int piece = b.subPiece[shares[i].cell]; piece >= 0) {
      const QuadricPiece& q = b.quadrics[static_cast<std::size_t>(piece)];
      auto& area = choice.pieceLayerArea[static_cast<std::size_t>(piece)];
      area.resize(q.layers.size() * materialArea.size(), 0.0);
      const std::size_t k = q.layerOf(b.cellAt(shares[i].cell)[static_cast<std::size_t>(q.e)]);
      for (std::size_t m = 0; m < materialArea.size(); ++m) area[k * materialArea.size() + m] += materialArea[m];
    }
    i = j;
  }
  std::vector<std::uint8_t> seenFace(b.shape.size(), 0);
  for (const Builder::Share& share : shares) seenFace[share.cell] |= share.side != kUnderside;
  exposedBoxMaterials(b, seenFace, choice.cell);
  return choice;
}

// S of a quarter-round piece: one cell across, its box's layers along e, each layer in the
// material of largest area over its cells' shares (the piece's own without any). Layers all alike
// (the usual case) make S one cell tall: every cell of a column of the box then shows S from its
// bottom, so the column shares one record and its cells are equal (`uniform`).
Block subBlockOf(Builder& b, const QuadricPiece& q, const std::vector<double>& layerArea, bool& uniform) {
  const std::size_t materialCount = b.mesh.materials.size();
  std::vector<Cell> layers;
  for (std::size_t k = 0; k < q.layers.size(); ++k) {
    std::uint16_t material = q.material;
    if (!layerArea.empty()) {
      const auto first = layerArea.begin() + static_cast<std::ptrdiff_t>(k * materialCount);
      const auto best = std::max_element(first, first + static_cast<std::ptrdiff_t>(materialCount));
      if (*best > 0) material = static_cast<std::uint16_t>(best - first);
    }
    layers.push_back(Cell::solidCell(Solid{static_cast<std::uint8_t>(q.layers[k])}, material));
  }
  uniform = std::all_of(layers.begin(), layers.end(), [&](const Cell& c) { return c == layers.front(); });
  if (uniform) layers.resize(1);
  Block s;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto& B = b.bounds[a];
    const double base = B[static_cast<std::size_t>(q.lo[a])];
    const bool layered = static_cast<int>(a) == q.e && !uniform;
    for (int k = q.lo[a]; k <= q.hi[a]; ++k)
      if (layered || k == q.lo[a] || k == q.hi[a])
        s.boundsM[a].push_back(snapToUnits(B[static_cast<std::size_t>(k)] - base));
  }
  s.cells = layers;
  for (const Cell& c : layers)
    (q.planar     ? b.stats.pyramidCells
     : q.octant() ? b.stats.sphereOctantCells
                  : b.stats.quadricCells) += c.solid.index != 0;
  b.stats.solidCells += static_cast<long long>(layers.size());
  return s;
}

// Every cell of the piece's box redirects to S, offset by minus its place in S so that it shows
// its part of S (clipped by the cell), also where the arc does not pass: cells placing S at the
// same place merge when the boundaries between them go, and the block stage turns those left on
// one side of the arc into plain cells (blocks.cpp).
void redirectToSubBlock(const Builder& b, Block& block, const QuadricPiece& q, const SharedSubBlock& shown,
                        bool uniform) {
  const auto firstRecord = static_cast<std::ptrdiff_t>(block.redirections.size());
  std::array<int, 3> c{};
  for (c[2] = q.lo[2]; c[2] < q.hi[2]; ++c[2])
    for (c[1] = q.lo[1]; c[1] < q.hi[1]; ++c[1])
      for (c[0] = q.lo[0]; c[0] < q.hi[0]; ++c[0]) {
        glm::dvec3 offset(0.0);
        for (std::size_t a = 0; a < 3; ++a)
          if (static_cast<int>(a) != q.e || !uniform || q.octant())
            offset[static_cast<int>(a)] = -snapToUnits(b.bounds[a][static_cast<std::size_t>(c[a])] -
                                                       b.bounds[a][static_cast<std::size_t>(q.lo[a])]);
        const Redirection r{shown.target,
                            offset + shown.offsetM,
                            Rotation{static_cast<std::uint8_t>(shown.cube), 0},
                            {false, false, false}};
        const auto shared = std::find(block.redirections.begin() + firstRecord, block.redirections.end(), r);
        block.cells[b.index(c)] = Cell::redirect(static_cast<std::uint32_t>(shared - block.redirections.begin()));
        if (shared == block.redirections.end()) block.redirections.push_back(r);
      }
}

}  // namespace

// Each cell takes the material of largest area among its shares. A quarter-round piece shown by
// a sub-block becomes S: one cell across, its box's layers along e (a sphere octant or a corner
// slope: one cell, which its box's cells redirect to offset along e too), each layer taking the
// material of largest area over the shares of its box's cells in G0; those cells redirect to S,
// offset by minus their place in S so that each shows its part of S (clipped by the cell).
void Builder::assignMaterials(Block& block, std::vector<Block>& subBlocks, const std::vector<Share>& shares) {
  block.cells.assign(shape.size(), Cell::empty());
  const MaterialChoice choice = chooseMaterials(*this, shares);
  subBlocks.clear();
  for (std::size_t piece = 0; piece < quadrics.size(); ++piece) {
    const QuadricPiece& q = quadrics[piece];
    if (!q.represented || !q.subBlock) continue;
    bool uniform = false;
    Block s = subBlockOf(*this, q, choice.pieceLayerArea[piece], uniform);
    redirectToSubBlock(*this, block, q, shareTurned(subBlocks, std::move(s)), uniform);
  }
  for (std::size_t id = 0; id < shape.size(); ++id) {
    if (shape[id] < 0 || subPiece[id] >= 0) continue;
    block.cells[id] = Cell::solidCell(Solid{static_cast<std::uint8_t>(shape[id])}, choice.cell[id]);
    ++stats.solidCells;
    const SolidGroup group = solidGroup(Solid{static_cast<std::uint8_t>(shape[id])});
    stats.wedgeCells += group == SolidGroup::Wedge;
    stats.quadricCells += group == SolidGroup::QuarterCylinder || group == SolidGroup::InverseQuarterCylinder;
    stats.sphereOctantCells += group == SolidGroup::SphereOctant || group == SolidGroup::InverseSphereOctant;
    stats.pyramidCells += group == SolidGroup::Pyramid || group == SolidGroup::InversePyramid;
  }
}

}  // namespace nut::converter::solid
