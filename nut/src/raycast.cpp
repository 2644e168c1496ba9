// The CPU reference ray caster (paper section 6, Algorithm 1): NUT traversal and redirection
// landing over the encoded image, in float like the shader. One Level per block instance on the
// stack; each keeps the ray in the block's frame and, per axis, the current cell, its two
// boundaries and the ray parameter of the next boundary. A step (paper Figure 14a) takes its new
// boundary from the block's boundary table, which holds what the shader's one metadata fetch per
// step reads: the positions of the pixels the j numbers lead to.
#include <nut/raycast.hpp>

#include "ray_packets.hpp"
#include "ray_walk.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <nut/heat_map.hpp>
#include <nut/hierarchy.hpp>
#include <nut/render_loop.hpp>
#include <nut/solids.hpp>
#include <nut/units.hpp>

namespace nut {

HniRayCaster::HniRayCaster(const Image& image, const glm::dvec3& originM, const glm::dmat3& worldFromRoot,
                           std::optional<BlockId> rootBlock)
    : image_(image),
      view_(image),
      originM_(originM),
      rootFromWorld_(glm::transpose(worldFromRoot)),
      worldFromRoot_(worldFromRoot),
      blockByHeader_(256 * 256, -1) {
  file_ = view_.fileRecord();
  for (int b = 0; b < file_.blockCount; ++b) {
    const TexelAddress at = view_.blockAddress(file_, b);
    Block block;
    block.header = view_.header(at);
    for (std::size_t a = 0; a < 3; ++a) {
      const AxisView& axis = block.axes[a] = view_.axis(block.header, static_cast<int>(a));
      block.heuristicBounds[a] = {0.0f};
      block.exactBounds[a] = {0.0f};
      for (int m = 1, k = axis.boundaryPixelAhead(0, 0, +1); m < axis.cells; ++m, k = axis.nextBoundaryPixel(k, +1)) {
        block.heuristicBounds[a].push_back(axis.boundaryHeuristic(k));
        block.exactBounds[a].push_back(axis.exactPosition(k));
      }
      block.heuristicBounds[a].push_back(axis.size);
      block.exactBounds[a].push_back(axis.size);
    }
    block.bottomRow = view_.cellTexel(block.header, {0, 0, 0});
    block.rowBytes = view_.rowBytes();
    blockByHeader_[static_cast<std::size_t>(at.v * 256 + at.u)] = static_cast<int>(blocks_.size());
    blocks_.push_back(block);
  }
  root_ = rootBlock ? static_cast<int>(*rootBlock) : blockAt(file_.root);  // blocks_[id] is block id
  for (int m = 0; m < file_.materialCount; ++m) materials_.push_back(view_.material(file_, m));
  // Every redirection record a cell uses, decoded once.
  redirectByRecord_.assign(256 * 256, -1);
  for (const Block& block : blocks_) {
    const glm::ivec3 n = block.header.cells;
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          const std::uint8_t* texel = block.cellTexel({x, y, z});
          if (texel[3] == format::kCellPlane) addPlaneCell(readU24(texel));
          if (texel[3] != format::kCellRedirection) continue;
          int& index = redirectByRecord_[static_cast<std::size_t>(texel[1] * 256 + texel[0])];
          if (index >= 0) continue;
          const RedirectionRecord r = view_.redirection({texel[0], texel[1]});
          index = static_cast<int>(redirects_.size());
          redirects_.push_back({glm::mat3(rotationMatrix(Rotation{r.cubeRotation, r.yaw})), glm::vec3(r.offsetUnits),
                                blockAt(r.target), r.wrap, r.cubeRotation == 0 && r.yaw == 0,
                                static_cast<float>(lodFootprintM(r.lodCode) / format::kMetresPerUnit)});
        }
  }
  packetTables_ = std::make_shared<const RayPacketTables>(RayPackets::build(*this));
}

void HniRayCaster::addPlaneCell(std::uint32_t packedRecord) {
  const auto [it, added] = planeCellByRecord_.try_emplace(packedRecord, static_cast<int>(planeCells_.size()));
  if (!added) return;
  const PlaneRecord record = view_.planeRecord(unpackAddress(packedRecord));
  PlaneCell cell{{glm::vec3(0.0f), glm::vec3(0.0f)}, {0.0f, 0.0f}, static_cast<PlaneCombine>(record.combine),
                 record.material, {record.material, record.material}};
  // Decoded in float with the shader's operations, so that both casters cut the same planes.
  for (std::size_t p = 0; p < static_cast<std::size_t>(record.planeCount()); ++p) {
    const EncodedPlane& e = record.planes[p];
    cell.normals[p] = decodeNormalFloat(e.octX, e.octY);
    cell.offsets[p] = static_cast<float>(e.offset) / static_cast<float>(format::kPlaneOffsetStepsPerUnit);
    if (record.surfaceMaterialCodes[p] != 0)
      cell.surfaceMaterials[p] = static_cast<std::uint16_t>(record.surfaceMaterialCodes[p] - 1);
  }
  planeCells_.push_back(cell);
}

int HniRayCaster::blockAt(TexelAddress header) const {
  return blockByHeader_[static_cast<std::size_t>(header.v * 256 + header.u)];
}

WorldBox HniRayCaster::bounds() const {
  const glm::dvec3 size =
      glm::dvec3(blocks_[static_cast<std::size_t>(root_)].header.sizeUnits) * format::kMetresPerUnit;
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
  RayResult result;
  if (options.lookup == Lookup::Exact)
    Walk<Lookup::Exact>(*this, direction, pixelAngle, options, result).run(originM);
  else
    Walk<Lookup::Heuristic>(*this, direction, pixelAngle, options, result).run(originM);
  return result;
}

namespace {

// The pixel loop of renderRays and renderHni, one tile at a time: traceTile(eye, directions,
// pixelAngle, results) traces the rays of a tile's pixels, row by row.
template <typename TraceTile>
RenderOutput renderRaysWith(const Camera& camera, const TraceTile& traceTile, int threads, RenderStats* stats) {
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
  const int count = forEachTile(camera.width, camera.height, threads, [&](int x0, int y0, int x1, int y1) {
    std::array<glm::dvec3, kRenderTile * kRenderTile> directions;
    std::array<RayResult, kRenderTile * kRenderTile> results;
    std::size_t n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) directions[n++] = rays.direction(x, y);
    traceTile(camera.eye, std::span<const glm::dvec3>(directions.data(), n), pixelAngle,
              std::span<RayResult>(results.data(), n));
    n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const RayResult& r = results[n];
        const glm::dvec3& dir = directions[n++];
        const std::size_t i =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x);
        std::uint8_t* p = out.colour.at(x, y);
        p[0] = r.colour[0], p[1] = r.colour[1], p[2] = r.colour[2], p[3] = 255;
        if (r.hit) {
          out.distanceM[i] = static_cast<float>(r.distanceM);
          out.windowDepth[i] = static_cast<float>(rays.windowDepth(r.distanceM, dir));
        }
        out.iterations[i] = static_cast<std::uint16_t>(std::min(r.iterations, 65535));
        if (r.capped) ++cappedRays;
      }
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

}  // namespace

RenderOutput renderRays(const Camera& camera, const RayFunction& trace, int threads, RenderStats* stats) {
  return renderRaysWith(
      camera,
      [&](const glm::dvec3& eye, std::span<const glm::dvec3> directions, double pixelAngle,
          std::span<RayResult> results) {
        for (std::size_t i = 0; i < directions.size(); ++i) results[i] = trace(eye, directions[i], pixelAngle);
      },
      threads, stats);
}

RenderOutput renderHni(const HniRayCaster& caster, const Camera& camera, const RayCastOptions& options, int threads,
                       RenderStats* stats) {
  return renderRaysWith(
      camera,
      [&](const glm::dvec3& eye, std::span<const glm::dvec3> directions, double pixelAngle,
          std::span<RayResult> results) {
        if (options.packets) return caster.traceMany({&eye, 1}, directions, pixelAngle, options, results);
        for (std::size_t i = 0; i < directions.size(); ++i)
          results[i] = caster.trace(eye, directions[i], pixelAngle, options);
      },
      threads, stats);
}

}  // namespace nut
