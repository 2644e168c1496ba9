// What the converter's tests and benchmarks share to judge a conversion: the source mesh and the
// HNIs + complementary meshes rendered from the same cameras (docs/RENDERING.md), composited by
// distance, and compared. No test framework: convert_bench links it too.
#pragma once

#include <string>
#include <vector>

#include <converter/convert.hpp>
#include <nut/camera.hpp>
#include <nut/image.hpp>
#include <nut/image_compare.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::converter::testing {

// The default camera fitted to `box` (fitCamera) and three more: from behind on the left, from
// high above, and low along the side, each at the distance where the bounding sphere fits.
std::vector<Camera> fidelityViews(const WorldBox& box, int width, int height);

// Every conversion's HNI ray-cast on the CPU (heuristic lookup) and its complementary mesh traced
// with Embree, as one scene (meshref/scene_render.hpp): each pixel shows the nearest surface.
Image renderConversions(const std::vector<const Conversion*>& conversions, const Camera& camera);

// The source mesh traced with Embree.
Image renderMesh(const TriangleMesh& mesh, const Camera& camera);

struct Fidelity {
  double worstWithinPct = 100;          // lowest share of pixels within the threshold over the views
  std::vector<double> withinPct;        // per view
};

// Renders both sides from every view and compares them (threshold 8/255); writes
// <stem>.view<N>.{nut,mesh,diff}.png when a view is below minPct.
Fidelity measureFidelity(const TriangleMesh& source, const std::vector<const Conversion*>& conversions, const std::string& stem,
                         double minPct, int width = 640, int height = 360);

}  // namespace nut::converter::testing
