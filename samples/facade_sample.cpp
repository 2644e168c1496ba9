// samples/facade_sample.cpp — a 25 m x 20 m shop-and-flats facade that shows object wrapping
// (paper Figure 3a): one 3 m x 3 m window bay is drawn once and repeated 8 x 5 times by a single
// redirection cell whose wrap flags are set on x and y; the ground-floor shop unit repeats 4 times
// along x the same way, and so does a 1 m cornice module with dentils.
//
// Frame: x to the right along the facade, y up, z out of the building (the front faces +z).
// Depth zones, from the back: a dark back wall of the rooms, 2.5 m of room, the 0.4 m wall, and a
// 5 cm layer for things that stand proud of the wall (sill noses, architraves, the sign board).
#include "sample_kit.hpp"
#include "samples.hpp"

namespace samples {

namespace {

constexpr double kBackWall = 0.1;
constexpr double kRoom = 2.5;
constexpr double kWall = 0.4;
constexpr double kProud = 0.05;
constexpr double kWallInside = kBackWall + kRoom;  // z of the wall's inner face
constexpr double kWallFace = kWallInside + kWall;  // z of the wall's outer face
constexpr double kBodyDepth = kWallFace + kProud;  // what a bay or shop unit spans in z
constexpr double kCorniceDepth = 0.4;              // how far the cornice projects

struct Palette {
  std::uint16_t render, stone, darkStone, frame, glass, interior, floor, shopFrame, sign, doorWood;
};

Palette makePalette(nut::Hierarchy& h) {
  Palette p{};
  p.render = colour(h, 222, 196, 152);     // ochre lime render
  p.stone = colour(h, 204, 198, 182);      // limestone: sills, cornice, pilasters
  p.darkStone = colour(h, 150, 146, 138);  // ground-floor masonry
  p.frame = colour(h, 238, 236, 228);      // painted window frames
  p.glass = colour(h, 62, 76, 92, 90);     // dark blue-grey glass, a little reflective
  p.interior = colour(h, 58, 50, 44);      // unlit room interior
  p.floor = colour(h, 118, 88, 60);        // timber floor
  p.shopFrame = colour(h, 48, 46, 44);     // bronze shop front
  p.sign = colour(h, 28, 72, 52);          // painted sign board
  p.doorWood = colour(h, 92, 52, 30);
  return p;
}

// A 1.2 m x 1.6 m casement in the 0.4 m wall opening: two lights with a transom, the frame set
// 0.15 m back from the wall face, a timber board inside and a sloped stone sill outside.
nut::BlockId addWindow(nut::Hierarchy& h, const Palette& p) {
  const double frameBack = 0.2, glassBack = 0.22, glassFront = 0.24, frameFront = 0.25;
  nut::Block b = makeGrid({1.2, 1.6, kWall}, {0.07, 0.57, 0.63, 1.13}, {0.08, 0.15, 1.15, 1.21, 1.53},
                          {frameBack, glassBack, glassFront, frameFront});
  fill(b, region(0, 0, 0, 1.2, 0.08, frameBack), nut::Cell::box(p.frame));           // inner board
  fill(b, region(0, 0, frameBack, 1.2, 0.08, frameFront), nut::Cell::box(p.stone));  // sill under frame
  // The sill falls outwards (wedge hugging its low back edge) so rain runs off the wall.
  fill(b, region(0, 0, frameFront, 1.2, 0.08, kWall), wedge(Along, Lo, Lo, p.stone));
  fill(b, region(0, 0.08, frameBack, 1.2, 1.6, frameFront), nut::Cell::box(p.frame));
  for (double x0 : {0.07, 0.63})
    for (const auto& [y0, y1] : {std::pair{0.15, 1.15}, std::pair{1.21, 1.53}}) {
      fill(b, region(x0, y0, frameBack, x0 + 0.5, y1, frameFront), nut::Cell::empty());
      fill(b, region(x0, y0, glassBack, x0 + 0.5, y1, glassFront), nut::Cell::box(p.glass));
    }
  return h.addBlock(std::move(b));
}

// One 3 m x 3 m upper-floor bay: a room (floor slab, dark back wall), the wall with the window
// opening redirected to the window block, and a stone sill nose and architrave standing proud.
nut::BlockId addBay(nut::Hierarchy& h, const Palette& p, nut::BlockId window) {
  nut::Block b = makeGrid({3.0, 3.0, kBodyDepth}, {0.85, 0.9, 2.1, 2.15}, {0.2, 0.84, 0.9, 2.5, 2.6},
                          {kBackWall, kWallInside, kWallFace});
  fill(b, region(0, 0, 0, 3.0, 3.0, kBackWall), nut::Cell::box(p.interior));
  fill(b, region(0, 0, kBackWall, 3.0, 0.2, kWallInside), nut::Cell::box(p.floor));
  fill(b, region(0, 0, kWallInside, 3.0, 3.0, kWallFace), nut::Cell::box(p.render));
  place(h, b, region(0.9, 0.9, kWallInside, 2.1, 2.5, kWallFace), showing(window));
  fill(b, region(0.85, 0.84, kWallFace, 2.15, 0.9, kBodyDepth), nut::Cell::box(p.stone));  // sill nose
  fill(b, region(0.85, 0.9, kWallFace, 0.9, 2.6, kBodyDepth), nut::Cell::box(p.stone));    // architrave
  fill(b, region(2.1, 0.9, kWallFace, 2.15, 2.6, kBodyDepth), nut::Cell::box(p.stone));
  fill(b, region(0.9, 2.5, kWallFace, 2.1, 2.6, kBodyDepth), nut::Cell::box(p.stone));
  return h.addBlock(std::move(b));
}

// A 1.2 m wide module of shop glazing with half mullions at both ends, tiled along x to fill the
// shop window whatever its width in modules.
nut::BlockId addShopGlazing(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({1.2, 2.4, kWall}, {0.03, 1.17}, {0.06, 2.34}, {0.29, 0.31, 0.33, 0.35});
  fill(b, region(0, 0, 0.29, 1.2, 2.4, 0.35), nut::Cell::box(p.shopFrame));
  fill(b, region(0.03, 0.06, 0.29, 1.17, 2.34, 0.35), nut::Cell::empty());
  fill(b, region(0.03, 0.06, 0.31, 1.17, 2.34, 0.33), nut::Cell::box(p.glass));
  return h.addBlock(std::move(b));
}

// A 1.3 m x 2.8 m shop door: panelled bottom, glazed top, fanlight, 0.15 m behind the face.
nut::BlockId addShopDoor(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGridFromSizes({0.08, 1.14, 0.08}, {0.9, 0.08, 1.3, 0.08, 0.36, 0.08}, {0.2, 0.05, 0.15});
  fillCells(b, 0, 3, 0, 6, 1, 2, nut::Cell::box(p.doorWood));
  fillCells(b, 1, 2, 2, 3, 1, 2, nut::Cell::box(p.glass));
  fillCells(b, 1, 2, 4, 5, 1, 2, nut::Cell::box(p.glass));
  return h.addBlock(std::move(b));
}

// A 6 m x 4 m shop unit: a 3.6 m shop window (glazing module tiled three times), a door, a
// stall riser and a sign board, with the shop floor and a dark back wall behind.
nut::BlockId addShopUnit(nut::Hierarchy& h, const Palette& p, nut::BlockId glazing, nut::BlockId door) {
  nut::Block b =
      makeGrid({6.0, 4.0, kBodyDepth}, {0.4, 4.0, 4.3, 5.6}, {0.2, 0.6, 3.0, 3.2}, {kBackWall, kWallInside, kWallFace});
  fill(b, region(0, 0, 0, 6.0, 4.0, kBackWall), nut::Cell::box(p.interior));
  fill(b, region(0, 0, kBackWall, 6.0, 0.2, kWallInside), nut::Cell::box(p.darkStone));
  fill(b, region(0, 0, kWallInside, 6.0, 4.0, kWallFace), nut::Cell::box(p.darkStone));
  place(h, b, region(0.4, 0.6, kWallInside, 4.0, 3.0, kWallFace), showing(glazing, /*wrapX=*/true));
  place(h, b, region(4.3, 0.2, kWallInside, 5.6, 3.0, kWallFace), showing(door));
  fill(b, region(0.4, 0.2, kWallFace, 4.0, 0.6, kBodyDepth), nut::Cell::box(p.stone));  // stall riser
  fill(b, region(0, 3.2, kWallFace, 6.0, 4.0, kBodyDepth), nut::Cell::box(p.sign));
  return h.addBlock(std::move(b));
}

// A 1 m cornice module (profile in y-z, dentils along x): fascia with a cove under the dentil
// course, a bed moulding, the corona and a rounded cap. Tiled along the whole facade.
nut::BlockId addCornice(nut::Hierarchy& h, const Palette& p) {
  nut::Block b = makeGrid({1.0, 0.7, kCorniceDepth}, {0.1, 0.25, 0.35, 0.5, 0.6, 0.75, 0.85}, {0.15, 0.27, 0.32, 0.55},
                          {0.05, 0.15, 0.25});
  fill(b, region(0, 0, 0, 1.0, 0.15, 0.05), nut::Cell::box(p.stone));
  fill(b, region(0, 0, 0.05, 1.0, 0.15, 0.15), coveCylinder(Along, Lo, Hi, p.stone));  // concave, under the dentils
  fill(b, region(0, 0.15, 0, 1.0, 0.27, 0.15), nut::Cell::box(p.stone));
  for (double x0 : {0.1, 0.35, 0.6, 0.85})
    fill(b, region(x0, 0.15, 0.15, x0 + 0.15, 0.27, 0.25), nut::Cell::box(p.stone));
  fill(b, region(0, 0.27, 0, 1.0, 0.32, 0.25), nut::Cell::box(p.stone));
  fill(b, region(0, 0.32, 0, 1.0, 0.55, kCorniceDepth), nut::Cell::box(p.stone));
  fill(b, region(0, 0.55, 0, 1.0, 0.7, 0.25), nut::Cell::box(p.stone));
  fill(b, region(0, 0.55, 0.25, 1.0, 0.7, kCorniceDepth), quarterCylinder(Along, Lo, Lo, p.stone));  // ovolo
  return h.addBlock(std::move(b));
}

}  // namespace

nut::Hierarchy buildFacadeSample() {
  nut::Hierarchy h;
  const Palette p = makePalette(h);
  const nut::BlockId window = addWindow(h, p);
  const nut::BlockId bay = addBay(h, p, window);
  const nut::BlockId shop = addShopUnit(h, p, addShopGlazing(h, p), addShopDoor(h, p));
  const nut::BlockId cornice = addCornice(h, p);

  // The root: ground floor (4 shop units), a string course, five floors of eight bays, and the
  // cornice, between two stone end pilasters. Its only z cut is the front of the proud layer, so
  // the whole 24 m x 15 m block of upper floors is ONE cell: the bay wraps along x and y.
  const double width = 25.0, height = 20.0, groundTop = 4.0, upperBottom = 4.3, upperTop = 19.3;
  const double depth = kWallFace + kCorniceDepth;
  nut::Block root = makeGrid({width, height, depth}, {0.5, 24.5}, {groundTop, upperBottom, upperTop}, {kBodyDepth});
  place(h, root, region(0.5, 0, 0, 24.5, groundTop, kBodyDepth), showing(shop, /*wrapX=*/true));
  place(h, root, region(0.5, upperBottom, 0, 24.5, upperTop, kBodyDepth), showing(bay, true, true));
  fill(root, region(0, 0, 0, 0.5, upperTop, kBodyDepth), nut::Cell::box(p.stone));
  fill(root, region(24.5, 0, 0, width, upperTop, kBodyDepth), nut::Cell::box(p.stone));
  fill(root, region(0, groundTop, 0, width, upperBottom, kBodyDepth), nut::Cell::box(p.stone));
  // The cornice row: solid up to the front of the proud layer (which is the cornice's fascia),
  // then the cornice module shifted back by that layer so its profile continues from there.
  fill(root, region(0, upperTop, 0, width, height, kBodyDepth), nut::Cell::box(p.stone));
  place(h, root, region(0, upperTop, kBodyDepth, width, height, depth),
        showing(cornice, /*wrapX=*/true, false, false, {0, 0, -kProud}));
  h.root = h.addBlock(std::move(root));
  return h;
}

}  // namespace samples
