#include "gl_scenes.hpp"

#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>

namespace nut::gltest {

namespace {

const std::vector<Material> kMaterials{{200, 60, 40, 255, 0},  {60, 160, 90, 255, 0}, {70, 90, 200, 255, 0},
                                       {230, 210, 80, 255, 0}, {120, 200, 230, 96, 0}, {250, 250, 250, 160, 0}};

}  // namespace

Scene sampleScene(const std::string& name, int width, int height) {
  Scene s;
  s.name = name;
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png");
  if (!png) {
    ADD_FAILURE() << png.error().message;
    return s;
  }
  auto h = decode(png->image);
  if (!h) {
    ADD_FAILURE() << h.error().message;
    return s;
  }
  auto bounds = contentBounds(*h, png->text.originM);
  if (!bounds) {
    ADD_FAILURE() << bounds.error().message;
    return s;
  }
  s.model = std::move(*h);
  s.image = std::move(png->image);
  s.originM = png->text.originM;
  s.camera = fitCamera(*bounds, width, height);
  return s;
}

Scene compiledScene(const std::string& name, const Hierarchy& h, const glm::dvec3& originM, int width, int height) {
  Scene s;
  s.name = name;
  s.model = h;
  s.originM = originM;
  auto image = compile(h);
  if (!image) {
    ADD_FAILURE() << name << ": " << image.error().message;
    return s;
  }
  s.image = std::move(*image);
  // Hierarchies deeper than the mesh exporter follows have no content bounds: their root box then.
  auto bounds = contentBounds(h, originM);
  s.camera = fitCamera(bounds ? *bounds : WorldBox{originM, originM + h.blocks[h.root].sizeM()}, width, height);
  return s;
}

Hierarchy translucentPanes() {
  // Coloured boxes behind two layers of panes of different opacity, and one pane in front of nothing.
  Hierarchy h;
  h.materials = kMaterials;
  Block b = Block::fromSizes({{{1.0, 1.0, 1.0, 1.0}, {1.0, 1.0}, {0.1, 0.9, 0.1, 0.9, 1.0}}});
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 2; ++y) {
      b.cell(x, y, 4) = Cell::box(static_cast<std::uint16_t>((x + y) % 4));
      if (x != 3) b.cell(x, y, 2) = Cell::box(4);
      if ((x + y) % 2 == 0) b.cell(x, y, 0) = Cell::box(5);
    }
  b.cell(3, 1, 4) = Cell::empty();
  h.addBlock(std::move(b));
  return h;
}

Hierarchy nestedChain(int levels) {
  Hierarchy h;
  h.materials = kMaterials;
  std::mt19937_64 rng(7);
  // Quarter turns about y keep every level's floor below its middle cell, so a camera above the
  // centre looks down through all of them.
  std::vector<std::uint8_t> aboutY;
  for (int i = 0; i < 24; ++i)
    if (cubeRotationMatrix(i)[1] == glm::ivec3(0, 1, 0)) aboutY.push_back(static_cast<std::uint8_t>(i));
  double side = 1000.0;
  for (int k = 0; k < levels; ++k) {
    const std::vector<double> cells{0.05 * side, 0.9 * side, 0.05 * side};
    Block b = Block::fromSizes({cells, cells, cells});
    // A floor under the middle cell and one corner post, so that every level shows.
    for (int x = 0; x < 3; ++x)
      for (int z = 0; z < 3; ++z) b.cell(x, 0, z) = Cell::box(static_cast<std::uint16_t>(k % 4));
    b.cell(0, 1, 0) = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, static_cast<int>(rng() % 12)),
                                      static_cast<std::uint16_t>((k + 1) % 4));
    if (k + 1 < levels) {
      // Every fifth child is turned by a free yaw and made small enough (65 % of the cell) to fit
      // under any angle; the others fill 95 % of it. Each child's centre is its cell's centre.
      Redirection r;
      r.target = static_cast<BlockId>(k + 1);
      r.rotation.cube = aboutY[rng() % aboutY.size()];
      if (k % 5 == 4) r.rotation.yaw = static_cast<std::uint16_t>(rng() % 65536);
      const double childSide = (r.rotation.yaw != 0 ? 0.65 : 0.95) * 0.9 * side;
      r.offsetM = glm::dvec3(0.45 * side) - rotationMatrix(r.rotation) * glm::dvec3(0.5 * childSide);
      b.redirections.push_back(r);
      b.cell(1, 1, 1) = Cell::redirect(0);
      side = childSide;
    }
    h.addBlock(std::move(b));
  }
  return h;
}

Hierarchy centimetreCells() {
  // 500 m root -> 20 m block -> 0.6 m block of 1 cm cells (each step within the metadata's
  // widest / narrowest cell ratio).
  Hierarchy h;
  h.materials = kMaterials;
  Block root = Block::fromSizes({{{240.0, 20.0, 240.0}, {1.0, 19.0}, {240.0, 20.0, 240.0}}});
  root.cell(1, 0, 1) = Cell::redirect(0);
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {false, false, false}});
  for (int x = 0; x < 3; ++x)
    for (int z = 0; z < 3; ++z)
      if (x != 1 || z != 1) root.cell(x, 0, z) = Cell::box(3);
  h.addBlock(std::move(root));
  Block middle = Block::fromSizes({{{9.7, 0.6, 9.7}, {0.1, 0.9}, {9.7, 0.6, 9.7}}});
  middle.cell(1, 0, 1) = Cell::redirect(0);
  middle.redirections.push_back({2, glm::dvec3(0.0), {}, {false, false, false}});
  for (int x = 0; x < 3; ++x)
    for (int z = 0; z < 3; ++z)
      if (x != 1 || z != 1) middle.cell(x, 0, z) = Cell::box(2);
  h.addBlock(std::move(middle));
  Block detail = Block::fromSizes({{std::vector<double>(60, 0.01), {0.01, 0.08, 0.01}, std::vector<double>(60, 0.01)}});
  std::mt19937_64 rng(11);
  for (int x = 0; x < 60; ++x)
    for (int z = 0; z < 60; ++z) {
      detail.cell(x, 0, z) = Cell::box(static_cast<std::uint16_t>((x / 10 + z / 10) % 3));
      if (rng() % 7 == 0) detail.cell(x, 1, z) = Cell::box(static_cast<std::uint16_t>(rng() % 4));
    }
  h.addBlock(std::move(detail));
  return h;
}

Hierarchy thousandFoldWrap() {
  Hierarchy h;
  h.materials = kMaterials;
  Block row = Block::fromSizes({{{1000.0}, {2.0}, {2.0}}});
  Redirection r{1, glm::dvec3(0.0), {}, {true, false, false}};
  row.redirections.push_back(r);
  row.cell(0, 0, 0) = Cell::redirect(0);
  h.addBlock(std::move(row));
  // One metre of the row in five cells: a thin post on the far side, a sill low on the near side;
  // the middle of the cross-section is free, so a ray along the row visits five cells per metre.
  Block tile = Block::fromSizes({{{0.2, 0.2, 0.2, 0.2, 0.2}, {0.2, 1.6, 0.2}, {0.2, 1.6, 0.2}}});
  tile.cell(2, 1, 0) = Cell::box(0);
  for (int x = 0; x < 5; ++x) tile.cell(x, 0, 2) = Cell::box(static_cast<std::uint16_t>(1 + x % 3));
  h.addBlock(std::move(tile));
  return h;
}

}  // namespace nut::gltest
