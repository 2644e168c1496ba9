// samples/building_sample.cpp — a four-storey mixed-use corner building with a hipped slate roof,
// built by hand from 80 NUT blocks (compare the paper's Figure 12: 40 NUTs).
//
// 22.7 m x 15.4 m footprint (7 x 4 bays of 3 m inside 0.4 m walls), shops and an entrance on the
// ground floor, three floors of flats with pedimented windows, balconies and a staircase at the
// back, rusticated ground floor, quoined corner pilasters, a cornice that turns the corners, and a
// hipped roof with dormers, a ridge cap and a chimney. Behind every window there are floor slabs,
// partition and corridor walls (and the staircase), so a camera looking in sees rooms.
//
// Frames. Every facade piece (window, bay, row, facade) is drawn facing +z: x runs left to right
// as seen from outside, y up, z = 0 at the wall's inner face, z = 0.4 at its outer face, then the
// projection zone (sills, pediments, balconies, cornice). The back and side facades are the same
// kind of block placed by cube rotations about y (90, 180, 270 degrees) in the body; the hipped
// ends of the roof are a square pyramid seen through a redirection with a 45-degree yaw.
//
// Hierarchy (depth 7): root -> roof -> middle section -> strip -> dormer -> dormer body -> window
// -> glazing module; root -> body -> facade -> floor row -> bay -> window -> glazing module.
#include <cmath>
#include <numbers>
#include <optional>

#include "sample_kit.hpp"
#include "samples.hpp"

namespace samples {

namespace {

using nut::BlockId;
using nut::Cell;

// ---- Dimensions (metres) ----
constexpr double kWall = 0.4;       // wall thickness
constexpr double kFrontProj = 1.3;  // projection zone of front and back facades (balconies)
constexpr double kSideProj = 0.45;  // projection zone of side facades (= cornice projection)
constexpr double kProud = 0.12;     // sill noses, string course, plinth, pediments
constexpr double kFrontDepth = kWall + kFrontProj;
constexpr double kSideDepth = kWall + kSideProj;
constexpr double kCorner = kSideDepth;  // corner column of a front facade: side zone + wall

constexpr double kBay = 3.0;
constexpr double kFrontWidth = 7 * kBay;  // 21.0 between the corners
constexpr double kSideWidth = 4 * kBay;   // 12.0 between front and back

constexpr double kGroundRowH = 4.2;     // ground floor incl. plinth and string course
constexpr double kGroundModuleH = 3.9;  // ground floor without the string course
constexpr double kStoreyH = 3.0;
constexpr double kSlab = 0.25;  // storey floor slab
constexpr double kCorniceH = 0.8;
constexpr double kBodyH = kGroundRowH + 3 * kStoreyH + kCorniceH;  // 14.0

// A window's frame plane lies 0.2 m from the wall's inner face, 0.14 m behind its outer face.
constexpr double kFrameBack = 0.2, kFrameFront = 0.26;
// Glazing modules: 0.26 m x 0.35 m panes; every leaf is a whole number of panes.
constexpr double kPaneW = 0.26, kPaneH = 0.35;

// ---- Roof ----
// The eaves overhang the walls by the cornice's projection on all four sides.
constexpr double kRoofDepth = kSideWidth + 2 * kSideDepth;  // 13.7
constexpr double kRoofWidth = kFrontWidth + 2 * kCorner;    // 22.7
// Rise over run (31 degrees); every key height and the depth where a slope reaches it are whole mm.
constexpr double kRoofPitch = 0.6;
constexpr double kHalfDepth = kRoofDepth / 2;
constexpr double kRidgeH = kRoofPitch * kHalfDepth;  // 4.11
constexpr double kRidgeCap = 0.12;                   // radius of the half-round ridge cap
constexpr double kRoofH = 5.31;                      // up to the top of the chimney pots

struct Palette {
  std::uint16_t render, stone, stoneAlt, darkStone, whiteFrame, greenFrame, brownFrame, glass, frosted, iron, doorWood,
      doorPanel, bronze, sign, slate, zinc, brick, terracotta, floorWood, floorTile, interiorWall, shutter;
};

Palette makePalette(nut::Hierarchy& h) {
  Palette p{};
  p.render = colour(h, 216, 190, 148);     // warm lime render
  p.stone = colour(h, 206, 200, 184);      // limestone dressings
  p.stoneAlt = colour(h, 190, 184, 168);   // alternate quoin course
  p.darkStone = colour(h, 150, 146, 138);  // plinth and rustication
  p.whiteFrame = colour(h, 240, 238, 230);
  p.greenFrame = colour(h, 44, 82, 62);
  p.brownFrame = colour(h, 98, 70, 46);
  p.glass = colour(h, 60, 74, 90, 90);  // dark blue-grey, slightly reflective
  p.frosted = colour(h, 172, 186, 196, 40);
  p.iron = colour(h, 34, 34, 38);
  p.doorWood = colour(h, 88, 48, 28);
  p.doorPanel = colour(h, 108, 62, 36);
  p.bronze = colour(h, 62, 56, 48);
  p.sign = colour(h, 30, 66, 86);
  p.slate = colour(h, 78, 84, 96);
  p.zinc = colour(h, 132, 138, 142);
  p.brick = colour(h, 148, 72, 52);
  p.terracotta = colour(h, 184, 98, 60);
  p.floorWood = colour(h, 120, 88, 58);
  p.floorTile = colour(h, 150, 144, 132);
  p.interiorWall = colour(h, 118, 106, 92);  // rooms read darker than the street
  p.shutter = colour(h, 62, 108, 80);
  return p;
}

Cell box(std::uint16_t m) { return Cell::box(m); }

// =============================== Small parts (leaves of the DAG) ===============================

// One pane of a glazed leaf: frame bars on all four sides, glass in the middle plane. Windows
// tile it along x and y, so glazing bars come out 4 cm wide between panes.
BlockId addGlazingPane(nut::Hierarchy& h, std::uint16_t frame, std::uint16_t glass) {
  nut::Block b = makeGridFromSizes({0.02, kPaneW - 0.04, 0.02}, {0.02, kPaneH - 0.04, 0.02}, {0.02, 0.02, 0.02});
  fillCells(b, 0, 3, 0, 3, 0, 3, box(frame));
  fillCells(b, 1, 2, 1, 2, 0, 3, Cell::empty());
  fillCells(b, 1, 2, 1, 2, 1, 2, box(glass));
  return h.addBlock(std::move(b));
}

// Vertical security bars (2 cm every 12 cm), tiled over ground-floor openings.
BlockId addBars(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.02, 0.10}, {1.0}, {0.04, 0.02, 0.08});
  fillCells(b, 0, 1, 0, 1, 1, 2, box(p.iron));
  return h.addBlock(std::move(b));
}

// A wrought-iron balustrade module: one 4 cm baluster every 16 cm, 0.9 m tall, 6 cm deep.
BlockId addBalustrade(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.04, 0.12}, {0.9}, {0.06});
  fillCells(b, 0, 1, 0, 1, 0, 1, box(p.iron));
  return h.addBlock(std::move(b));
}

// One louvre slat of a shutter, a wedge whose top falls outwards so rain runs off; tiled on y.
BlockId addLouvre(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.52}, {0.08}, {0.04});
  b.cell(0, 0, 0) = wedge(Along, Lo, Lo, p.shutter);
  return h.addBlock(std::move(b));
}

// An open louvred shutter (0.6 m x 1.6 m) lying flat against the wall beside a window.
BlockId addShutter(nut::Hierarchy& h, const Palette& p, BlockId louvre) {
  nut::Block b = makeGrid({0.6, 1.6, 0.04}, {0.04, 0.56}, {0.04, 1.56}, {});
  fill(b, wholeBlock(b), box(p.shutter));
  place(h, b, region(0.04, 0.04, 0, 0.56, 1.56, 0.04), showing(louvre, false, true));
  return h.addBlock(std::move(b));
}

// Vertical boarding of the back door: 15 cm boards with a 1 cm groove, tiled along x.
BlockId addBoarding(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.14, 0.01}, {2.1}, {0.05, 0.01});
  fillCells(b, 0, 2, 0, 1, 0, 1, box(p.greenFrame));
  fillCells(b, 0, 1, 0, 1, 1, 2, box(p.greenFrame));
  return h.addBlock(std::move(b));
}

// A panelled entrance-door leaf (0.72 m x 2.2 m): stiles and rails, a sunk panel below, glass above.
BlockId addPanelledLeaf(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.1, 0.52, 0.1}, {0.2, 0.7, 0.15, 1.0, 0.15}, {0.02, 0.02, 0.02});
  fillCells(b, 0, 3, 0, 5, 0, 3, box(p.doorWood));
  fillCells(b, 1, 2, 1, 2, 0, 3, Cell::empty());
  fillCells(b, 1, 2, 1, 2, 1, 2, box(p.doorPanel));
  fillCells(b, 1, 2, 3, 4, 0, 3, Cell::empty());
  fillCells(b, 1, 2, 3, 4, 1, 2, box(p.glass));
  return h.addBlock(std::move(b));
}

// A glazed shop-door leaf (1.04 m x 2.35 m): bronze frame and kick plate.
BlockId addGlazedLeaf(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.08, 0.88, 0.08}, {0.25, 2.02, 0.08}, {0.02, 0.02, 0.02});
  fillCells(b, 0, 3, 0, 3, 0, 3, box(p.bronze));
  fillCells(b, 1, 2, 1, 2, 0, 3, Cell::empty());
  fillCells(b, 1, 2, 1, 2, 1, 2, box(p.glass));
  return h.addBlock(std::move(b));
}

// =============================== Windows and doors ===============================

struct WindowSpec {
  double width = 1.2, height = 1.6;
  int leaves = 2;
  BlockId pane = 0;
  std::uint16_t frame = 0;
  bool slopedSill = true;       // false for French windows: a flat threshold
  std::optional<BlockId> bars;  // security bars in the reveal
};

// A casement window filling a wall opening of width x height x 0.4 m: a window board inside, a
// stone sill outside (sloped so rain runs off), the frame plane 0.14 m behind the face, and the
// leaves filled with glazing modules tiled from their lower left corner.
BlockId addWindow(nut::Hierarchy& h, const Palette& p, const WindowSpec& w) {
  const double sill = 0.08, bar = 0.06, mullion = 0.04;
  const double leafW = w.leaves == 2 ? (w.width - 2 * bar - mullion) / 2 : w.width - 2 * bar;
  const double leafH = w.height - sill - 2 * bar;
  std::vector<double> cutsX{bar, w.width - bar};
  if (w.leaves == 2) cutsX.insert(cutsX.end(), {bar + leafW, bar + leafW + mullion});
  nut::Block b =
      makeGrid({w.width, w.height, kWall}, cutsX, {sill, sill + bar, sill + bar + leafH}, {kFrameBack, kFrameFront});
  fill(b, region(0, 0, 0, w.width, sill, kFrameBack), box(p.whiteFrame));  // window board
  fill(b, region(0, 0, kFrameBack, w.width, sill, kFrameFront), box(p.stone));
  fill(b, region(0, 0, kFrameFront, w.width, sill, kWall), w.slopedSill ? wedge(Along, Lo, Lo, p.stone) : box(p.stone));
  fill(b, region(0, sill, kFrameBack, w.width, w.height, kFrameFront), box(w.frame));
  for (int leaf = 0; leaf < w.leaves; ++leaf) {
    const double x0 = bar + leaf * (leafW + mullion);
    place(h, b, region(x0, sill + bar, kFrameBack, x0 + leafW, sill + bar + leafH, kFrameFront),
          showing(w.pane, true, true));
  }
  if (w.bars)
    place(h, b, region(bar, sill + bar, kFrameFront, w.width - bar, w.height - bar, kWall),
          showing(*w.bars, true, true));
  return h.addBlock(std::move(b));
}

// Shop glazing, one 1.2 m x 2.5 m module with half mullions at both ends; tiled along x.
BlockId addShopGlazing(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({1.2, 2.5, kWall}, {0.03, 1.17}, {0.06, 2.44}, {0.25, 0.27, 0.29, 0.31});
  fill(b, region(0, 0, 0.25, 1.2, 2.5, 0.31), box(p.bronze));
  fill(b, region(0.03, 0.06, 0.25, 1.17, 2.44, 0.31), Cell::empty());
  fill(b, region(0.03, 0.06, 0.27, 1.17, 2.44, 0.29), box(p.glass));
  return h.addBlock(std::move(b));
}

// A semicircular fanlight (1.6 m x 0.8 m): inverse quarter cylinders of stone cut the arch out
// of the wall in front of and behind a glass plane.
BlockId addFanlight(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({1.6, 0.8, kWall}, {0.8}, {}, {kFrameBack, kFrameFront});
  for (const auto& [z0, z1] : {std::pair{0.0, kFrameBack}, std::pair{kFrameFront, kWall}}) {
    fill(b, region(0, 0, z0, 0.8, 0.8, z1), coveCylinder(Hi, Lo, Along, p.stone));  // arc centre at the springing
    fill(b, region(0.8, 0, z0, 1.6, 0.8, z1), coveCylinder(Lo, Lo, Along, p.stone));
  }
  fill(b, region(0, 0, kFrameBack, 1.6, 0.8, kFrameFront), box(p.glass));
  return h.addBlock(std::move(b));
}

// The main entrance: a stone threshold, two panelled leaves, a transom and the arched fanlight.
BlockId addEntranceDoor(nut::Hierarchy& h, const Palette& p, BlockId leaf, BlockId fanlight) {
  nut::Block b = makeGrid({1.6, 3.35, kWall}, {0.08, 0.8, 1.52}, {0.25, 2.45, 2.55}, {kFrameBack, kFrameFront});
  fill(b, region(0, 0, 0, 1.6, 0.25, kWall), box(p.stone));
  fill(b, region(0, 0.25, kFrameBack, 1.6, 2.55, kFrameFront), box(p.doorWood));
  place(h, b, region(0.08, 0.25, kFrameBack, 0.8, 2.45, kFrameFront), showing(leaf));
  place(h, b, region(0.8, 0.25, kFrameBack, 1.52, 2.45, kFrameFront), showing(leaf));
  place(h, b, region(0, 2.55, 0, 1.6, 3.35, kWall), showing(fanlight));
  return h.addBlock(std::move(b));
}

// A shop door (1.2 m x 2.85 m): bronze frame, glazed leaf, fanlight.
BlockId addShopDoor(nut::Hierarchy& h, const Palette& p, BlockId leaf) {
  const double back = 0.25, front = 0.31;
  nut::Block b = makeGrid({1.2, 2.85, kWall}, {0.08, 1.12}, {0.1, 2.45, 2.53}, {back, front});
  fill(b, region(0, 0, 0, 1.2, 0.1, kWall), box(p.stone));
  fill(b, region(0, 0.1, back, 1.2, 2.85, front), box(p.bronze));
  place(h, b, region(0.08, 0.1, back, 1.12, 2.45, front), showing(leaf));
  fill(b, region(0.08, 2.53, back, 1.12, 2.85, front), box(p.glass));
  return h.addBlock(std::move(b));
}

// The back door (1.0 m x 2.3 m): boarded leaf in a green frame.
BlockId addBackDoor(nut::Hierarchy& h, const Palette& p, BlockId boarding) {
  nut::Block b = makeGrid({1.0, 2.3, kWall}, {0.05, 0.95}, {0.1, 2.2}, {kFrameBack, kFrameFront});
  fill(b, region(0, 0, 0, 1.0, 0.1, kWall), box(p.stone));
  fill(b, region(0, 0.1, kFrameBack, 1.0, 2.3, kFrameFront), box(p.greenFrame));
  place(h, b, region(0.05, 0.1, kFrameBack, 0.95, 2.2, kFrameFront), showing(boarding, true));
  return h.addBlock(std::move(b));
}

// A round window (0.8 m): four inverse quarter cylinders around the centre cut the hole through
// the wall, glass in the middle plane.
BlockId addOculus(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({0.8, 0.8, kWall}, {0.4}, {0.4}, {kFrameBack, kFrameFront});
  for (const auto& [z0, z1] : {std::pair{0.0, kFrameBack}, std::pair{kFrameFront, kWall}}) {
    fill(b, region(0, 0, z0, 0.4, 0.4, z1), coveCylinder(Hi, Hi, Along, p.render));
    fill(b, region(0.4, 0, z0, 0.8, 0.4, z1), coveCylinder(Lo, Hi, Along, p.render));
    fill(b, region(0, 0.4, z0, 0.4, 0.8, z1), coveCylinder(Hi, Lo, Along, p.render));
    fill(b, region(0.4, 0.4, z0, 0.8, 0.8, z1), coveCylinder(Lo, Lo, Along, p.render));
  }
  fill(b, region(0, 0, kFrameBack, 0.8, 0.8, kFrameFront), box(p.glass));
  return h.addBlock(std::move(b));
}

// =============================== Mouldings and masonry ===============================

// A triangular pediment over a window (1.6 m x 0.36 m, 0.12 m proud): a shelf and two wedges.
BlockId addPediment(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({1.6, 0.36, kProud}, {0.8}, {0.06}, {});
  fill(b, region(0, 0, 0, 1.6, 0.06, kProud), box(p.stone));
  fill(b, region(0, 0.06, 0, 0.8, 0.36, kProud), wedge(Hi, Lo, Along, p.stone));  // rises to the apex
  fill(b, region(0.8, 0.06, 0, 1.6, 0.36, kProud), wedge(Lo, Lo, Along, p.stone));
  return h.addBlock(std::move(b));
}

// Banded rustication: 0.45 m stone courses, 4 cm proud, with a V joint of two wedges; tiled.
BlockId addRustication(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.0}, {0.02, 0.02, 0.41}, {kWall, 0.04});
  fillCells(b, 0, 1, 0, 3, 0, 1, box(p.darkStone));
  b.cell(0, 0, 1) = wedge(Along, Lo, Lo, p.darkStone);  // lower lip of the joint
  b.cell(0, 1, 1) = wedge(Along, Hi, Lo, p.darkStone);  // upper lip
  b.cell(0, 2, 1) = box(p.darkStone);
  return h.addBlock(std::move(b));
}

// The plinth course (0.5 m, 0.12 m proud) with a chamfered top; tiled along x.
BlockId addPlinth(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.0}, {0.42, 0.08}, {kWall, kProud});
  fillCells(b, 0, 1, 0, 2, 0, 1, box(p.darkStone));
  b.cell(0, 0, 1) = box(p.darkStone);
  b.cell(0, 1, 1) = wedge(Along, Lo, Lo, p.darkStone);
  return h.addBlock(std::move(b));
}

// The string course over the ground floor (0.3 m): a cove below, a band, a sloped weathering.
BlockId addStringCourse(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.0}, {0.06, 0.18, 0.06}, {kWall, kProud});
  fillCells(b, 0, 1, 0, 3, 0, 1, box(p.stone));
  b.cell(0, 0, 1) = coveCylinder(Along, Lo, Hi, p.stone);
  b.cell(0, 1, 1) = box(p.stone);
  b.cell(0, 2, 1) = wedge(Along, Lo, Lo, p.stone);
  return h.addBlock(std::move(b));
}

// Quoins of a corner pilaster, drawn for the left front corner (outer faces -x and +z): two
// 0.28 m courses in two stone shades, 5 cm proud on both faces, with recessed joints; tiled on y.
BlockId addQuoins(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.05, kWall}, {0.28, 0.02, 0.28, 0.02}, {kWall, 0.05});
  fillCells(b, 0, 2, 0, 1, 0, 2, box(p.stone));
  fillCells(b, 0, 2, 2, 3, 0, 2, box(p.stoneAlt));
  fillCells(b, 1, 2, 1, 2, 0, 1, box(p.stone));
  fillCells(b, 1, 2, 3, 4, 0, 1, box(p.stone));
  return h.addBlock(std::move(b));
}

// The main cornice profile: rows from the bottom (frieze, cove, fillet, corona, cap) by layers
// outward from the wall face. Kinds: E empty, B box, C cove (concave), R round (convex).
enum class Profile { E, B, C, R };
constexpr double kCorniceRows[] = {0.3, 0.12, 0.05, 0.2, 0.13};
constexpr double kCorniceLayers[] = {0.15, 0.05, 0.25};  // sums to kSideProj
constexpr Profile kCornice[5][3] = {
    {Profile::E, Profile::E, Profile::E},  // frieze (the wall itself)
    {Profile::C, Profile::E, Profile::E},  // cove
    {Profile::B, Profile::B, Profile::E},  // fillet
    {Profile::B, Profile::B, Profile::B},  // corona
    {Profile::B, Profile::B, Profile::R},  // cap, rounded at the front
};

// A straight 1 m run of the cornice (wall layer included), tiled along x.
BlockId addCorniceRun(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.0}, {std::begin(kCorniceRows), std::end(kCorniceRows)},
                                   {kWall, kCorniceLayers[0], kCorniceLayers[1], kCorniceLayers[2]});
  for (int row = 0; row < 5; ++row) {
    b.cell(0, row, 0) = box(row == 0 ? p.render : p.stone);
    for (int layer = 0; layer < 3; ++layer) {
      const Profile kind = kCornice[row][layer];
      Cell c = kind == Profile::B   ? box(p.stone)
               : kind == Profile::C ? coveCylinder(Along, Lo, Hi, p.stone)
               : kind == Profile::R ? quarterCylinder(Along, Lo, Lo, p.stone)
                                    : Cell::empty();
      b.cell(0, row, layer + 1) = c;
    }
  }
  return h.addBlock(std::move(b));
}

// The cornice mitred round the left front corner (outer faces -x and +z): each cell is where the
// side run and the front run overlap. Where both are curved, a sphere octant (convex) or an
// inverse octant (concave) stands in for the intersection of the two quarter cylinders.
BlockId addCorniceCorner(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({kCorniceLayers[2], kCorniceLayers[1], kCorniceLayers[0], kWall},
                                   {std::begin(kCorniceRows), std::end(kCorniceRows)},
                                   {kWall, kCorniceLayers[0], kCorniceLayers[1], kCorniceLayers[2]});
  for (int row = 0; row < 5; ++row)
    for (int xi = 0; xi < 4; ++xi)
      for (int zi = 0; zi < 4; ++zi) {
        // Layer index of the side profile (outward = -x) and the front profile (outward = +z);
        // -1 means "inside the wall", which is solid for that profile.
        const int side = xi < 3 ? 2 - xi : -1;
        const int front = zi - 1;
        const Profile s = side < 0 ? Profile::B : kCornice[row][side];
        const Profile f = front < 0 ? Profile::B : kCornice[row][front];
        Cell c = Cell::empty();
        if (side < 0 && front < 0)
          c = box(row == 0 ? p.render : p.stone);
        else if (s == Profile::E || f == Profile::E)
          c = Cell::empty();
        else if (s == Profile::B && f == Profile::B)
          c = box(p.stone);
        else if (s == Profile::B)
          c = f == Profile::C ? coveCylinder(Along, Lo, Hi, p.stone) : quarterCylinder(Along, Lo, Lo, p.stone);
        else if (f == Profile::B)
          c = s == Profile::C ? coveCylinder(Lo, Lo, Along, p.stone) : quarterCylinder(Hi, Lo, Along, p.stone);
        else
          c = s == Profile::C ? coveOctant(Lo, Lo, Hi, p.stone) : octant(Hi, Lo, Lo, p.stone);
        b.cell(xi, row, zi) = c;
      }
  return h.addBlock(std::move(b));
}

// The corner column of a front or back facade (0.85 m square, full height): quoins up to the
// cornice, the mitred cornice corner on top. Drawn for the left corner; the right one is the
// same block turned 90 degrees about y.
BlockId addFacadeCorner(nut::Hierarchy& h, BlockId quoins, BlockId corniceCorner) {
  const double quoinsTop = kBodyH - kCorniceH;
  nut::Block b = makeGrid({kCorner, kBodyH, kCorner}, {kSideProj - 0.05}, {quoinsTop}, {kWall + 0.05});
  place(h, b, region(kSideProj - 0.05, 0, 0, kCorner, quoinsTop, kWall + 0.05), showing(quoins, false, true));
  place(h, b, region(0, quoinsTop, 0, kCorner, kBodyH, kCorner), showing(corniceCorner));
  return h.addBlock(std::move(b));
}

// =============================== Bays (3 m x 3 m facade modules) ===============================

// Shared parts a bay may use.
struct Parts {
  BlockId windowFront, windowFrontTop, frenchWindow, frenchWindowBack, windowBack, windowGround, windowBathroom,
      windowStair, oculus, pediment, balustrade, shutter;
};

// A bay's wall: solid render over the wall layer, the rest (projection zone) empty.
nut::Block bayShell(double depth, std::vector<double> cutsX, std::vector<double> cutsY, std::vector<double> cutsZ,
                    std::uint16_t wallMaterial) {
  cutsZ.push_back(kWall);
  nut::Block b = makeGrid({kBay, kStoreyH, depth}, std::move(cutsX), std::move(cutsY), std::move(cutsZ));
  fill(b, region(0, 0, 0, kBay, kStoreyH, kWall), box(wallMaterial));
  return b;
}

// A window in a bay at [x0, x1] x [y0, y1] with a stone sill nose under it.
void windowWithSill(const nut::Hierarchy& h, nut::Block& b, const Palette& p, BlockId window, double x0, double x1,
                    double y0, double y1) {
  place(h, b, region(x0, y0, 0, x1, y1, kWall), showing(window));
  fill(b, region(x0 - 0.05, y0 - 0.06, kWall, x1 + 0.05, y0, kWall + 0.06), box(p.stone));
}

// A stone architrave 10 cm wide and 6 cm proud round [x0, x1] x [y0, y1], with a 15 cm head.
void architrave(nut::Block& b, const Palette& p, double x0, double x1, double y0, double y1) {
  const double z1 = kWall + 0.06;
  fill(b, region(x0 - 0.1, y0, kWall, x0, y1, z1), box(p.stone));
  fill(b, region(x1, y0, kWall, x1 + 0.1, y1, z1), box(p.stone));
  fill(b, region(x0 - 0.1, y1, kWall, x1 + 0.1, y1 + 0.15, z1), box(p.stone));
}

std::vector<double> cutsAround(double x0, double x1) { return {x0 - 0.1, x0 - 0.05, x0, x1, x1 + 0.05, x1 + 0.1}; }

// Front, second floor: a casement in a stone architrave.
BlockId addBayFront(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kFrontDepth, cutsAround(0.9, 2.1), {0.84, 0.9, 2.5, 2.65}, {kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowFront, 0.9, 2.1, 0.9, 2.5);
  architrave(b, p, 0.9, 2.1, 0.9, 2.5);
  return h.addBlock(std::move(b));
}

// Front, first floor: the same casement, set lower, under a triangular pediment.
BlockId addBayFrontPediment(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  std::vector<double> cutsX = cutsAround(0.9, 2.1);
  cutsX.insert(cutsX.end(), {0.7, 2.3});
  nut::Block b = bayShell(kFrontDepth, cutsX, {0.74, 0.8, 2.4, 2.55, 2.91}, {kWall + 0.06, kWall + kProud}, p.render);
  windowWithSill(h, b, p, parts.windowFront, 0.9, 2.1, 0.8, 2.4);
  architrave(b, p, 0.9, 2.1, 0.8, 2.4);
  place(h, b, region(0.7, 2.55, kWall, 2.3, 2.91, kWall + kProud), showing(parts.pediment));
  return h.addBlock(std::move(b));
}

// Front, top floor: a shorter casement with a plain sill.
BlockId addBayFrontTop(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kFrontDepth, {0.85, 0.9, 2.1, 2.15}, {0.84, 0.9, 2.15}, {kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowFrontTop, 0.9, 2.1, 0.9, 2.15);
  return h.addBlock(std::move(b));
}

// A balcony 1.2 m deep on two wedge brackets, with a tiled iron balustrade in front and the same
// balustrade turned 90 degrees for the two returns; French window behind.
BlockId addBayBalcony(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  const double slabBottom = 0.35, floorLevel = 0.5, railTop = 1.4, handrail = 1.46;
  const double bracketDepth = kWall + 0.4, railBack = kWall + 1.14, front = kWall + 1.2;
  nut::Block b = bayShell(kFrontDepth, {0.25, 0.37, 0.9, 2.1, 2.63, 2.75},
                          {slabBottom, floorLevel, railTop, handrail, 2.8}, {bracketDepth, railBack, front}, p.render);
  place(h, b, region(0.9, floorLevel, 0, 2.1, 2.8, kWall), showing(parts.frenchWindow));
  fill(b, region(0.25, slabBottom, kWall, 2.75, floorLevel, front), box(p.stone));
  for (double x0 : {0.25, 2.63}) {
    // Bracket: a wedge hugging the wall and the slab, 0.4 m deep.
    fill(b, region(x0, 0, kWall, x0 + 0.12, slabBottom, bracketDepth), wedge(Along, Hi, Lo, p.stone));
    // Return: the balustrade turned so that its x runs along z, centred in the 12 cm rail.
    nut::Redirection side = rotatedFit(h, parts.balustrade, turnAboutY(1), {0.03, 0, 0});
    side.wrap = {true, false, false};
    place(h, b, region(x0, floorLevel, kWall, x0 + 0.12, railTop, railBack), side);
    fill(b, region(x0, railTop, kWall, x0 + 0.12, handrail, railBack), box(p.iron));
  }
  place(h, b, region(0.25, floorLevel, railBack, 2.75, railTop, front), showing(parts.balustrade, true));
  fill(b, region(0.25, railTop, railBack, 2.75, handrail, front), box(p.iron));
  return h.addBlock(std::move(b));
}

// Back: a loggia-like balcony with a solid rendered parapet and a stone coping.
BlockId addBayBackBalcony(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  const double slabBottom = 0.35, floorLevel = 0.5, parapetTop = 1.5, copingTop = 1.56;
  const double inner = kWall + 1.05, front = kWall + 1.2;
  nut::Block b = bayShell(kFrontDepth, {0.25, 0.4, 0.9, 2.1, 2.6, 2.75},
                          {slabBottom, floorLevel, parapetTop, copingTop, 2.8}, {inner, front}, p.render);
  place(h, b, region(0.9, floorLevel, 0, 2.1, 2.8, kWall), showing(parts.frenchWindowBack));
  fill(b, region(0.25, slabBottom, kWall, 2.75, floorLevel, front), box(p.stone));
  fill(b, region(0.25, floorLevel, inner, 2.75, parapetTop, front), box(p.render));
  fill(b, region(0.25, floorLevel, kWall, 0.4, parapetTop, inner), box(p.render));
  fill(b, region(2.6, floorLevel, kWall, 2.75, parapetTop, inner), box(p.render));
  fill(b, region(0.25, parapetTop, inner, 2.75, copingTop, front), box(p.stone));
  fill(b, region(0.25, parapetTop, kWall, 0.4, copingTop, inner), box(p.stone));
  fill(b, region(2.6, parapetTop, kWall, 2.75, copingTop, inner), box(p.stone));
  return h.addBlock(std::move(b));
}

// Back: a plain casement.
BlockId addBayBack(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kFrontDepth, {0.85, 0.9, 2.1, 2.15}, {0.84, 0.9, 2.5}, {kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowBack, 0.9, 2.1, 0.9, 2.5);
  return h.addBlock(std::move(b));
}

// Back: a small frosted bathroom window set high.
BlockId addBayBathroom(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kFrontDepth, {1.13, 1.18, 1.82, 1.87}, {1.54, 1.6, 2.5}, {kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowBathroom, 1.18, 1.82, 1.6, 2.5);
  return h.addBlock(std::move(b));
}

// Back, centre: the tall staircase window, lighting the half landing.
BlockId addBayStair(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kFrontDepth, {1.13, 1.18, 1.82, 1.87}, {0.54, 0.6, 2.9}, {kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowStair, 1.18, 1.82, 0.6, 2.9);
  return h.addBlock(std::move(b));
}

// Side: a casement between two open louvred shutters.
BlockId addBaySide(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b =
      bayShell(kSideDepth, {0.3, 0.85, 0.9, 2.1, 2.15, 2.7}, {0.84, 0.9, 2.5}, {kWall + 0.04, kWall + 0.06}, p.render);
  windowWithSill(h, b, p, parts.windowBack, 0.9, 2.1, 0.9, 2.5);
  place(h, b, region(0.3, 0.9, kWall, 0.9, 2.5, kWall + 0.04), showing(parts.shutter));
  place(h, b, region(2.1, 0.9, kWall, 2.7, 2.5, kWall + 0.04), showing(parts.shutter));
  return h.addBlock(std::move(b));
}

// Side, middle bays: blank wall with a round window in a stone ring.
BlockId addBayOculus(nut::Hierarchy& h, const Palette& p, const Parts& parts) {
  nut::Block b = bayShell(kSideDepth, {1.0, 1.1, 1.9, 2.0}, {1.2, 1.3, 2.1, 2.2}, {kWall + 0.05}, p.render);
  place(h, b, region(1.1, 1.3, 0, 1.9, 2.1, kWall), showing(parts.oculus));
  // Keystones at the four quarters of the ring.
  fill(b, region(1.1, 1.2, kWall, 1.9, 1.3, kWall + 0.05), box(p.stone));
  fill(b, region(1.1, 2.1, kWall, 1.9, 2.2, kWall + 0.05), box(p.stone));
  fill(b, region(1.0, 1.3, kWall, 1.1, 2.1, kWall + 0.05), box(p.stone));
  fill(b, region(1.9, 1.3, kWall, 2.0, 2.1, kWall + 0.05), box(p.stone));
  return h.addBlock(std::move(b));
}

// =============================== Ground-floor modules (3.9 m tall) ===============================

struct GroundParts {
  BlockId rustication, plinth, shopGlazing, shopDoor, entranceDoor, backDoor, windowGround, canopy;
};

// A ground-floor module shell: plinth course at the bottom, rusticated wall above.
nut::Block groundShell(const nut::Hierarchy& h, double width, std::vector<double> cutsX, std::vector<double> cutsY,
                       std::vector<double> cutsZ, const GroundParts& g) {
  cutsY.push_back(0.5);
  cutsZ.insert(cutsZ.end(), {kWall, kWall + kProud});
  nut::Block b = makeGrid({width, kGroundModuleH, kFrontDepth}, std::move(cutsX), std::move(cutsY), std::move(cutsZ));
  place(h, b, region(0, 0, 0, width, 0.5, kWall + kProud), showing(g.plinth, true));
  place(h, b, region(0, 0.5, 0, width, kGroundModuleH, kWall + kProud), showing(g.rustication, true, true));
  return b;
}

// An opening through the ground-floor wall: the door or window in the wall layer, and the
// proud layer in front of it cleared of plinth and rustication.
void groundOpening(const nut::Hierarchy& h, nut::Block& b, double x0, double y0, double x1, double y1,
                   const nut::Redirection& red) {
  place(h, b, region(x0, y0, 0, x1, y1, kWall), red);
  fill(b, region(x0, y0, kWall, x1, y1, kWall + kProud), Cell::empty());
}

// Shop fascia: a stone band over the shop with a sign board standing proud.
void fascia(nut::Block& b, const Palette& p, double x0, double x1) {
  fill(b, region(0, 3.2, 0, b.sizeM().x, kGroundModuleH, kWall), box(p.stone));
  fill(b, region(x0, 3.2, kWall, x1, kGroundModuleH, kWall + kProud), box(p.sign));
}

// A 6 m shop: a 3.6 m window (three glazing modules) and a door, under a sign.
BlockId addShop(nut::Hierarchy& h, const Palette& p, const GroundParts& g) {
  nut::Block b = groundShell(h, 6.0, {0.45, 4.05, 4.4, 5.6}, {0.15, 3.0, 3.2}, {}, g);
  groundOpening(h, b, 0.45, 0.5, 4.05, 3.0, showing(g.shopGlazing, true));
  fill(b, region(0.45, 3.0, 0, 4.05, 3.2, kWall), box(p.stone));
  fill(b, region(4.4, 0, 0, 5.6, 0.15, kWall + kProud), box(p.stone));  // door step
  groundOpening(h, b, 4.4, 0.15, 5.6, 3.0, showing(g.shopDoor));
  fill(b, region(4.4, 3.0, 0, 5.6, 3.2, kWall), box(p.stone));
  fascia(b, p, 0.45, 5.6);
  return h.addBlock(std::move(b));
}

// A 3 m shop window (two glazing modules) under a sign.
BlockId addShopWindow(nut::Hierarchy& h, const Palette& p, const GroundParts& g) {
  nut::Block b = groundShell(h, kBay, {0.3, 2.7}, {3.0, 3.2}, {}, g);
  groundOpening(h, b, 0.3, 0.5, 2.7, 3.0, showing(g.shopGlazing, true));
  fill(b, region(0.3, 3.0, 0, 2.7, 3.2, kWall), box(p.stone));
  fascia(b, p, 0.3, 2.7);
  return h.addBlock(std::move(b));
}

// The entrance to the flats: steps, stone jambs, the arched double door and a keystone.
BlockId addEntrance(nut::Hierarchy& h, const Palette& p, const GroundParts& g) {
  const double doorBottom = 0.15, crown = 3.5, steps = kWall + 0.42;
  nut::Block b = groundShell(h, kBay, {0.6, 0.7, 1.4, 1.6, 2.3, 2.4}, {doorBottom, crown}, {steps}, g);
  fill(b, region(0.6, 0, 0, 2.4, doorBottom, steps), box(p.stone));
  fill(b, region(0.6, doorBottom, 0, 0.7, crown, kWall + kProud), box(p.stone));
  fill(b, region(2.3, doorBottom, 0, 2.4, crown, kWall + kProud), box(p.stone));
  groundOpening(h, b, 0.7, doorBottom, 2.3, crown, showing(g.entranceDoor));
  fill(b, region(0.6, crown, 0, 2.4, kGroundModuleH, kWall), box(p.stone));
  fill(b, region(1.4, crown, kWall, 1.6, kGroundModuleH, kWall + kProud), box(p.stone));  // keystone
  return h.addBlock(std::move(b));
}

// Back and sides: a barred casement in the rusticated wall.
BlockId addGroundWindow(nut::Hierarchy& h, const Palette& p, const GroundParts& g) {
  nut::Block b = groundShell(h, kBay, {0.85, 0.9, 2.1, 2.15}, {1.44, 1.5, 3.1}, {}, g);
  groundOpening(h, b, 0.9, 1.5, 2.1, 3.1, showing(g.windowGround));
  fill(b, region(0.85, 1.44, kWall, 2.15, 1.5, kWall + kProud), box(p.stone));
  return h.addBlock(std::move(b));
}

// A small zinc lean-to canopy (1.6 m x 0.3 m, 0.8 m deep): one wedge. It is a block of its own
// because the ground modules cut their proud layer at 0.52 m, and a wedge must fill one cell.
BlockId addCanopy(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.6}, {0.3}, {0.8});
  b.cell(0, 0, 0) = wedge(Along, Lo, Lo, p.zinc);
  return h.addBlock(std::move(b));
}

// Back, centre: the back door with a step and a small zinc lean-to canopy.
BlockId addGroundBackDoor(nut::Hierarchy& h, const Palette& p, const GroundParts& g) {
  const double canopyFront = kWall + 0.8;
  nut::Block b = groundShell(h, kBay, {0.7, 1.0, 2.0, 2.3}, {0.15, 2.45, 2.7, 3.0}, {canopyFront}, g);
  fill(b, region(0.7, 0, 0, 2.3, 0.15, canopyFront), box(p.stone));
  groundOpening(h, b, 1.0, 0.15, 2.0, 2.45, showing(g.backDoor));
  place(h, b, region(0.7, 2.7, kWall, 2.3, 3.0, canopyFront), showing(g.canopy));
  return h.addBlock(std::move(b));
}

// =============================== Floor rows and facades ===============================

// A row of bays: one block per bay (left to right), each 3 m wide.
BlockId addRow(nut::Hierarchy& h, double height, double depth, const std::vector<BlockId>& bays) {
  std::vector<double> cuts;
  for (std::size_t i = 1; i < bays.size(); ++i) cuts.push_back(kBay * static_cast<double>(i));
  nut::Block b = makeGrid({kBay * static_cast<double>(bays.size()), height, depth}, cuts, {}, {});
  for (std::size_t i = 0; i < bays.size(); ++i) {
    const double x0 = kBay * static_cast<double>(i);
    place(h, b, region(x0, 0, 0, x0 + kBay, height, depth), showing(bays[i]));
  }
  return h.addBlock(std::move(b));
}

// A ground-floor row: modules of any width side by side, with the string course on top.
BlockId addGroundRow(nut::Hierarchy& h, double depth, const std::vector<std::pair<BlockId, double>>& modules,
                     BlockId stringCourse) {
  double width = 0;
  std::vector<double> cuts;
  for (const auto& m : modules) cuts.push_back(width += m.second);
  nut::Block b = makeGrid({width, kGroundRowH, depth}, cuts, {kGroundModuleH}, {kWall + kProud});
  double x = 0;
  for (const auto& [module, w] : modules) {
    place(h, b, region(x, 0, 0, x + w, kGroundModuleH, depth), showing(module));
    x += w;
  }
  place(h, b, region(0, kGroundModuleH, 0, width, kGroundRowH, kWall + kProud), showing(stringCourse, true));
  return h.addBlock(std::move(b));
}

// A front or back facade (22.7 m x 14 m x 1.7 m): the ground row, three floor rows (or one row
// tiled three times), the cornice, and the corner columns (the right one turned 90 degrees).
BlockId addLongFacade(nut::Hierarchy& h, BlockId groundRow, const std::vector<BlockId>& floorRows, BlockId cornice,
                      BlockId corner) {
  const double width = kFrontWidth + 2 * kCorner, corniceBottom = kBodyH - kCorniceH;
  const double right = kCorner + kFrontWidth;
  nut::Block b = makeGrid({width, kBodyH, kFrontDepth}, {kCorner, right},
                          {kGroundRowH, kGroundRowH + kStoreyH, kGroundRowH + 2 * kStoreyH, corniceBottom}, {kCorner});
  place(h, b, region(kCorner, 0, 0, right, kGroundRowH, kFrontDepth), showing(groundRow));
  if (floorRows.size() == 1) {
    place(h, b, region(kCorner, kGroundRowH, 0, right, corniceBottom, kFrontDepth), showing(floorRows[0], false, true));
  } else {
    for (std::size_t i = 0; i < floorRows.size(); ++i) {
      const double y0 = kGroundRowH + kStoreyH * static_cast<double>(i);
      place(h, b, region(kCorner, y0, 0, right, y0 + kStoreyH, kFrontDepth), showing(floorRows[i]));
    }
  }
  place(h, b, region(kCorner, corniceBottom, 0, right, kBodyH, kCorner), showing(cornice, true));
  place(h, b, region(0, 0, 0, kCorner, kBodyH, kCorner), showing(corner));
  place(h, b, region(right, 0, 0, width, kBodyH, kCorner), rotatedFit(h, corner, turnAboutY(1)));
  return h.addBlock(std::move(b));
}

// A side facade (12 m x 14 m x 0.85 m): ground row, one floor row tiled three times, cornice.
BlockId addSideFacade(nut::Hierarchy& h, BlockId groundRow, BlockId floorRow, BlockId cornice) {
  const double corniceBottom = kBodyH - kCorniceH;
  nut::Block b = makeGrid({kSideWidth, kBodyH, kSideDepth}, {}, {kGroundRowH, corniceBottom}, {});
  place(h, b, region(0, 0, 0, kSideWidth, kGroundRowH, kSideDepth), showing(groundRow));
  place(h, b, region(0, kGroundRowH, 0, kSideWidth, corniceBottom, kSideDepth), showing(floorRow, false, true));
  place(h, b, region(0, corniceBottom, 0, kSideWidth, kBodyH, kSideDepth), showing(cornice, true));
  return h.addBlock(std::move(b));
}

// =============================== Interior ===============================

// One flight of 8 steps rising 1.375 m towards +z over 2.7 m, with a sloped soffit: the step
// cells are boxes and the cells under them wedges, so the underside is one straight slope.
BlockId addStairFlight(nut::Hierarchy& h, const Palette& p) {
  constexpr int kSteps = 8;
  nut::Block b =
      makeGridFromSizes({1.2}, std::vector<double>(kSteps, 1.375 / kSteps), std::vector<double>(kSteps, 2.7 / kSteps));
  for (int k = 0; k < kSteps; ++k) {
    b.cell(0, k, k) = box(p.stone);
    if (k > 0) b.cell(0, k - 1, k) = wedge(Along, Hi, Lo, p.stone);
  }
  return h.addBlock(std::move(b));
}

// A storey of the staircase (2.5 m x 3 m x 5 m): floor slab, a flight up towards the back wall,
// the half landing under the stair window, and the same flight turned 180 degrees back up.
BlockId addStaircase(nut::Hierarchy& h, const Palette& p, BlockId flight) {
  const double halfLanding = kSlab + 1.375, landingBack = 1.1, flightEnd = 3.8;
  nut::Block b = makeGrid({2.5, kStoreyH, 5.0}, {1.2, 1.3}, {kSlab, halfLanding}, {landingBack, flightEnd});
  fill(b, region(0, 0, 0, 2.5, kSlab, 5.0), box(p.floorWood));
  fill(b, region(0, kSlab, 0, 2.5, halfLanding, landingBack), box(p.stone));
  place(h, b, region(0, kSlab, landingBack, 1.2, halfLanding, flightEnd), rotatedFit(h, flight, turnAboutY(2)));
  place(h, b, region(1.3, halfLanding, landingBack, 2.5, kStoreyH, flightEnd), showing(flight));
  return h.addBlock(std::move(b));
}

// Partition walls between the units at x = 6, 9, 12 and 15 m (20 cm thick).
const std::vector<double> kPartitionCuts = {5.9, 6.1, 8.9, 9.1, 11.9, 12.1, 14.9, 15.1};

// An upper storey (21 m x 3 m x 12 m): slab, back rooms, a corridor, front rooms, and the
// staircase in the middle of the back.
BlockId addStorey(nut::Hierarchy& h, const Palette& p, BlockId staircase) {
  std::vector<double> cutsX = kPartitionCuts;
  cutsX.insert(cutsX.end(), {9.25, 11.75});
  nut::Block b = makeGrid({kFrontWidth, kStoreyH, kSideWidth}, cutsX, {kSlab}, {5.0, 5.2, 6.7, 6.9});
  fill(b, region(0, 0, 0, kFrontWidth, kSlab, kSideWidth), box(p.floorWood));
  for (double z0 : {5.0, 6.7}) fill(b, region(0, kSlab, z0, kFrontWidth, kStoreyH, z0 + 0.2), box(p.interiorWall));
  for (std::size_t i = 0; i < kPartitionCuts.size(); i += 2)
    for (const auto& [z0, z1] : {std::pair{0.0, 5.0}, std::pair{6.9, kSideWidth}})
      fill(b, region(kPartitionCuts[i], kSlab, z0, kPartitionCuts[i + 1], kStoreyH, z1), box(p.interiorWall));
  place(h, b, region(9.25, 0, 0, 11.75, kStoreyH, 5.0), showing(staircase));
  return h.addBlock(std::move(b));
}

// The ground floor (21 m x 4.2 m x 12 m): tiled floor, party walls between the shops, the shops'
// back walls (the hall runs through to the back door) and a counter in each large shop.
BlockId addGroundInterior(nut::Hierarchy& h, const Palette& p) {
  std::vector<double> cutsX = kPartitionCuts;
  cutsX.insert(cutsX.end(), {1.5, 4.5, 16.5, 19.5});
  nut::Block b = makeGrid({kFrontWidth, kGroundRowH, kSideWidth}, cutsX, {0.15, 1.1}, {5.0, 5.2, 8.0, 8.6});
  fill(b, region(0, 0, 0, kFrontWidth, 0.15, kSideWidth), box(p.floorTile));
  for (std::size_t i = 0; i < kPartitionCuts.size(); i += 2)
    fill(b, region(kPartitionCuts[i], 0.15, 0, kPartitionCuts[i + 1], kGroundRowH, kSideWidth), box(p.interiorWall));
  fill(b, region(0, 0.15, 5.0, 8.9, kGroundRowH, 5.2), box(p.interiorWall));
  fill(b, region(12.1, 0.15, 5.0, kFrontWidth, kGroundRowH, 5.2), box(p.interiorWall));
  for (double x0 : {1.5, 16.5}) fill(b, region(x0, 0.15, 8.0, x0 + 3.0, 1.1, 8.6), box(p.doorWood));
  return h.addBlock(std::move(b));
}

// Everything inside the walls: ground floor, three storeys (one block tiled on y), the top slab.
BlockId addInterior(nut::Hierarchy& h, const Palette& p, BlockId ground, BlockId storey) {
  const double top = kBodyH - kCorniceH;
  nut::Block b = makeGrid({kFrontWidth, kBodyH, kSideWidth}, {}, {kGroundRowH, top}, {});
  place(h, b, region(0, 0, 0, kFrontWidth, kGroundRowH, kSideWidth), showing(ground));
  place(h, b, region(0, kGroundRowH, 0, kFrontWidth, top, kSideWidth), showing(storey, false, true));
  fill(b, region(0, top, 0, kFrontWidth, kBodyH, kSideWidth), box(p.floorWood));
  return h.addBlock(std::move(b));
}

// =============================== Roof ===============================

// A square pyramid roof drawn as a diamond: four corner pyramids meeting at the centre of a
// 2d x 2d block. Seen through a 45-degree yaw it is an axis-aligned square pyramid of side
// d * sqrt(2), which a hip-end cell clips to half: the hipped end of the roof.
BlockId addHipPyramid(nut::Hierarchy& h, const Palette& p, double d) {
  nut::Block b = makeGridFromSizes({d, d}, {kRidgeH}, {d, d});
  b.cell(0, 0, 0) = pyramid(Hi, Lo, Hi, p.slate);  // each pyramid's right-angle corner is at the centre
  b.cell(1, 0, 0) = pyramid(Lo, Lo, Hi, p.slate);
  b.cell(0, 0, 1) = pyramid(Hi, Lo, Lo, p.slate);
  b.cell(1, 0, 1) = pyramid(Lo, Lo, Lo, p.slate);
  return h.addBlock(std::move(b));
}

// The dormer's interior: the underside of the main roof slope (one wedge), clipped by its cell.
BlockId addAtticSlope(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.2}, {1.5}, {1.5 / kRoofPitch});
  b.cell(0, 0, 0) = wedge(Along, Lo, Lo, p.interiorWall);
  return h.addBlock(std::move(b));
}

// The dormer's body below its roof (1.4 m x 1.5 m x 3 m): zinc cheeks, a front wall with the
// window, the room behind it, and the main roof's mass where the slope is above the body.
BlockId addDormerBody(nut::Hierarchy& h, const Palette& p, BlockId window, BlockId atticSlope) {
  // The main slope enters the body's top at z = 0.5 (1.8 m - 0.6 * 0.5 = 1.5 m).
  const double slopeEnters = 0.5, wallBack = 3.0 - kWall;
  nut::Block b = makeGrid({1.4, 1.5, 3.0}, {0.1, 1.3}, {0.25}, {slopeEnters, wallBack});
  fill(b, region(0, 0, 0, 0.1, 1.5, 3.0), box(p.zinc));
  fill(b, region(1.3, 0, 0, 1.4, 1.5, 3.0), box(p.zinc));
  fill(b, region(0.1, 0, 0, 1.3, 1.5, slopeEnters), box(p.interiorWall));
  place(h, b, region(0.1, 0, slopeEnters, 1.3, 1.5, wallBack), showing(atticSlope));
  fill(b, region(0.1, 0, wallBack, 1.3, 0.25, 3.0), box(p.zinc));
  place(h, b, region(0.1, 0.25, wallBack, 1.3, 1.5, 3.0), showing(window));
  return h.addBlock(std::move(b));
}

// A shed dormer (1.4 m x 1.8 m x 3 m) standing on the front slope: its box of a body and a zinc
// roof falling gently forward. Its cell spans [0.9, 2.7] m of roof height, and the main slope
// runs exactly corner to corner through it, so no piece of the main roof is lost.
BlockId addDormer(nut::Hierarchy& h, const Palette& p, BlockId body) {
  nut::Block b = makeGrid({1.4, 1.8, 3.0}, {}, {1.5}, {});
  place(h, b, region(0, 0, 0, 1.4, 1.5, 3.0), showing(body));
  fill(b, region(0, 1.5, 0, 1.4, 1.8, 3.0), wedge(Along, Lo, Lo, p.zinc));
  return h.addBlock(std::move(b));
}

// A chimney pot: a cylinder of four quarter cylinders around a vertical axis.
BlockId addChimneyPot(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.1, 0.1}, {0.21}, {0.1, 0.1});
  b.cell(0, 0, 0) = quarterCylinder(Hi, Along, Hi, p.terracotta);
  b.cell(1, 0, 0) = quarterCylinder(Lo, Along, Hi, p.terracotta);
  b.cell(0, 0, 1) = quarterCylinder(Hi, Along, Lo, p.terracotta);
  b.cell(1, 0, 1) = quarterCylinder(Lo, Along, Lo, p.terracotta);
  return h.addBlock(std::move(b));
}

// The chimney stack (0.8 m x 2.31 m x 0.6 m): brick, a stone cap band, two pots.
BlockId addChimney(nut::Hierarchy& h, const Palette& p, BlockId pot) {
  nut::Block b = makeGrid({0.8, 2.31, 0.6}, {0.15, 0.35, 0.45, 0.65}, {2.0, 2.1}, {0.2, 0.4});
  fill(b, region(0, 0, 0, 0.8, 2.0, 0.6), box(p.brick));
  fill(b, region(0, 2.0, 0, 0.8, 2.1, 0.6), box(p.stone));
  for (double x0 : {0.15, 0.45}) place(h, b, region(x0, 2.1, 0.2, x0 + 0.2, 2.31, 0.4), showing(pot));
  return h.addBlock(std::move(b));
}

// Roof height above the eaves at depth z (0 at the back eaves, kRoofDepth at the front).
double roofHeight(double z) { return kRoofPitch * std::min(z, kRoofDepth - z); }

// Fills the gable-section part [x0, x1] of the roof: below the slopes box, on them a wedge, above
// empty. The grid holds, for every key height, the depths where each slope reaches it, so the
// slope always runs corner to corner through its cells (checked here).
void fillSlopes(nut::Block& b, const Palette& p, double x0, double x1) {
  const auto& by = b.boundsM[1];
  const auto& bz = b.boundsM[2];
  for (std::size_t j = 0; j + 1 < by.size() && by[j] < kRidgeH - 1e-9; ++j)
    for (std::size_t k = 0; k + 1 < bz.size(); ++k) {
      const double y0 = by[j], y1 = by[j + 1], z0 = bz[k], z1 = bz[k + 1];
      const bool back = z1 <= kHalfDepth + 1e-9;  // back slope rises with z, front slope falls
      const double low = std::min(roofHeight(z0), roofHeight(z1)), high = std::max(roofHeight(z0), roofHeight(z1));
      Cell c = Cell::empty();
      if (y1 <= low + 1e-9)
        c = box(p.slate);
      else if (y0 >= high - 1e-9)
        c = Cell::empty();
      else if (std::abs(y0 - low) < 1e-6 && std::abs(y1 - high) < 1e-6)
        c = back ? wedge(Along, Lo, Hi, p.slate) : wedge(Along, Lo, Lo, p.slate);
      else
        throw SampleError("roof grid: the slope does not run through the corners of a cell");
      fill(b, region(x0, y0, z0, x1, y1, z1), c);
    }
}

// The half-round ridge cap: two quarter cylinders whose axis is the ridge line; tiled along x.
// It is a block of its own so that its 12 cm cells do not cut the slopes' grid: fine cells
// across a 13.7 m axis would need a long metadata array (at least 13.7 / 0.12 pixels).
BlockId addRidgeCap(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({1.0}, {0.15}, {kRidgeCap, kRidgeCap});
  b.cell(0, 0, 0) = quarterCylinder(Along, Lo, Hi, p.zinc);
  b.cell(0, 0, 1) = quarterCylinder(Along, Lo, Lo, p.zinc);
  return h.addBlock(std::move(b));
}

// A strip of the roof's middle section, `width` m along the ridge: both slopes and the ridge cap.
// Its grid holds the ridge and `keyHeights` (where dormers or the chimney meet a slope), each with
// the depths where the two slopes reach it; `cutsX` and `height` leave room for what the caller adds.
nut::Block roofStrip(const nut::Hierarchy& h, const Palette& p, BlockId ridgeCap, double width,
                     std::vector<double> keyHeights, std::vector<double> cutsX, double height) {
  const double capTop = kRidgeH + h.blocks[ridgeCap].sizeM().y;
  keyHeights.push_back(kRidgeH);
  std::vector<double> cutsZ, cutsY = keyHeights;
  cutsY.push_back(capTop);
  for (double y : keyHeights) cutsZ.insert(cutsZ.end(), {y / kRoofPitch, kRoofDepth - y / kRoofPitch});
  nut::Block b = makeGrid({width, height, kRoofDepth}, std::move(cutsX), cutsY, cutsZ);
  fillSlopes(b, p, 0, width);
  place(h, b, region(0, kRidgeH, 0, width, capTop, kRoofDepth),
        showing(ridgeCap, /*wrapX=*/true, false, false, {0, 0, kHalfDepth - kRidgeCap}));
  return b;
}

// Where dormers stand: the slope between 0.9 m and 2.7 m of roof height (3 m of run).
constexpr double kDormerLow = 0.9, kDormerHigh = 2.7, kDormerW = 1.4;
constexpr double kChimneyLow = 3.0, kChimneyHigh = 3.36;  // where the chimney leaves the back slope

// A dormer on the front slope of a strip as wide as the dormer (the block drawn facing +z).
void frontDormer(const nut::Hierarchy& h, nut::Block& b, BlockId dormer) {
  place(h, b, region(0, kDormerLow, kRoofDepth - kDormerHigh / kRoofPitch, kDormerW, kDormerHigh,
                     kRoofDepth - kDormerLow / kRoofPitch),
        showing(dormer));
}

// A strip with a dormer on each slope: the back one is the same block turned 180 degrees.
BlockId addDormerStrip(nut::Hierarchy& h, const Palette& p, BlockId ridgeCap, BlockId dormer) {
  nut::Block b = roofStrip(h, p, ridgeCap, kDormerW, {kDormerLow, kDormerHigh}, {}, kRoofH);
  frontDormer(h, b, dormer);
  place(h, b, region(0, kDormerLow, kDormerLow / kRoofPitch, kDormerW, kDormerHigh, kDormerHigh / kRoofPitch),
        rotatedFit(h, dormer, turnAboutY(2)));
  return h.addBlock(std::move(b));
}

// The central strip: a dormer at the front, the chimney rising through the back slope.
BlockId addChimneyStrip(nut::Hierarchy& h, const Palette& p, BlockId ridgeCap, BlockId dormer, BlockId chimney) {
  const double x0 = 0.3, x1 = 1.1;
  nut::Block b =
      roofStrip(h, p, ridgeCap, kDormerW, {kDormerLow, kDormerHigh, kChimneyLow, kChimneyHigh}, {x0, x1}, kRoofH);
  frontDormer(h, b, dormer);
  place(h, b, region(x0, kChimneyLow, kChimneyLow / kRoofPitch, x1, kRoofH, kChimneyHigh / kRoofPitch),
        showing(chimney));
  return h.addBlock(std::move(b));
}

// The middle (gable) section of the hipped roof, 9 m along the ridge: plain strips of slope (one
// 1.6 m block, clipped where a gap is narrower) between two dormer strips and the chimney strip,
// so that the dormers' and chimney's cuts stay inside their own strips.
BlockId addRoofMiddle(nut::Hierarchy& h, const Palette& p, BlockId dormer, BlockId chimney) {
  const double width = kRoofWidth - kRoofDepth;  // 9.0: the ridge's length
  const BlockId ridgeCap = addRidgeCap(h, p);
  const BlockId plain = h.addBlock(roofStrip(h, p, ridgeCap, 1.6, {}, {}, kRoofH));
  const BlockId dormers = addDormerStrip(h, p, ridgeCap, dormer);
  const BlockId centre = addChimneyStrip(h, p, ridgeCap, dormer, chimney);
  // Dormers over the 3rd, 4th and 5th bays: strips at 0.8, 3.8 and 6.8 m.
  const std::vector<std::pair<double, BlockId>> strips = {{0.0, plain}, {0.8, dormers}, {2.2, plain}, {3.8, centre},
                                                           {5.2, plain}, {6.8, dormers}, {8.2, plain}};
  std::vector<double> cutsX;
  for (const auto& strip : strips) cutsX.push_back(strip.first);
  nut::Block b = makeGrid({width, kRoofH, kRoofDepth}, cutsX, {}, {});
  for (std::size_t i = 0; i < strips.size(); ++i) {
    const double x1 = i + 1 < strips.size() ? strips[i + 1].first : width;
    place(h, b, region(strips[i].first, 0, 0, x1, kRoofH, kRoofDepth), showing(strips[i].second));
  }
  return h.addBlock(std::move(b));
}

// The hipped roof (22.7 m x 5.31 m x 13.7 m, eaves 0.45 m beyond the walls): three cells, the
// middle section between the two hipped ends. Each end shows the square pyramid through a
// 45-degree yaw with its apex pinned to that end of the ridge; the cell clips it to half.
BlockId addRoof(nut::Hierarchy& h, BlockId middle, BlockId hip, double hipD) {
  const double hipEnd = kHalfDepth, gableEnd = kRoofWidth - kHalfDepth;  // 6.85, 15.85
  nut::Block b = makeGrid({kRoofWidth, kRoofH, kRoofDepth}, {hipEnd, gableEnd}, {}, {});
  const glm::dvec3 apex(hipD, 0, hipD);
  place(h, b, region(0, 0, 0, hipEnd, kRoofH, kRoofDepth), pinned(hip, yawSteps(8192), apex, {hipEnd, 0, kHalfDepth}));
  place(h, b, region(hipEnd, 0, 0, gableEnd, kRoofH, kRoofDepth), showing(middle));
  place(h, b, region(gableEnd, 0, 0, kRoofWidth, kRoofH, kRoofDepth),
        pinned(hip, yawSteps(8192), apex, {0, 0, kHalfDepth}));
  return h.addBlock(std::move(b));
}

}  // namespace

nut::Hierarchy buildBuildingSample() {
  nut::Hierarchy h;
  const Palette p = makePalette(h);

  // Leaves: glazing modules in four frame/glass combinations, bars, balusters, louvres, boards.
  const BlockId paneWhite = addGlazingPane(h, p.whiteFrame, p.glass);
  const BlockId paneGreen = addGlazingPane(h, p.greenFrame, p.glass);
  const BlockId paneFrosted = addGlazingPane(h, p.greenFrame, p.frosted);
  const BlockId paneBrown = addGlazingPane(h, p.brownFrame, p.glass);
  const BlockId bars = addBars(h, p);

  Parts parts{};
  parts.windowFront = addWindow(h, p, {1.2, 1.6, 2, paneWhite, p.whiteFrame, true, {}});
  parts.windowFrontTop = addWindow(h, p, {1.2, 1.25, 2, paneWhite, p.whiteFrame, true, {}});
  parts.frenchWindow = addWindow(h, p, {1.2, 2.3, 2, paneWhite, p.whiteFrame, false, {}});
  parts.frenchWindowBack = addWindow(h, p, {1.2, 2.3, 2, paneGreen, p.greenFrame, false, {}});
  parts.windowBack = addWindow(h, p, {1.2, 1.6, 2, paneGreen, p.greenFrame, true, {}});
  parts.windowGround = addWindow(h, p, {1.2, 1.6, 2, paneGreen, p.greenFrame, true, bars});
  parts.windowBathroom = addWindow(h, p, {0.64, 0.9, 1, paneFrosted, p.greenFrame, true, {}});
  parts.windowStair = addWindow(h, p, {0.64, 2.3, 1, paneGreen, p.greenFrame, true, {}});
  const BlockId windowDormer = addWindow(h, p, {1.2, 1.25, 2, paneBrown, p.brownFrame, true, {}});
  parts.oculus = addOculus(h, p);
  parts.pediment = addPediment(h, p);
  parts.balustrade = addBalustrade(h, p);
  parts.shutter = addShutter(h, p, addLouvre(h, p));

  GroundParts ground{};
  ground.rustication = addRustication(h, p);
  ground.plinth = addPlinth(h, p);
  ground.shopGlazing = addShopGlazing(h, p);
  ground.shopDoor = addShopDoor(h, p, addGlazedLeaf(h, p));
  ground.entranceDoor = addEntranceDoor(h, p, addPanelledLeaf(h, p), addFanlight(h, p));
  ground.backDoor = addBackDoor(h, p, addBoarding(h, p));
  ground.windowGround = parts.windowGround;
  ground.canopy = addCanopy(h, p);
  const BlockId stringCourse = addStringCourse(h, p);

  // Bays.
  const BlockId bayFront = addBayFront(h, p, parts);
  const BlockId bayPediment = addBayFrontPediment(h, p, parts);
  const BlockId bayTop = addBayFrontTop(h, p, parts);
  const BlockId bayBalcony = addBayBalcony(h, p, parts);
  const BlockId bayBack = addBayBack(h, p, parts);
  const BlockId bayBackBalcony = addBayBackBalcony(h, p, parts);
  const BlockId bayBathroom = addBayBathroom(h, p, parts);
  const BlockId bayStair = addBayStair(h, p, parts);
  const BlockId baySide = addBaySide(h, p, parts);
  const BlockId bayOculus = addBayOculus(h, p, parts);

  // Ground-floor modules.
  const BlockId shop = addShop(h, p, ground);
  const BlockId shopWindow = addShopWindow(h, p, ground);
  const BlockId entrance = addEntrance(h, p, ground);
  const BlockId groundWindow = addGroundWindow(h, p, ground);
  const BlockId backDoor = addGroundBackDoor(h, p, ground);

  // Rows: the front changes floor by floor; the back repeats one row; the sides too.
  const BlockId frontGround = addGroundRow(
      h, kFrontDepth, {{shop, 6.0}, {shopWindow, 3.0}, {entrance, 3.0}, {shopWindow, 3.0}, {shop, 6.0}}, stringCourse);
  const BlockId front1 =
      addRow(h, kStoreyH, kFrontDepth,
             {bayPediment, bayBalcony, bayPediment, bayPediment, bayPediment, bayBalcony, bayPediment});
  const BlockId front2 =
      addRow(h, kStoreyH, kFrontDepth, {bayFront, bayBalcony, bayFront, bayFront, bayFront, bayBalcony, bayFront});
  const BlockId front3 = addRow(h, kStoreyH, kFrontDepth, std::vector<BlockId>(7, bayTop));
  const BlockId backGround = addGroundRow(h, kFrontDepth,
                                          {{groundWindow, 3.0},
                                           {groundWindow, 3.0},
                                           {groundWindow, 3.0},
                                           {backDoor, 3.0},
                                           {groundWindow, 3.0},
                                           {groundWindow, 3.0},
                                           {groundWindow, 3.0}},
                                          stringCourse);
  const BlockId backFloor = addRow(
      h, kStoreyH, kFrontDepth, {bayBack, bayBackBalcony, bayBathroom, bayStair, bayBathroom, bayBackBalcony, bayBack});
  const BlockId sideGround =
      addGroundRow(h, kSideDepth, {{groundWindow, 3.0}, {groundWindow, 3.0}, {groundWindow, 3.0}, {groundWindow, 3.0}},
                   stringCourse);
  const BlockId sideFloor = addRow(h, kStoreyH, kSideDepth, {baySide, bayOculus, bayOculus, baySide});

  // Facades.
  const BlockId cornice = addCorniceRun(h, p);
  const BlockId corner = addFacadeCorner(h, addQuoins(h, p), addCorniceCorner(h, p));
  const BlockId frontFacade = addLongFacade(h, frontGround, {front1, front2, front3}, cornice, corner);
  const BlockId backFacade = addLongFacade(h, backGround, {backFloor}, cornice, corner);
  const BlockId sideFacade = addSideFacade(h, sideGround, sideFloor, cornice);

  // Interior.
  const BlockId staircase = addStaircase(h, p, addStairFlight(h, p));
  const BlockId interior = addInterior(h, p, addGroundInterior(h, p), addStorey(h, p, staircase));

  // Body: four facades round the interior; back and sides are turned about y.
  const double width = kFrontWidth + 2 * kCorner, depth = kSideWidth + 2 * kFrontDepth;  // 22.7 x 15.4
  nut::Block body =
      makeGrid({width, kBodyH, depth}, {kCorner, kCorner + kFrontWidth}, {}, {kFrontDepth, kFrontDepth + kSideWidth});
  const double frontZ = kFrontDepth + kSideWidth;
  place(h, body, region(0, 0, frontZ, width, kBodyH, depth), showing(frontFacade));
  place(h, body, region(0, 0, 0, width, kBodyH, kFrontDepth), rotatedFit(h, backFacade, turnAboutY(2)));
  place(h, body, region(kCorner + kFrontWidth, 0, kFrontDepth, width, kBodyH, frontZ),
        rotatedFit(h, sideFacade, turnAboutY(1)));
  place(h, body, region(0, 0, kFrontDepth, kCorner, kBodyH, frontZ), rotatedFit(h, sideFacade, turnAboutY(3)));
  place(h, body, region(kCorner, 0, kFrontDepth, kCorner + kFrontWidth, kBodyH, frontZ), showing(interior));
  const BlockId bodyId = h.addBlock(std::move(body));

  // Roof.
  const double hipD = kHalfDepth * std::numbers::sqrt2;  // half-diagonal of the diamond
  const BlockId dormer = addDormer(h, p, addDormerBody(h, p, windowDormer, addAtticSlope(h, p)));
  const BlockId chimney = addChimney(h, p, addChimneyPot(h, p));
  const BlockId roof = addRoof(h, addRoofMiddle(h, p, dormer, chimney), addHipPyramid(h, p, hipD), hipD);

  // Root: the body with the roof on top, its eaves over the cornice.
  const double eaves = (depth - kRoofDepth) / 2;
  nut::Block root = makeGrid({width, kBodyH + kRoofH, depth}, {}, {kBodyH}, {eaves, depth - eaves});
  place(h, root, region(0, 0, 0, width, kBodyH, depth), showing(bodyId));
  place(h, root, region(0, kBodyH, eaves, width, kBodyH + kRoofH, depth - eaves), showing(roof));
  h.root = h.addBlock(std::move(root));
  return h;
}

}  // namespace samples
