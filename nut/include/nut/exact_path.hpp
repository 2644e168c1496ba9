// nut/exact_path.hpp — the exact path: rays traced through the editable model (nut::Hierarchy) in
// double precision, with no metadata arrays and no image. It is the ground truth the float ray
// caster (raycast.hpp) is tested against, so it shares none of the caster's traversal: it follows
// only the model's documented semantics (hierarchy.hpp, docs/FORMAT.md) and the shading of
// docs/RENDERING.md. Full detail only (no level of detail). Slow by design; meant for tests.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>
#include <nut/raycast.hpp>

namespace nut {

// A ray whose traversal visits more cells than this (every wrapped tile copy counts) ends capped.
inline constexpr long long kExactMaxCells = 1'000'000;

// The surface that stopped the ray, for error bounds of renderers whose boundaries are
// approximate. It belongs to the last block of `path`: a cell face or clip face of that block, or
// the surface of a solid inside one of its cells. The content of a cell is placed relative to the
// cell's minimum corner, so a renderer that moves the boundaries of every block B along its axis a
// by at most delta(B)_a moves the surface by at most delta(B)_a along each axis of every block of
// the path, and the hit distance by at most
//     sum over the path of sum_a |normal_a| delta(block)_a, divided by |surface normal . direction|
// (to first order on curved solids). Where planes of several blocks coincide at the hit, one of
// them is reported.
struct ExactSurface {
  struct Level {
    BlockId block = 0;
    glm::dvec3 normal{0.0};  // the surface's unit normal in this block's frame, facing the ray
  };
  std::vector<Level> path;  // from the root down to the block the surface belongs to
};

struct ExactOptions {
  // Redirections nested deeper than this end the ray capped.
  int maxDepth = kMaxStackDepth - 1;  // redirections below the root, as the caster's stack holds
  // Solids that the ray crosses for less than this (metres, first entry to last exit within the
  // cell) are ignored. 0 = none. Tests set it to a float tolerance to get the exact answer of a
  // scene perturbed by that much: the flat faces of inverse solids touch their solid only along a
  // tangent, so a ray entering such a face near the tangent crosses a sliver a float renderer
  // cannot resolve.
  double minThicknessM = 0.0;
  // When given and the ray hits, receives the surface that was hit.
  ExactSurface* surface = nullptr;
};

// Traces one ray through h, whose root block has its minimum corner at originM (world metres).
// rayOrigin is in world metres, unitDirection has length 1. The result follows docs/RENDERING.md:
// distanceM along the ray to the first opaque surface, its world normal facing the ray, the shaded
// colour with translucent cells composited front to back over it (or over the background on a
// miss). A solid hit where a clipped target meets its cell's face takes the normal of that face.
// iterations counts the cells visited. A ray that needs more than kExactMaxCells cells or
// redirections deeper than options.maxDepth ends with capped = true and kCappedColour.
// h must pass checkHierarchy().
RayResult traceExact(const Hierarchy& h, const glm::dvec3& originM, const glm::dvec3& rayOrigin,
                     const glm::dvec3& unitDirection, const ExactOptions& options = {});

}  // namespace nut
