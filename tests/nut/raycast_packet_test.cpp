// The packet caster (HniRayCaster::traceMany) against the one-ray caster (trace), the reference:
// the same answer to the bit for every ray, on every sample HNI, with both lookups, with level of
// detail, from outside, close up and inside, at image sizes that are not multiples of the 16 x 16
// tile, and in batches of any size. The stress suite traces every ray it casts through both too
// (tests/stress/stress_support.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <nut/camera.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

#include "ray_printing.hpp"

namespace nut {
namespace {

struct Sample {
  std::string name;
  PngFile png;
};

std::vector<Sample> samples() {
  std::vector<Sample> out;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(NUT_SOURCE_DIR) + "/samples/hni")) {
    auto png = readPng(entry.path().string());
    EXPECT_TRUE(png) << entry.path();
    if (png) out.push_back({entry.path().stem().string(), std::move(*png)});
  }
  EXPECT_GE(out.size(), 4u);
  return out;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The first difference between two answers for one ray, or "".
std::string difference(const RayResult& one, const RayResult& packet) {
  if (one.hit != packet.hit) return "hit";
  if (!sameBits(one.distanceM, packet.distanceM)) return "distance";
  for (int a = 0; a < 3; ++a)
    if (!sameBits(one.normal[a], packet.normal[a])) return "normal";
  if (one.colour != packet.colour) return "colour";
  if (one.iterations != packet.iterations) return "iterations";
  if (one.capped != packet.capped) return "capped";
  return "";
}

// Renders the camera both ways and expects the same frame: colour, distance and iterations. On a
// difference writes both images and the diff to the test output folder.
void expectSameRender(const HniRayCaster& caster, const Camera& camera, RayCastOptions options,
                      const std::string& label) {
  options.packets = false;
  const RenderOutput one = renderHni(caster, camera, options, 2);
  options.packets = true;
  const RenderOutput packets = renderHni(caster, camera, options, 2);
  const bool same = one.colour == packets.colour &&
                    std::memcmp(one.distanceM.data(), packets.distanceM.data(), one.distanceM.size() * 4) == 0 &&
                    one.iterations == packets.iterations;
  EXPECT_TRUE(same) << label;
  if (!same) {
    const std::string stem = std::string(NUT_TEST_OUTPUT_DIR) + "/packets_" + label;
    std::filesystem::create_directories(NUT_TEST_OUTPUT_DIR);
    (void)writePng(stem + "_one_ray.png", one.colour);
    (void)writePng(stem + "_packets.png", packets.colour);
    if (auto diff = compareImages(one.colour, packets.colour, 0)) (void)writePng(stem + "_diff.png", diff->diff);
  }
}

TEST(Packets, EverySampleRendersAsTheOneRayCaster) {
  for (const Sample& sample : samples()) {
    const HniRayCaster caster(sample.png.image, sample.png.text.originM);
    const auto h = decode(sample.png.image);
    ASSERT_TRUE(h) << sample.name;
    const WorldBox box = *contentBounds(*h, sample.png.text.originM);
    // 317 x 203: neither a multiple of the 16-pixel tile.
    const Camera outside = fitCamera(box, 317, 203);
    Camera close = outside;
    close.eye = close.target + 0.35 * (close.eye - close.target);
    Camera inside = outside;
    inside.eye = 0.5 * (box.min + box.max) + glm::dvec3(0.01, 0.013, 0.007) * (box.max - box.min);
    inside.target = inside.eye + glm::dvec3(0.3, -0.2, 1.0);
    const std::pair<const char*, Camera> cameras[] = {{"outside", outside}, {"close", close}, {"inside", inside}};
    for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic})
      for (const auto& [view, camera] : cameras) {
        RayCastOptions options;
        options.lookup = lookup;
        const std::string label = sample.name + "_" + view + (lookup == Lookup::Exact ? "_exact" : "_heuristic");
        expectSameRender(caster, camera, options, label);
      }
    // Level of detail, from three times as far, and the heat map.
    Camera far = outside;
    far.eye = far.target + 3.0 * (far.eye - far.target);
    far.farM *= 3.0;
    RayCastOptions lodPx;
    lodPx.lodPx = 4;
    expectSameRender(caster, far, lodPx, sample.name + "_lod_4px");
    RayCastOptions lodAuto;
    lodAuto.lodAuto = true;
    expectSameRender(caster, far, lodAuto, sample.name + "_lod_auto");
    RayCastOptions heat;
    heat.heatMap = true;
    expectSameRender(caster, close, heat, sample.name + "_heat_map");
    // A cap most rays reach.
    RayCastOptions capped;
    capped.maxIterations = 3;
    expectSameRender(caster, close, capped, sample.name + "_capped");
  }
}

// Batches of any size, rays from different origins, every direction: the answers of trace().
TEST(Packets, BatchesOfAnySizeGiveTheOneRayAnswers) {
  for (const Sample& sample : samples()) {
    const HniRayCaster caster(sample.png.image, sample.png.text.originM);
    const WorldBox box = caster.bounds();
    const glm::dvec3 centre = 0.5 * (box.min + box.max), extent = box.max - box.min;
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const std::size_t batch : {1u, 2u, 5u, 17u, 64u, 333u, 1000u}) {
      std::vector<glm::dvec3> origins, directions;
      for (std::size_t i = 0; i < batch; ++i) {
        // From outside or inside the box, towards a point in it.
        const double reach = i % 3 == 0 ? 0.4 : 1.5;
        const glm::dvec3 from = centre + reach * extent * glm::dvec3(unit(rng), unit(rng), unit(rng));
        const glm::dvec3 to = centre + 0.5 * extent * glm::dvec3(unit(rng), unit(rng), unit(rng));
        origins.push_back(from);
        directions.push_back(glm::normalize(to - from));
      }
      for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
        RayCastOptions options;
        options.lookup = lookup;
        std::vector<RayResult> packets(batch);
        caster.traceMany(origins, directions, 1e-3, options, packets);
        int failures = 0;
        for (std::size_t i = 0; i < batch && failures < 5; ++i) {
          const RayResult one = caster.trace(origins[i], directions[i], 1e-3, options);
          const std::string what = difference(one, packets[i]);
          if (what.empty()) continue;
          ++failures;
          ADD_FAILURE() << sample.name << ", batch of " << batch << ", ray " << i << ": " << what << " differs; "
                        << "origin " << testing::describe(origins[i]) << " direction "
                        << testing::describe(directions[i]) << "; one ray: " << testing::describe(one)
                        << "; packet: " << testing::describe(packets[i]);
        }
      }
    }
  }
}

}  // namespace
}  // namespace nut
