// docs/FORMAT.md read as a contract. Each test takes a rule of the document, writes down what the
// document says independently of the code that implements it (tables typed from the document,
// recipes coded here from its prose), and checks the library and the committed samples against
// it: the 24 cube rotation matrices and the rotations sample, the solid catalogue's orientation
// rules, the recipe for a cell's corners from the metadata pixels (j numbers, faces, exact row,
// float32 lookups), the image size limits, the pixels that a premultiplied upload destroys, what
// is done with textures, and the figures of `nut info`.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <nut/camera.hpp>
#include <nut/exact_path.hpp>
#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

namespace nut {
namespace {

const std::vector<std::string> kSamples{"facade", "building", "solids", "rotations"};

PngFile loadSample(const std::string& name) {
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png");
  EXPECT_TRUE(png.ok()) << name << ": " << (png.ok() ? "" : png.error().message);
  return png.ok() ? std::move(*png) : PngFile{};
}

// ---- Cube rotations ("Redirection record", table of the 24 rotations) -------------------------

// The document's table: the images of +x, +y, +z (the matrix's columns), as signed axes.
struct SignedAxes {
  std::array<glm::ivec3, 3> column;
};
const std::array<SignedAxes, 24> kSpecRotations{{
    {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}},     // 0   +x +y +z
    {{{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}},   // 1   -x -y +z
    {{{{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}},   // 2   -x +y -z
    {{{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}},   // 3   +x -y -z
    {{{{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}}},    // 4   -x +z +y
    {{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}}},    // 5   +x -z +y
    {{{{1, 0, 0}, {0, 0, 1}, {0, -1, 0}}}},    // 6   +x +z -y
    {{{{-1, 0, 0}, {0, 0, -1}, {0, -1, 0}}}},  // 7   -x -z -y
    {{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}}},    // 8   -y +x +z
    {{{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}}},    // 9   +y -x +z
    {{{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}}},    // 10  +y +x -z
    {{{{0, -1, 0}, {-1, 0, 0}, {0, 0, -1}}}},  // 11  -y -x -z
    {{{{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}}},     // 12  +y +z +x
    {{{{0, -1, 0}, {0, 0, -1}, {1, 0, 0}}}},   // 13  -y -z +x
    {{{{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}}}},   // 14  -y +z -x
    {{{{0, 1, 0}, {0, 0, -1}, {-1, 0, 0}}}},   // 15  +y -z -x
    {{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}}},     // 16  +z +x +y
    {{{{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}}},   // 17  -z -x +y
    {{{{0, 0, -1}, {1, 0, 0}, {0, -1, 0}}}},   // 18  -z +x -y
    {{{{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}}}},   // 19  +z -x -y
    {{{{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}}},    // 20  -z +y +x
    {{{{0, 0, 1}, {0, -1, 0}, {1, 0, 0}}}},    // 21  +z -y +x
    {{{{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}}}},    // 22  +z +y -x
    {{{{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}}}},  // 23  -z -y -x
}};

glm::dmat3 specMatrix(int index) {
  const SignedAxes& r = kSpecRotations[static_cast<std::size_t>(index)];
  return glm::dmat3(glm::dvec3(r.column[0]), glm::dvec3(r.column[1]), glm::dvec3(r.column[2]));
}

TEST(CubeRotations, TheTableIsTheTwentyFourProperRotationsInTheDocumentedOrder) {
  // The table itself: 24 distinct signed permutation matrices of determinant +1, and each row
  // follows the enumeration rule (permutation p in lexicographic order, then sign mask).
  std::set<std::vector<int>> distinct;
  int previousKey = -1;
  for (int i = 0; i < 24; ++i) {
    const glm::dmat3 m = specMatrix(i);
    EXPECT_EQ(glm::determinant(m), 1.0) << "rotation " << i;
    int permutationRank = 0, mask = 0;
    std::vector<int> entries;
    for (int c = 0; c < 3; ++c) {
      const glm::ivec3 column = kSpecRotations[static_cast<std::size_t>(i)].column[static_cast<std::size_t>(c)];
      const int p = column.x != 0 ? 0 : column.y != 0 ? 1 : 2;  // column c = +-e_p[c]
      permutationRank = permutationRank * 3 + p;                // lexicographic order of p
      mask |= (column[p] < 0 ? 1 : 0) << c;
      entries.insert(entries.end(), {column.x, column.y, column.z});
    }
    const int key = permutationRank * 8 + mask;
    EXPECT_GT(key, previousKey) << "rotation " << i << " is out of the documented order";
    previousKey = key;
    distinct.insert(entries);
  }
  EXPECT_EQ(distinct.size(), 24u);
}

TEST(CubeRotations, TheLibraryUsesTheDocumentedMatrices) {
  for (int i = 0; i < 24; ++i) {
    const glm::mat<3, 3, int> m = cubeRotationMatrix(i);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(m[c], kSpecRotations[static_cast<std::size_t>(i)].column[static_cast<std::size_t>(c)])
          << "rotation " << i << " column " << c;
  }
}

// The rotations sample: the tripod (samples/rotations_sample.cpp) seen through every rotation.
struct TripodProbe {
  glm::dvec3 local;  // a point of the tripod block, metres
  int material;      // its material in rotations.png, or -1 for an empty point
};
// Materials of rotations.png: 0 base, 1 hub, 2 x arm, 3 y arm, 4 z arm, 5 wedge.
const std::array<TripodProbe, 7> kTripodProbes{{
    {{0.15, 0.15, 0.15}, 1},
    {{0.75, 0.15, 0.15}, 2},
    {{0.15, 0.60, 0.15}, 3},
    {{0.15, 0.15, 0.45}, 4},
    {{0.40, 0.40, 0.15}, 5},   // near the wedge's right-angle edge
    {{1.10, 0.85, 0.15}, -1},  // the wedge cell's far corner, cut away
    {{1.00, 0.70, 0.45}, -1},  // an empty cell
}};

TEST(RotationsSample, UsesEveryCubeRotationOnce) {
  const PngFile png = loadSample("rotations");
  auto h = decode(png.image);
  ASSERT_TRUE(h.ok()) << h.error().message;
  std::multiset<int> used;
  for (const Block& b : h->blocks)
    for (const Redirection& r : b.redirections) used.insert(r.rotation.cube);
  for (int i = 0; i < 24; ++i) EXPECT_EQ(used.count(i), 1u) << "rotation " << i;
  EXPECT_EQ(used.size(), 24u);
}

// Each display cube shows the tripod where the document's matrix puts it: a ray starting at the
// predicted point of an arm is inside that arm's solid (distance 0, its material), and one
// starting at a predicted empty point is not inside anything. Both the caster (over the image)
// and the exact path (over the decoded model) are asked.
TEST(RotationsSample, EveryRotatedTripodIsWhereTheDocumentedMatrixPutsIt) {
  const PngFile png = loadSample("rotations");
  auto decoded = decode(png.image);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  const Hierarchy& h = *decoded;
  const Block& root = h.blocks[h.root];
  const HniRayCaster caster(png.image, glm::dvec3(0.0));
  RayCastOptions options;
  options.lookup = Lookup::Exact;
  // Away from the light: a surface facing the ray is lit by the ambient term alone.
  const glm::dvec3 dir = -kLightDirection;
  for (int z = 0; z < root.cellCount(2); ++z)
    for (int x = 0; x < root.cellCount(0); ++x) {
      const Cell& cell = root.cell(x, 1, z);
      if (cell.kind != CellKind::Redirection) continue;
      const Redirection& red = root.redirections[cell.redirection];
      const glm::dvec3 cellMin(root.boundsM[0][static_cast<std::size_t>(x)], root.boundsM[1][1],
                               root.boundsM[2][static_cast<std::size_t>(z)]);
      for (const TripodProbe& probe : kTripodProbes) {
        const glm::dvec3 at = cellMin + red.offsetM + specMatrix(red.rotation.cube) * probe.local;
        const RayResult fromImage = caster.trace(at, dir, 1e-3, options);
        const RayResult fromModel = traceExact(h, glm::dvec3(0.0), at, dir);
        const std::string where = "rotation " + std::to_string(red.rotation.cube) + " probe (" +
                                  std::to_string(probe.local.x) + ", " + std::to_string(probe.local.y) + ", " +
                                  std::to_string(probe.local.z) + ")";
        for (const RayResult& r : {fromImage, fromModel}) {
          if (probe.material < 0) {
            EXPECT_FALSE(r.hit && r.distanceM == 0.0) << where << ": inside a solid, expected empty";
            continue;
          }
          const Material& m = h.materials[static_cast<std::size_t>(probe.material)];
          EXPECT_TRUE(r.hit && r.distanceM == 0.0) << where << ": not inside a solid";
          EXPECT_EQ(r.colour, shade({m.r, m.g, m.b}, -dir, dir)) << where << ": wrong material";
        }
      }
    }
}

// Whether pixel (x, y) of a render has a neighbour of another colour or of another hit state.
bool nearEdge(const RenderOutput& r, int x, int y) {
  const int w = r.colour.width, ht = r.colour.height;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= ht) continue;
      for (int c = 0; c < 3; ++c)
        if (std::abs(r.colour.at(x, y)[c] - r.colour.at(nx, ny)[c]) > 8) return true;
      const float a = r.distanceM[static_cast<std::size_t>(y * w + x)];
      const float b = r.distanceM[static_cast<std::size_t>(ny * w + nx)];
      if (std::isinf(a) != std::isinf(b) || std::abs(a - b) > 0.02f * std::min(a, b)) return true;
    }
  return false;
}

TEST(RotationsSample, CasterRenderMatchesTheExactPath) {
  const PngFile png = loadSample("rotations");
  auto decoded = decode(png.image);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  const Hierarchy& h = *decoded;
  auto content = contentBounds(h, png.text.originM);
  ASSERT_TRUE(content.ok()) << content.error().message;
  Camera camera = fitCamera(*content, 320, 180);
  // From high above the front and nearer than the fitted camera (whose sphere is loose around the
  // flat sample), so that the arms of every display cube are in view and large.
  const double distance = 0.6 * glm::length(camera.eye - camera.target);
  camera.eye = camera.target + distance * glm::normalize(glm::dvec3(0.3, 1.6, 1.0));
  const HniRayCaster caster(png.image, png.text.originM);
  RayCastOptions options;
  options.lookup = Lookup::Exact;
  const RenderOutput fromImage = renderHni(caster, camera, options);
  const RenderOutput fromModel = renderRays(camera, [&](const glm::dvec3& eye, const glm::dvec3& d, double) {
    return traceExact(h, png.text.originM, eye, d);
  });
  long long differing = 0, offEdge = 0, hits = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * camera.width + x);
      hits += !std::isinf(fromModel.distanceM[i]);
      bool differs = std::isinf(fromImage.distanceM[i]) != std::isinf(fromModel.distanceM[i]);
      for (int c = 0; c < 3; ++c) differs |= std::abs(fromImage.colour.at(x, y)[c] - fromModel.colour.at(x, y)[c]) > 3;
      differing += differs;
      offEdge += differs && !nearEdge(fromModel, x, y);
    }
  const std::filesystem::path dir = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / "format_spec";
  std::filesystem::create_directories(dir);
  if (differing > 0 || ::testing::Test::HasFailure()) {
    (void)writePng((dir / "rotations.caster.png").string(), fromImage.colour);
    (void)writePng((dir / "rotations.exact.png").string(), fromModel.colour);
  }
  std::printf("rotations.png: %lld of %d px differ (%lld off edges), %lld px hit\n", differing,
              camera.width * camera.height, offEdge, hits);
  EXPECT_GT(hits, camera.width * camera.height / 4);
  EXPECT_LE(differing, camera.width * camera.height / 200);
  EXPECT_EQ(offEdge, 0) << "see " << dir.string();
}

// ---- Solids ("Solids"): the orientation rules, from the document's text ---------------------

// The region of solid `index` as FORMAT.md states it: edge-based groups (wedge, quarter cylinder,
// inverse quarter cylinder) measure u', v' from the edge named by the corner bits, corner-based
// groups (pyramids, octants and their inverses) x', y', z' from the corner named by the corner
// bits. P is {value <= 1}; a solid is the cube intersected with P, an inverse one the cube minus P.
struct SpecRegion {
  double value = 0;
  bool inverse = false;
  bool contains() const { return inverse ? value >= 1 : value <= 1; }
};

SpecRegion specRegion(int index, const glm::dvec3& p) {
  struct Group {
    int first, count;
    bool edgeBased, ball, inverse;
  };
  static const Group kGroups[] = {{0, 1, false, false, false},  {1, 12, true, false, false},
                                  {13, 8, false, false, false}, {21, 8, false, false, true},
                                  {29, 12, true, true, false},  {41, 12, true, true, true},
                                  {53, 8, false, true, false},  {61, 8, false, true, true}};
  for (const Group& g : kGroups) {
    if (index < g.first || index >= g.first + g.count) continue;
    if (index == 0) return {0.0, false};  // the box: P is everything
    const int o = index - g.first;
    std::vector<double> primed;
    if (g.edgeBased) {
      const int axis = o / 4, corner = o % 4;
      const double u = p[(axis + 1) % 3], v = p[(axis + 2) % 3];
      primed = {(corner & 1) ? 1 - u : u, (corner & 2) ? 1 - v : v};
    } else {
      for (int a = 0; a < 3; ++a) primed.push_back((o >> a & 1) ? 1 - p[a] : p[a]);
    }
    SpecRegion r{0.0, g.inverse};
    for (double q : primed) r.value += g.ball ? q * q : q;
    return r;
  }
  ADD_FAILURE() << "solid " << index << " is in no group";
  return {};
}

TEST(Solids, EveryIndexFollowsTheDocumentedOrientationRule) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int index = 0; index < 69; ++index) {
    const Solid solid{static_cast<std::uint8_t>(index)};
    int inside = 0;
    for (int n = 0; n < 2000; ++n) {
      const glm::dvec3 p(unit(rng), unit(rng), unit(rng));
      const SpecRegion r = specRegion(index, p);
      if (std::abs(r.value - 1) < 1e-12) continue;  // on the surface: a solid and its inverse alike
      inside += r.contains();
      ASSERT_EQ(solidContains(solid, p), r.contains())
          << "solid " << index << " (" << solidName(solid) << ") at (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
    EXPECT_GT(inside, 0) << "solid " << index;
  }
}

TEST(Solids, InverseQuarterCylinderCornerBitsNameTheEdgeItCutsAway) {
  // The corner bits name the edge where u' = v' = 0: the quarter cylinder's own right-angle edge,
  // and the axis of the quarter disc that the inverse quarter cylinder removes (so that edge is
  // empty, and the solid's own right-angle edge is the opposite one, u' = v' = 1).
  for (int o = 0; o < 12; ++o) {
    const int axis = o / 4, corner = o % 4;
    glm::dvec3 nearNamedEdge(0.5), nearOppositeEdge(0.5);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    nearNamedEdge[u] = (corner & 1) ? 0.95 : 0.05;
    nearNamedEdge[v] = (corner & 2) ? 0.95 : 0.05;
    nearOppositeEdge[u] = 1 - nearNamedEdge[u];
    nearOppositeEdge[v] = 1 - nearNamedEdge[v];
    const Solid cylinder = makeSolid(SolidGroup::QuarterCylinder, o);
    const Solid inverse = makeSolid(SolidGroup::InverseQuarterCylinder, o);
    EXPECT_TRUE(solidContains(cylinder, nearNamedEdge)) << o;
    EXPECT_FALSE(solidContains(cylinder, nearOppositeEdge)) << o;
    EXPECT_FALSE(solidContains(inverse, nearNamedEdge)) << o;
    EXPECT_TRUE(solidContains(inverse, nearOppositeEdge)) << o;
  }
}

// ---- Metadata items: lookups and a cell's corners, as the document's recipe states them ------

// One axis read the way FORMAT.md's "Lookups" and "A cell's extent" sections say, in float32.
struct SpecAxis {
  const std::uint8_t* meta;   // row 0: i, f, j_left, j_right
  const std::uint8_t* exact;  // row 1: u24 boundary, 0
  int M = 0, W = 0;
  std::uint32_t D = 0;

  const std::uint8_t* pixel(int k) const { return meta + 4 * k; }
  std::uint32_t exactAt(int k) const { return exact[4 * k] | exact[4 * k + 1] << 8 | exact[4 * k + 2] << 16; }

  // t = x * fl(M / D) in float32; q = floor(256 t) clamped to [0, 256 M - 1]; k = q div 256.
  int stepOf(float x) const {
    const float scale = static_cast<float>(M) / static_cast<float>(D);
    const float q = x * (scale * 256.0f);
    return static_cast<int>(std::min(std::max(q, 0.0f), std::nextafter(static_cast<float>(256 * M), 0.0f)));
  }
  int heuristicCell(float x, int& k) const {
    const int q = stepOf(x);
    k = q / 256;
    const int f = pixel(k)[1];
    return pixel(k)[0] + (f != 0 && q % 256 >= f ? 1 : 0);
  }
  int exactCell(float x, int& k) const {
    k = stepOf(x) / 256;
    const int f = pixel(k)[1];
    return pixel(k)[0] + (f != 0 && x >= static_cast<float>(exactAt(k)) ? 1 : 0);
  }
  // The pixel holding the boundary below (side -1) or above (side +1) cell c, found at pixel k,
  // or -1 / M for the faces.
  int boundaryPixel(int c, int k, int side) const {
    const std::uint8_t* p = pixel(k);
    if (side < 0) {
      if (c == 0) return -1;
      return p[1] != 0 && c == p[0] + 1 ? k : k - p[2];
    }
    if (c == W - 1) return M;
    return p[1] != 0 && c == p[0] ? k : k + p[3];
  }
  double exactPosition(int k) const { return k < 0 ? 0.0 : k >= M ? D : exactAt(k); }
  double heuristicPosition(int k) const {
    return k < 0 ? 0.0 : k >= M ? D : (k + pixel(k)[1] / 256.0) * D / M;
  }
};

SpecAxis specAxis(const Image& image, const BlockHeader& h, int a) {
  const HniView view(image);
  const TexelAddress at = h.meta[static_cast<std::size_t>(a)];
  return {view.texel(at), view.texel(at, 0, 1), h.metaPixels[a], h.cells[a],
          static_cast<std::uint32_t>(h.sizeUnits[a])};
}

// Blocks whose axes exercise the cases: many uneven cells, one cell, M = 256 with a boundary in
// pixel 0 (its j_right to the far face is clamped from 256 to 255), and small D.
Hierarchy metadataCases() {
  Hierarchy h;
  h.addMaterial({});
  Block many = Block::fromSizes({{{0.013, 2.5, 0.7, 0.001, 3.3, 1.25, 0.4}, {4.0}, {0.006, 0.004, 0.005}}});
  many.cell(0, 0, 0) = Cell::box(0);
  h.addBlock(many);
  Block wide = Block::fromSizes({{{0.1, 299.9}, {0.2, 0.1, 0.3}, {300.0}}});
  wide.cell(1, 2, 0) = Cell::box(0);
  h.addBlock(wide);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> cells(1, 24), mm(50, 3000);
  for (int b = 0; b < 6; ++b) {
    std::array<std::vector<double>, 3> sizes;
    for (auto& s : sizes) {
      const int n = cells(rng);
      for (int c = 0; c < n; ++c) s.push_back(mm(rng) / 1000.0);
    }
    h.addBlock(Block::fromSizes(sizes));
  }
  return h;
}

TEST(MetadataRecipe, CellCornersComeFromTheJNumbersTheFacesAndTheExactRow) {
  const Hierarchy h = quantized(metadataCases());
  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniView view(*image);
  const FileRecord file = view.fileRecord();
  bool sawClampedFace = false;
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader header = view.header(view.blockAddress(file, b));
    for (int a = 0; a < 3; ++a) {
      const SpecAxis axis = specAxis(*image, header, a);
      const std::vector<double>& boundsM = h.blocks[static_cast<std::size_t>(b)].boundsM[static_cast<std::size_t>(a)];
      const double bound = static_cast<double>(axis.D) / (512.0 * axis.M) * (1 + 1e-12);  // heuristic error
      for (int c = 0; c < axis.W; ++c) {
        const auto lo = static_cast<std::uint32_t>(std::llround(boundsM[static_cast<std::size_t>(c)] * 1000));
        const auto hi = static_cast<std::uint32_t>(std::llround(boundsM[static_cast<std::size_t>(c) + 1] * 1000));
        for (const float x : {static_cast<float>(lo), std::nextafter(static_cast<float>(hi), 0.0f),
                              0.5f * static_cast<float>(lo + hi)}) {
          int k = 0;
          ASSERT_EQ(axis.exactCell(x, k), c) << "block " << b << " axis " << a << " x " << x;
          EXPECT_EQ(axis.exactPosition(axis.boundaryPixel(c, k, -1)), static_cast<double>(lo)) << "block " << b;
          EXPECT_EQ(axis.exactPosition(axis.boundaryPixel(c, k, +1)), static_cast<double>(hi)) << "block " << b;
          const int hc = axis.heuristicCell(x, k);
          EXPECT_LE(std::abs(hc - c), 1);
          const auto mm = [&](int m) {
            return static_cast<double>(std::llround(boundsM[static_cast<std::size_t>(m)] * 1000));
          };
          EXPECT_NEAR(axis.heuristicPosition(axis.boundaryPixel(hc, k, -1)), mm(hc), bound);
          EXPECT_NEAR(axis.heuristicPosition(axis.boundaryPixel(hc, k, +1)), mm(hc + 1), bound);
        }
      }
      // The j numbers at the faces: j_left = k where the previous boundary is face 0, and
      // j_right = min(M - k, 255) where the next one is face W.
      for (int k = 0; k < axis.M; ++k) {
        const std::uint8_t* p = axis.pixel(k);
        const int previous = p[0], next = p[0] + (p[1] != 0 ? 2 : 1);
        const std::string where =
            "block " + std::to_string(b) + " axis " + std::to_string(a) + " pixel " + std::to_string(k);
        if (previous == 0) {
          EXPECT_EQ(p[2], k) << where;
        }
        if (next == axis.W) {
          EXPECT_EQ(p[3], std::min(axis.M - k, 255)) << where;
        }
        sawClampedFace |= next == axis.W && axis.M - k == 256;
      }
    }
  }
  EXPECT_TRUE(sawClampedFace) << "no axis of the cases has M = 256 with a boundary in pixel 0";
}

TEST(MetadataRecipe, Float32LookupsAreTheLibrarysAndTheExactOneIsExactForEveryFloat) {
  const Hierarchy h = quantized(metadataCases());
  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniView view(*image);
  const FileRecord file = view.fileRecord();
  std::mt19937_64 rng(5);
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader header = view.header(view.blockAddress(file, b));
    for (int a = 0; a < 3; ++a) {
      const SpecAxis axis = specAxis(*image, header, a);
      const AxisView library = view.axis(header, a);
      const std::vector<double>& boundsM = h.blocks[static_cast<std::size_t>(b)].boundsM[static_cast<std::size_t>(a)];
      std::vector<std::int64_t> bounds;  // mm, interior boundaries
      for (std::size_t m = 1; m + 1 < boundsM.size(); ++m) bounds.push_back(std::llround(boundsM[m] * 1000));
      // Random coordinates, and every float within 64 ulps of each boundary and pixel edge.
      std::vector<float> xs;
      std::uniform_real_distribution<float> any(0.0f, static_cast<float>(axis.D));
      for (int n = 0; n < 2000; ++n) xs.push_back(any(rng));
      std::vector<double> marks(bounds.begin(), bounds.end());
      for (int k = 1; k < axis.M; ++k) marks.push_back(static_cast<double>(k) * axis.D / axis.M);
      for (double mark : marks) {
        float x = static_cast<float>(mark);
        for (int i = 0; i < 64; ++i) x = std::nextafter(x, 0.0f);
        for (int i = 0; i < 128; ++i, x = std::nextafter(x, std::numeric_limits<float>::infinity())) xs.push_back(x);
      }
      for (float x : xs) {
        if (x < 0 || x >= static_cast<float>(axis.D)) continue;
        int k = 0;
        ASSERT_EQ(axis.heuristicCell(x, k), library.cellHeuristic(x)) << "block " << b << " axis " << a << " x " << x;
        const int exact = axis.exactCell(x, k);
        ASSERT_EQ(exact, library.cellExact(x)) << "block " << b << " axis " << a << " x " << x;
        // The cell of x: how many interior boundaries lie at or below it.
        const int truth = static_cast<int>(
            std::count_if(bounds.begin(), bounds.end(), [&](std::int64_t bd) { return static_cast<double>(bd) <= x; }));
        ASSERT_EQ(exact, truth) << "block " << b << " axis " << a << " x " << x;
      }
    }
  }
}

// ---- Image size (validation rule 1) -----------------------------------------------------------

TEST(ImageSize, WidthFromSixAndHeightFromOneUpTo4096) {
  const auto message = [](const Image& image) {
    const Status s = validate(image);
    return s.ok() ? std::string("valid") : s.error().message;
  };
  EXPECT_NE(message(Image(5, 300)).find("too small"), std::string::npos);
  EXPECT_NE(message(Image(300, 0)).find("too small"), std::string::npos);
  EXPECT_NE(message(Image(4097, 1)).find("exceeds"), std::string::npos);
  EXPECT_NE(message(Image(6, 4097)).find("exceeds"), std::string::npos);
  // Six pixels pass the size rule (the next rule, the magic, fails on zero pixels).
  EXPECT_NE(message(Image(6, 1)).find("magic"), std::string::npos);
  EXPECT_NE(message(Image(4096, 4096)).find("magic"), std::string::npos);
  // A header (12 x 1) and a metadata item (M x 2) must fit too: the least compiled HNI.
  Hierarchy h;
  h.addBlock(Block::fromSizes({{{1.0}, {1.0}, {1.0}}}));
  auto image = compile(h);
  ASSERT_TRUE(image.ok());
  EXPECT_GE(image->width, 12);
  EXPECT_GE(image->height, 2);
}

// ---- Pixels a premultiplied or colour-converted upload would change ("Decoding in a browser") --

TEST(Upload, SamplesHoldPixelsWithAlphaZeroAndColourThatPremultiplicationDestroys) {
  // The counts FORMAT.md quotes, per sample: pixels whose A = 0 and whose R, G or B is not.
  const std::array<long long, 4> documented{-1, 1027, -1, -1};
  for (std::size_t s = 0; s < kSamples.size(); ++s) {
    const PngFile png = loadSample(kSamples[s]);
    long long alphaZero = 0, translucent = 0;
    Image premultiplied = png.image;
    for (std::size_t i = 0; i < png.image.pixels.size(); i += 4) {
      const std::uint8_t* p = &png.image.pixels[i];
      alphaZero += p[3] == 0 && (p[0] | p[1] | p[2]) != 0;
      translucent += p[3] != 0 && p[3] != 255;
      // What a premultiplied store and its un-premultiplication return.
      for (std::size_t c = 0; c < 3; ++c) {
        const long stored = std::lround(p[c] * p[3] / 255.0);
        premultiplied.pixels[i + c] =
            static_cast<std::uint8_t>(p[3] == 0 ? 0 : std::min(255L, std::lround(stored * 255.0 / p[3])));
      }
    }
    std::printf("%s.png: %lld of %d px have A = 0 and RGB != 0; %lld px have 0 < A < 255\n", kSamples[s].c_str(),
                alphaZero, png.image.width * png.image.height, translucent);
    EXPECT_GT(alphaZero, 0) << kSamples[s];
    if (documented[s] >= 0) {
      EXPECT_EQ(alphaZero, documented[s]) << kSamples[s] << ": update docs/FORMAT.md";
    }
    const auto original = decode(png.image);
    const auto damaged = decode(premultiplied);
    ASSERT_TRUE(original.ok()) << kSamples[s];
    EXPECT_TRUE(!damaged.ok() || !(original->blocks == damaged->blocks && original->materials == damaged->materials))
        << kSamples[s] << ": the premultiplied image still decodes to the same hierarchy";
  }
}

// ---- Textures ("Texture-info array"): carried, checked, not drawn ------------------------------

Hierarchy texturedPanel(bool textured) {
  Hierarchy h;
  const std::uint16_t brick = h.addMaterial({180, 90, 60});
  Block b = Block::fromSizes({{{1.0, 2.0}, {3.0}, {0.5}}});
  b.cell(0, 0, 0) = Cell::solidCell(Solid{0}, brick, textured ? 1 : 0);
  b.cell(1, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 2 * 4 + 1), brick);
  h.addBlock(b);
  if (textured) h.textures.push_back({{0.5, -0.25, 1.0}, 0x1234});
  return h;
}

TEST(Textures, TextureInfosAreStoredAsDocumentedAndIgnoredByTheRenderers) {
  auto textured = compile(texturedPanel(true));
  auto plain = compile(texturedPanel(false));
  ASSERT_TRUE(textured.ok() && plain.ok());
  ASSERT_TRUE(validate(*textured).ok());
  // The file record's pixel 4 (origin, per row) and pixel 5 R (count), read by hand.
  const std::uint8_t* p4 = textured->at(4, 0);
  const std::uint32_t origin = p4[0] | p4[1] << 8 | p4[2] << 16;
  EXPECT_EQ(p4[3], 1);
  EXPECT_EQ(textured->at(5, 0)[0], 1);
  const std::uint8_t* entry = textured->at(static_cast<int>(origin & 0xfff), static_cast<int>(origin >> 12));
  const auto s24 = [](const std::uint8_t* p) {
    const int u = p[0] | p[1] << 8 | p[2] << 16;
    return u >= 1 << 23 ? u - (1 << 24) : u;
  };
  EXPECT_EQ(s24(entry), 500);
  EXPECT_EQ(s24(entry + 4), -250);
  EXPECT_EQ(s24(entry + 8), 1000);
  EXPECT_EQ(entry[3] | entry[7] << 8, 0x1234);
  EXPECT_EQ(entry[11], 0);
  auto decoded = decode(*textured);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->textures, texturedPanel(true).textures);
  EXPECT_EQ(decoded->blocks[0].cell(0, 0, 0).texture, 1);

  // The same picture with and without the texture: no renderer of this version draws textures.
  Camera camera = fitCamera({glm::dvec3(0.0), glm::dvec3(3.0, 3.0, 0.5)}, 96, 64);
  RayCastOptions options;
  const RenderOutput withTexture = renderHni(HniRayCaster(*textured, glm::dvec3(0.0)), camera, options);
  const RenderOutput without = renderHni(HniRayCaster(*plain, glm::dvec3(0.0)), camera, options);
  EXPECT_EQ(withTexture.colour, without.colour);

  // A cell may name texture info 1..count; one more is rejected.
  Image broken = *textured;
  const HniView view(*textured);
  const BlockHeader header = view.header(view.fileRecord().root);
  broken.at(header.data.u, header.data.v + header.cells.y - 1)[2] = 2;  // cell (0, 0, 0)
  const Status s = validate(broken);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("texture 2 out of range"), std::string::npos) << s.error().message;
}

// ---- `nut info` figures ("nut info figures") ---------------------------------------------------

TEST(InfoFigures, CellsPerBlockRecordsByAddressDepthFromTheRoot) {
  Hierarchy h;
  const std::uint16_t stone = h.addMaterial({150, 150, 150});
  Block shared = Block::fromSizes({{{1.0, 1.0}, {1.0, 1.0}, {1.0}}});  // 4 cells, one solid
  shared.cell(0, 0, 0) = Cell::box(stone);
  const BlockId a = h.addBlock(shared);
  const BlockId twin = h.addBlock(shared);  // equal cells: one data component for both
  Block holder = Block::fromSizes({{{2.0}, {2.0}, {1.0}}});  // 1 cell, redirecting to a
  holder.redirections.push_back({a, glm::dvec3(0.0), {}, {false, false, false}});
  holder.cell(0, 0, 0) = Cell::redirect(0);
  const BlockId c = h.addBlock(holder);
  h.addBlock(Block::fromSizes({{{1.0, 1.0, 1.0}, {1.0}, {1.0}}}));  // 3 cells, reached by nothing
  Block root = Block::fromSizes({{{2.0, 2.0, 2.0, 2.0}, {2.0}, {1.0}}});  // 4 cells
  root.redirections.push_back({a, glm::dvec3(0.0), {}, {false, false, false}});  // the same as c's
  root.redirections.push_back({twin, glm::dvec3(0.0), {}, {false, false, false}});
  root.redirections.push_back({c, glm::dvec3(0.0), {}, {false, false, false}});
  root.cell(0, 0, 0) = Cell::redirect(0);
  root.cell(1, 0, 0) = Cell::redirect(1);
  root.cell(2, 0, 0) = Cell::redirect(2);
  root.cell(3, 0, 0) = Cell::redirect(0);
  h.root = h.addBlock(root);

  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniView view(*image);
  const FileRecord file = view.fileRecord();
  EXPECT_EQ(view.header(view.blockAddress(file, static_cast<int>(a))).data,
            view.header(view.blockAddress(file, static_cast<int>(twin))).data);
  const HniStats s = computeStats(*image);
  EXPECT_EQ(s.blocks, 5);
  EXPECT_EQ(s.cells, 4 + 4 + 1 + 3 + 4);     // per block, shared data components counted twice
  EXPECT_EQ(s.solidCells, 2);
  EXPECT_EQ(s.redirectionCells, 1 + 4);
  EXPECT_EQ(s.redirections, 3);              // root->a and c->a are one record
  EXPECT_EQ(s.dagDepth, 2);                  // root -> c -> a
  EXPECT_EQ(s.bytesRaw, 4LL * image->width * image->height);
}

}  // namespace
}  // namespace nut
