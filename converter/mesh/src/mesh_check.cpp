// Mesh checks and orientation repair. This is one of the two translation units that include CGAL
// (its headers cost about 25 s and 2 GB to compile, docs/CONVERTER.md).
#include <converter/mesh_check.hpp>
#include <converter/winding.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <glm/geometric.hpp>

#include "closed_surface.hpp"
#include "union_find.hpp"
#include "weld.hpp"

namespace nut::converter {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using glm::dvec3;

// Altitude below which a triangle counts as a sliver (it keeps its area, but its normal is noisy).
constexpr double kSliverAltitudeM = 1e-4;
// An open piece's side is judged by the winding number this far in front of and behind its
// largest faces (a share of the face's size, at most 1 cm), at most this many faces per piece,
// for pieces holding at least this share of the mesh's area.
constexpr double kSideSampleShare = 0.01, kSideSampleMaxM = 0.01;
constexpr std::size_t kSideSamplesPerPiece = 16;
constexpr double kSidePieceMinShare = 0.001;
// Smaller open pieces (a window pane: about 0.1 % of a house's surface) are judged by the rest of
// the mesh farther out on either side, if they hold at most this share of the area.
constexpr double kFarPieceMaxShare = 0.01;
constexpr double kFarSampleMinM = 0.05, kFarSampleMaxM = 1.0;
constexpr std::uint32_t kNoFace = 0xffffffffu;

// Whether b is a cyclic rotation of a (same orientation) or of a reversed (flipped).
enum class Turn { Same, Flipped, Other };
Turn compareCorners(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
  for (int r = 0; r < 3; ++r) {
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return Turn::Same;
    if (a[0] == b[r] && a[1] == b[(r + 2) % 3] && a[2] == b[(r + 1) % 3]) return Turn::Flipped;
  }
  return Turn::Other;
}

// Per undirected edge of the welded mesh: the faces using it and the way they run it.
struct EdgeUse {
  std::uint64_t key;  // lo << 32 | hi
  std::uint32_t face;
  bool forward;  // the face runs lo -> hi
};

std::vector<EdgeUse> edgeUses(const Welded& w) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * w.triangles.size());
  for (std::size_t f = 0; f < w.triangles.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = w.triangles[f][static_cast<std::size_t>(e)],
                          b = w.triangles[f][static_cast<std::size_t>((e + 1) % 3)];
      const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
      uses.push_back({static_cast<std::uint64_t>(lo) << 32 | hi, static_cast<std::uint32_t>(f), a == lo});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });
  return uses;
}

// Calls f(first, last) for each run of uses of one edge.
template <typename F>
void forEachEdge(const std::vector<EdgeUse>& uses, F&& f) {
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    f(i, j);
    i = j;
  }
}

// Calls sample(centroid, unit normal, area) for a piece's largest faces (kSideSamplesPerPiece at
// most); `faces` is reordered.
template <typename Sample>
void forLargestFaces(const Welded& w, std::vector<std::uint32_t>& faces, Sample&& sample) {
  const auto areaVector = [&](std::uint32_t f) {
    const auto& t = w.triangles[f];
    return 0.5 * glm::cross(w.points[t[1]] - w.points[t[0]], w.points[t[2]] - w.points[t[0]]);
  };
  const std::size_t samples = std::min(faces.size(), kSideSamplesPerPiece);
  std::partial_sort(
      faces.begin(), faces.begin() + static_cast<std::ptrdiff_t>(samples), faces.end(),
      [&](std::uint32_t a, std::uint32_t b) { return glm::length(areaVector(a)) > glm::length(areaVector(b)); });
  for (std::size_t i = 0; i < samples; ++i) {
    const auto& t = w.triangles[faces[i]];
    const dvec3 av = areaVector(faces[i]);
    const double area = glm::length(av);
    sample((w.points[t[0]] + w.points[t[1]] + w.points[t[2]]) / 3.0, av / area, area);
  }
}

// Which open pieces face into the solid the rest of the mesh encloses. The winding number just
// in front of a face and just behind it is about (0, 1) where the face looks out of the solid and
// about (-1, 0) where it looks in (a piece turned inwards, or the whole mesh: walls and a roof
// without a floor, all facing in); a piece whose samples sum below zero faces in. `openPieces`
// holds the faces of each piece to ask (empty for the others).
std::vector<std::uint8_t> piecesFacingIn(const Welded& w, std::vector<std::vector<std::uint32_t>> openPieces) {
  std::vector<std::uint8_t> facingIn(openPieces.size(), 0);
  std::optional<WindingNumber> winding;  // built only if some piece is asked
  for (std::size_t p = 0; p < openPieces.size(); ++p) {
    if (openPieces[p].empty()) continue;
    if (!winding) winding.emplace(w.points, w.triangles);
    double sum = 0;
    forLargestFaces(w, openPieces[p], [&](const dvec3& centroid, const dvec3& normal, double area) {
      const dvec3 offset = std::min(kSideSampleShare * std::sqrt(area), kSideSampleMaxM) * normal;
      sum += area * ((*winding)(centroid + offset) + (*winding)(centroid - offset));
    });
    facingIn[p] = sum < 0;
  }
  return facingIn;
}

// Which small open pieces face into the solid. Near a piece that fills a hole in the rest of the
// mesh (a pane in a window opening) the rest's winding number is about 1/2 on both sides, and the
// piece adds the same jump turned either way, so piecesFacingIn cannot tell; farther out the rest
// tells which side is outside air and which the building. A piece faces out when the rest is
// lower in front of its largest faces than behind them, half the piece's size out (at least
// 5 cm, at most 1 m). `pieces` holds the faces of each piece to ask (empty for the others).
std::vector<std::uint8_t> smallPiecesFacingIn(const Welded& w, std::vector<std::vector<std::uint32_t>> pieces,
                                              const std::vector<double>& pieceArea) {
  std::vector<std::uint8_t> facingIn(pieces.size(), 0);
  std::optional<WindingNumber> whole;  // built only if some piece is asked
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].empty()) continue;
    if (!whole) whole.emplace(w.points, w.triangles);
    std::vector<std::array<std::uint32_t, 3>> own;
    for (std::uint32_t f : pieces[p]) own.push_back(w.triangles[f]);
    const auto rest = [&](const dvec3& q) {
      const double all = (*whole)(q);
      return all - exactWindingNumber(w.points, own, q);
    };
    const double distance = std::clamp(0.5 * std::sqrt(pieceArea[p]), kFarSampleMinM, kFarSampleMaxM);
    double behindLessFront = 0;
    forLargestFaces(w, pieces[p], [&](const dvec3& centroid, const dvec3& normal, double area) {
      behindLessFront += area * (rest(centroid - distance * normal) - rest(centroid + distance * normal));
    });
    facingIn[p] = behindLessFront < 0;
  }
  return facingIn;
}

// One check and repair: the welded mesh, the uses of its edges, which faces are turned and why,
// and its pieces. The steps run in the order of checkAndRepair's comment.
class Repair {
 public:
  Repair(TriangleMesh& mesh, MeshCheck& check) : mesh_(mesh), check_(check), w_(weld(mesh.positions, mesh.triangles)) {}

  void run() {
    removeDegenerateFaces();
    countVertices();
    countEdges();
    orientConsistently();
    findPieces();
    describePieces();
    check_.components = info_.size();
    turnPiecesOut();
    LineChains chains = chainsOfUncancelled();
    check_.closedSurface = chains.cancel;
    ParityUnionFind agree(info_.size());
    if (!check_.closedSurface) agreeAlongLines(chains, agree);
    // Inside must be w >= 1/2 everywhere: the occupancy step keeps the sign, since outside an
    // open mesh seen through its missing side w reaches -1/2 (in front of a roof whose walls
    // behind it are missing).
    if (check_.closedSurface)
      turnOpenPiecesByVolume();
    else
      turnOpenPiecesByWinding(agree);
    check_.flippedTriangles = static_cast<std::size_t>(std::count(flipped_.begin(), flipped_.end(), 1));
  }

 private:
  struct Piece {
    double area = 0;
    dvec3 weightedCentre{0.0};
    double volume = 0;
    double turnedArea = 0;  // area of faces the consistency repair turned over
    bool open = false;
  };

  std::size_t faceCount() const { return w_.triangles.size(); }
  Piece& pieceOf(std::size_t f) { return info_[pieceIndex_[root_[f]]]; }
  std::size_t pieceIndexOf(std::size_t f) { return pieceIndex_[root_[f]]; }

  // Degenerate faces go (exact predicate); slivers and duplicates are counted.
  void removeDegenerateFaces() {
    std::vector<std::uint8_t> keep(faceCount(), 1);
    std::vector<std::array<std::uint32_t, 3>> sorted;
    sorted.reserve(faceCount());
    for (std::size_t f = 0; f < faceCount(); ++f) {
      const auto& t = w_.triangles[f];
      const dvec3 &a = w_.points[t[0]], &b = w_.points[t[1]], &c = w_.points[t[2]];
      if (CGAL::collinear(Point(a.x, a.y, a.z), Point(b.x, b.y, b.z), Point(c.x, c.y, c.z))) {
        keep[f] = 0;
        ++check_.degenerate;
        continue;
      }
      const double twiceArea = glm::length(glm::cross(b - a, c - a));
      const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
      if (twiceArea / longest < kSliverAltitudeM) ++check_.slivers;
      auto s = t;
      std::sort(s.begin(), s.end());
      sorted.push_back(s);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i) check_.duplicateFaces += sorted[i] == sorted[i - 1];
    if (check_.degenerate == 0) return;
    std::size_t out = 0;
    for (std::size_t f = 0; f < keep.size(); ++f)
      if (keep[f]) {
        mesh_.triangles[out] = mesh_.triangles[f];
        mesh_.triangleMaterial[out] = mesh_.triangleMaterial[f];
        w_.triangles[out] = w_.triangles[f];
        ++out;
      }
    mesh_.triangles.resize(out);
    mesh_.triangleMaterial.resize(out);
    w_.triangles.resize(out);
  }

  void countVertices() {
    std::vector<std::uint8_t> used(w_.points.size(), 0);
    for (const auto& t : w_.triangles)
      for (std::uint32_t v : t) used[v] = 1;
    check_.vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
  }

  void countEdges() {
    uses_ = edgeUses(w_);
    forEachEdge(uses_, [&](std::size_t i, std::size_t j) {
      if (j - i == 1)
        ++check_.boundaryEdges;
      else if (j - i > 2)
        ++check_.nonManifoldEdges;
      else if (uses_[i].forward == uses_[i + 1].forward)
        ++check_.inconsistentEdges;
    });
  }

  void turn(std::size_t f) {
    std::swap(w_.triangles[f][1], w_.triangles[f][2]);
    std::swap(mesh_.triangles[f][1], mesh_.triangles[f][2]);
  }
  void turnOut(std::size_t f) {
    turn(f);
    flipped_[f] ^= 1;
    turnedOut_[f] ^= 1;
  }

  // CGAL reverses polygons so that manifold neighbours agree (it duplicates points where the
  // surface cannot be made manifold, which are mapped back here).
  void orientConsistently() {
    flipped_.assign(faceCount(), 0);
    if (check_.inconsistentEdges == 0) return;
    std::vector<Point> points;
    points.reserve(w_.points.size());
    for (const dvec3& p : w_.points) points.emplace_back(p.x, p.y, p.z);
    std::vector<std::array<std::size_t, 3>> polygons;
    polygons.reserve(faceCount());
    for (const auto& t : w_.triangles) polygons.push_back({t[0], t[1], t[2]});
    CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
    if (polygons.size() != faceCount()) return;
    std::unordered_map<dvec3, std::uint32_t, PositionHash> ids;
    for (std::size_t v = 0; v < w_.points.size(); ++v) ids.emplace(w_.points[v], static_cast<std::uint32_t>(v));
    const auto original = [&](std::size_t v) {
      if (v < w_.points.size()) return static_cast<std::uint32_t>(v);
      const Point& p = points[v];
      return ids.at(dvec3(p.x(), p.y(), p.z()));
    };
    for (std::size_t f = 0; f < polygons.size(); ++f) {
      const std::array<std::uint32_t, 3> turned{original(polygons[f][0]), original(polygons[f][1]),
                                                original(polygons[f][2])};
      if (compareCorners(w_.triangles[f], turned) == Turn::Flipped) {
        flipped_[f] = 1;
        turn(f);
      }
    }
  }

  // Pieces through manifold edges whose two faces now agree; faces on other edges are open.
  void findPieces() {
    pieces_.emplace(faceCount());
    open_.assign(faceCount(), 0);
    // A face turned over runs each of its edges the other way; the edges and their order stay.
    for (EdgeUse& use : uses_) use.forward = use.forward != (flipped_[use.face] != 0);
    forEachEdge(uses_, [&](std::size_t i, std::size_t j) {
      if (j - i == 2 && uses_[i].forward != uses_[i + 1].forward) {
        pieces_->unite(uses_[i].face, uses_[i + 1].face);
      } else {
        for (std::size_t k = i; k < j; ++k) open_[uses_[k].face] = 1;
      }
    });
  }

  void describePieces() {
    root_.resize(faceCount());
    pieceIndex_.clear();
    for (std::size_t f = 0; f < faceCount(); ++f) {
      root_[f] = pieces_->find(static_cast<std::uint32_t>(f));
      pieceIndex_.try_emplace(root_[f], pieceIndex_.size());
    }
    info_.assign(pieceIndex_.size(), Piece{});
    for (std::size_t f = 0; f < faceCount(); ++f) {
      const auto& t = w_.triangles[f];
      const dvec3 &a = w_.points[t[0]], &b = w_.points[t[1]], &c = w_.points[t[2]];
      const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
      Piece& p = pieceOf(f);
      p.area += area;
      p.weightedCentre += area * (a + b + c) / 3.0;
      p.turnedArea += flipped_[f] ? area : 0.0;
      p.open = p.open || open_[f];
    }
    for (std::size_t f = 0; f < faceCount(); ++f) {
      Piece& p = pieceOf(f);
      const dvec3 centre = p.weightedCentre / p.area;  // the volume of a closed piece does not depend on it
      const auto& t = w_.triangles[f];
      p.volume +=
          glm::dot(w_.points[t[0]] - centre, glm::cross(w_.points[t[1]] - centre, w_.points[t[2]] - centre)) / 6.0;
    }
  }

  // A closed piece faces outwards when its volume is positive. An open one has no inside to go
  // by (a roof tray between parapets has a negative volume and is right), so it keeps the
  // orientation most of its area came with, until the whole mesh says otherwise (below).
  void turnPiecesOut() {
    turnedOut_.assign(faceCount(), 0);
    for (std::size_t f = 0; f < faceCount(); ++f) {
      const Piece& p = pieceOf(f);
      if (p.open ? 2 * p.turnedArea > p.area : p.volume < 0) turnOut(f);
    }
  }

  // Closed surface: what the repaired faces leave uncancelled on an edge cancels along its line.
  LineChains chainsOfUncancelled() {
    std::vector<UncancelledEdge> uncancelled;
    firstUse_.clear();
    forEachEdge(uses_, [&](std::size_t i, std::size_t j) {
      int weight = 0;
      for (std::size_t k = i; k < j; ++k) weight += uses_[k].forward != (turnedOut_[uses_[k].face] != 0) ? 1 : -1;
      if (weight == 0) return;
      uncancelled.push_back({static_cast<std::uint32_t>(uses_[i].key >> 32),
                             static_cast<std::uint32_t>(uses_[i].key & 0xffffffffu), weight});
      firstUse_.push_back(i);
    });
    return chainsAlongLines(w_.points, uncancelled);
  }

  // Open pieces meeting along a line agree where two of their edges alone cover a stretch of it
  // and run opposite ways (as two faces agree across a manifold edge). Where the mesh is not a
  // closed surface yet, the pieces are made to agree, the smaller area of each group turning (a
  // floor's quad turned over among the car park's T-junctions), and the groups are asked as one
  // later: a floor's piece asked alone may see through its slab.
  void agreeAlongLines(const LineChains& chains, ParityUnionFind& agree) {
    const auto pieceOfEdge = [&](std::size_t e) -> std::optional<std::size_t> {  // of the one face using edge e
      const std::size_t i = firstUse_[e];
      if (i + 1 < uses_.size() && uses_[i + 1].key == uses_[i].key) return std::nullopt;
      return pieceIndexOf(uses_[i].face);
    };
    for (const LineChains::Pair& pair : chains.alone) {
      const auto a = pieceOfEdge(pair.a), b = pieceOfEdge(pair.b);
      if (a && b && *a != *b) agree.unite(static_cast<std::uint32_t>(*a), static_cast<std::uint32_t>(*b), pair.sameWay);
    }
    std::vector<double> areaTurned(info_.size(), 0), areaKept(info_.size(), 0);  // per group's root
    for (std::uint32_t p = 0; p < info_.size(); ++p) {
      const auto [group, turn] = agree.find(p);
      (turn ? areaTurned : areaKept)[group] += info_[p].area;
    }
    bool turned = false;
    for (std::size_t f = 0; f < faceCount(); ++f) {
      const auto [group, turn] = agree.find(static_cast<std::uint32_t>(pieceIndexOf(f)));
      const bool minority = turn ? areaTurned[group] <= areaKept[group] : areaKept[group] < areaTurned[group];
      if (minority) {
        turnOut(f);
        turned = true;
      }
    }
    if (turned) check_.closedSurface = chainsOfUncancelled().cancel;
  }

  // A closed surface agrees with itself along every line, so its volume says which way its open
  // pieces face (the closed ones were turned by their own volumes, and since each cancels on its
  // own, the open ones together are a closed surface too).
  void turnOpenPiecesByVolume() {
    const dvec3 centre = w_.points.empty() ? dvec3(0.0) : w_.points.front();
    double volume = 0;
    for (std::size_t f = 0; f < faceCount(); ++f) {
      if (!pieceOf(f).open) continue;
      const auto& t = w_.triangles[f];
      volume += glm::dot(w_.points[t[0]] - centre, glm::cross(w_.points[t[1]] - centre, w_.points[t[2]] - centre));
    }
    if (volume < 0)
      for (std::size_t f = 0; f < faceCount(); ++f)
        if (pieceOf(f).open) turnOut(f);
  }

  // An open mesh is asked piece by piece, each group of pieces that agree along lines as one:
  // first the pieces large enough to be judged just in front of and behind their faces, then the
  // small ones by the rest of the mesh as that step left it.
  void turnOpenPiecesByWinding(ParityUnionFind& agree) {
    std::vector<std::uint32_t> faceOfGroup(info_.size(), kNoFace);
    for (std::uint32_t f = 0; f < faceCount(); ++f) {
      std::uint32_t& first = faceOfGroup[agree.find(static_cast<std::uint32_t>(pieceIndexOf(f))).first];
      if (first == kNoFace) first = f;
      pieces_->unite(first, f);
    }
    describePieces();
    double totalArea = 0;
    for (const Piece& p : info_) totalArea += p.area;
    // The faces of each piece that `ask` picks (empty for the others).
    const auto facesOfPieces = [&](auto ask) {
      std::vector<std::vector<std::uint32_t>> faces(info_.size());
      for (std::size_t f = 0; f < faceCount(); ++f)
        if (ask(pieceOf(f))) faces[pieceIndexOf(f)].push_back(static_cast<std::uint32_t>(f));
      return faces;
    };
    bool turned = false;
    const auto turnPieces = [&](const std::vector<std::uint8_t>& facingIn) {
      for (std::size_t f = 0; f < faceCount(); ++f)
        if (facingIn[pieceIndexOf(f)]) {
          turnOut(f);
          turned = true;
        }
    };
    turnPieces(piecesFacingIn(
        w_, facesOfPieces([&](const Piece& p) { return p.open && p.area >= kSidePieceMinShare * totalArea; })));
    std::vector<double> pieceArea;
    for (const Piece& p : info_) pieceArea.push_back(p.area);
    turnPieces(smallPiecesFacingIn(
        w_, facesOfPieces([&](const Piece& p) { return p.open && p.area < kFarPieceMaxShare * totalArea; }),
        pieceArea));
    if (turned) check_.closedSurface = chainsOfUncancelled().cancel;  // pieces facing each other's way may now close it
  }

  TriangleMesh& mesh_;
  MeshCheck& check_;
  Welded w_;
  std::vector<EdgeUse> uses_;
  std::vector<std::uint8_t> flipped_;    // turned by any step
  std::vector<std::uint8_t> turnedOut_;  // turned after the consistency repair
  std::optional<UnionFind> pieces_;      // of faces
  std::vector<std::uint8_t> open_;       // the face has an edge that is not manifold and agreeing
  std::vector<std::uint32_t> root_;      // each face's piece root
  std::unordered_map<std::uint32_t, std::size_t> pieceIndex_;
  std::vector<Piece> info_;            // per piece
  std::vector<std::size_t> firstUse_;  // of each uncancelled edge, in uses_
};

}  // namespace

std::string MeshCheck::summary() const {
  std::string s = std::to_string(triangles) + " triangles, " + std::to_string(vertices) + " vertices, " +
                  std::to_string(components) + " pieces; " +
                  (closed() ? std::string("closed")
                            : std::string("open: ") + std::to_string(boundaryEdges) + " boundary edges, " +
                                  std::to_string(nonManifoldEdges) + " edges shared by more than two faces" +
                                  (closedSurface ? ", a closed surface once T-junctions are matched" : ""));
  if (degenerate) s += "; " + std::to_string(degenerate) + " degenerate faces removed";
  if (slivers) s += "; " + std::to_string(slivers) + " slivers";
  if (duplicateFaces) s += "; " + std::to_string(duplicateFaces) + " duplicate faces";
  if (inconsistentEdges) s += "; " + std::to_string(inconsistentEdges) + " edges with inconsistent orientation";
  if (flippedTriangles) s += "; " + std::to_string(flippedTriangles) + " faces turned outwards";
  return s;
}

MeshCheck checkAndRepair(TriangleMesh& mesh) {
  MeshCheck check;
  check.triangles = mesh.triangles.size();
  Repair(mesh, check).run();
  return check;
}

}  // namespace nut::converter
