// Houses with roofs of plane cells (format version 3) for tests: a ridge (inside both of two roof
// planes) or a valley (inside either), its line at an odd angle across a grid of unequal cells,
// over walls of box cells, with 1 m of empty space around. The model's own semantics decide each
// cell from its corners: box, empty, or plane cell; so every roof cell a plane crosses shares it.
#pragma once

#include <array>

#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>

namespace nut::testing {

struct PlaneRoof {
  Hierarchy h;
  PlaneCut cut;        // the roof's two planes, in the root block's frame
  glm::dvec3 lo, hi;   // the house's box: footprint and floor to the highest roof point
  double eaves = 0.0;  // top of the box walls; the roof lies above it
  // Signed distance from p to the house's surface, positive inside (the largest ball about p
  // inside the house has this radius).
  double depthInside(const glm::dvec3& p) const;
  // Whether p lies inside the house.
  bool contains(const glm::dvec3& p) const { return depthInside(p) >= 0.0; }
};

// ridgeYawDeg turns the ridge (or valley) line about y from the x axis; pitchDeg is the slope of
// both roof planes.
PlaneRoof planeRoofHouse(PlaneCombine combine, double ridgeYawDeg = 23.0, double pitchDeg = 20.0);

}  // namespace nut::testing
