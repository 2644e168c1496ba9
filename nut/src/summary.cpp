// Visual summaries (paper 4.1): per block side, the colour a viewer far away sees, from the
// block's own cells and, through redirections, from its sub-blocks' summaries.
#include <nut/summary.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace nut {

namespace {

constexpr int kSides = 6;

// Shares of a side whose parallel rays, through a 24 x 24 grid of sample points, meet each of N
// surfaces first: `surface(fu, fv)` traces the ray at fractions (fu, fv) of the side's two axes and
// returns the surface's index, or -1 for a miss.
template <std::size_t N, typename Surface>
std::array<double, N> sampledShares(const Surface& surface) {
  constexpr int kSamples = 24;
  std::array<int, N> counts{};
  for (int i = 0; i < kSamples; ++i)
    for (int j = 0; j < kSamples; ++j)
      if (const int k = surface((i + 0.5) / kSamples, (j + 0.5) / kSamples); k >= 0)
        ++counts[static_cast<std::size_t>(k)];
  std::array<double, N> shares{};
  for (std::size_t k = 0; k < N; ++k) shares[k] = static_cast<double>(counts[k]) / (kSamples * kSamples);
  return shares;
}

// The share of a side hit at all (`hit(fu, fv)` as above, true for a hit).
template <typename Hit>
double sampledShare(const Hit& hit) {
  return sampledShares<1>([&](double fu, double fv) { return hit(fu, fv) ? 0 : -1; })[0];
}

// Fraction of side `side` of the unit cube behind which the solid is visible, looking at the side
// from outside along its axis.
double solidCoverage(Solid solid, int side) {
  const int axis = side / 2;
  const double sign = side % 2 == 0 ? 1.0 : -1.0;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return sampledShare([&](double fu, double fv) {
    glm::dvec3 origin(0.0), dir(0.0);
    origin[u] = fu;
    origin[v] = fv;
    origin[axis] = sign > 0 ? 2.0 : -1.0;
    dir[axis] = -sign;
    return intersectSolid(solid, origin, dir, 1.0, 2.0).has_value();
  });
}

const std::array<std::array<double, kSides>, kSolidCount>& coverageTable() {
  static const auto table = [] {
    std::array<std::array<double, kSides>, kSolidCount> t{};
    for (int s = 0; s < kSolidCount; ++s)
      for (int side = 0; side < kSides; ++side)
        t[static_cast<std::size_t>(s)][static_cast<std::size_t>(side)] =
            solidCoverage(Solid{static_cast<std::uint8_t>(s)}, side);
    return t;
  }();
  return table;
}

// The same for a plane cell spanning [lo, hi] of its block, per surface the rays hit first: the
// box's side (0) or plane 0 or 1 (1, 2), which may show other materials.
std::array<double, 3> planeCellCoverage(const PlaneCut& cut, const glm::dvec3& lo, const glm::dvec3& hi, int side) {
  const int axis = side / 2;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  glm::dvec3 dir(0.0);
  dir[axis] = side % 2 == 0 ? -1.0 : 1.0;
  return sampledShares<3>([&](double fu, double fv) {
    glm::dvec3 origin(0.0);
    origin[u] = lo[u] + fu * (hi[u] - lo[u]);
    origin[v] = lo[v] + fv * (hi[v] - lo[v]);
    origin[axis] = side % 2 == 0 ? hi[axis] : lo[axis];
    const auto span = intersectPlaneCut(cut, origin, dir, 0.0, hi[axis] - lo[axis]);
    return span ? span->plane + 1 : -1;
  });
}

// The side of a redirected block that faces the same way as `side` of the parent cell.
int targetSide(const Rotation& rotation, int side) {
  glm::dvec3 normal(0.0);
  normal[side / 2] = side % 2 == 0 ? 1.0 : -1.0;
  const glm::dvec3 local = glm::transpose(rotationMatrix(rotation)) * normal;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(local[a]) > std::abs(local[axis])) axis = a;
  return 2 * axis + (local[axis] > 0 ? 0 : 1);
}

struct Accumulator {
  glm::dvec3 colour{0.0};  // sum of area * visibility * colour
  double covered = 0.0;    // sum of area * visibility
  double area = 0.0;
};

VisualSummary summarize(const Hierarchy& h, const Block& block,
                        const std::vector<VisualSummary>& done) {
  const auto& coverage = coverageTable();
  VisualSummary out;
  for (int side = 0; side < kSides; ++side) {
    const int axis = side / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int n = block.cellCount(axis);
    Accumulator acc;
    glm::ivec3 c(0);
    for (c[u] = 0; c[u] < block.cellCount(u); ++c[u]) {
      for (c[v] = 0; c[v] < block.cellCount(v); ++c[v]) {
        const double area = (block.boundsM[u][c[u] + 1] - block.boundsM[u][c[u]]) *
                            (block.boundsM[v][c[v] + 1] - block.boundsM[v][c[v]]);
        acc.area += area;
        double remaining = 1.0;  // fraction of the column still unseen
        for (int step = 0; step < n && remaining > 1e-3; ++step) {
          c[axis] = side % 2 == 0 ? n - 1 - step : step;
          const Cell& cell = block.cell(c.x, c.y, c.z);
          glm::dvec3 colour(0.0);
          double opacity = 0.0;
          if (cell.kind == CellKind::Solid) {
            const Material& m = h.materials[cell.material];
            colour = glm::dvec3(m.r, m.g, m.b);
            opacity = coverage[cell.solid.index][static_cast<std::size_t>(side)] * m.opacity / 255.0;
          } else if (cell.kind == CellKind::Plane) {
            const PlaneCut& cut = block.cuts[cell.cut];
            glm::dvec3 lo, hi;
            for (int a = 0; a < 3; ++a) lo[a] = block.boundsM[a][c[a]], hi[a] = block.boundsM[a][c[a] + 1];
            const std::array<double, 3> shares = planeCellCoverage(cut, lo, hi, side);
            glm::dvec3 weighted(0.0);
            for (std::size_t k = 0; k < 3; ++k) {
              const Material& m =
                  h.materials[k == 0 ? cell.material : cut.surfaceMaterials[k - 1].value_or(cell.material)];
              opacity += shares[k] * m.opacity / 255.0;
              weighted += shares[k] * m.opacity / 255.0 * glm::dvec3(m.r, m.g, m.b);
            }
            if (opacity > 0) colour = weighted / opacity;
          } else if (cell.kind == CellKind::Redirection) {
            const Redirection& r = block.redirections[cell.redirection];
            const Rgba8 s = done[r.target][static_cast<std::size_t>(targetSide(r.rotation, side))];
            colour = glm::dvec3(s.r, s.g, s.b);
            opacity = s.a / 255.0;
          }
          acc.colour += area * remaining * opacity * colour;
          acc.covered += area * remaining * opacity;
          remaining *= 1.0 - opacity;
        }
      }
    }
    Rgba8& s = out[static_cast<std::size_t>(side)];
    if (acc.covered > 0) {
      const glm::dvec3 mean = acc.colour / acc.covered;
      s = {static_cast<std::uint8_t>(std::lround(mean.r)), static_cast<std::uint8_t>(std::lround(mean.g)),
           static_cast<std::uint8_t>(std::lround(mean.b)),
           static_cast<std::uint8_t>(std::lround(255.0 * acc.covered / acc.area))};
    }
  }
  return out;
}

}  // namespace

std::vector<VisualSummary> computeSummaries(const Hierarchy& h) {
  std::vector<VisualSummary> done(h.blocks.size());
  std::vector<bool> ready(h.blocks.size(), false);
  // Sub-blocks first: the DAG has no cycles (checkHierarchy), so the recursion ends.
  std::function<void(BlockId)> visit = [&](BlockId b) {
    if (ready[b]) return;
    const Block& block = h.blocks[b];
    for (const Redirection& r : block.redirections) visit(r.target);
    done[b] = block.summary ? *block.summary : summarize(h, block, done);
    ready[b] = true;
  };
  for (BlockId b = 0; b < h.blocks.size(); ++b) visit(b);
  return done;
}

}  // namespace nut
