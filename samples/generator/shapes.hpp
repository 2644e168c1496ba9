// samples/generator/shapes.hpp — the parts of a sample building a painted grid cannot make:
// sloped and curved solids, each a closed surface added to the builder's current object.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "obj_builder.hpp"
#include "paint_grid.hpp"

namespace nut::samples {

// A convex polyhedron from its faces (each a planar polygon, any winding): faces are turned to face
// away from the centroid of all corners, so callers need not mind the winding.
struct ConvexFace {
  std::vector<glm::dvec3> corners;
  int material;
};
void convexSolid(ObjBuilder& out, const std::vector<ConvexFace>& faces);

// A gable roof on the box [x0, x1] x {yBase} x [z0, z1], ridge along x at mid z, `height` above yBase:
// slopes in `roof`, the triangular gable ends in `gable`.
void gableRoof(ObjBuilder& out, double x0, double x1, double z0, double z1, double yBase, double height, int roof, int gable);

// A slab of `thickness` rising along x from yLow at x0 to yHigh at x1, over z in [z0, z1] (a ramp).
void ramp(ObjBuilder& out, double x0, double x1, double z0, double z1, double yLow, double yHigh, double thickness,
          int material);

// A quarter of a vertical cylinder: axis at (cx, cz), radius r, from y0 to y1, in the quadrant
// (signX, signZ) (each +1 or -1), `segments` facets on the arc.
void quarterCylinder(ObjBuilder& out, double cx, double cz, double r, double y0, double y1, int signX, int signZ,
                     int segments, int material);

// A vertical cylinder (drum) of radius r from y0 to y1 with a hemisphere (dome) on top.
void domedDrum(ObjBuilder& out, double cx, double cz, double r, double y0, double y1, int segments, int rings, int drum,
               int dome);

// Facade helpers over a painted grid. A facade is the plane `normalAxis` (0 = x, 2 = z) at
// `plane`, facing `sign` (+1 / -1); `along` runs the other horizontal axis.
struct Facade {
  int normalAxis;
  int sign;
  double plane;
  // The box that spans [n0, n1] outwards from the plane (negative: into the wall), [t0, t1] along
  // the facade and [y0, y1] up.
  void box(PaintGrid& grid, double n0, double n1, double t0, double t1, double y0, double y1, int material) const;
};

struct WindowStyle {
  double depth = 0.2;        // reveal depth
  double sillOut = 0.06;     // sill protrusion (0: none)
  double mullion = 0.06;     // width of the vertical bar at the centre (0: none)
  double transomAt = 0;      // height of a horizontal bar as a fraction of the window (0: none)
  double trim = 0;           // protruding frame ring around the opening (0: none)
  int glass = 0, frame = 0;  // materials
};

// A recessed window of width w and height h with its lower left corner at (t0, y0) on the facade.
void window(PaintGrid& grid, const Facade& f, double t0, double y0, double w, double h, const WindowStyle& style);

}  // namespace nut::samples
