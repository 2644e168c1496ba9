// ray_packets.hpp (internal to the core) — what the packet caster (raycast_packet.cpp) reads: the
// caster's block headers, boundary tables and redirection records flattened into arrays that SIMD
// lanes gather from by index, and RayPackets, the caster's friend that lets it reach them and the
// one-ray walk it hands rays over to.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/raycast.hpp>

#include "ray_walk.hpp"

namespace nut {

struct RayPacketTables {
  const std::int32_t* pixels = nullptr;  // the HNI's texels, one 32-bit word each (little-endian RGBA)
  std::int32_t rowPixels = 0;            // texels per image row
  // Per block, at the caster's block index: the texel of cell (0, 0, 0) and the cells along x.
  std::vector<std::int32_t> bottomPixel, cellsX;
  // Per block axis, at 3 * block + axis: AxisView's constants, the texels where its metadata and
  // exact rows start, and where its boundaries b_0 .. b_W start in the boundary arrays.
  std::vector<float> size, scale, exactLast, stepScale, lastStep;
  std::vector<std::int32_t> cells, metaPixel, exactPixel, boundsStart;
  std::vector<float> heuristicBounds, exactBounds;
  // Redirection record (256 * v + u) -> index r into the arrays below (the caster's redirects_),
  // or -1.
  std::vector<std::int32_t> redirectByRecord;
  std::array<std::vector<float>, 3> offset;   // units
  std::array<std::vector<float>, 9> toChild;  // the cell's frame to the target's: glm's [c][r] at 3 c + r
  std::vector<glm::mat3> rotation;            // the target's frame to the cell's
  std::vector<std::int32_t> target, wrap, unrotated;
  std::vector<float> lodFootprint;  // units; 0 = none
};

// The packet caster is built per SIMD target outside the caster's class; this friend gives it the
// caster's tables and one-ray walk.
struct RayPackets {
  template <Lookup mode>
  using Walk = HniRayCaster::Walk<mode>;
  static RayPacketTables build(const HniRayCaster& caster);
  static const RayPacketTables& tables(const HniRayCaster& caster) { return *caster.packetTables_; }
};

// One call of the packet caster: the rays, their results written in order.
struct RayPacketJob {
  const HniRayCaster* caster;
  const glm::dvec3* origins;  // one per ray, or one for all
  bool oneOrigin;
  const glm::dvec3* directions;
  std::size_t count;
  double pixelAngle;
  const RayCastOptions* options;
  RayResult* results;
};

}  // namespace nut
