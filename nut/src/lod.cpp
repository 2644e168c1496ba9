// Level of detail from measured error: summary against full render per block, side and view.
#include <nut/lod.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include <nut/camera.hpp>
#include <nut/raycast.hpp>
#include <nut/render_loop.hpp>
#include <nut/hni_view.hpp>

namespace nut {

namespace {

// One view of one side: parallel rays through the side's face, which lies in the plane
// axis = faceCoordinate and spans [0, size_u) x [0, size_v) along the other two axes.
struct SideView {
  int axis = 0, u = 1, v = 2;
  double faceCoordinate = 0;
  glm::dvec3 outward{0.0}, direction{0.0};
};

std::vector<SideView> sideViews(const glm::dvec3& sizeM) {
  const double tilt = std::tan(std::numbers::pi / 6);  // 30 degrees
  std::vector<SideView> views;
  for (int side = 0; side < 6; ++side) {
    SideView view;
    view.axis = side / 2;
    view.u = (view.axis + 1) % 3;
    view.v = (view.axis + 2) % 3;
    const bool positive = side % 2 == 0;
    view.faceCoordinate = positive ? sizeM[view.axis] : 0.0;
    view.outward[view.axis] = positive ? 1.0 : -1.0;
    glm::dvec3 eu(0.0), ev(0.0);
    eu[view.u] = tilt;
    ev[view.v] = tilt;
    for (const glm::dvec3& lean : {glm::dvec3(0.0), eu, -eu, ev, -ev}) {
      view.direction = glm::normalize(-view.outward + lean);
      views.push_back(view);
    }
  }
  return views;
}

// Rays per largest side of the reference render at least: enough to resolve windows on a 20 m
// facade, so that a coarse level's pixel averages the block's pattern rather than aliases it.
constexpr int kMinReferencePixels = 64;

class BlockMeasurer {
 public:
  BlockMeasurer(const Image& image, BlockId block, const glm::dvec3& sizeM, const VisualSummary& summary,
                const LodMeasureOptions& options)
      : caster_(image, glm::dvec3(0.0), glm::dmat3(1.0), block), sizeM_(sizeM), summary_(summary), options_(options) {
    castOptions_.lookup = Lookup::Exact;
  }

  // The finest level (pixels across the largest side, a power of two) that this view passes with
  // all coarser ones, searched up to `limit`; 0 when it fails at one pixel.
  int finestPassingLevel(const SideView& view, int limit) const {
    const int resolution = std::max(kMinReferencePixels, options_.supersampling * limit);
    const Differences d = differences(view, resolution);
    int passed = 0;
    for (int level = 1; level <= limit; level *= 2) {
      if (!d.passes(resolution / level, options_.tolerance)) break;
      passed = level;
    }
    return passed;
  }

 private:
  // Reference minus candidate per reference pixel, as a summed-area table, so any level's pixel
  // (a square of reference pixels) reads its mean difference in four lookups.
  struct Differences {
    int columns = 0, rows = 0;
    std::vector<glm::dvec3> sums;  // (columns + 1) x (rows + 1), sums[0][*] = sums[*][0] = 0
    glm::dvec3 sum(int c0, int r0, int c1, int r1) const {
      const auto at = [&](int c, int r) { return sums[static_cast<std::size_t>(r) * (columns + 1) + c]; };
      return at(c1, r1) - at(c0, r1) - at(c1, r0) + at(c0, r0);
    }
    bool passes(int step, int tolerance) const {
      for (int r0 = 0; r0 < rows; r0 += step)
        for (int c0 = 0; c0 < columns; c0 += step) {
          // Reference pixels past the face are background in both renders: their difference is 0.
          const glm::dvec3 mean =
              glm::abs(sum(c0, r0, std::min(c0 + step, columns), std::min(r0 + step, rows))) / double(step * step);
          if (std::max({mean.x, mean.y, mean.z}) > tolerance) return false;
        }
      return true;
    }
  };

  Differences differences(const SideView& view, int resolution) const {
    const double pixel = std::max({sizeM_.x, sizeM_.y, sizeM_.z}) / resolution;
    Differences d;
    d.columns = static_cast<int>(std::ceil(sizeM_[view.u] / pixel - 1e-9));
    d.rows = static_cast<int>(std::ceil(sizeM_[view.v] / pixel - 1e-9));
    d.sums.assign(static_cast<std::size_t>(d.columns + 1) * (d.rows + 1), glm::dvec3(0.0));
    const glm::dvec3 candidate = toVec(summaryColour(view));
    // Rays start outside the block: from the face, back along the direction by more than its size.
    const double back = 2.0 * std::max({sizeM_.x, sizeM_.y, sizeM_.z}) + 1.0;
    for (int row = 0; row < d.rows; ++row) {
      glm::dvec3 rowSum(0.0);
      for (int column = 0; column < d.columns; ++column) {
        glm::dvec3 onFace(0.0);
        onFace[view.axis] = view.faceCoordinate;
        onFace[view.u] = (column + 0.5) * pixel;
        onFace[view.v] = (row + 0.5) * pixel;
        if (onFace[view.u] < sizeM_[view.u] && onFace[view.v] < sizeM_[view.v])
          rowSum += toVec(caster_.trace(onFace - back * view.direction, view.direction, 0.0, castOptions_).colour) -
                    candidate;
        const std::size_t at = static_cast<std::size_t>(row + 1) * (d.columns + 1) + column + 1;
        d.sums[at] = d.sums[at - static_cast<std::size_t>(d.columns + 1)] + rowSum;
      }
    }
    return d;
  }

  // What the caster draws where the summary stands in and the ray enters through this side.
  std::array<std::uint8_t, 3> summaryColour(const SideView& view) const {
    const int side = 2 * view.axis + (view.outward[view.axis] > 0 ? 0 : 1);
    const Rgba8 s = summary_[static_cast<std::size_t>(side)];
    const auto shaded = shade({s.r, s.g, s.b}, view.outward, view.direction);
    if (s.a == 255) return shaded;
    Composite composite;
    composite.add(shaded, s.a / 255.0);
    return composite.finish(kBackground);
  }

  static glm::dvec3 toVec(const std::array<std::uint8_t, 3>& c) { return {c[0], c[1], c[2]}; }

  HniRayCaster caster_;
  glm::dvec3 sizeM_;
  VisualSummary summary_;
  LodMeasureOptions options_;
  RayCastOptions castOptions_;
};

}  // namespace

void measureLevelOfDetail(Hierarchy& h, const Image& image, const LodMeasureOptions& options) {
  std::vector<bool> targeted(h.blocks.size(), false);
  for (const Block& block : h.blocks)
    for (const Redirection& r : block.redirections) targeted[r.target] = true;
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  for (BlockId b = 0; b < h.blocks.size(); ++b) {
    h.blocks[b].lodFootprintM = 0.0;
    if (!targeted[b]) continue;
    // The summary and size as encoded: what the caster draws.
    const BlockHeader header = view.header(view.blockAddress(file, static_cast<int>(b)));
    const glm::dvec3 sizeM = glm::dvec3(header.sizeUnits) * format::kMetresPerUnit;
    const BlockMeasurer measurer(image, b, sizeM, header.summary, options);
    // Each view only needs searching up to the finest level every earlier view passed.
    int level = options.finestPixels;
    for (const SideView& side : sideViews(sizeM)) {
      level = measurer.finestPassingLevel(side, level);
      if (level == 0) break;
    }
    if (level > 0) h.blocks[b].lodFootprintM = std::max({sizeM.x, sizeM.y, sizeM.z}) / level;
  }
}

}  // namespace nut
