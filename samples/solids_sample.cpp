// samples/solids_sample.cpp — a showcase of the 69 cell solids and of rotated redirections.
//
// On a 16 m x 12 m plinth with rounded edges (quarter cylinders, sphere-octant corners):
//  - a display cabinet at the back holding every solid of the catalogue, one shelf per group
//    (box, wedges, pyramids, inverse pyramids, quarter cylinders and their inverses, sphere
//    octants and their inverses), each group in its own colour;
//  - a domed pavilion: round corners from quarter cylinders, concave fillets from inverse quarter
//    cylinders at the foot of the walls, four arched portals (one block turned by the four cube
//    rotations about y), a ball statue of eight octants, a dome of four sphere octants and a
//    pyramid finial seen through a 45-degree yaw;
//  - a gatehouse turned 22.5 degrees (a free yaw), with a hipped roof of wedges and corner pyramids
//    (the hipped ends: a square pyramid of four corner pyramids seen through a 45-degree yaw);
//  - a standing column and the same column fallen over (a cube rotation that is not about y).
#include <numbers>

#include "sample_kit.hpp"
#include "samples.hpp"

namespace samples {

namespace {

using nut::BlockId;
using nut::Cell;
using nut::SolidGroup;

constexpr double kPlinthH = 0.5;
constexpr int kYaw45 = 8192;  // 1/8 turn, exact in the format's 1/65536-turn steps
constexpr int kYaw22_5 = 4096;
constexpr double kPortalH = 3.0;

struct Palette {
  std::uint16_t plinth, wood, marble, ochre, copper, tiles;
  std::uint16_t group[8];  // by nut::SolidGroup
};

Palette makePalette(nut::Hierarchy& h) {
  Palette p{};
  p.plinth = colour(h, 120, 118, 112);
  p.wood = colour(h, 112, 80, 52);
  p.marble = colour(h, 236, 232, 222);
  p.ochre = colour(h, 214, 170, 104);
  p.copper = colour(h, 96, 160, 136);  // weathered copper dome
  p.tiles = colour(h, 176, 84, 56);    // terracotta roof
  // One hue per family, the inverse group a darker shade of its solid group.
  p.group[static_cast<int>(SolidGroup::Box)] = colour(h, 200, 200, 204);
  p.group[static_cast<int>(SolidGroup::Wedge)] = colour(h, 226, 124, 58);
  p.group[static_cast<int>(SolidGroup::Pyramid)] = colour(h, 236, 204, 72);
  p.group[static_cast<int>(SolidGroup::InversePyramid)] = colour(h, 168, 146, 52);
  p.group[static_cast<int>(SolidGroup::QuarterCylinder)] = colour(h, 74, 152, 214);
  p.group[static_cast<int>(SolidGroup::InverseQuarterCylinder)] = colour(h, 52, 96, 160);
  p.group[static_cast<int>(SolidGroup::SphereOctant)] = colour(h, 210, 84, 124);
  p.group[static_cast<int>(SolidGroup::InverseSphereOctant)] = colour(h, 136, 58, 108);
  return p;
}

// ---------------------------------- The solid cabinet ----------------------------------

constexpr double kSolidSize = 0.7, kGap = 0.15;
constexpr double kShelfDepth = 0.75, kBackPanel = 0.1;
constexpr double kCabinetRowWidth = 12 * (kGap + kSolidSize) + kGap;  // room for the widest group

// One shelf's worth: every orientation of one group, 0.7 m cubes 0.15 m apart, in index order.
BlockId addGroupRow(nut::Hierarchy& h, const Palette& p, SolidGroup group) {
  const int count = nut::groupOrientationCount(group);
  std::vector<double> sizesX;
  for (int i = 0; i < count; ++i) sizesX.insert(sizesX.end(), {kGap, kSolidSize});
  sizesX.push_back(kGap);
  nut::Block b = makeGridFromSizes(sizesX, {kSolidSize}, {kSolidSize});
  for (int i = 0; i < count; ++i)
    b.cell(2 * i + 1, 0, 0) = solidCell(nut::makeSolid(group, i), p.group[static_cast<int>(group)]);
  return h.addBlock(std::move(b));
}

// A wooden cabinet with eight shelves, the groups from the inverse octants at the bottom to the
// box at the top, each row centred on its shelf.
BlockId addCabinet(nut::Hierarchy& h, const Palette& p) {
  const SolidGroup bottomToTop[] = {SolidGroup::InverseSphereOctant,
                                    SolidGroup::SphereOctant,
                                    SolidGroup::InverseQuarterCylinder,
                                    SolidGroup::QuarterCylinder,
                                    SolidGroup::InversePyramid,
                                    SolidGroup::Pyramid,
                                    SolidGroup::Wedge,
                                    SolidGroup::Box};
  const double side = 0.15, width = kCabinetRowWidth + 2 * side, depth = kBackPanel + kShelfDepth;
  const double rowPitch = kSolidSize + kGap, height = kGap + 8 * rowPitch;
  std::vector<double> cutsY;
  for (int row = 0; row < 8; ++row)
    cutsY.insert(cutsY.end(), {kGap + row * rowPitch, kGap + row * rowPitch + kSolidSize});
  nut::Block b = makeGrid({width, height, depth}, {side, width - side}, cutsY, {kBackPanel});
  fill(b, wholeBlock(b), Cell::box(p.wood));  // the carcass; the shelves' spaces are cut out below
  for (int row = 0; row < 8; ++row) {
    const double y0 = kGap + row * rowPitch;
    const Region space = region(side, y0, kBackPanel, width - side, y0 + kSolidSize, depth);
    fill(b, space, Cell::empty());
    const BlockId groupRow = addGroupRow(h, p, bottomToTop[row]);
    const double rowWidth = h.blocks[groupRow].sizeM().x;
    const glm::dvec3 centred((kCabinetRowWidth - rowWidth) / 2, 0, (kShelfDepth - kSolidSize) / 2);
    place(h, b, space, showing(groupRow, false, false, false, centred));
  }
  return h.addBlock(std::move(b));
}

// ---------------------------------- The pavilion ----------------------------------

// An arched portal (3 m x 3 m x 0.5 m) facing +z: two piers and a semicircular arch cut by two
// inverse quarter cylinders whose axis is the arch's centre line.
BlockId addPortal(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.6, 0.9, 0.9, 0.6}, {kPortalH - 0.9, 0.9}, {0.5});
  fillCells(b, 0, 1, 0, 2, 0, 1, Cell::box(p.marble));
  fillCells(b, 3, 4, 0, 2, 0, 1, Cell::box(p.marble));
  b.cell(1, 1, 0) = coveCylinder(Hi, Lo, Along, p.marble);
  b.cell(2, 1, 0) = coveCylinder(Lo, Lo, Along, p.marble);
  return h.addBlock(std::move(b));
}

// A ball of eight sphere octants (0.5 m radius) on a cubic pedestal.
BlockId addStatue(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5});
  fillCells(b, 0, 2, 0, 1, 0, 2, Cell::box(p.marble));
  for (int x = 0; x < 2; ++x)
    for (int y = 1; y < 3; ++y)
      for (int z = 0; z < 2; ++z)  // each octant's corner is the ball's centre
        b.cell(x, y, z) = octant(x == 0 ? Hi : Lo, y == 1 ? Hi : Lo, z == 0 ? Hi : Lo, p.copper);
  return h.addBlock(std::move(b));
}

// The pavilion's body with its fillets (4.6 m x 3 m x 4.6 m): quarter-cylinder corner columns,
// the portal on all four sides (turned 0, 90, 180 and 270 degrees about y), concave fillets of
// inverse quarter cylinders in the angle between the floor and each wall's straight part, and the
// statue in the middle.
BlockId addPavilionBody(nut::Hierarchy& h, const Palette& p, BlockId portal, BlockId statue) {
  const double f = 0.3;  // fillet radius
  const double c = 0.5;  // corner radius
  const double w = 3.0;  // straight wall (a portal)
  const double a = f + c, bEnd = a + w, size = bEnd + c + f;  // 0.8, 3.8, 4.6
  nut::Block b = makeGridFromSizes({f, c, w, c, f}, {f, kPortalH - f}, {f, c, w, c, f});
  fill(b, region(f, 0, f, a, kPortalH, a), quarterCylinder(Hi, Along, Hi, p.marble));  // round outside
  fill(b, region(bEnd, 0, f, size - f, kPortalH, a), quarterCylinder(Lo, Along, Hi, p.marble));
  fill(b, region(f, 0, bEnd, a, kPortalH, size - f), quarterCylinder(Hi, Along, Lo, p.marble));
  fill(b, region(bEnd, 0, bEnd, size - f, kPortalH, size - f), quarterCylinder(Lo, Along, Lo, p.marble));
  place(h, b, region(a, 0, bEnd, bEnd, kPortalH, size - f), showing(portal));
  place(h, b, region(bEnd, 0, a, size - f, kPortalH, bEnd), rotatedFit(h, portal, turnAboutY(1)));
  place(h, b, region(a, 0, f, bEnd, kPortalH, a), rotatedFit(h, portal, turnAboutY(2)));
  place(h, b, region(f, 0, a, a, kPortalH, bEnd), rotatedFit(h, portal, turnAboutY(3)));
  // Each fillet hugs the wall and the floor: the removed quarter disc is centred on the far edge.
  fill(b, region(0, 0, a, f, f, bEnd), coveCylinder(Lo, Hi, Along, p.marble));
  fill(b, region(size - f, 0, a, size, f, bEnd), coveCylinder(Hi, Hi, Along, p.marble));
  fill(b, region(a, 0, 0, bEnd, f, f), coveCylinder(Along, Hi, Lo, p.marble));
  fill(b, region(a, 0, size - f, bEnd, f, size), coveCylinder(Along, Hi, Hi, p.marble));
  place(h, b, region(a, 0, a, bEnd, kPortalH, bEnd), showing(statue, false, false, false, {1.0, 0, 1.0}));
  return h.addBlock(std::move(b));
}

// The cornice slab over the body, 0.3 m overhang, its corners rounded by quarter cylinders.
BlockId addPavilionCornice(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.8, 3.0, 0.8}, {0.3}, {0.8, 3.0, 0.8});
  fill(b, wholeBlock(b), Cell::box(p.marble));
  b.cell(0, 0, 0) = quarterCylinder(Hi, Along, Hi, p.marble);
  b.cell(2, 0, 0) = quarterCylinder(Lo, Along, Hi, p.marble);
  b.cell(0, 0, 2) = quarterCylinder(Hi, Along, Lo, p.marble);
  b.cell(2, 0, 2) = quarterCylinder(Lo, Along, Lo, p.marble);
  return h.addBlock(std::move(b));
}

// A hemispherical dome of radius 1.6 m: four sphere octants meeting at its centre.
BlockId addDome(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.6, 1.6}, {1.6}, {1.6, 1.6});
  for (int x = 0; x < 2; ++x)
    for (int z = 0; z < 2; ++z) b.cell(x, 0, z) = octant(x == 0 ? Hi : Lo, Lo, z == 0 ? Hi : Lo, p.copper);
  return h.addBlock(std::move(b));
}

// A square pyramid drawn as a diamond: four corner pyramids around the centre of a 2d x 2d
// block. Seen through a 45-degree yaw it is an axis-aligned pyramid of side d * sqrt(2).
BlockId addDiamondPyramid(nut::Hierarchy& h, std::uint16_t material, double d, double height) {
  nut::Block b = makeGridFromSizes({d, d}, {height}, {d, d});
  for (int x = 0; x < 2; ++x)
    for (int z = 0; z < 2; ++z) b.cell(x, 0, z) = pyramid(x == 0 ? Hi : Lo, Lo, z == 0 ? Hi : Lo, material);
  return h.addBlock(std::move(b));
}

// The pavilion (6 m x 5.7 m x 6 m) as a stack of one-cell rows, each piece placed by its offset
// (one redirection record each): podium, body, cornice, dome, and the finial seen through a
// 45-degree yaw with its base centred on the dome's top.
BlockId addPavilion(nut::Hierarchy& h, const Palette& p, BlockId body, BlockId cornice, BlockId dome, BlockId finial) {
  const double size = 6.0, podium = 0.3, bodyTop = podium + kPortalH, corniceTop = bodyTop + 0.3;
  const double domeTop = corniceTop + 1.6, top = domeTop + 0.5;
  nut::Block b = makeGrid({size, top, size}, {}, {podium, bodyTop, corniceTop, domeTop}, {});
  const auto centred = [&](BlockId target) {
    const double inset = (size - h.blocks[target].sizeM().x) / 2;
    return showing(target, false, false, false, {inset, 0, inset});
  };
  fill(b, region(0, 0, 0, size, podium, size), Cell::box(p.plinth));
  place(h, b, region(0, podium, 0, size, bodyTop, size), centred(body));
  place(h, b, region(0, bodyTop, 0, size, corniceTop, size), centred(cornice));
  place(h, b, region(0, corniceTop, 0, size, domeTop, size), centred(dome));
  const double d = h.blocks[finial].sizeM().x / 2;
  place(h, b, region(0, domeTop, 0, size, top, size),
        pinned(finial, yawSteps(kYaw45), {d, 0, d}, {size / 2, 0, size / 2}));
  return h.addBlock(std::move(b));
}

// ---------------------------------- The gatehouse ----------------------------------

// The gatehouse walls (4 m x 3 m x 3 m) with the same portal front and back: a gate passage.
BlockId addGatehouseBody(nut::Hierarchy& h, const Palette& p, BlockId portal) {
  nut::Block b = makeGridFromSizes({0.5, 3.0, 0.5}, {3.0}, {0.5, 2.0, 0.5});
  fill(b, wholeBlock(b), Cell::box(p.ochre));
  b.cell(1, 0, 1) = Cell::empty();
  place(h, b, region(0.5, 0, 2.5, 3.5, 3.0, 3.0), showing(portal));
  place(h, b, region(0.5, 0, 0, 3.5, 3.0, 0.5), rotatedFit(h, portal, turnAboutY(2)));
  return h.addBlock(std::move(b));
}

// The gatehouse's hipped roof (4.4 m x 1 m x 3.4 m, 0.2 m eaves): wedges over the middle, the
// diamond pyramid through a 45-degree yaw at the two hipped ends. It is a block of its own so
// that the walls' cuts at the eaves do not split the wedges (a wedge must fill one cell).
BlockId addGatehouseRoof(nut::Hierarchy& h, const Palette& p, BlockId hip) {
  const double width = 4.4, depth = 3.4, half = depth / 2, rise = 1.0;
  nut::Block b = makeGrid({width, rise, depth}, {half, width - half}, {}, {half});
  fill(b, region(half, 0, 0, width - half, rise, half), wedge(Along, Lo, Hi, p.tiles));
  fill(b, region(half, 0, half, width - half, rise, depth), wedge(Along, Lo, Lo, p.tiles));
  const double d = h.blocks[hip].sizeM().x / 2;
  place(h, b, region(0, 0, 0, half, rise, depth), pinned(hip, yawSteps(kYaw45), {d, 0, d}, {half, 0, half}));
  place(h, b, region(width - half, 0, 0, width, rise, depth), pinned(hip, yawSteps(kYaw45), {d, 0, d}, {0, 0, half}));
  return h.addBlock(std::move(b));
}

// The gatehouse (4.4 m x 4 m x 3.4 m): the walls under the roof.
BlockId addGatehouse(nut::Hierarchy& h, BlockId body, BlockId roof) {
  const double width = 4.4, depth = 3.4, wall = 3.0, top = 4.0;
  nut::Block b = makeGrid({width, top, depth}, {0.2, 4.2}, {wall}, {0.2, 3.2});
  place(h, b, region(0.2, 0, 0.2, 4.2, wall, 3.2), showing(body));
  place(h, b, region(0, wall, 0, width, top, depth), showing(roof));
  return h.addBlock(std::move(b));
}

// ---------------------------------- Column and plinth ----------------------------------

// A 4 m column: square base and capital, a round shaft of four quarter cylinders (0.3 m radius).
BlockId addColumn(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.1, 0.3, 0.3, 0.1}, {0.25, 3.5, 0.25}, {0.1, 0.3, 0.3, 0.1});
  fillCells(b, 0, 4, 0, 1, 0, 4, Cell::box(p.marble));
  fillCells(b, 0, 4, 2, 3, 0, 4, Cell::box(p.marble));
  b.cell(1, 1, 1) = quarterCylinder(Hi, Along, Hi, p.marble);
  b.cell(2, 1, 1) = quarterCylinder(Lo, Along, Hi, p.marble);
  b.cell(1, 1, 2) = quarterCylinder(Hi, Along, Lo, p.marble);
  b.cell(2, 1, 2) = quarterCylinder(Lo, Along, Lo, p.marble);
  return h.addBlock(std::move(b));
}

// The 16 m x 0.5 m x 12 m plinth, its top edges rounded (0.2 m quarter cylinders) and its top
// corners sphere octants, which is exactly the corner of a rounded box.
BlockId addPlinth(nut::Hierarchy& h, const Palette& p) {
  const double r = 0.2, w = 16.0, d = 12.0, low = kPlinthH - r;
  nut::Block b = makeGrid({w, kPlinthH, d}, {r, w - r}, {low}, {r, d - r});
  fill(b, wholeBlock(b), Cell::box(p.plinth));
  fill(b, region(r, low, d - r, w - r, kPlinthH, d), quarterCylinder(Along, Lo, Lo, p.plinth));
  fill(b, region(r, low, 0, w - r, kPlinthH, r), quarterCylinder(Along, Lo, Hi, p.plinth));
  fill(b, region(0, low, r, r, kPlinthH, d - r), quarterCylinder(Hi, Lo, Along, p.plinth));
  fill(b, region(w - r, low, r, w, kPlinthH, d - r), quarterCylinder(Lo, Lo, Along, p.plinth));
  fill(b, region(0, low, 0, r, kPlinthH, r), octant(Hi, Lo, Hi, p.plinth));
  fill(b, region(w - r, low, 0, w, kPlinthH, r), octant(Lo, Lo, Hi, p.plinth));
  fill(b, region(0, low, d - r, r, kPlinthH, d), octant(Hi, Lo, Lo, p.plinth));
  fill(b, region(w - r, low, d - r, w, kPlinthH, d), octant(Lo, Lo, Lo, p.plinth));
  return h.addBlock(std::move(b));
}

}  // namespace

nut::Hierarchy buildSolidsSample() {
  nut::Hierarchy h;
  const Palette p = makePalette(h);
  const BlockId plinth = addPlinth(h, p);
  const BlockId cabinet = addCabinet(h, p);
  const BlockId portal = addPortal(h, p);
  const BlockId pavilion = addPavilion(h, p, addPavilionBody(h, p, portal, addStatue(h, p)), addPavilionCornice(h, p),
                                       addDome(h, p), addDiamondPyramid(h, p.copper, 0.15 * std::numbers::sqrt2, 0.5));
  const BlockId gatehouseRoof = addGatehouseRoof(h, p, addDiamondPyramid(h, p.tiles, 1.7 * std::numbers::sqrt2, 1.0));
  const BlockId gatehouse = addGatehouse(h, addGatehouseBody(h, p, portal), gatehouseRoof);
  const BlockId column = addColumn(h, p);

  // Two strips in front of the cabinet, each a block of two cells whose pieces are placed by offset.
  // The colonnade: a standing column and the same column fallen over, by the cube rotation that
  // takes its axis (+y) to +x (and +x to -y): a rotation that is not about y.
  const double colonnadeDepth = 1.75, forecourtDepth = 7.8;
  nut::Block colonnade = makeGrid({16.0, 4.0, colonnadeDepth}, {7.5}, {}, {});
  place(h, colonnade, region(0, 0, 0, 7.5, 4.0, colonnadeDepth),
        rotatedFit(h, column, cubeRotationMapping({0, -1, 0}, {1, 0, 0}), {1.5, 0, 0.35}));
  place(h, colonnade, region(7.5, 0, 0, 16.0, 4.0, colonnadeDepth),
        showing(column, false, false, false, {2.0, 0, 0.35}));
  const BlockId colonnadeId = h.addBlock(std::move(colonnade));
  // The forecourt: the pavilion, and the gatehouse turned 22.5 degrees about its own centre.
  nut::Block forecourt = makeGrid({16.0, 5.7, forecourtDepth}, {7.75}, {}, {});
  place(h, forecourt, region(0, 0, 0, 7.75, 5.7, forecourtDepth),
        showing(pavilion, false, false, false, {1.0, 0, 0.9}));
  place(h, forecourt, region(7.75, 0, 0, 16.0, 5.7, forecourtDepth),
        pinned(gatehouse, yawSteps(kYaw22_5), {2.2, 0, 1.7}, {4.25, 0, forecourtDepth / 2}));
  const BlockId forecourtId = h.addBlock(std::move(forecourt));

  // The root: the plinth, and above it the cabinet, the colonnade and the forecourt from back to front.
  const double top = kPlinthH + h.blocks[cabinet].sizeM().y, backStrip = 1.85;
  const double colonnadeEnd = backStrip + colonnadeDepth, forecourtEnd = colonnadeEnd + forecourtDepth;
  nut::Block root = makeGrid({16.0, top, 12.0}, {}, {kPlinthH}, {backStrip, colonnadeEnd, forecourtEnd});
  place(h, root, region(0, 0, 0, 16.0, kPlinthH, 12.0), showing(plinth));
  place(h, root, region(0, kPlinthH, 0, 16.0, top, backStrip), showing(cabinet, false, false, false, {2.7, 0, 0.5}));
  place(h, root, region(0, kPlinthH, backStrip, 16.0, top, colonnadeEnd), showing(colonnadeId));
  place(h, root, region(0, kPlinthH, colonnadeEnd, 16.0, top, forecourtEnd), showing(forecourtId));
  h.root = h.addBlock(std::move(root));
  return h;
}

}  // namespace samples
