// samples/generator/paint_grid.hpp — axis-aligned building parts modelled as painted boxes, turned
// into the surface an exporter would write.
//
// Boxes are painted in order into a non-uniform grid made of all their coordinates (a later box
// wins; material -1 carves). The surface is every cell face between a painted and an empty cell,
// oriented outwards and merged greedily into large rectangles per plane and material, so walls
// are a few big quads with T-junctions around the openings, as CAD exports are.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "obj_builder.hpp"

namespace nut::samples {

class PaintGrid {
 public:
  static constexpr int kCarve = -1;
  void box(const glm::dvec3& lo, const glm::dvec3& hi, int material);
  // Appends the surface to the builder's current object.
  void emit(ObjBuilder& out) const;

 private:
  struct Box {
    glm::dvec3 lo, hi;
    int material;
  };
  std::vector<Box> boxes_;
};

}  // namespace nut::samples
