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
  std::uint64_t key;   // lo << 32 | hi
  std::uint32_t face;
  bool forward;        // the face runs lo -> hi
};

std::vector<EdgeUse> edgeUses(const Welded& w) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * w.triangles.size());
  for (std::size_t f = 0; f < w.triangles.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = w.triangles[f][static_cast<std::size_t>(e)], b = w.triangles[f][static_cast<std::size_t>((e + 1) % 3)];
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
  std::partial_sort(faces.begin(), faces.begin() + static_cast<std::ptrdiff_t>(samples), faces.end(),
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
    const auto rest = [&](const dvec3& q) { return (*whole)(q) - exactWindingNumber(w.points, own, q); };
    const double distance = std::clamp(0.5 * std::sqrt(pieceArea[p]), kFarSampleMinM, kFarSampleMaxM);
    double behindLessFront = 0;
    forLargestFaces(w, pieces[p], [&](const dvec3& centroid, const dvec3& normal, double area) {
      behindLessFront += area * (rest(centroid - distance * normal) - rest(centroid + distance * normal));
    });
    facingIn[p] = behindLessFront < 0;
  }
  return facingIn;
}

}  // namespace

std::string MeshCheck::summary() const {
  std::string s = std::to_string(triangles) + " triangles, " + std::to_string(vertices) + " vertices, " +
                  std::to_string(components) + " pieces; " +
                  (closed() ? std::string("closed") : std::string("open: ") + std::to_string(boundaryEdges) +
                                                          " boundary edges, " + std::to_string(nonManifoldEdges) +
                                                          " edges shared by more than two faces" +
                                                          (closedSurface ? ", a closed surface once T-junctions are matched" : ""));
  if (degenerate) s += "; " + std::to_string(degenerate) + " degenerate faces removed";
  if (slivers) s += "; " + std::to_string(slivers) + " slivers";
  if (duplicateFaces) s += "; " + std::to_string(duplicateFaces) + " duplicate faces";
  if (inconsistentEdges) s += "; " + std::to_string(inconsistentEdges) + " edges with inconsistent orientation";
  if (flippedTriangles) s += "; " + std::to_string(flippedTriangles) + " faces turned outwards";
  return s;
}

MeshCheck checkAndRepair(Mesh& mesh) {
  MeshCheck check;
  check.triangles = mesh.triangles.size();
  Welded w = weld(mesh.positions, mesh.triangles);

  // Degenerate faces go (exact predicate); slivers and duplicates are counted.
  {
    std::vector<std::uint8_t> keep(w.triangles.size(), 1);
    std::vector<std::array<std::uint32_t, 3>> sorted;
    sorted.reserve(w.triangles.size());
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      const auto& t = w.triangles[f];
      const dvec3 &a = w.points[t[0]], &b = w.points[t[1]], &c = w.points[t[2]];
      if (CGAL::collinear(Point(a.x, a.y, a.z), Point(b.x, b.y, b.z), Point(c.x, c.y, c.z))) {
        keep[f] = 0;
        ++check.degenerate;
        continue;
      }
      const double twiceArea = glm::length(glm::cross(b - a, c - a));
      const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
      if (twiceArea / longest < kSliverAltitudeM) ++check.slivers;
      auto s = t;
      std::sort(s.begin(), s.end());
      sorted.push_back(s);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i) check.duplicateFaces += sorted[i] == sorted[i - 1];
    if (check.degenerate > 0) {
      std::size_t out = 0;
      for (std::size_t f = 0; f < keep.size(); ++f)
        if (keep[f]) {
          mesh.triangles[out] = mesh.triangles[f];
          mesh.triangleMaterial[out] = mesh.triangleMaterial[f];
          w.triangles[out] = w.triangles[f];
          ++out;
        }
      mesh.triangles.resize(out);
      mesh.triangleMaterial.resize(out);
      w.triangles.resize(out);
    }
  }
  {
    std::vector<std::uint8_t> used(w.points.size(), 0);
    for (const auto& t : w.triangles)
      for (std::uint32_t v : t) used[v] = 1;
    check.vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
  }

  // Edge statistics.
  std::vector<EdgeUse> uses = edgeUses(w);
  forEachEdge(uses, [&](std::size_t i, std::size_t j) {
    if (j - i == 1) ++check.boundaryEdges;
    else if (j - i > 2) ++check.nonManifoldEdges;
    else if (uses[i].forward == uses[i + 1].forward) ++check.inconsistentEdges;
  });

  // Consistent orientation: CGAL reverses polygons so that manifold neighbours agree (it
  // duplicates points where the surface cannot be made manifold, which we map back).
  std::vector<std::uint8_t> flipped(w.triangles.size(), 0);
  if (check.inconsistentEdges > 0) {
    std::vector<Point> points;
    points.reserve(w.points.size());
    for (const dvec3& p : w.points) points.emplace_back(p.x, p.y, p.z);
    std::vector<std::array<std::size_t, 3>> polygons;
    polygons.reserve(w.triangles.size());
    for (const auto& t : w.triangles) polygons.push_back({t[0], t[1], t[2]});
    CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
    std::unordered_map<dvec3, std::uint32_t, PositionHash> ids;
    for (std::size_t v = 0; v < w.points.size(); ++v) ids.emplace(w.points[v], static_cast<std::uint32_t>(v));
    const auto original = [&](std::size_t v) {
      if (v < w.points.size()) return static_cast<std::uint32_t>(v);
      const Point& p = points[v];
      return ids.at(dvec3(p.x(), p.y(), p.z()));
    };
    if (polygons.size() == w.triangles.size()) {
      for (std::size_t f = 0; f < polygons.size(); ++f) {
        const std::array<std::uint32_t, 3> turned{original(polygons[f][0]), original(polygons[f][1]), original(polygons[f][2])};
        if (compareCorners(w.triangles[f], turned) == Turn::Flipped) flipped[f] = 1;
      }
    }
  }
  const auto apply = [&](std::size_t f) {
    std::swap(w.triangles[f][1], w.triangles[f][2]);
    std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
  };
  for (std::size_t f = 0; f < flipped.size(); ++f)
    if (flipped[f]) apply(f);

  // Pieces through manifold edges whose two faces now agree; each turned outwards.
  UnionFind pieces(w.triangles.size());
  std::vector<std::uint8_t> open(w.triangles.size(), 0);
  // A face turned over runs each of its edges the other way; the edges and their order stay.
  for (EdgeUse& use : uses) use.forward = use.forward != (flipped[use.face] != 0);
  forEachEdge(uses, [&](std::size_t i, std::size_t j) {
    if (j - i == 2 && uses[i].forward != uses[i + 1].forward) {
      pieces.unite(uses[i].face, uses[i + 1].face);
    } else {
      for (std::size_t k = i; k < j; ++k) open[uses[k].face] = 1;
    }
  });
  struct Piece {
    double area = 0;
    dvec3 weightedCentre{0.0};
    double volume = 0;
    double turnedArea = 0;  // area of faces the consistency repair turned over
    bool open = false;
  };
  std::vector<std::uint32_t> root(w.triangles.size());
  std::unordered_map<std::uint32_t, std::size_t> pieceIndex;
  std::vector<Piece> info;
  const auto describePieces = [&] {
    pieceIndex.clear();
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      root[f] = pieces.find(static_cast<std::uint32_t>(f));
      pieceIndex.try_emplace(root[f], pieceIndex.size());
    }
    info.assign(pieceIndex.size(), Piece{});
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      const auto& t = w.triangles[f];
      const dvec3 &a = w.points[t[0]], &b = w.points[t[1]], &c = w.points[t[2]];
      const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
      Piece& p = info[pieceIndex[root[f]]];
      p.area += area;
      p.weightedCentre += area * (a + b + c) / 3.0;
      p.turnedArea += flipped[f] ? area : 0.0;
      p.open = p.open || open[f];
    }
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      Piece& p = info[pieceIndex[root[f]]];
      const dvec3 centre = p.weightedCentre / p.area;  // the volume of a closed piece does not depend on it
      const auto& t = w.triangles[f];
      p.volume += glm::dot(w.points[t[0]] - centre, glm::cross(w.points[t[1]] - centre, w.points[t[2]] - centre)) / 6.0;
    }
  };
  describePieces();
  check.components = info.size();
  // A closed piece faces outwards when its volume is positive. An open one has no inside to go
  // by (a roof tray between parapets has a negative volume and is right), so it keeps the
  // orientation most of its area came with, until the whole mesh says otherwise (below).
  std::vector<std::uint8_t> turnedOut(w.triangles.size(), 0);
  const auto turnOut = [&](std::size_t f) {
    apply(f);
    flipped[f] ^= 1;
    turnedOut[f] ^= 1;
  };
  for (std::size_t f = 0; f < w.triangles.size(); ++f) {
    const Piece& p = info[pieceIndex[root[f]]];
    if (p.open ? 2 * p.turnedArea > p.area : p.volume < 0) turnOut(f);
  }

  // Closed surface: what the repaired faces leave uncancelled on an edge cancels along its line.
  std::vector<std::size_t> firstUse;  // of each uncancelled edge, in `uses`
  const auto chainsOfUncancelled = [&] {
    std::vector<UncancelledEdge> uncancelled;
    firstUse.clear();
    forEachEdge(uses, [&](std::size_t i, std::size_t j) {
      int weight = 0;
      for (std::size_t k = i; k < j; ++k) weight += uses[k].forward != (turnedOut[uses[k].face] != 0) ? 1 : -1;
      if (weight == 0) return;
      uncancelled.push_back({static_cast<std::uint32_t>(uses[i].key >> 32), static_cast<std::uint32_t>(uses[i].key & 0xffffffffu), weight});
      firstUse.push_back(i);
    });
    return chainsAlongLines(w.points, uncancelled);
  };
  LineChains chains = chainsOfUncancelled();
  check.closedSurface = chains.cancel;

  // Open pieces meeting along a line agree where two of their edges alone cover a stretch of it
  // and run opposite ways (as two faces agree across a manifold edge). Where the mesh is not a
  // closed surface yet, the pieces are made to agree, the smaller area of each group turning (a
  // floor's quad turned over among the car park's T-junctions), and the groups are asked as one
  // below: a floor's piece asked alone may see through its slab.
  ParityUnionFind agree(info.size());
  if (!check.closedSurface) {
    const auto pieceOf = [&](std::size_t e) -> std::optional<std::size_t> {  // of the one face using edge e
      const std::size_t i = firstUse[e];
      if (i + 1 < uses.size() && uses[i + 1].key == uses[i].key) return std::nullopt;
      return pieceIndex[root[uses[i].face]];
    };
    for (const LineChains::Pair& pair : chains.alone) {
      const auto a = pieceOf(pair.a), b = pieceOf(pair.b);
      if (a && b && *a != *b) agree.unite(static_cast<std::uint32_t>(*a), static_cast<std::uint32_t>(*b), pair.sameWay);
    }
    std::vector<double> areaTurned(info.size(), 0), areaKept(info.size(), 0);  // per group's root
    for (std::uint32_t p = 0; p < info.size(); ++p) {
      const auto [group, turn] = agree.find(p);
      (turn ? areaTurned : areaKept)[group] += info[p].area;
    }
    bool turned = false;
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      const auto [group, turn] = agree.find(static_cast<std::uint32_t>(pieceIndex[root[f]]));
      const bool minority = turn ? areaTurned[group] <= areaKept[group] : areaKept[group] < areaTurned[group];
      if (minority) {
        turnOut(f);
        turned = true;
      }
    }
    if (turned) {
      chains = chainsOfUncancelled();
      check.closedSurface = chains.cancel;
    }
  }

  // Inside must be w >= 1/2 everywhere: the occupancy step keeps the sign, since outside an open
  // mesh seen through its missing side w reaches -1/2 (in front of a roof whose walls behind it
  // are missing). A closed surface agrees with itself along every line, so its volume says which
  // way its open pieces face (the closed ones were turned by their own volumes above, and since
  // each cancels on its own, the open ones together are a closed surface too); an open mesh is
  // asked piece by piece.
  if (check.closedSurface) {
    const dvec3 centre = w.points.empty() ? dvec3(0.0) : w.points.front();
    double volume = 0;
    for (std::size_t f = 0; f < w.triangles.size(); ++f) {
      if (!info[pieceIndex[root[f]]].open) continue;
      const auto& t = w.triangles[f];
      volume += glm::dot(w.points[t[0]] - centre, glm::cross(w.points[t[1]] - centre, w.points[t[2]] - centre));
    }
    if (volume < 0)
      for (std::size_t f = 0; f < w.triangles.size(); ++f)
        if (info[pieceIndex[root[f]]].open) turnOut(f);
  } else {
    // Each group of pieces that agree (above) is one piece from here on.
    std::vector<std::uint32_t> faceOfGroup(info.size(), kNoFace);
    for (std::uint32_t f = 0; f < w.triangles.size(); ++f) {
      std::uint32_t& first = faceOfGroup[agree.find(static_cast<std::uint32_t>(pieceIndex[root[f]])).first];
      if (first == kNoFace) first = f;
      pieces.unite(first, f);
    }
    describePieces();
    double totalArea = 0;
    for (const Piece& p : info) totalArea += p.area;
    // The faces of each piece that `ask` picks (empty for the others).
    const auto facesOfPieces = [&](auto ask) {
      std::vector<std::vector<std::uint32_t>> faces(info.size());
      for (std::size_t f = 0; f < w.triangles.size(); ++f)
        if (ask(info[pieceIndex[root[f]]])) faces[pieceIndex[root[f]]].push_back(static_cast<std::uint32_t>(f));
      return faces;
    };
    bool turned = false;
    const auto turnPieces = [&](const std::vector<std::uint8_t>& facingIn) {
      for (std::size_t f = 0; f < w.triangles.size(); ++f)
        if (facingIn[pieceIndex[root[f]]]) {
          turnOut(f);
          turned = true;
        }
    };
    turnPieces(piecesFacingIn(w, facesOfPieces([&](const Piece& p) { return p.open && p.area >= kSidePieceMinShare * totalArea; })));
    // Then the small pieces, by the rest of the mesh as the step above left it.
    std::vector<double> pieceArea;
    for (const Piece& p : info) pieceArea.push_back(p.area);
    turnPieces(smallPiecesFacingIn(w, facesOfPieces([&](const Piece& p) { return p.open && p.area < kFarPieceMaxShare * totalArea; }),
                                   pieceArea));
    if (turned) check.closedSurface = chainsOfUncancelled().cancel;  // pieces facing each other's way may now close it
  }
  check.flippedTriangles = static_cast<std::size_t>(std::count(flipped.begin(), flipped.end(), 1));
  return check;
}

}  // namespace nut::converter
