// nut/hierarchy.hpp — the editable NUT model: a DAG of non-uniform 3D grids (blocks).
//
// Producers (the mesh converter, the grammar compiler, hand-written samples) build a Hierarchy;
// compile() turns it into an HNI image and decode() turns an image back into it. Lengths are metres
// here; the encoding stores integer millimetres, so compile rounds every boundary position and
// offset to the nearest millimetre (docs/FORMAT.md, "Units"). A Hierarchy that is already on the
// millimetre grid round-trips exactly.
//
// Frames: a block's local frame has its origin at the block's minimum corner and its axes along
// the block's axes; cell (x, y, z) spans [bounds[0][x], bounds[0][x+1]] x ... in that frame.
// A redirection cell shows its target block placed at `offsetM` from the cell's minimum corner
// and rotated by `rotation` about the target's origin: for a point p in the cell's frame (relative
// to the cell's minimum corner), the target-local point is  inverse(R) * (p - offset).
// The target is clipped by the cell, and repeats along the target's axes whose wrap flag is set.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/error.hpp>
#include <nut/plane_cells.hpp>
#include <nut/solids.hpp>

namespace nut {

using BlockId = std::uint32_t;

struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 0;
  friend bool operator==(const Rgba8&, const Rgba8&) = default;
};

struct Material {
  std::uint8_t r = 200, g = 200, b = 200;  // diffuse colour, sRGB
  std::uint8_t opacity = 255;              // 255 = opaque; less tints the ray and lets it continue
  std::uint8_t reflectance = 0;            // 0..255 -> 0..1, carried for renderers that use it
  friend bool operator==(const Material&, const Material&) = default;
};

// A texture placed on a cell by a 3D offset (paper 4.3); the texture's physical size comes from
// the texture table of whoever renders it.
struct TextureInfo {
  glm::dvec3 offsetM{0.0};
  std::uint16_t textureId = 0;
  friend bool operator==(const TextureInfo&, const TextureInfo&) = default;
};

// A rotation of a redirected block: one of the 24 axis-aligned rotations of the cube, followed by
// a free yaw about the parent's y (up) axis in 1/65536 turns. R = yaw * cube.
struct Rotation {
  std::uint8_t cube = 0;   // 0..23, see cubeRotationMatrix(); 0 is the identity
  std::uint16_t yaw = 0;   // fraction of a full turn about +y, counter-clockwise seen from above
  friend bool operator==(const Rotation&, const Rotation&) = default;
};

// The 24 rotations of the cube as integer matrices (columns are images of the x, y, z axes).
glm::mat<3, 3, int> cubeRotationMatrix(int index);
glm::dmat3 rotationMatrix(const Rotation& r);

// The solid whose region is the image of s's region under cube rotation `cube` about the unit
// cube's centre: what a cell holding s looks like from a block turned by that rotation. Used to
// re-express a block in another axis order (the same group, another orientation).
Solid rotateSolid(Solid s, int cube);

struct Redirection {
  BlockId target = 0;
  glm::dvec3 offsetM{0.0};            // target origin relative to the cell's minimum corner
  Rotation rotation;
  std::array<bool, 3> wrap{false, false, false};  // tile the target along its x, y, z axes
  friend bool operator==(const Redirection&, const Redirection&) = default;
};

// Plane: the cell's box cut by the planes of one of its block's PlaneCuts (plane_cells.hpp).
enum class CellKind : std::uint8_t { Empty, Redirection, Solid, Plane };

struct Cell {
  CellKind kind = CellKind::Empty;
  Solid solid;                        // when kind == Solid
  std::uint16_t material = 0;         // index into Hierarchy::materials (solids and plane cells)
  std::uint8_t texture = 0;           // 0 = none, n = Hierarchy::textures[n - 1]
  std::uint32_t redirection = 0;      // index into Block::redirections (redirection cells)
  std::uint32_t cut = 0;              // index into Block::cuts (plane cells)

  static Cell empty() { return {}; }
  static Cell solidCell(Solid s, std::uint16_t material, std::uint8_t texture = 0) {
    return {CellKind::Solid, s, material, texture, 0, 0};
  }
  static Cell box(std::uint16_t material) { return solidCell(Solid{0}, material); }
  static Cell redirect(std::uint32_t redirectionIndex) {
    return {CellKind::Redirection, Solid{}, 0, 0, redirectionIndex, 0};
  }
  static Cell planeCell(std::uint32_t cutIndex, std::uint16_t material, std::uint8_t texture = 0) {
    return {CellKind::Plane, Solid{}, material, texture, 0, cutIndex};
  }
  // Whether material and texture mean something: solids and plane cells.
  bool hasMaterial() const { return kind == CellKind::Solid || kind == CellKind::Plane; }
  friend bool operator==(const Cell&, const Cell&) = default;
};

// Colour of one side of a block seen from outside (level of detail); a = covered fraction.
using VisualSummary = std::array<Rgba8, 6>;  // +x, -x, +y, -y, +z, -z

struct Block {
  // Boundary positions per axis in metres, from 0 to the block size, strictly increasing;
  // axis a has bounds[a].size() - 1 cells.
  std::array<std::vector<double>, 3> boundsM;
  std::vector<Cell> cells;                 // x fastest, then y, then z
  std::vector<Redirection> redirections;   // referenced by redirection cells
  std::vector<PlaneCut> cuts;              // referenced by plane cells, in this block's frame
  // Producers may supply the summary (e.g. from a grammar's own subtree); otherwise compile
  // computes it from the content. decode() fills it from the image.
  std::optional<VisualSummary> summary;
  // Level of detail: where one pixel spans more than this many metres at the block, its visual
  // summary may stand in for it (measureLevelOfDetail, lod.hpp); 0 = never. Stored in the records
  // that redirect to the block, so the root's is not kept.
  double lodFootprintM = 0.0;

  // A block of the given per-axis cell sizes (metres), all cells empty.
  static Block fromSizes(const std::array<std::vector<double>, 3>& sizesM);

  int cellCount(int axis) const { return static_cast<int>(boundsM[axis].size()) - 1; }
  glm::dvec3 sizeM() const { return {boundsM[0].back(), boundsM[1].back(), boundsM[2].back()}; }
  std::size_t cellIndex(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(cellCount(0)) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(cellCount(1)) * z);
  }
  Cell& cell(int x, int y, int z) { return cells[cellIndex(x, y, z)]; }
  const Cell& cell(int x, int y, int z) const { return cells[cellIndex(x, y, z)]; }

  friend bool operator==(const Block&, const Block&) = default;
};

struct Hierarchy {
  std::vector<Block> blocks;
  std::vector<Material> materials;
  std::vector<TextureInfo> textures;
  BlockId root = 0;

  BlockId addBlock(Block b) {
    blocks.push_back(std::move(b));
    return static_cast<BlockId>(blocks.size() - 1);
  }
  std::uint16_t addMaterial(const Material& m);  // returns the index of an equal one if present

  friend bool operator==(const Hierarchy&, const Hierarchy&) = default;
};

// Structural checks of the model, before any encoding: bounds increasing, cell counts, indices in
// range, no cycles. The message names the block, axis or cell.
Status checkHierarchy(const Hierarchy& h);

// Depth of the DAG below the root: 0 for a root without redirections.
int dagDepth(const Hierarchy& h);

// The hierarchy snapped to the encoding's millimetre grid: what decode(compile(h)) returns,
// except for summaries, which compile fills in.
Hierarchy quantized(const Hierarchy& h);

}  // namespace nut
