// ray_walk.hpp (internal to the core) — one ray's walk through an HNI, shared by the one-ray
// caster (raycast.cpp) and the packet caster (raycast_packet.cpp): the stack level, the landing
// and the step, and HniRayCaster::Walk, which the packet caster also resumes from a state it
// built, when a ray meets something its lanes do not draw.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <nut/heat_map.hpp>
#include <nut/hierarchy.hpp>
#include <nut/raycast.hpp>
#include <nut/render_loop.hpp>
#include <nut/solids.hpp>
#include <nut/units.hpp>

namespace nut {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Three floats or ints indexed by a run-time axis: glm's operator[] is a switch, which the
// traversal would pay at every step.
using Float3 = std::array<float, 3>;
using Int3 = std::array<int, 3>;

inline glm::vec3 toVec(const Float3& v) { return {v[0], v[1], v[2]}; }
inline Float3 toArray(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Members are set by land() before use: no initialisers, so that the per-ray stack costs nothing
// to create.
struct Level {
  int block;
  Float3 o, d;        // the ray in this block's frame, units (mm)
  Float3 invD;        // 1 / d: the traversal multiplies instead of dividing
  glm::mat3 toWorld;  // rotation from this frame to the world
  std::uint8_t wrap;
  float tExit;       // the level ends here (box or parent cell exit)
  float tStepLimit;  // a step crossing at or after this leaves the level instead (see land())
  Int3 cell;
  Float3 lo, hi;  // the cell's boundaries along each axis, within the tile
  Float3 tile;    // start of the current tile (multiple of D) on wrapped axes
  Float3 tNext;   // ray parameter where the ray leaves the cell, per axis
  // The face through which the ray entered the visible part of the current cell: a boundary
  // perpendicular to entryAxis of this block (a step or the block's box), or, when entryAxis is
  // -1, the face the level below entered through when this level landed (that level does not
  // move while this one is on the stack), or for the root the camera's own "face". Kept as an
  // axis so that steps and landings cost no matrix product; entryNormalWorld() builds the normal
  // for the one hit that needs it.
  int entryAxis;
};

// The face normal, in the level's frame, of a boundary perpendicular to axis a met by the ray.
inline glm::vec3 faceNormal(const Float3& d, int a) {
  glm::vec3 n(0.0f);
  n[a] = d[static_cast<std::size_t>(a)] > 0 ? -1.0f : 1.0f;
  return n;
}

// The world normal of the face through which the ray entered the current cell of stack[top].
// inline: called at every hit, and g++ would otherwise call it out of line.
inline glm::vec3 entryNormalWorld(const Level* stack, int top, const glm::vec3& direction) {
  for (; top >= 0; --top) {
    const Level& L = stack[top];
    if (L.entryAxis >= 0) return L.toWorld * faceNormal(L.d, L.entryAxis);
  }
  return -direction;  // a camera inside the root box sees what is in front of it
}

// Boundaries b_0 .. b_W of axis a as the lookup places them.
template <Lookup mode>
inline const float* boundsOf(const HniRayCaster::Block& block, std::size_t a) {
  return (mode == Lookup::Exact ? block.exactBounds : block.heuristicBounds)[a].data();
}

inline float exitParameter(const Level& L, std::size_t a) {
  if (L.d[a] > 0) return (L.tile[a] + L.hi[a] - L.o[a]) * L.invD[a];
  if (L.d[a] < 0) return (L.tile[a] + L.lo[a] - L.o[a]) * L.invD[a];
  return kInfinity;
}

inline void setDirection(Level& L, const glm::vec3& d) {
  L.d = toArray(d);
  // +-infinity on zero components, which exitParameter never multiplies
  for (std::size_t a = 0; a < 3; ++a) L.invD[a] = 1.0f / L.d[a];
}

// The cell of axis a holding in-tile coordinate x, its boundaries and the ray parameter of the
// exit along a.
template <Lookup mode>
inline void enterAxis(Level& L, const HniRayCaster::Block& block, std::size_t a, float x) {
  const AxisView& axis = block.axes[a];
  const int c = mode == Lookup::Exact ? axis.cellExact(x) : axis.cellHeuristic(x);
  const float* bounds = boundsOf<mode>(block, a);
  L.cell[a] = c;
  L.lo[a] = bounds[c];
  L.hi[a] = bounds[c + 1];
  L.tNext[a] = exitParameter(L, a);
}

// Redirection landing (paper Figure 14b): clips [tStart, tLimit] by the block's box (axes without
// wrapping) and finds the landing cell. Returns the landing parameter, or a negative value when
// the ray misses the block inside that interval. The ray enters through the face the level below
// entered its cell by, or through the block's own box face when the box starts later.
template <Lookup mode>
inline float land(Level& L, const HniRayCaster::Block& block, float tStart, float tLimit) {
  float t0 = tStart, t1 = tLimit;
  L.entryAxis = -1;
  for (std::size_t a = 0; a < 3; ++a) {
    if (L.wrap & (1 << a)) continue;
    const float size = block.axes[a].size;
    if (L.d[a] == 0) {
      if (L.o[a] < 0 || L.o[a] > size) return -1.0f;
      continue;
    }
    float ta = -L.o[a] * L.invD[a], tb = (size - L.o[a]) * L.invD[a];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) t0 = ta, L.entryAxis = static_cast<int>(a);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return -1.0f;
  L.tExit = t1;
  // The landing cell is looked up a few float ulps past t0 (never past the middle of the
  // interval): the transform into this frame carries that much rounding, and a cell the ray would
  // cross for less than it is an artefact of rounding (the parent's clip face and a boundary of
  // this block that coincide), not geometry. The ray is still processed from t0. For the same
  // reason a boundary crossed that close before t1 is not crossed: the ray leaves the level there.
  // (t1 is finite: the root does not wrap, and a sub-block's limit is its parent cell's exit.)
  const float reach = std::max({std::abs(L.o[0]), std::abs(L.o[1]), std::abs(L.o[2])});
  constexpr float kUlps = 4.0f * std::numeric_limits<float>::epsilon();
  const float tProbe = t0 + std::min(kUlps * (std::abs(t0) + reach), 0.5f * (t1 - t0));
  L.tStepLimit = t1 - std::min(kUlps * (std::abs(t1) + reach), 0.5f * (t1 - t0));
  for (std::size_t a = 0; a < 3; ++a) {
    const AxisView& axis = block.axes[a];
    float x = L.o[a] + tProbe * L.d[a];
    L.tile[a] = (L.wrap & (1 << a)) ? std::floor(x / axis.size) * axis.size : 0.0f;
    x -= L.tile[a];
    enterAxis<mode>(L, block, a, x);
  }
  return t0;
}

// Steps into the neighbouring cell along axis a. Returns false when the ray leaves a block along
// an axis without wrapping.
template <Lookup mode>
inline bool step(Level& L, const HniRayCaster::Block& block, std::size_t a) {
  const AxisView& axis = block.axes[a];
  L.entryAxis = static_cast<int>(a);
  int& cell = L.cell[a];
  if (L.d[a] > 0 && ++cell == axis.cells) {
    if (!(L.wrap & (1 << a))) return false;
    cell = 0;
    L.tile[a] += axis.size;
  } else if (L.d[a] < 0 && --cell < 0) {
    if (!(L.wrap & (1 << a))) return false;
    cell = axis.cells - 1;
    L.tile[a] -= axis.size;
  }
  const float* bounds = boundsOf<mode>(block, a);
  L.lo[a] = bounds[cell];
  L.hi[a] = bounds[cell + 1];
  L.tNext[a] = exitParameter(L, a);
  return true;
}

inline std::size_t argMin(const Float3& v) { return v[0] <= v[1] ? (v[0] <= v[2] ? 0 : 2) : (v[1] <= v[2] ? 1 : 2); }

// One ray's walk through the hierarchy (paper Algorithm 1): the stack of block levels, the ray
// parameter t reached so far and the translucent tints met on the way. Each visit of the top
// level's current cell hits its solid, lands in its sub-block or passes through it; a ray that
// passes leaves the cell through its nearest boundary, and a level it leaves ends and returns to
// its parent. Each of these is a method, inlined into run().
template <Lookup mode>
class HniRayCaster::Walk {
 public:
  // The walk writes into `result`, which the caller returns (no copy of it on the way out).
  Walk(const HniRayCaster& caster, const glm::dvec3& direction, double pixelAngle, const RayCastOptions& options,
       RayResult& result)
      : caster_(caster),
        direction_(direction),
        directionF_(direction),
        pixelAngle_(static_cast<float>(pixelAngle)),
        options_(options),
        result_(result) {}

  void run(const glm::dvec3& originM) {
    const float t = enterRoot(originM);
    if (t >= 0) walkFrom(t, 0);  // else it misses the root box: background
  }

  // The packet caster's hand-over: the walk goes on from a state its lanes built in stack(),
  // levels 0 .. top, at parameter t after `iterations` iterations, as run() would have.
  void resume(float t, int top, int iterations) {
    result_.iterations = iterations;
    walkFrom(t, top);
  }
  Level* stack() { return stack_.data(); }
  // descend() from level `top`, whose current cell is the redirection `texel`, into level top + 1.
  float descendFrom(int top, const std::uint8_t* texel, float t, float tCellExit) {
    return descend(stack_[static_cast<std::size_t>(top)], redirectOf(texel), t, tCellExit,
                   stack_[static_cast<std::size_t>(top + 1)]);
  }

  // The root level: the ray in the root block's frame, landed in its box. Returns the landing
  // parameter, negative when the ray misses the box.
  float enterRoot(const glm::dvec3& originM) {
    Level& root = stack_[0];
    root.block = caster_.root_;
    root.toWorld = caster_.worldFromRoot_;
    root.wrap = 0;
    // The subtraction happens in double: world coordinates may be near 10^6 m (city origins).
    root.o = toArray(glm::vec3(caster_.rootFromWorld_ * (originM - caster_.originM_) / format::kMetresPerUnit));
    setDirection(root, glm::vec3(caster_.rootFromWorld_ * direction_));
    return land<mode>(root, blockOf(caster_.root_), 0.0f, kInfinity);
  }

 private:
  // t and the top of the stack are kept in this loop, not in members: a member's address escapes
  // with the stack's into land() and step(), and would be reloaded after every call.
  void walkFrom(float t, int top) {
    while (true) {
      if (++result_.iterations > options_.maxIterations) {
        result_.capped = true;
        result_.colour = kCappedColour;
        return;
      }
      // Visit the current cell of the top level from t: hit it, land in it, or pass through it.
      // It is not entered when only touched (landing on a boundary moving away).
      const Level& L = stack_[static_cast<std::size_t>(top)];
      const float tCellExit = std::min(L.tNext[argMin(L.tNext)], L.tExit);
      const std::uint8_t* texel =
          tCellExit > t ? blockOf(L.block).cellTexel({L.cell[0], L.cell[1], L.cell[2]}) : nullptr;
      const int g = texel ? texel[3] : format::kCellEmpty;
      if (g == format::kCellPlane) {
        if (hitPlaneCell(L, texel, t, tCellExit, top)) return;
      } else if (g >= format::kCellFirstSolid) {
        if (hitSolid(L, texel, t, tCellExit, top)) return;
      } else if (g == format::kCellRedirection) {
        const Redirect& record = redirectOf(texel);
        if (top + 1 == kMaxStackDepth || summaryStandsIn(L, record, t)) {
          if (drawSummary(L, record, t, top)) return;
        } else {
          const float landed = descend(L, record, t, tCellExit, stack_[static_cast<std::size_t>(top + 1)]);
          if (landed >= 0) {
            t = landed;
            ++top;
            continue;
          }  // else the sub-block does not reach into this part of the cell
        }
      }
      if (!leaveCell(t, top)) return;
    }
  }

  const Block& blockOf(int index) const { return caster_.blocks_[static_cast<std::size_t>(index)]; }
  const Redirect& redirectOf(const std::uint8_t* texel) const {
    return caster_.redirects_[static_cast<std::size_t>(
        caster_.redirectByRecord_[static_cast<std::size_t>(texel[1] * 256 + texel[0])])];
  }

  // A solid cell entered at t: a box is hit there, where the ray enters the cell's visible part,
  // another solid where intersectSolid says. Returns true when the ray ends here (opaque).
  bool hitSolid(const Level& L, const std::uint8_t* texel, float t, float tCellExit, int top) {
    float tHit = t;
    glm::vec3 surfaceNormal(0.0f);  // unit-cube normal of a hit inside the cell, else 0
    if (texel[3] != format::kCellFirstSolid) {
      const glm::vec3 lo = toVec(L.lo), size = toVec(L.hi) - lo;
      const Solid solid{static_cast<std::uint8_t>(texel[3] - format::kCellFirstSolid)};
      const auto hit =
          intersectSolid<float>(solid, (toVec(L.o) - toVec(L.tile) - lo) / size, toVec(L.d) / size, t, tCellExit);
      if (!hit) return false;
      tHit = hit->t;
      if (tHit != t) surfaceNormal = glm::normalize(hit->normal / size);
    }
    const Material& m = caster_.materials_[static_cast<std::size_t>(texel[0] | texel[1] << 8)];
    // A hit where the ray enters the cell's visible part is on that face, which may be a cell
    // boundary, a box face or the face of an ancestor cell that clips this block. A camera on or
    // inside a solid sees it at distance 0, facing itself (as intersectSolid's origin-inside rule).
    const glm::vec3 normalWorld = tHit <= 0   ? -directionF_
                                  : tHit == t ? entryNormalWorld(stack_.data(), top, directionF_)
                                              : glm::normalize(L.toWorld * surfaceNormal);
    return add(tHit, normalWorld, {m.r, m.g, m.b}, m.opacity);
  }

  // A plane cell entered at t: hit where the ray first lies inside its planes' cut, on the face it
  // entered the cell by or on a plane. Returns true when the ray ends here (opaque).
  bool hitPlaneCell(const Level& L, const std::uint8_t* texel, float t, float tCellExit, int top) {
    const PlaneCell& cell =
        caster_.planeCells_[static_cast<std::size_t>(caster_.planeCellByRecord_.find(readU24(texel))->second)];
    const auto span = intersectPlaneCut<float>(cell.normals, cell.offsets, cell.combine, toVec(L.o) - toVec(L.tile),
                                               toVec(L.d), t, tCellExit);
    if (!span) return false;
    const Material& m =
        caster_
            .materials_[span->plane < 0 ? cell.material : cell.surfaceMaterials[static_cast<std::size_t>(span->plane)]];
    const glm::vec3 normalWorld = span->tIn <= 0 ? -directionF_
                                  : span->plane < 0
                                      ? entryNormalWorld(stack_.data(), top, directionF_)
                                      : glm::normalize(L.toWorld * cell.normals[static_cast<std::size_t>(span->plane)]);
    return add(span->tIn, normalWorld, {m.r, m.g, m.b}, m.opacity);
  }

  // Level of detail: one pixel spans t * pixelAngle at the ray's distance. With --lod auto the
  // target's summary stands in where that exceeds the record's footprint; with --lod-px where the
  // cell (of size s, spanning s / (t * pixelAngle) pixels) spans fewer than lodPx pixels.
  bool summaryStandsIn(const Level& L, const Redirect& record, float t) const {
    const float pixelSpan = std::max(t, 1.0f) * pixelAngle_;
    if (options_.lodAuto && record.lodFootprint > 0 && pixelSpan > record.lodFootprint) return true;
    if (options_.lodPx <= 0) return false;
    const float cellSize = std::max({L.hi[0] - L.lo[0], L.hi[1] - L.lo[1], L.hi[2] - L.lo[2]});
    return cellSize < static_cast<float>(options_.lodPx) * pixelSpan;
  }

  // A redirection cell drawn as its target's visual summary of the face the ray entered through.
  // Returns true when the ray ends here (opaque).
  bool drawSummary(const Level& L, const Redirect& record, float t, int top) {
    const glm::vec3 normalWorld = entryNormalWorld(stack_.data(), top, directionF_);
    const glm::vec3 inTarget = glm::transpose(L.toWorld * record.rotation) * normalWorld;
    const int axis = static_cast<int>(argMin(toArray(-glm::abs(inTarget))));
    const int side = 2 * axis + (inTarget[axis] > 0 ? 0 : 1);
    const Rgba8 s = blockOf(record.target).header.summary[static_cast<std::size_t>(side)];
    return add(t, normalWorld, {s.r, s.g, s.b}, s.a);
  }

  // Sets `child` to the record's target, the ray turned into its frame, and lands in it. Returns
  // the landing parameter, negative when the sub-block does not reach into [t, tCellExit].
  float descend(const Level& L, const Redirect& record, float t, float tCellExit, Level& child) const {
    child.block = record.target;
    const glm::vec3 inCell = toVec(L.o) - toVec(L.tile) - toVec(L.lo) - record.offset;
    if (record.unrotated) {
      child.o = toArray(inCell);
      child.d = L.d;
      child.invD = L.invD;
      child.toWorld = L.toWorld;
    } else {
      const glm::mat3 toChild = glm::transpose(record.rotation);
      child.o = toArray(toChild * inCell);
      setDirection(child, toChild * toVec(L.d));
      child.toWorld = L.toWorld * record.rotation;
    }
    child.wrap = record.wrap;
    return land<mode>(child, blockOf(record.target), t, tCellExit);
  }

  // Leaves the current cell through its nearest boundary; a level left ends, and its parent leaves
  // the cell that held it. Returns false when the ray leaves the root block: the background,
  // tinted by what it passed.
  bool leaveCell(float& t, int& top) {
    while (true) {
      Level& L = stack_[static_cast<std::size_t>(top)];
      const std::size_t a = argMin(L.tNext);
      const float tCross = L.tNext[a];
      if (tCross < L.tStepLimit && step<mode>(L, blockOf(L.block), a)) {
        t = std::max(t, tCross);
        return true;
      }
      if (top == 0) {
        result_.colour = composite_.finish(kBackground);
        return false;
      }
      t = L.tExit;
      --top;
    }
  }

  // A surface of this albedo and opacity met at tHit: an opaque one ends the ray (true), a
  // translucent one tints what lies behind it.
  bool add(float tHit, const glm::vec3& normalWorld, const std::array<std::uint8_t, 3>& albedo, std::uint8_t opacity) {
    const auto colour = shade(albedo, glm::dvec3(normalWorld), direction_);
    if (opacity != 255) {
      composite_.add(colour, opacity / 255.0);
      return false;
    }
    result_.hit = true;
    result_.distanceM = tHit * format::kMetresPerUnit;
    result_.normal = glm::dvec3(normalWorld);
    if (glm::dot(result_.normal, direction_) > 0) result_.normal = -result_.normal;
    result_.colour =
        options_.heatMap ? heatColour(result_.iterations, options_.maxIterations) : composite_.finish(colour);
    return true;
  }

  const HniRayCaster& caster_;
  glm::dvec3 direction_;
  glm::vec3 directionF_;
  float pixelAngle_;  // radians
  const RayCastOptions& options_;
  RayResult& result_;
  Composite composite_;
  std::array<Level, kMaxStackDepth> stack_;
};

}  // namespace nut
