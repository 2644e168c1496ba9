// samples/sample_kit.hpp — small helpers for building NUT hierarchies by hand, shared by the
// make_samples generators: grids from cut positions, filling and redirecting regions given in
// metres, solids named by where their edge or corner sits, rotations about the up axis, and the
// compile -> validate -> decode -> compare -> write pipeline that every sample goes through.
//
// Construction mistakes in a sample (a region edge that is not a cell boundary, a rotation that
// does not exist) throw SampleError; make_samples turns it into "error: ..." and a non-zero exit.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>
#include <nut/solids.hpp>

namespace samples {

struct SampleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- Grids and regions --------------------------------------------------------------------

// An axis-aligned box in a block's frame, metres.
struct Region {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
};
inline Region region(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{x0, y0, z0}, {x1, y1, z1}};
}

// A block of the given size whose cells are cut at the given positions (any order; duplicates,
// 0 and the size itself are ignored). All cells start empty.
nut::Block makeGrid(const glm::dvec3& size, std::vector<double> cutsX, std::vector<double> cutsY,
                    std::vector<double> cutsZ);

// A block of consecutive cell sizes per axis (nut::Block::fromSizes, named for symmetry).
nut::Block makeGridFromSizes(const std::vector<double>& sizesX, const std::vector<double>& sizesY,
                             const std::vector<double>& sizesZ);

// The whole block as a region.
Region wholeBlock(const nut::Block& b);

// Sets every cell inside `r` (whose faces must lie on cell boundaries) to `cell`.
void fill(nut::Block& b, const Region& r, const nut::Cell& cell);

// Shows `red.target` (a block already in h) over the region: its origin lands at
// r.min + red.offsetM, rotated by red.rotation. Each cell of the region gets the offset that keeps
// this one placement (the format measures offsets from each cell's own minimum corner), so a
// region may span many cells; each distinct offset costs a redirection record, except that
// offsets along wrapped axes are reduced modulo the tile, so tiled cells share records.
void place(const nut::Hierarchy& h, nut::Block& b, const Region& r, nut::Redirection red);

// Index-based variants for tabular blocks: cells [x0, x1) x [y0, y1) x [z0, z1).
void fillCells(nut::Block& b, int x0, int x1, int y0, int y1, int z0, int z1, const nut::Cell& cell);

// ---- Solids --------------------------------------------------------------------------------

// Where a solid's right-angle edge (wedges, quarter cylinders) or corner (pyramids, octants)
// lies in its cell, per axis: Lo = the cell's minimum side, Hi = its maximum side, Along = the
// extrusion axis of an edge-based solid. Filled solids hug that edge/corner; inverse solids are
// the cell minus the same shape, so they hug the opposite side.
enum Side : int { Lo = -1, Along = 0, Hi = 1 };

nut::Solid edgeSolid(nut::SolidGroup group, Side x, Side y, Side z);
nut::Solid cornerSolid(nut::SolidGroup group, Side x, Side y, Side z);

inline nut::Cell solidCell(nut::Solid s, std::uint16_t material) { return nut::Cell::solidCell(s, material); }
inline nut::Cell wedge(Side x, Side y, Side z, std::uint16_t m) {
  return solidCell(edgeSolid(nut::SolidGroup::Wedge, x, y, z), m);
}
inline nut::Cell quarterCylinder(Side x, Side y, Side z, std::uint16_t m) {
  return solidCell(edgeSolid(nut::SolidGroup::QuarterCylinder, x, y, z), m);
}
inline nut::Cell coveCylinder(Side x, Side y, Side z, std::uint16_t m) {  // inverse quarter cylinder
  return solidCell(edgeSolid(nut::SolidGroup::InverseQuarterCylinder, x, y, z), m);
}
inline nut::Cell pyramid(Side x, Side y, Side z, std::uint16_t m) {
  return solidCell(cornerSolid(nut::SolidGroup::Pyramid, x, y, z), m);
}
inline nut::Cell octant(Side x, Side y, Side z, std::uint16_t m) {
  return solidCell(cornerSolid(nut::SolidGroup::SphereOctant, x, y, z), m);
}
inline nut::Cell coveOctant(Side x, Side y, Side z, std::uint16_t m) {  // inverse sphere octant
  return solidCell(cornerSolid(nut::SolidGroup::InverseSphereOctant, x, y, z), m);
}

// ---- Rotations and placement ---------------------------------------------------------------

// The cube rotation by quarterTurns * 90 degrees about +y, counter-clockwise seen from above
// (1: a facade's outward +z turns to +x; 2: to -z; 3: to -x).
nut::Rotation turnAboutY(int quarterTurns);
// The cube rotation whose matrix maps +x, +y, +z to the given signed axes (e.g. {1, 0, 0}).
nut::Rotation cubeRotationMapping(const glm::ivec3& imageOfX, const glm::ivec3& imageOfY);
// A free yaw about +y in the format's 1/65536 turns; `steps` must be exact (e.g. 8192 = 45 deg).
nut::Rotation yawSteps(int steps);

// A redirection to `target` rotated by `rotation`, shifted so that the rotated target's bounding
// box starts at the region's minimum corner (plus `shiftM`, in the parent's frame).
nut::Redirection rotatedFit(const nut::Hierarchy& h, nut::BlockId target, nut::Rotation rotation,
                            glm::dvec3 shiftM = glm::dvec3(0.0));
// A redirection that puts the target-local point `targetPoint` at `regionPoint` (relative to the
// region's minimum corner) after rotating by `rotation`.
nut::Redirection pinned(nut::BlockId target, nut::Rotation rotation, const glm::dvec3& targetPoint,
                        const glm::dvec3& regionPoint);
// A plain redirection (no rotation) at `offsetM` with the given wrap flags.
nut::Redirection showing(nut::BlockId target, bool wrapX = false, bool wrapY = false, bool wrapZ = false,
                         glm::dvec3 offsetM = glm::dvec3(0.0));

// ---- Materials -----------------------------------------------------------------------------

inline std::uint16_t colour(nut::Hierarchy& h, int r, int g, int b, int reflectance = 0) {
  return h.addMaterial({static_cast<std::uint8_t>(r), static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(b), 255,
                        static_cast<std::uint8_t>(reflectance)});
}

// ---- Pipeline ------------------------------------------------------------------------------

struct SampleSummary {
  std::string file;
  int width = 0, height = 0;
  long long bytesRaw = 0;
  long long bytesPng = 0;
  double wastePct = 0;
  int blocks = 0;
  int dagDepth = 0;
};

// Compiles `h`, validates and decodes the image, checks decode(compile(h)) == quantized(h)
// (summaries aside), writes `outDir/fileName` with HNI text metadata, reads it back bit-exactly,
// and returns the numbers. Throws SampleError on any failure.
SampleSummary writeSample(const nut::Hierarchy& h, const std::string& outDir, const std::string& fileName,
                          const std::string& title);

// "facade.png: 84x40 px, raw 13440 B, PNG 2917 B, waste 0.4%, 7 blocks, DAG depth 2"
std::string describe(const SampleSummary& s);

}  // namespace samples
