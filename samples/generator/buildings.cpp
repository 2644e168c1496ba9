// The sample buildings (buildings.hpp): sizes in metres, y up, the ground at y = 0, the main
// facade facing +z.
#include "buildings.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "paint_grid.hpp"
#include "shapes.hpp"

namespace nut::samples {

namespace {

using glm::dvec3;

// Windows evenly along a facade span [t0, t1]: `count` windows of width w, centred in equal bays.
template <typename F>
void bays(double t0, double t1, int count, double w, F&& place) {
  const double bay = (t1 - t0) / count;
  for (int i = 0; i < count; ++i) place(t0 + (i + 0.5) * bay - 0.5 * w, i);
}

}  // namespace

void highRise(ObjBuilder& out) {
  const int wall = out.material("highrise_stone", {196, 188, 172});
  const int base = out.material("highrise_base", {92, 88, 84});
  const int glass = out.material("highrise_glass", {58, 78, 96});
  const int frame = out.material("highrise_frame", {232, 232, 226});
  const int roof = out.material("highrise_roof", {120, 120, 124});
  const int door = out.material("highrise_door", {70, 50, 36});
  out.object("highrise");
  PaintGrid g;
  constexpr double W = 32, D = 24, ground = 5.0, storey = 3.4;
  constexpr int floors = 40;
  const double top = ground + floors * storey;
  g.box({0, 0, 0}, {W, ground, D}, base);
  g.box({0, ground, 0}, {W, top, D}, wall);
  // Cornice band above the base and a parapet on the roof.
  g.box({-0.3, ground - 0.4, -0.3}, {W + 0.3, ground, D + 0.3}, frame);
  g.box({0, top, 0}, {W, top + 1.2, D}, wall);
  g.box({0.3, top + 0.2, 0.3}, {W - 0.3, top + 1.2, D - 0.3}, PaintGrid::kCarve);
  g.box({0.3, top, 0.3}, {W - 0.3, top + 0.2, D - 0.3}, roof);
  g.box({10, top, 8}, {20, top + 4.5, 15}, roof);  // machine room

  const WindowStyle style{0.22, 0.06, 0.06, 0.62, 0.05, glass, frame};
  const WindowStyle shop{0.3, 0, 0.08, 0.78, 0, glass, frame};
  const Facade facades[4] = {{2, +1, D}, {2, -1, 0}, {0, +1, W}, {0, -1, 0}};
  for (const Facade& f : facades) {
    const double span = f.normalAxis == 2 ? W : D;
    const int count = f.normalAxis == 2 ? 13 : 10;
    for (int floor = 0; floor < floors; ++floor)
      bays(0.0, span, count, 1.5, [&](double t, int) { window(g, f, t, ground + floor * storey + 0.95, 1.5, 1.95, style); });
    bays(0.0, span, f.normalAxis == 2 ? 6 : 4, 3.6, [&](double t, int i) {
      if (f.normalAxis == 2 && f.sign > 0 && i == 2) {  // the entrance
        f.box(g, -0.5, 0.0, t, t + 3.6, 0.0, 3.4, PaintGrid::kCarve);
        f.box(g, -0.55, -0.5, t, t + 3.6, 0.0, 3.4, door);
      } else {
        window(g, f, t, 0.6, 3.6, 3.4, shop);
      }
    });
  }
  g.emit(out);
}

void residential(ObjBuilder& out) {
  const int wall = out.material("residential_render", {226, 214, 186});
  const int plinth = out.material("residential_plinth", {140, 128, 112});
  const int glass = out.material("residential_glass", {66, 84, 102});
  const int frame = out.material("residential_frame", {245, 245, 240});
  const int roof = out.material("residential_tiles", {152, 62, 44});
  const int slab = out.material("residential_concrete", {178, 176, 170});
  const int rail = out.material("residential_railing", {60, 62, 66});
  const int door = out.material("residential_door", {96, 60, 40});
  const int chimney = out.material("residential_brick", {140, 76, 58});
  out.object("residential");
  PaintGrid g;
  constexpr double L = 42, D = 11, storey = 2.9;
  constexpr int floors = 5;
  const double eaves = floors * storey + 0.4;
  g.box({0, 0, 0}, {L, eaves, D}, wall);
  g.box({-0.05, 0, -0.05}, {L + 0.05, 0.5, D + 0.05}, plinth);
  const WindowStyle style{0.18, 0.05, 0.05, 0, 0, glass, frame};
  const Facade front{2, +1, D}, back{2, -1, 0}, east{0, +1, L}, west{0, -1, 0};
  for (int floor = 0; floor < floors; ++floor) {
    const double y = 0.4 + floor * storey;
    bays(0.0, L, 12, 1.3, [&](double t, int i) {
      if (i % 3 == 1 && floor > 0) {
        // Balcony: a door, a slab and a railing on three sides.
        const double t0 = t - 0.85, t1 = t + 2.15;
        front.box(g, -0.18, 0.0, t + 0.2, t + 1.1, y, y + 2.2, PaintGrid::kCarve);
        front.box(g, -0.23, -0.18, t + 0.2, t + 1.1, y, y + 2.2, glass);
        front.box(g, 0.0, 1.4, t0, t1, y - 0.16, y, slab);
        front.box(g, 1.35, 1.4, t0, t1, y, y + 1.0, rail);
        front.box(g, 0.0, 1.35, t0, t0 + 0.05, y, y + 1.0, rail);
        front.box(g, 0.0, 1.35, t1 - 0.05, t1, y, y + 1.0, rail);
      } else if (!(floor == 0 && i == 6)) {
        window(g, front, t, y + 0.9, 1.3, 1.4, style);
      }
      if (floor == 0 && (i == 3 || i == 8)) {
        back.box(g, -0.25, 0.0, t, t + 1.2, 0.0, 2.3, PaintGrid::kCarve);
        back.box(g, -0.3, -0.25, t, t + 1.2, 0.0, 2.3, door);
      } else {
        window(g, back, t, y + 0.9, 1.3, 1.4, style);
      }
    });
    bays(0.0, D, 3, 1.0, [&](double t, int) {
      window(g, east, t, y + 0.9, 1.0, 1.4, style);
      window(g, west, t, y + 0.9, 1.0, 1.4, style);
    });
  }
  // Entrance on the front, with a canopy.
  front.box(g, -0.3, 0.0, 19.9, 22.1, 0.0, 2.5, PaintGrid::kCarve);
  front.box(g, -0.35, -0.3, 19.9, 22.1, 0.0, 2.5, door);
  front.box(g, 0.0, 1.2, 19.5, 22.5, 2.7, 2.85, slab);
  // Chimneys rise through the roof.
  g.box({9, eaves, 3}, {9.8, eaves + 5.2, 3.8}, chimney);
  g.box({31, eaves, 7}, {31.8, eaves + 5.2, 7.8}, chimney);
  g.emit(out);
  gableRoof(out, 0, L, 0, D, eaves, 4.6, roof, wall);
}

void carPark(ObjBuilder& out) {
  const int concrete = out.material("carpark_concrete", {170, 168, 162});
  const int deck = out.material("carpark_deck", {98, 100, 104});
  const int pillar = out.material("carpark_pillar", {196, 192, 180});
  const int stripe = out.material("carpark_stripe", {222, 186, 52});
  const int stairs = out.material("carpark_stairs", {120, 132, 146});
  const int ramps = out.material("carpark_ramp", {110, 108, 104});
  out.object("carpark");
  PaintGrid g;
  constexpr double W = 48, D = 32, level = 3.0, slabT = 0.3;
  constexpr int levels = 4;
  // Ramps run along x in the strip z in [rz0, rz1]; the slab above each ramp has an opening.
  constexpr double rx0 = 10, rx1 = 26, rz0 = 26.5, rz1 = 30.5;
  for (int k = 0; k <= levels; ++k) {
    const double y = k * level;
    g.box({0, y, 0}, {W, y + slabT, D}, concrete);
    g.box({0.2, y + slabT - 0.01, 0.2}, {W - 0.2, y + slabT, D - 0.2}, deck);
    if (k > 0) {
      g.box({rx0, y, rz0}, {rx1, y + slabT, rz1}, PaintGrid::kCarve);
      // Parapets with a yellow band.
      const double p = y + slabT;
      g.box({0, p, 0}, {W, p + 1.0, 0.2}, concrete);
      g.box({0, p, D - 0.2}, {W, p + 1.0, D}, concrete);
      g.box({0, p, 0}, {0.2, p + 1.0, D}, concrete);
      g.box({W - 0.2, p, 0}, {W, p + 1.0, D}, concrete);
      g.box({-0.02, p + 0.7, -0.02}, {W + 0.02, p + 0.85, D + 0.02}, stripe);
      g.box({0.2, p + 0.7, 0.2}, {W - 0.2, p + 0.85, D - 0.2}, PaintGrid::kCarve);
    }
    if (k < levels)
      for (double x = 6; x < W - 1; x += 7.5)
        for (double z = 5; z < D - 1; z += 7.5) g.box({x - 0.25, y + slabT, z - 0.25}, {x + 0.25, y + level, z + 0.25}, pillar);
  }
  // Stair tower at a corner, one storey above the roof deck.
  g.box({W - 5, 0, 0}, {W, levels * level + 3.2, 5}, stairs);
  g.box({W - 3.5, 0, -0.01}, {W - 2.3, 2.2, 0.2}, PaintGrid::kCarve);
  g.emit(out);
  for (int k = 1; k <= levels; ++k)
    ramp(out, rx0, rx1, rz0 + 0.1, rz1 - 0.1, (k - 1) * level + slabT - 0.25, k * level + slabT - 0.25, 0.25, ramps);
}

void house(ObjBuilder& out) {
  const int wall = out.material("house_render", {236, 228, 210});
  const int glass = out.material("house_glass", {70, 92, 112});
  const int frame = out.material("house_frame", {90, 70, 56});
  const int copper = out.material("house_dome", {92, 150, 128});
  const int drum = out.material("house_drum", {214, 200, 170});
  const int roof = out.material("house_roof", {128, 124, 120});
  const int door = out.material("house_door", {110, 62, 40});
  out.object("house");
  PaintGrid g;
  constexpr double W = 14, D = 10, H = 6.6, r = 1.5;
  g.box({0, 0, 0}, {W, H, D}, wall);
  g.box({0.3, H - 0.01, 0.3}, {W - 0.3, H, D - 0.3}, roof);
  // Corners are rounded: the grid leaves an r x r notch that a quarter cylinder fills.
  for (const double x : {0.0, W - r})
    for (const double z : {0.0, D - r}) g.box({x, 0, z}, {x + r, H, z + r}, PaintGrid::kCarve);
  const WindowStyle style{0.2, 0.05, 0.05, 0.6, 0.06, glass, frame};
  const Facade front{2, +1, D}, back{2, -1, 0}, east{0, +1, W}, west{0, -1, 0};
  for (int floor = 0; floor < 2; ++floor) {
    const double y = floor * 3.2 + 0.9;
    bays(r, W - r, 4, 1.2, [&](double t, int i) {
      if (!(floor == 0 && i == 1)) window(g, front, t, y, 1.2, 1.5, style);
      window(g, back, t, y, 1.2, 1.5, style);
    });
    bays(r, D - r, 2, 1.2, [&](double t, int) {
      window(g, east, t, y, 1.2, 1.5, style);
      window(g, west, t, y, 1.2, 1.5, style);
    });
  }
  front.box(g, -0.25, 0.0, 4.6, 5.8, 0.0, 2.3, PaintGrid::kCarve);
  front.box(g, -0.3, -0.25, 4.6, 5.8, 0.0, 2.3, door);
  g.emit(out);
  quarterCylinder(out, r, r, r, 0, H, -1, -1, 16, wall);
  quarterCylinder(out, W - r, r, r, 0, H, +1, -1, 16, wall);
  quarterCylinder(out, r, D - r, r, 0, H, -1, +1, 16, wall);
  quarterCylinder(out, W - r, D - r, r, 0, H, +1, +1, 16, wall);
  domedDrum(out, W / 2, D / 2, 2.4, H, H + 1.6, 48, 16, drum, copper);
}

void streetBlock(ObjBuilder& out) {
  struct Spec {
    const char* name;
    double x0, x1, z0, z1;
    int floors;
    std::array<int, 3> wall, trim;
  };
  // Four buildings touching along their party walls; windows only on the block's outer facades.
  const Spec specs[4] = {{"street_a", 0, 16, 14, 30, 6, {210, 180, 150}, {240, 236, 226}},
                         {"street_b", 16, 34, 14, 30, 4, {168, 188, 204}, {250, 250, 250}},
                         {"street_c", 0, 16, 0, 14, 5, {196, 120, 96}, {236, 226, 200}},
                         {"street_d", 16, 34, 0, 14, 8, {220, 220, 206}, {120, 120, 126}}};
  const int glass = out.material("street_glass", {62, 82, 100});
  const int roof = out.material("street_roof", {110, 110, 112});
  const int shopGlass = out.material("street_shop_glass", {46, 64, 80});
  for (const Spec& s : specs) {
    const int wall = out.material(std::string(s.name) + "_wall", s.wall);
    const int trim = out.material(std::string(s.name) + "_trim", s.trim);
    out.object(s.name);
    PaintGrid g;
    constexpr double ground = 4.2, storey = 3.1;
    const double top = ground + s.floors * storey;
    g.box({s.x0, 0, s.z0}, {s.x1, top, s.z1}, wall);
    g.box({s.x0, top, s.z0}, {s.x1, top + 0.9, s.z1}, wall);
    g.box({s.x0 + 0.3, top + 0.15, s.z0 + 0.3}, {s.x1 - 0.3, top + 0.9, s.z1 - 0.3}, PaintGrid::kCarve);
    g.box({s.x0 + 0.3, top, s.z0 + 0.3}, {s.x1 - 0.3, top + 0.15, s.z1 - 0.3}, roof);
    const WindowStyle style{0.2, 0.06, 0.05, 0.65, 0.08, glass, trim};
    const WindowStyle shop{0.25, 0, 0.08, 0, 0, shopGlass, trim};
    std::vector<Facade> outer;
    if (s.z1 == 30) outer.push_back({2, +1, 30});
    if (s.z0 == 0) outer.push_back({2, -1, 0});
    if (s.x1 == 34) outer.push_back({0, +1, 34});
    if (s.x0 == 0) outer.push_back({0, -1, 0});
    for (const Facade& f : outer) {
      const double t0 = f.normalAxis == 2 ? s.x0 : s.z0, t1 = f.normalAxis == 2 ? s.x1 : s.z1;
      const int count = static_cast<int>((t1 - t0) / 2.6);
      for (int floor = 0; floor < s.floors; ++floor)
        bays(t0, t1, count, 1.3, [&](double t, int) { window(g, f, t, ground + floor * storey + 0.9, 1.3, 1.8, style); });
      bays(t0, t1, std::max(1, count / 2), 3.2, [&](double t, int) { window(g, f, t, 0.5, 3.2, 3.0, shop); });
      f.box(g, 0.0, 0.12, t0, t1, ground - 0.35, ground - 0.1, trim);  // string course
    }
    g.emit(out);
  }
}

}  // namespace nut::samples
