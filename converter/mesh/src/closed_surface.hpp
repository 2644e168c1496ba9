// converter/mesh/src/closed_surface.hpp — whether the edges a mesh leaves uncancelled cancel
// along their lines: the last step of deciding that a mesh is a closed surface (MeshCheck::
// closedSurface), on which the occupancy step may count a line's crossings instead of asking the
// winding number.
//
// A surface is closed where every edge is run as often one way as the other. Generated and
// exported buildings are full of T-junctions (a wall's long edge against three windows' short
// ones), so the edges that do not cancel between their own two vertices are gathered per
// supporting line, and the surface is open only where their runs along a line do not cancel
// either (a roof sheet overhanging its gable, a pane filling a wall's hole, walls standing on a
// base plate without a floor of their own). Vertices a millimetre apart are one place and a
// T-junction's vertex may lie up to a millimetre off the edge it meets: a mesh turned or written
// with few decimals has them a little off. Where two edges alone cover a stretch of a line, the
// faces using them must run it opposite ways: the mesh check makes open pieces agree by them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace nut::converter {

// An edge between vertices a and b (indices into the mesh's points) that the faces using it run
// `weight` more times a -> b than b -> a.
struct UncancelledEdge {
  std::uint32_t a, b;
  int weight;
};

// The edges grouped into chains of collinear edges meeting end to end, one or more per line.
struct LineChains {
  // Every chain's runs sum to zero all along it: the surface is closed.
  bool cancel = true;
  // Two edges that alone cover a stretch of their line: they cancel there if they run opposite
  // ways, so the faces using them agree, or would if one were turned over (sameWay).
  struct Pair {
    std::uint32_t a, b;
    bool sameWay;
  };
  std::vector<Pair> alone;
};

// Vertices closer than this are one place, and an edge lies on another's line when its far end is
// this close to that line. The car park sample turned 37° about the vertical and written to the
// micrometre has its T-junctions 1-2 µm off the edges they meet: matched exactly, that closed
// surface would be taken for an open one. A millimetre is a tenth of the default plane tolerance;
// a gap this narrow is no opening.
inline constexpr double kSamePlaceM = 1e-3;

// The place of each vertex in `used`: vertices within `radius` of each other (transitively) are
// one place, named by one of them. Entries of vertices not in `used` are unset.
std::vector<std::uint32_t> placesOf(std::span<const glm::dvec3> points, std::span<const std::uint32_t> used,
                                    double radius = kSamePlaceM);

LineChains chainsAlongLines(std::span<const glm::dvec3> points, std::span<const UncancelledEdge> edges);

}  // namespace nut::converter
