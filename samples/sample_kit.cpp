// samples/sample_kit.cpp — grid, solid, rotation and pipeline helpers for the hand-built samples.
#include "sample_kit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>
#include <nut/units.hpp>

namespace samples {

namespace {

// Boundaries are sums of decimal lengths, so equal positions differ only by rounding noise.
constexpr double kSameBoundaryM = 1e-6;

const char* axisName(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f m", v);
  return text;
}

// Index of the boundary at `position` on `axis`; throws when there is none.
int boundaryIndex(const nut::Block& b, int axis, double position) {
  const auto& bounds = b.boundsM[static_cast<std::size_t>(axis)];
  for (std::size_t i = 0; i < bounds.size(); ++i)
    if (std::abs(bounds[i] - position) < kSameBoundaryM) return static_cast<int>(i);
  throw SampleError("region edge at " + metres(position) + " on axis " + axisName(axis) +
                    " is not a cell boundary of the block");
}

struct CellRanges {
  std::array<int, 3> first{}, last{};  // half-open [first, last) per axis
};

CellRanges rangesOf(const nut::Block& b, const Region& r) {
  CellRanges c;
  for (int a = 0; a < 3; ++a) {
    c.first[static_cast<std::size_t>(a)] = boundaryIndex(b, a, r.min[a]);
    c.last[static_cast<std::size_t>(a)] = boundaryIndex(b, a, r.max[a]);
    if (c.last[static_cast<std::size_t>(a)] <= c.first[static_cast<std::size_t>(a)])
      throw SampleError(std::string("empty region on axis ") + axisName(a) + " (" + metres(r.min[a]) + " to " +
                        metres(r.max[a]) + ")");
  }
  return c;
}

std::uint32_t redirectionIndex(nut::Block& b, const nut::Redirection& red) {
  const auto it = std::find(b.redirections.begin(), b.redirections.end(), red);
  if (it != b.redirections.end()) return static_cast<std::uint32_t>(it - b.redirections.begin());
  b.redirections.push_back(red);
  return static_cast<std::uint32_t>(b.redirections.size() - 1);
}

std::vector<double> boundariesFromCuts(double size, std::vector<double> cuts) {
  std::vector<double> bounds{0.0};
  std::sort(cuts.begin(), cuts.end());
  for (double c : cuts)
    if (c > kSameBoundaryM && c < size - kSameBoundaryM && c - bounds.back() > kSameBoundaryM) bounds.push_back(c);
  bounds.push_back(size);
  return bounds;
}

nut::Rotation findCubeRotation(const glm::ivec3& imageOfX, const glm::ivec3& imageOfY, const glm::ivec3& imageOfZ) {
  for (int i = 0; i < 24; ++i) {
    const glm::mat<3, 3, int> m = nut::cubeRotationMatrix(i);
    if (m[0] == imageOfX && m[1] == imageOfY && m[2] == imageOfZ) return nut::Rotation{static_cast<std::uint8_t>(i), 0};
  }
  throw SampleError("no cube rotation maps the axes as asked (not a proper rotation)");
}

// Blocks that the root reaches; every block of a sample should be used.
std::vector<bool> reachableBlocks(const nut::Hierarchy& h) {
  std::vector<bool> seen(h.blocks.size(), false);
  std::vector<nut::BlockId> stack{h.root};
  seen[h.root] = true;
  while (!stack.empty()) {
    const nut::BlockId b = stack.back();
    stack.pop_back();
    for (const nut::Cell& c : h.blocks[b].cells) {
      if (c.kind != nut::CellKind::Redirection) continue;
      const nut::BlockId t = h.blocks[b].redirections[c.redirection].target;
      if (!seen[t]) seen[t] = true, stack.push_back(t);
    }
  }
  return seen;
}

// Where two hierarchies first differ, in words; empty when they are equal.
std::string firstDifference(const nut::Hierarchy& expected, const nut::Hierarchy& actual) {
  if (expected.root != actual.root) return "root block differs";
  if (expected.materials != actual.materials) return "material arrays differ";
  if (expected.textures != actual.textures) return "texture arrays differ";
  if (expected.blocks.size() != actual.blocks.size())
    return std::to_string(expected.blocks.size()) + " blocks expected, " + std::to_string(actual.blocks.size()) +
           " decoded";
  for (std::size_t i = 0; i < expected.blocks.size(); ++i) {
    const nut::Block& e = expected.blocks[i];
    const nut::Block& a = actual.blocks[i];
    const std::string where = "block " + std::to_string(i) + ": ";
    for (int axis = 0; axis < 3; ++axis)
      if (e.boundsM[static_cast<std::size_t>(axis)] != a.boundsM[static_cast<std::size_t>(axis)])
        return where + "boundaries of axis " + axisName(axis) + " differ";
    if (e.redirections != a.redirections) return where + "redirections differ";
    for (std::size_t c = 0; c < e.cells.size() && c < a.cells.size(); ++c)
      if (!(e.cells[c] == a.cells[c])) return where + "cell " + std::to_string(c) + " differs";
    if (e.cells.size() != a.cells.size()) return where + "cell counts differ";
  }
  return expected == actual ? "" : "hierarchies differ";
}

// A tiled target repeats with its own size along each wrapped axis, so an offset along the
// parent axis that such a target axis maps to matters only modulo that size. Reducing it (in whole
// millimetres, the format's unit) lets the cells of a large tiled region share one record.
// Only for axis-aligned placements (no yaw), where a target axis maps to one parent axis.
glm::dvec3 reduceWrappedOffset(const nut::Hierarchy& h, const nut::Redirection& red, glm::dvec3 offset) {
  if (red.rotation.yaw != 0) return offset;
  const glm::mat<3, 3, int> m = nut::cubeRotationMatrix(red.rotation.cube);
  const glm::dvec3 size = h.blocks.at(red.target).sizeM();
  for (int a = 0; a < 3; ++a) {
    if (!red.wrap[static_cast<std::size_t>(a)]) continue;
    const int parentAxis = m[a][0] != 0 ? 0 : m[a][1] != 0 ? 1 : 2;
    const std::int64_t period = nut::toUnits(size[a]);
    const std::int64_t units = nut::toUnits(offset[parentAxis]);
    offset[parentAxis] = nut::toMetres(((units % period) + period) % period);
  }
  return offset;
}

template <typename T>
T orFail(nut::Result<T> result, const std::string& what) {
  if (!result) throw SampleError(what + ": " + result.error().message);
  return std::move(result).value();
}

}  // namespace

// ---- Grids and regions --------------------------------------------------------------------

nut::Block makeGrid(const glm::dvec3& size, std::vector<double> cutsX, std::vector<double> cutsY,
                    std::vector<double> cutsZ) {
  nut::Block b;
  b.boundsM[0] = boundariesFromCuts(size.x, std::move(cutsX));
  b.boundsM[1] = boundariesFromCuts(size.y, std::move(cutsY));
  b.boundsM[2] = boundariesFromCuts(size.z, std::move(cutsZ));
  b.cells.assign(static_cast<std::size_t>(b.cellCount(0) * b.cellCount(1) * b.cellCount(2)), nut::Cell::empty());
  return b;
}

nut::Block makeGridFromSizes(const std::vector<double>& sizesX, const std::vector<double>& sizesY,
                             const std::vector<double>& sizesZ) {
  return nut::Block::fromSizes({sizesX, sizesY, sizesZ});
}

Region wholeBlock(const nut::Block& b) { return {glm::dvec3(0.0), b.sizeM()}; }

void fill(nut::Block& b, const Region& r, const nut::Cell& cell) {
  const CellRanges c = rangesOf(b, r);
  // A shaped solid stretches over its one cell: filling several cells with it repeats the shape
  // per cell, which is only what was meant along the extrusion axis of a wedge or cylinder.
  if (cell.kind == nut::CellKind::Solid && cell.solid.index != 0) {
    const nut::SolidGroup g = nut::solidGroup(cell.solid);
    const bool edgeBased = nut::groupOrientationCount(g) == 12;
    const int extrusionAxis = edgeBased ? nut::solidOrientation(cell.solid) / 4 : -1;
    for (int a = 0; a < 3; ++a)
      if (a != extrusionAxis && c.last[static_cast<std::size_t>(a)] - c.first[static_cast<std::size_t>(a)] > 1)
        throw SampleError(nut::solidName(cell.solid) + " over " +
                          std::to_string(c.last[static_cast<std::size_t>(a)] - c.first[static_cast<std::size_t>(a)]) +
                          " cells on axis " + axisName(a) + " (region " + metres(r.min[a]) + " to " + metres(r.max[a]) +
                          "): a shaped solid must fill one cell across its profile");
  }
  fillCells(b, c.first[0], c.last[0], c.first[1], c.last[1], c.first[2], c.last[2], cell);
}

void fillCells(nut::Block& b, int x0, int x1, int y0, int y1, int z0, int z1, const nut::Cell& cell) {
  if (x0 < 0 || y0 < 0 || z0 < 0 || x1 > b.cellCount(0) || y1 > b.cellCount(1) || z1 > b.cellCount(2))
    throw SampleError("cell range outside the block");
  for (int z = z0; z < z1; ++z)
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) b.cell(x, y, z) = cell;
}

void place(const nut::Hierarchy& h, nut::Block& b, const Region& r, nut::Redirection red) {
  const CellRanges c = rangesOf(b, r);
  const glm::dvec3 anchor = r.min + red.offsetM;  // target placement in the block's frame
  for (int z = c.first[2]; z < c.last[2]; ++z)
    for (int y = c.first[1]; y < c.last[1]; ++y)
      for (int x = c.first[0]; x < c.last[0]; ++x) {
        const glm::dvec3 cellMin(b.boundsM[0][static_cast<std::size_t>(x)], b.boundsM[1][static_cast<std::size_t>(y)],
                                 b.boundsM[2][static_cast<std::size_t>(z)]);
        nut::Redirection perCell = red;
        perCell.offsetM = reduceWrappedOffset(h, red, anchor - cellMin);
        b.cell(x, y, z) = nut::Cell::redirect(redirectionIndex(b, perCell));
      }
}

// ---- Solids --------------------------------------------------------------------------------

nut::Solid edgeSolid(nut::SolidGroup group, Side x, Side y, Side z) {
  const std::array<Side, 3> side{x, y, z};
  const auto along = std::count(side.begin(), side.end(), Along);
  if (nut::groupOrientationCount(group) != 12 || along != 1)
    throw SampleError("edgeSolid needs a wedge or quarter-cylinder group and exactly one Along axis");
  const int axis = static_cast<int>(std::find(side.begin(), side.end(), Along) - side.begin());
  const Side u = side[static_cast<std::size_t>((axis + 1) % 3)];
  const Side v = side[static_cast<std::size_t>((axis + 2) % 3)];
  const int corner = (u == Hi ? 1 : 0) | (v == Hi ? 2 : 0);
  return nut::makeSolid(group, axis * 4 + corner);
}

nut::Solid cornerSolid(nut::SolidGroup group, Side x, Side y, Side z) {
  if (nut::groupOrientationCount(group) != 8 || x == Along || y == Along || z == Along)
    throw SampleError("cornerSolid needs a pyramid or octant group and a side on every axis");
  return nut::makeSolid(group, (x == Hi ? 1 : 0) | (y == Hi ? 2 : 0) | (z == Hi ? 4 : 0));
}

// ---- Rotations and placement ---------------------------------------------------------------

nut::Rotation turnAboutY(int quarterTurns) {
  // Counter-clockwise seen from above (right-handed about +y): x -> (c, 0, -s), z -> (s, 0, c).
  static constexpr int kCos[4] = {1, 0, -1, 0};
  static constexpr int kSin[4] = {0, 1, 0, -1};
  const int q = ((quarterTurns % 4) + 4) % 4;
  return findCubeRotation({kCos[q], 0, -kSin[q]}, {0, 1, 0}, {kSin[q], 0, kCos[q]});
}

nut::Rotation cubeRotationMapping(const glm::ivec3& imageOfX, const glm::ivec3& imageOfY) {
  const glm::ivec3 imageOfZ(imageOfX.y * imageOfY.z - imageOfX.z * imageOfY.y,
                            imageOfX.z * imageOfY.x - imageOfX.x * imageOfY.z,
                            imageOfX.x * imageOfY.y - imageOfX.y * imageOfY.x);
  return findCubeRotation(imageOfX, imageOfY, imageOfZ);
}

nut::Rotation yawSteps(int steps) {
  if (steps < 0 || steps > 0xffff) throw SampleError("yaw steps out of range");
  return nut::Rotation{0, static_cast<std::uint16_t>(steps)};
}

nut::Redirection rotatedFit(const nut::Hierarchy& h, nut::BlockId target, nut::Rotation rotation, glm::dvec3 shiftM) {
  const glm::dvec3 size = h.blocks.at(target).sizeM();
  const glm::dmat3 r = nut::rotationMatrix(rotation);
  glm::dvec3 low(std::numeric_limits<double>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? size.x : 0.0, (corner & 2) ? size.y : 0.0, (corner & 4) ? size.z : 0.0);
    low = glm::min(low, r * p);
  }
  nut::Redirection red;
  red.target = target;
  red.rotation = rotation;
  red.offsetM = shiftM - low;
  return red;
}

nut::Redirection pinned(nut::BlockId target, nut::Rotation rotation, const glm::dvec3& targetPoint,
                        const glm::dvec3& regionPoint) {
  nut::Redirection red;
  red.target = target;
  red.rotation = rotation;
  red.offsetM = regionPoint - nut::rotationMatrix(rotation) * targetPoint;
  return red;
}

nut::Redirection showing(nut::BlockId target, bool wrapX, bool wrapY, bool wrapZ, glm::dvec3 offsetM) {
  nut::Redirection red;
  red.target = target;
  red.offsetM = offsetM;
  red.wrap = {wrapX, wrapY, wrapZ};
  return red;
}

// ---- Pipeline ------------------------------------------------------------------------------

SampleSummary writeSample(const nut::Hierarchy& h, const std::string& outDir, const std::string& fileName,
                          const std::string& title) {
  const std::string where = fileName;
  if (nut::Status s = nut::checkHierarchy(h); !s) throw SampleError(where + ": " + s.error().message);
  const std::vector<bool> reachable = reachableBlocks(h);
  for (std::size_t b = 0; b < reachable.size(); ++b)
    if (!reachable[b]) throw SampleError(where + ": block " + std::to_string(b) + " is not used by the root");

  const nut::Image image = orFail(nut::compile(h), where + ": compile");
  if (nut::Status s = nut::validate(image); !s)
    throw SampleError(where + ": the compiled image does not validate (a bug in the core): " + s.error().message);
  nut::Hierarchy decoded = orFail(nut::decode(image), where + ": decode (a bug in the core)");

  // compile fills in the visual summaries; everything else must come back exactly as quantized.
  nut::Hierarchy expected = nut::quantized(h);
  for (nut::Block& b : expected.blocks) b.summary.reset();
  for (nut::Block& b : decoded.blocks) b.summary.reset();
  if (const std::string diff = firstDifference(expected, decoded); !diff.empty())
    throw SampleError(where + ": decode(compile(h)) != quantized(h) (a bug in the core): " + diff);

  const std::string path = (std::filesystem::path(outDir) / fileName).string();
  nut::HniText text;
  text.name = title;
  text.generator = "nut make_samples";
  // text.units keeps its default, "m" (assigning the literal trips a GCC 12 -Wrestrict false positive).
  text.originM = glm::dvec3(0.0);
  if (nut::Status s = nut::writeHni(path, image, text); !s) throw SampleError(where + ": " + s.error().message);
  const nut::PngFile reread = orFail(nut::readPng(path), where + ": reading back");
  if (!(reread.image == image)) throw SampleError(where + ": the PNG read back differs from the compiled image");

  const nut::HniStats stats = nut::computeStats(image);
  if (stats.dagDepth != nut::dagDepth(h))
    throw SampleError(where + ": image DAG depth " + std::to_string(stats.dagDepth) + " != model depth " +
                      std::to_string(nut::dagDepth(h)));
  SampleSummary summary;
  summary.file = fileName;
  summary.width = stats.width;
  summary.height = stats.height;
  summary.bytesRaw = stats.bytesRaw;
  summary.bytesPng = static_cast<long long>(std::filesystem::file_size(path));
  summary.wastePct = stats.wastePct;
  summary.blocks = stats.blocks;
  summary.dagDepth = stats.dagDepth;
  return summary;
}

std::string describe(const SampleSummary& s) {
  char line[256];
  std::snprintf(line, sizeof line, "%s: %dx%d px, raw %lld B, PNG %lld B, waste %.1f%%, %d blocks, DAG depth %d",
                s.file.c_str(), s.width, s.height, s.bytesRaw, s.bytesPng, s.wastePct, s.blocks, s.dagDepth);
  return line;
}

}  // namespace samples
