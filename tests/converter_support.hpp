// What the converter tests share: the source mesh and the HNIs + complementary meshes rendered
// from the same cameras (docs/RENDERING.md), composited by distance, and compared.
#pragma once

#include <string>
#include <vector>

#include <converter/convert.hpp>
#include <converter/mesh.hpp>
#include <meshref/image_compare.hpp>
#include <meshref/obj.hpp>
#include <nut/camera.hpp>
#include <nut/image.hpp>
#include <nut/solids.hpp>

namespace nut::converter::testing {

// The converter's mesh as the reference renderer's.
meshref::TriangleMesh toTriangleMesh(const Mesh& mesh);

// The default camera fitted to `box` (fitCamera) and three more: from behind on the left, from
// high above, and low along the side, each at the distance where the bounding sphere fits.
std::vector<Camera> fidelityViews(const WorldBox& box, int width, int height);

// Every conversion's HNI ray-cast on the CPU (heuristic lookup) and its complementary mesh traced
// with Embree, keeping at each pixel the nearest surface.
Image renderConversions(const std::vector<const Conversion*>& conversions, const Camera& camera);

// The source mesh traced with Embree.
Image renderMesh(const Mesh& mesh, const Camera& camera);

struct Fidelity {
  double worstWithinPct = 100;          // lowest share of pixels within the threshold over the views
  std::vector<double> withinPct;        // per view
};

// Renders both sides from every view and compares them (threshold 8/255); writes
// <stem>.view<N>.{nut,mesh,diff}.png into the test output folder when a view is below minPct.
Fidelity measureFidelity(const Mesh& source, const std::vector<const Conversion*>& conversions, const std::string& stem,
                         double minPct, int width = 640, int height = 360);

// The test output folder for a group of tests (created).
std::string outputDir(const std::string& group);

// convertMesh, failing the current test (and returning an empty conversion) when it fails.
Conversion convertOrFail(const Mesh& mesh, const ConvertOptions& options = {});

// The share of the mesh's surface shown by grid cells.
double nutFraction(const Conversion& c);

// Cells of the HNI in one solid group (every block, as stored).
int cellsOf(const Conversion& c, SolidGroup group);

}  // namespace nut::converter::testing
