// The CPU reference ray caster (paper section 6, Algorithm 1): NUT traversal and redirection
// landing over the encoded image, in float like the shader. One Level per block instance on the
// stack; each keeps the ray in the block's frame and, per axis, the current cell, its two
// boundaries, the metadata pixels holding them and the ray parameter of the next boundary, so
// that a step reads one metadata pixel (paper Figure 14a).
#include <nut/raycast.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <nut/hierarchy.hpp>
#include <nut/render_loop.hpp>
#include <nut/solids.hpp>

namespace nut {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Members are set by land() before use: no initialisers, so that the per-ray stack costs nothing
// to create.
struct Level {
  int block;
  glm::vec3 o, d;        // the ray in this block's frame, units (mm)
  glm::vec3 invD;        // 1 / d: the traversal multiplies instead of dividing
  glm::mat3 toWorld;     // rotation from this frame to the world
  std::uint8_t wrap;
  float tExit;           // the level ends here (box or parent cell exit)
  glm::ivec3 cell;
  glm::vec3 lo, hi;      // the cell's boundaries along each axis, within the tile
  glm::ivec3 kLo, kHi;   // metadata pixels holding them (-1 / M for the block faces)
  glm::vec3 tile;        // start of the current tile (multiple of D) on wrapped axes
  glm::vec3 tNext;       // ray parameter where the ray leaves the cell, per axis
  // The face through which the ray entered the visible part of the current cell: a boundary
  // perpendicular to entryAxis of this block (a step or the block's box), or, when entryAxis is
  // -1, entryNormal (world), inherited at landing from a clipping ancestor cell's face. Kept as an
  // axis so that a step costs no matrix product; entryNormalWorld() builds it for the rare hit.
  int entryAxis;
  glm::vec3 entryNormal;
};

// The face normal, in the level's frame, of a boundary perpendicular to axis a met by the ray.
glm::vec3 faceNormal(const glm::vec3& d, int a) {
  glm::vec3 n(0.0f);
  n[a] = d[a] > 0 ? -1.0f : 1.0f;
  return n;
}

template <Lookup mode>
float boundaryAt(const AxisView& axis, int k) {
  if (k < 0) return 0.0f;
  if (k >= axis.pixels) return axis.size;
  return mode == Lookup::Exact ? axis.exactPosition(k) : axis.boundaryHeuristic(k);
}

template <Lookup mode>
int cellAt(const AxisView& axis, float x) {
  return mode == Lookup::Exact ? axis.cellExact(x) : axis.cellHeuristic(x);
}

inline float exitParameter(const Level& L, int a) {
  if (L.d[a] > 0) return (L.tile[a] + L.hi[a] - L.o[a]) * L.invD[a];
  if (L.d[a] < 0) return (L.tile[a] + L.lo[a] - L.o[a]) * L.invD[a];
  return kInfinity;
}

void setDirection(Level& L, const glm::vec3& d) {
  L.d = d;
  L.invD = 1.0f / d;  // +-infinity on zero components, which exitParameter never multiplies
}

// Redirection landing (paper Figure 14b): clips [tStart, tLimit] by the block's box (axes without
// wrapping) and finds the landing cell. Returns the landing parameter, or a negative value when
// the ray misses the block inside that interval. entryNormal is the world normal of the face the
// ray crossed at tStart; the block's own box face replaces it when the box starts later.
template <Lookup mode>
float land(Level& L, const HniRayCaster::Block& block, float tStart, float tLimit, const glm::vec3& entryNormal) {
  float t0 = tStart, t1 = tLimit;
  L.entryAxis = -1;
  L.entryNormal = entryNormal;
  for (int a = 0; a < 3; ++a) {
    if (L.wrap & (1 << a)) continue;
    const float size = block.axes[static_cast<std::size_t>(a)].size;
    if (L.d[a] == 0) {
      if (L.o[a] < 0 || L.o[a] > size) return -1.0f;
      continue;
    }
    float ta = -L.o[a] * L.invD[a], tb = (size - L.o[a]) * L.invD[a];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) t0 = ta, L.entryAxis = a;
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return -1.0f;
  L.tExit = t1;
  // The landing cell is looked up a few float ulps past t0 (never past the middle of the
  // interval): the transform into this frame carries that much rounding, and a cell the ray would
  // cross for less than it is an artefact of rounding (the parent's clip face and a boundary of
  // this block that coincide), not geometry. The ray is still processed from t0.
  const float scale = std::abs(t0) + std::max({std::abs(L.o.x), std::abs(L.o.y), std::abs(L.o.z)});
  const float tProbe = t0 + std::min(4.0f * std::numeric_limits<float>::epsilon() * scale, 0.5f * (t1 - t0));
  for (int a = 0; a < 3; ++a) {
    const AxisView& axis = block.axes[static_cast<std::size_t>(a)];
    float x = L.o[a] + tProbe * L.d[a];
    L.tile[a] = (L.wrap & (1 << a)) ? std::floor(x / axis.size) * axis.size : 0.0f;
    x -= L.tile[a];
    const int c = cellAt<mode>(axis, x);
    const int k = axis.pixelOf(x);
    L.cell[a] = c;
    L.kLo[a] = c > 0 ? axis.boundaryPixelAhead(k, c, -1) : -1;
    L.kHi[a] = c + 1 < axis.cells ? axis.boundaryPixelAhead(k, c, +1) : axis.pixels;
    L.lo[a] = boundaryAt<mode>(axis, L.kLo[a]);
    L.hi[a] = boundaryAt<mode>(axis, L.kHi[a]);
    L.tNext[a] = exitParameter(L, a);
  }
  return t0;
}

// Steps into the neighbouring cell along axis a (one metadata fetch). Returns false when the ray
// leaves a block along an axis without wrapping.
template <Lookup mode>
bool step(Level& L, const HniRayCaster::Block& block, int a) {
  const AxisView& axis = block.axes[static_cast<std::size_t>(a)];
  L.entryAxis = a;
  if (L.d[a] > 0) {
    if (++L.cell[a] == axis.cells) {
      if (!(L.wrap & (1 << a))) return false;
      L.cell[a] = 0;
      L.tile[a] += axis.size;
      L.kHi[a] = -1;  // the new cell starts at the block face
    }
    L.kLo[a] = L.kHi[a];
    L.kHi[a] = L.cell[a] + 1 == axis.cells ? axis.pixels
               : L.kLo[a] < 0             ? axis.boundaryPixelAhead(0, 0, +1)
                                          : axis.nextBoundaryPixel(L.kLo[a], +1);
  } else {
    if (--L.cell[a] < 0) {
      if (!(L.wrap & (1 << a))) return false;
      L.cell[a] = axis.cells - 1;
      L.tile[a] -= axis.size;
      L.kLo[a] = axis.pixels;
    }
    L.kHi[a] = L.kLo[a];
    L.kLo[a] = L.cell[a] == 0                ? -1
               : L.kHi[a] >= axis.pixels     ? axis.boundaryPixelAhead(axis.pixels - 1, axis.cells - 1, -1)
                                             : axis.nextBoundaryPixel(L.kHi[a], -1);
  }
  L.lo[a] = boundaryAt<mode>(axis, L.kLo[a]);
  L.hi[a] = boundaryAt<mode>(axis, L.kHi[a]);
  L.tNext[a] = exitParameter(L, a);
  return true;
}

glm::vec3 entryNormalWorld(const Level& L) {
  return L.entryAxis >= 0 ? L.toWorld * faceNormal(L.d, L.entryAxis) : L.entryNormal;
}

int argMin(const glm::vec3& v) { return v.x <= v.y ? (v.x <= v.z ? 0 : 2) : (v.y <= v.z ? 1 : 2); }
}  // namespace

HniRayCaster::HniRayCaster(const Image& image, const glm::dvec3& originM, const glm::dmat3& worldFromRoot)
    : image_(image), view_(image), originM_(originM), rootFromWorld_(glm::transpose(worldFromRoot)), blockByHeader_(256 * 256, -1) {
  file_ = view_.fileRecord();
  for (int b = 0; b < file_.blockCount; ++b) {
    const TexelAddress at = view_.blockAddress(file_, b);
    Block block;
    block.header = view_.header(at);
    for (int a = 0; a < 3; ++a) block.axes[static_cast<std::size_t>(a)] = view_.axis(block.header, a);
    block.bottomRow = view_.cellTexel(block.header, {0, 0, 0});
    block.rowBytes = view_.rowBytes();
    blockByHeader_[static_cast<std::size_t>(at.v * 256 + at.u)] = static_cast<int>(blocks_.size());
    blocks_.push_back(block);
  }
  root_ = blockAt(file_.root);
  // Every redirection record a cell uses, decoded once.
  redirectByRecord_.assign(256 * 256, -1);
  for (const Block& block : blocks_) {
    const glm::ivec3 n = block.header.cells;
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          const std::uint8_t* texel = block.cellTexel({x, y, z});
          if (texel[3] != format::kCellRedirection) continue;
          int& index = redirectByRecord_[static_cast<std::size_t>(texel[1] * 256 + texel[0])];
          if (index >= 0) continue;
          const RedirectionRecord r = view_.redirection({texel[0], texel[1]});
          index = static_cast<int>(redirects_.size());
          redirects_.push_back({glm::mat3(rotationMatrix(Rotation{r.cubeRotation, r.yaw})), glm::vec3(r.offsetUnits),
                                blockAt(r.target), r.wrap, r.cubeRotation == 0 && r.yaw == 0});
        }
  }
}

int HniRayCaster::blockAt(TexelAddress header) const {
  return blockByHeader_[static_cast<std::size_t>(header.v * 256 + header.u)];
}

WorldBox HniRayCaster::bounds() const {
  const glm::dvec3 size = glm::dvec3(blocks_[static_cast<std::size_t>(root_)].header.sizeUnits) * format::kMetresPerUnit;
  const glm::dmat3 worldFromRoot = glm::transpose(rootFromWorld_);
  WorldBox box{originM_, originM_};
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner = originM_ + worldFromRoot * (size * glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    box.min = glm::min(box.min, corner);
    box.max = glm::max(box.max, corner);
  }
  return box;
}

RayResult HniRayCaster::trace(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                              const RayCastOptions& options) const {
  return options.lookup == Lookup::Exact ? traceWith<Lookup::Exact>(originM, direction, pixelAngle, options)
                                         : traceWith<Lookup::Heuristic>(originM, direction, pixelAngle, options);
}

template <Lookup mode>
RayResult HniRayCaster::traceWith(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                                  const RayCastOptions& options) const {
  RayResult result;
  Composite composite;
  std::array<Level, kMaxStackDepth> stack;
  int top = 0;
  Level& root = stack[0];
  root.block = root_;
  root.toWorld = glm::mat3(glm::transpose(rootFromWorld_));
  root.wrap = 0;
  // The subtraction happens in double: world coordinates may be near 10^6 m (city origins).
  root.o = glm::vec3(rootFromWorld_ * (originM - originM_) / format::kMetresPerUnit);
  setDirection(root, glm::vec3(rootFromWorld_ * direction));
  // A camera inside the root box sees what is in front of it: the entry "face" faces the ray.
  float t = land<mode>(root, blocks_[static_cast<std::size_t>(root_)], 0.0f, kInfinity, -glm::vec3(direction));
  if (t < 0) return result;  // misses the root box: background
  const float angle = static_cast<float>(pixelAngle);  // a cell of size s spans s / (t * angle) pixels
  bool advance = false;
  const auto finish = [&](float tHit, const glm::vec3& normalWorld, const std::array<std::uint8_t, 3>& colour) {
    result.hit = true;
    result.distanceM = tHit * format::kMetresPerUnit;
    result.normal = glm::dvec3(normalWorld);
    if (glm::dot(result.normal, direction) > 0) result.normal = -result.normal;
    result.colour = composite.finish(colour);
  };

  while (true) {
    Level& L = stack[static_cast<std::size_t>(top)];
    const Block& block = blocks_[static_cast<std::size_t>(L.block)];
    if (advance) {
      // Leave the current cell through the nearest boundary, or leave the level.
      const int a = argMin(L.tNext);
      const float tCross = L.tNext[a];
      if (tCross >= L.tExit || !step<mode>(L, block, a)) {
        if (top == 0) break;
        t = L.tExit;
        --top;
        continue;  // the parent advances past the cell that held this level
      }
      t = std::max(t, tCross);
      advance = false;
      continue;
    }
    if (++result.iterations > options.maxIterations) {
      result.capped = true;
      result.colour = kCappedColour;
      return result;
    }
    advance = true;
    const float tCellExit = std::min(L.tNext[argMin(L.tNext)], L.tExit);
    if (!(tCellExit > t)) continue;  // touched, not entered (landing on a boundary moving away)
    const std::uint8_t* texel = block.cellTexel(L.cell);
    const int g = texel[3];
    if (g >= format::kCellFirstSolid) {
      // A box is hit where the ray enters the cell's visible part (intersectSolid's answer too).
      float tHit = t;
      glm::vec3 surfaceNormal(0.0f);  // unit-cube normal of a hit inside the cell, else 0
      if (g != format::kCellFirstSolid) {
        const glm::vec3 size = L.hi - L.lo;
        const Solid solid{static_cast<std::uint8_t>(g - format::kCellFirstSolid)};
        const auto hit = intersectSolid<float>(solid, (L.o - L.tile - L.lo) / size, L.d / size, t, tCellExit);
        if (!hit) continue;
        tHit = hit->t;
        if (tHit != t) surfaceNormal = glm::normalize(hit->normal / size);
      }
      const Material m = view_.material(file_, texel[0] | texel[1] << 8);
      // A hit where the ray enters the cell's visible part is on that face, which may be a cell
      // boundary, a box face or the face of an ancestor cell that clips this block.
      // A camera on or inside a solid sees it at distance 0, facing itself (as intersectSolid's
      // origin-inside rule).
      const glm::vec3 normalWorld = tHit <= 0     ? -glm::vec3(direction)
                                    : tHit == t ? entryNormalWorld(L)
                                                : glm::normalize(L.toWorld * surfaceNormal);
      const auto colour = shade({m.r, m.g, m.b}, glm::dvec3(normalWorld), direction);
      if (m.opacity == 255) {
        finish(tHit, normalWorld, colour);
        return result;
      }
      composite.add(colour, m.opacity / 255.0);
      continue;
    }
    if (g != format::kCellRedirection) continue;

    const Redirect& record = redirects_[static_cast<std::size_t>(redirectByRecord_[static_cast<std::size_t>(texel[1] * 256 + texel[0])])];
    const int target = record.target;
    const glm::mat3& rotation = record.rotation;
    const auto belowLod = [&] {
      const glm::vec3 cellSize = L.hi - L.lo;
      return std::max({cellSize.x, cellSize.y, cellSize.z}) < static_cast<float>(options.lodPx) * std::max(t, 1.0f) * angle;
    };
    if (top + 1 == kMaxStackDepth || (options.lodPx > 0 && belowLod())) {
      // Level of detail: the target's visual summary of the face the ray entered through.
      const glm::vec3 normalWorld = entryNormalWorld(L);
      const glm::vec3 inTarget = glm::transpose(L.toWorld * rotation) * normalWorld;
      const int axis = argMin(-glm::abs(inTarget));
      const int side = 2 * axis + (inTarget[axis] > 0 ? 0 : 1);
      const Rgba8 s = blocks_[static_cast<std::size_t>(target)].header.summary[static_cast<std::size_t>(side)];
      const auto colour = shade({s.r, s.g, s.b}, glm::dvec3(normalWorld), direction);
      if (s.a == 255) {
        finish(t, normalWorld, colour);
        return result;
      }
      composite.add(colour, s.a / 255.0);
      continue;
    }
    Level& child = stack[static_cast<std::size_t>(top + 1)];
    child.block = target;
    if (record.unrotated) {
      child.o = L.o - L.tile - L.lo - record.offset;
      child.d = L.d;
      child.invD = L.invD;
      child.toWorld = L.toWorld;
    } else {
      const glm::mat3 toChild = glm::transpose(rotation);
      child.o = toChild * (L.o - L.tile - L.lo - record.offset);
      setDirection(child, toChild * L.d);
      child.toWorld = L.toWorld * rotation;
    }
    child.wrap = record.wrap;
    const float landed =
        land<mode>(child, blocks_[static_cast<std::size_t>(target)], t, tCellExit, entryNormalWorld(L));
    if (landed < 0) continue;  // the sub-block does not reach into this part of the cell
    t = landed;
    ++top;
    advance = false;
  }
  result.colour = composite.finish(kBackground);
  return result;
}

RenderOutput renderRays(const Camera& camera, const RayFunction& trace, int threads, RenderStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  RenderOutput out;
  out.colour = Image(camera.width, camera.height);
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
  out.distanceM.assign(pixels, kInfinity);
  out.windowDepth.assign(pixels, 1.0f);
  out.iterations.assign(pixels, 0);
  const RayGenerator rays(camera);
  const double pixelAngle = 2.0 * rays.tanHalfY / camera.height;
  std::atomic<long long> cappedRays{0};
  const int count = forEachPixelInTiles(camera.width, camera.height, threads, [&](int x, int y) {
    const glm::dvec3 dir = rays.direction(x, y);
    const RayResult r = trace(camera.eye, dir, pixelAngle);
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x);
    std::uint8_t* p = out.colour.at(x, y);
    p[0] = r.colour[0], p[1] = r.colour[1], p[2] = r.colour[2], p[3] = 255;
    if (r.hit) {
      out.distanceM[i] = static_cast<float>(r.distanceM);
      out.windowDepth[i] = static_cast<float>(rays.windowDepth(r.distanceM, dir));
    }
    out.iterations[i] = static_cast<std::uint16_t>(std::min(r.iterations, 65535));
    if (r.capped) ++cappedRays;
  });
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->raysPerSecond = static_cast<double>(pixels) / stats->seconds;
    long long sum = 0;
    int most = 0;
    for (std::uint16_t it : out.iterations) sum += it, most = std::max(most, static_cast<int>(it));
    stats->iterationsMean = static_cast<double>(sum) / static_cast<double>(pixels);
    stats->iterationsMax = most;
    stats->cappedPct = 100.0 * static_cast<double>(cappedRays) / static_cast<double>(pixels);
    stats->threads = count;
  }
  return out;
}

RenderOutput renderHni(const HniRayCaster& caster, const Camera& camera, const RayCastOptions& options, int threads,
                       RenderStats* stats) {
  return renderRays(
      camera, [&](const glm::dvec3& eye, const glm::dvec3& dir, double pixelAngle) { return caster.trace(eye, dir, pixelAngle, options); },
      threads, stats);
}

}  // namespace nut
