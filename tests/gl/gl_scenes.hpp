// The scenes the GL tests render with both ray casters: the sample HNIs and hand-built stress
// scenes (random hierarchies with every feature, a camera inside a building, city-sized world
// coordinates, centimetre cells in a half-kilometre block, translucent panes, a chain of nested
// blocks deeper than the traversal stack, a thousand-fold wrap that reaches the iteration cap).
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>

namespace nut::gltest {

struct Scene {
  std::string name;
  Hierarchy model;        // what the image encodes
  Image image;            // the HNI
  glm::dvec3 originM{0.0};
  Camera camera;
  RayCastOptions options;
};

// A sample of samples/hni/ with the default camera of `nut render` (fitted to the solid content).
Scene sampleScene(const std::string& name, int width, int height);

// Compiles h; the camera is fitted to its solid content, as for a sample (to the root block's box
// when h is too deep for the mesh exporter).
Scene compiledScene(const std::string& name, const Hierarchy& h, const glm::dvec3& originM, int width, int height);

Hierarchy translucentPanes();
// Nested cubes around one centre (a 1 km root), each in the middle cell of its parent, turned about
// y and every fifth by a free yaw: `levels` blocks deep (below kMaxStackDepth levels the casters
// draw visual summaries).
Hierarchy nestedChain(int levels);
// 1 cm cells (a 0.6 m block of 60 x 3 x 60 cells) in the middle of a 500 m root block, whose
// centre is at (250, 0, 250) m from the root's corner.
Hierarchy centimetreCells();
// A 1000 m row of one 1 m sub-block wrapped along x, seen along the row: rays that cross more cell
// boundaries than the iteration cap allows.
Hierarchy thousandFoldWrap();

}  // namespace nut::gltest
