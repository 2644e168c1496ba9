// The exact path: rays traced through nut::Hierarchy in double precision by recursive interval
// subdivision; the ground truth for the float ray caster's accuracy tests.
//
// It is deliberately a different algorithm from the ray caster: no metadata arrays and no stepping
// from cell to cell. A block is handed the ray's parameter interval [ta, tb]. It lists every
// boundary plane the ray crosses inside that interval (per axis, and over every tile copy on
// wrapped axes), sorts the crossings, and treats each sub-interval between consecutive crossings
// as one cell, found by binary search at the sub-interval's midpoint. So a crossing that rounds a
// little early or late, or several crossings at one point (edges, corners), never selects a wrong
// cell. Solids are intersected over their sub-interval; redirections recurse with it, which clips
// the target by the cell. The ray parameter is the world distance throughout, because every change
// of frame (root origin, cell corner, offset, rotation) is a rigid motion.
#include <nut/exact_path.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <nut/camera.hpp>

namespace nut {
namespace {

// The plane through which the ray enters a sub-interval. A solid hit exactly at the start of its
// sub-interval lies on this plane, which may belong to an ancestor's cell (a clipped target), so
// its normal is taken from here rather than from the solid's own unit cube.
struct EntryPlane {
  int level = 0;                // of the block it belongs to on the recursion path (root = 0)
  glm::dvec3 worldNormal{0.0};  // facing the ray
};

// The ray in the frame of one block of the recursion.
struct BlockFrame {
  BlockId id = 0;
  glm::dvec3 origin{0.0};     // block-local
  glm::dvec3 direction{0.0};  // block-local, unit
  glm::dmat3 toWorld{1.0};    // block-local directions to world directions
  std::array<bool, 3> wrap{false, false, false};
};

// A boundary plane of the current block crossed at ray parameter t.
struct Crossing {
  double t;
  int axis;
};

// The cell containing coordinate x of an axis with boundaries `bounds` (x already in [0, D]):
// the last boundary <= x, clamped so that the far face belongs to the last cell.
int cellAt(const std::vector<double>& bounds, double x) {
  const auto above = std::upper_bound(bounds.begin(), bounds.end(), x);
  return std::clamp(static_cast<int>(above - bounds.begin()) - 1, 0, static_cast<int>(bounds.size()) - 2);
}

class ExactTracer {
 public:
  ExactTracer(const Hierarchy& h, const glm::dvec3& worldDirection, const ExactOptions& options)
      : h_(h), worldDirection_(worldDirection), options_(options) {}

  RayResult trace(const BlockFrame& root) {
    path_.push_back(&root);
    // Until the ray crosses a plane it is at its origin, inside the root: a hit there faces the ray.
    traceBlock(root, 0.0, std::numeric_limits<double>::infinity(), {0, -worldDirection_});
    return finish();
  }

 private:
  // Traces the ray over [ta, tb] through the block of `frame`, the last of path_, entering through
  // `entry`. Returns true when the ray ended there (an opaque hit or the cap).
  bool traceBlock(const BlockFrame& frame, double ta, double tb, EntryPlane entry) {
    const Block& block = h_.blocks[frame.id];
    const glm::dvec3& o = frame.origin;
    const glm::dvec3& d = frame.direction;

    // Clip by the block's box along the axes that do not wrap (the others extend without end).
    for (int a = 0; a < 3; ++a) {
      if (frame.wrap[a]) continue;
      const double size = block.boundsM[a].back();
      if (d[a] == 0) {
        if (o[a] < 0 || o[a] > size) return false;
        continue;
      }
      const double t0 = -o[a] / d[a], t1 = (size - o[a]) / d[a];
      const double tNear = std::min(t0, t1), tFar = std::max(t0, t1);
      if (tNear > ta) {
        ta = tNear;
        entry = facePlane(frame, a);
      }
      tb = std::min(tb, tFar);
    }
    if (!(ta < tb)) return false;

    std::vector<Crossing> crossings;
    for (int a = 0; a < 3; ++a)
      if (!addCrossings(block.boundsM[a], frame.wrap[a], a, o[a], d[a], ta, tb, crossings)) return true;
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
    crossings.push_back({tb, -1});

    double start = ta;
    for (const Crossing& c : crossings) {
      const double end = std::clamp(c.t, start, tb);
      if (end > start && visitCell(frame, block, start, end, entry)) return true;
      start = end;
      if (c.axis >= 0) entry = facePlane(frame, c.axis);
    }
    return false;
  }

  // The result once the ray has ended: the background behind what was composited on a miss.
  RayResult finish() {
    RayResult r = result_;
    if (r.capped) {
      r.hit = false;
      r.colour = kCappedColour;
      return r;
    }
    if (!r.hit) addLayer(kBackground, 1.0);
    for (int i = 0; i < 3; ++i)
      r.colour[static_cast<std::size_t>(i)] =
          static_cast<std::uint8_t>(std::lround(std::clamp(colour_[i], 0.0, 255.0)));
    return r;
  }

  // The plane of axis a of the frame's block, with its normal facing the ray.
  EntryPlane facePlane(const BlockFrame& frame, int axis) const {
    glm::dvec3 n(0.0);
    n[axis] = frame.direction[axis] > 0 ? -1.0 : 1.0;
    return {depth(), frame.toWorld * n};
  }

  int depth() const { return static_cast<int>(path_.size()) - 1; }

  // Appends the parameters where the segment [ta, tb] crosses the interior boundaries of one axis
  // (on a wrapped axis: every boundary of every tile copy, tile seams included). Returns false
  // when that would exceed the cell budget.
  bool addCrossings(const std::vector<double>& bounds, bool wrap, int axis, double o, double d,
                    double ta, double tb, std::vector<Crossing>& out) {
    if (d == 0) return true;
    const double xa = o + ta * d, xb = o + tb * d;
    const double lo = std::min(xa, xb), hi = std::max(xa, xb);
    const auto add = [&](double x) {
      if (x > lo && x < hi) out.push_back({(x - o) / d, axis});
    };
    const long long cells = static_cast<long long>(bounds.size()) - 1;
    if (!wrap) {
      // Interior boundaries only: the faces are the ends of [ta, tb] after clipping.
      const auto last = bounds.end() - 1;
      for (auto it = std::upper_bound(bounds.begin() + 1, last, lo); it < last && *it < hi; ++it) add(*it);
      return true;
    }
    const double period = bounds.back();
    const double firstTile = std::floor(lo / period), lastTile = std::floor(hi / period);
    if ((lastTile - firstTile + 1) * static_cast<double>(cells) + static_cast<double>(cellsVisited_) >
        static_cast<double>(kExactMaxCells)) {
      result_.capped = true;
      return false;
    }
    for (double tile = firstTile; tile <= lastTile; ++tile)
      for (long long k = 0; k < cells; ++k) add(tile * period + bounds[static_cast<std::size_t>(k)]);
    return true;
  }

  // Where the ray meets a cell's content within [s, e], and the content's own unit normal in the
  // block's frame there (none where that is the face the ray entered the cell by).
  struct CellHit {
    double t;
    std::optional<glm::dvec3> normal;
    std::optional<std::uint16_t> material;  // a plane's surface material, when not the cell's
  };

  std::optional<CellHit> solidHit(Solid solid, const BlockFrame& frame, const glm::dvec3& cellMin,
                                  const glm::dvec3& cellSize, double s, double e) const {
    // The solid lives in the cell's unit cube; scaling the direction keeps t the world distance.
    const glm::dvec3 unitOrigin = (frame.origin - cellMin) / cellSize;
    const glm::dvec3 unitDirection = frame.direction / cellSize;
    const auto hit = intersectSolid<double>(solid, unitOrigin, unitDirection, s, e);
    if (!hit) return std::nullopt;
    if (options_.minThicknessM > 0) {
      // The last point inside the solid: the first hit of the reversed ray from the cell exit.
      const auto last =
          intersectSolid<double>(solid, unitOrigin + e * unitDirection, -unitDirection, 0.0, e - hit->t);
      if (last && e - last->t - hit->t < options_.minThicknessM) return std::nullopt;
    }
    if (hit->t == s) return CellHit{hit->t, std::nullopt};
    return CellHit{hit->t, glm::normalize(hit->normal / cellSize)};
  }

  // The planes are in the frame of the block's tile 0; the ray is moved into the cell's tile.
  std::optional<CellHit> planeHit(const PlaneCut& cut, const BlockFrame& frame, const glm::dvec3& tileStart,
                                  double s, double e) const {
    const auto span = intersectPlaneCut(cut, frame.origin - tileStart, frame.direction, s, e);
    if (!span || (options_.minThicknessM > 0 && span->tOut - span->tIn < options_.minThicknessM)) return std::nullopt;
    if (span->plane < 0) return CellHit{span->tIn, std::nullopt};
    const auto p = static_cast<std::size_t>(span->plane);
    return CellHit{span->tIn, cut.planes[p].normal, cut.surfaceMaterials[p]};
  }

  // One cell: the sub-interval [s, e] of the ray, all inside one cell of the frame's block.
  bool visitCell(const BlockFrame& frame, const Block& block, double s, double e, const EntryPlane& entry) {
    if (++cellsVisited_ > kExactMaxCells) {
      result_.capped = true;
      return true;
    }
    ++result_.iterations;
    const glm::dvec3 mid = frame.origin + (0.5 * (s + e)) * frame.direction;
    glm::ivec3 index(0);
    glm::dvec3 tileStart(0.0), cellMin(0.0), cellSize(1.0);
    for (int a = 0; a < 3; ++a) {
      const auto& bounds = block.boundsM[a];
      // On a wrapped axis the midpoint is reduced into tile 0 and the cell is placed back in its tile.
      tileStart[a] = frame.wrap[a] ? std::floor(mid[a] / bounds.back()) * bounds.back() : 0.0;
      index[a] = cellAt(bounds, mid[a] - tileStart[a]);
      const auto i = static_cast<std::size_t>(index[a]);
      cellMin[a] = tileStart[a] + bounds[i];
      cellSize[a] = bounds[i + 1] - bounds[i];
    }
    const Cell& cell = block.cell(index.x, index.y, index.z);

    if (cell.kind == CellKind::Solid || cell.kind == CellKind::Plane) {
      const std::optional<CellHit> hit = cell.kind == CellKind::Solid
                                             ? solidHit(cell.solid, frame, cellMin, cellSize, s, e)
                                             : planeHit(block.cuts[cell.cut], frame, tileStart, s, e);
      if (!hit) return false;
      EntryPlane surface = entry;
      if (hit->normal) {
        glm::dvec3 n = *hit->normal;
        if (glm::dot(n, frame.direction) > 0) n = -n;
        surface = {depth(), frame.toWorld * n};
      }
      const Material& m = h_.materials[hit->material.value_or(cell.material)];
      const auto shaded = shade({m.r, m.g, m.b}, surface.worldNormal, worldDirection_);
      if (m.opacity < 255) {
        addLayer(shaded, m.opacity / 255.0);
        return false;
      }
      addLayer(shaded, 1.0);
      result_.hit = true;
      result_.distanceM = hit->t;
      result_.normal = surface.worldNormal;
      if (options_.surface) {
        options_.surface->path.clear();
        for (int level = 0; level <= surface.level; ++level) {
          const BlockFrame& f = *path_[static_cast<std::size_t>(level)];
          options_.surface->path.push_back({f.id, glm::transpose(f.toWorld) * surface.worldNormal});
        }
      }
      return true;
    }

    if (cell.kind == CellKind::Redirection) {
      if (depth() + 1 > options_.maxDepth) {
        result_.capped = true;
        return true;
      }
      const Redirection& r = block.redirections[cell.redirection];
      const glm::dmat3 rotation = rotationMatrix(r.rotation);
      // Target-local point = R^-1 (p - cell corner - offset); R is orthonormal, so R^-1 = R^T.
      const glm::dmat3 inverse = glm::transpose(rotation);
      BlockFrame child;
      child.id = r.target;
      child.origin = inverse * (frame.origin - cellMin - r.offsetM);
      child.direction = inverse * frame.direction;
      child.toWorld = frame.toWorld * rotation;
      child.wrap = r.wrap;
      path_.push_back(&child);
      const bool ended = traceBlock(child, s, e, entry);
      path_.pop_back();
      return ended;
    }
    return false;  // empty
  }

  // Front-to-back compositing (docs/RENDERING.md): add transmittance * alpha * colour, then let
  // 1 - alpha of the light through.
  void addLayer(const std::array<std::uint8_t, 3>& colour, double alpha) {
    for (int i = 0; i < 3; ++i) colour_[i] += transmittance_ * alpha * colour[static_cast<std::size_t>(i)];
    transmittance_ *= 1.0 - alpha;
  }

  const Hierarchy& h_;
  glm::dvec3 worldDirection_;
  ExactOptions options_;
  RayResult result_;
  glm::dvec3 colour_{0.0};
  double transmittance_ = 1.0;
  long long cellsVisited_ = 0;
  std::vector<const BlockFrame*> path_;  // the frames from the root down to the one being traced
};

}  // namespace

RayResult traceExact(const Hierarchy& h, const glm::dvec3& originM, const glm::dvec3& rayOrigin,
                     const glm::dvec3& unitDirection, const ExactOptions& options) {
  BlockFrame root;
  root.id = h.root;
  // Subtract the root origin first: world coordinates may be near 1e6 m, the building is small.
  root.origin = rayOrigin - originM;
  root.direction = unitDirection;
  return ExactTracer(h, unitDirection, options).trace(root);
}

}  // namespace nut
