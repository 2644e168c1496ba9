// samples/rotations_sample.cpp — every one of the 24 cube rotations of a redirection record.
//
// One small "tripod" block (1.2 m x 0.9 m x 0.6 m, so that its axes differ in size too) holds a
// white hub box at its origin corner, a red box along +x, a green box along +y, a blue box along
// +z and a yellow wedge between the x and y arms whose right-angle edge runs along z at the hub.
// The root is a 6 x 4 grid of 1.2 m display cubes on a grey base slab; the display cube of index
// r (row-major, x fastest) shows the tripod turned by cube rotation r, placed so that the turned
// block starts at the cube's minimum corner. Seen from above, the colours of the arms tell the
// images of the axes, so every matrix of docs/FORMAT.md can be checked by eye, and
// tests/format_spec_test.cpp checks them by ray.
#include "sample_kit.hpp"
#include "samples.hpp"

namespace samples {

namespace {

using nut::BlockId;
using nut::Cell;

constexpr double kHub = 0.3;        // the hub cell's size along every axis
constexpr double kDisplay = 1.2;    // a display cube: holds the tripod in any rotation
constexpr double kGap = 0.3;        // between display cubes
constexpr double kBase = 0.2;       // the base slab's thickness
constexpr int kColumns = 6, kRows = 4;

// The tripod: cells of 0.3 m at the origin, then the arms (0.9 m along x, 0.6 m along y, 0.3 m
// along z).
BlockId addTripod(nut::Hierarchy& h) {
  const std::uint16_t white = colour(h, 236, 236, 236), red = colour(h, 214, 48, 40), green = colour(h, 52, 168, 72),
                      blue = colour(h, 40, 88, 214), yellow = colour(h, 232, 196, 40);
  nut::Block b = makeGridFromSizes({kHub, 0.9}, {kHub, 0.6}, {kHub, 0.3});
  b.cell(0, 0, 0) = Cell::box(white);
  b.cell(1, 0, 0) = Cell::box(red);
  b.cell(0, 1, 0) = Cell::box(green);
  b.cell(0, 0, 1) = Cell::box(blue);
  b.cell(1, 1, 0) = wedge(Lo, Lo, Along, yellow);
  return h.addBlock(std::move(b));
}

}  // namespace

nut::Hierarchy buildRotationsSample() {
  nut::Hierarchy h;
  const std::uint16_t grey = colour(h, 128, 124, 118);
  const BlockId tripod = addTripod(h);
  std::vector<double> sizesX{kGap}, sizesZ{kGap};
  for (int c = 0; c < kColumns; ++c) sizesX.insert(sizesX.end(), {kDisplay, kGap});
  for (int r = 0; r < kRows; ++r) sizesZ.insert(sizesZ.end(), {kDisplay, kGap});
  nut::Block root = makeGridFromSizes(sizesX, {kBase, kDisplay}, sizesZ);
  fillCells(root, 0, root.cellCount(0), 0, 1, 0, root.cellCount(2), Cell::box(grey));
  for (int index = 0; index < kColumns * kRows; ++index) {
    const int x = 2 * (index % kColumns) + 1, z = 2 * (index / kColumns) + 1;
    const nut::Rotation rotation{static_cast<std::uint8_t>(index), 0};
    const double x0 = root.boundsM[0][static_cast<std::size_t>(x)], z0 = root.boundsM[2][static_cast<std::size_t>(z)];
    place(h, root, region(x0, kBase, z0, x0 + kDisplay, kBase + kDisplay, z0 + kDisplay),
          rotatedFit(h, tripod, rotation));
  }
  h.root = h.addBlock(std::move(root));
  return h;
}

}  // namespace samples
