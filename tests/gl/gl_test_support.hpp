// What the GL tests share: the OSMesa renderer, scenes as the GL layer takes them, and the image
// comparison with its report and the files it leaves on failure (<name>.actual.png, .expected.png,
// .diff.png in the test output folder).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nut/hierarchy.hpp>
#include <nut/image.hpp>
#include <nut/mesh_export.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/offscreen.hpp>

namespace nut::gltest {

// tests/gl/output/<suite>, created.
std::filesystem::path outputDir(const std::string& suite);

// A renderer on OSMesa with the embedded shaders (NUT_SHADER_DIR overrides them, for development);
// nullptr after a test failure that says why.
std::unique_ptr<viewer::OffscreenRenderer> openRenderer(viewer::Backend backend = viewer::Backend::OSMesa);

// How closely a GL frame matches a reference frame.
struct Agreement {
  double withinPct = 0;             // pixels whose channels all differ by at most the threshold
  int maxDifference = 0;
  long long depthPixels = 0;        // pixels drawn in both whose colours agree: their depths are compared
  double worstDepthError = 0;       // largest |window depth GL - reference| among them
  double depthWithinBoundPct = 0;   // of them, within kWindowDepthBound of the reference
  long long depthOutOfRange = 0;    // of them, outside the reference's 3x3 range widened by the bound
};

// docs/GL.md: where both renderers draw a surface, the GL window depth lies within this of the
// reference's, or within the range of the reference's window depths over the pixel's 3x3
// neighbourhood widened by this. The bound, 2^-18 (64 float ulps at 1), covers a hit distance 8
// float ulps off (the float casters' tolerance, raycast_accuracy_test.cpp) through the slope of
// the window depth (at most 0.5 (f + n) / (f - n) + 0.5 per unit of relative distance, 1.5 to 2.5
// for fitted cameras), plus the float rounding of the depth formula (a few ulps of 2). The
// neighbourhood covers grazing faces and edges, where the two casters' different rounding moves a
// hit by a small fraction of a pixel and the depth changes fast across it.
inline constexpr double kWindowDepthBound = 1.0 / (1 << 18);

// Compares colours (threshold per channel) and, where both drew and the colours agree, window
// depths; prints one line, and writes the three images under `dir` with the stem `name` when the
// frame misses minWithinPct or has a depth out of range, or always when the environment variable
// NUT_TEST_KEEP_IMAGES is set (to look at the renders).
Agreement compareFrames(const std::filesystem::path& dir, const std::string& name, const Image& reference,
                        const std::vector<float>& referenceDepth, const Image& actual,
                        const std::vector<float>& actualDepth, int threshold, double minWithinPct);

}  // namespace nut::gltest
