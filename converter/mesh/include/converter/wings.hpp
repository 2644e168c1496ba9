// converter/wings.hpp — a wing turned against the rest of its building (docs/CONVERTER.md, "Turned
// wings").
//
// Yaw alignment (align.hpp) turns a building onto its dominant orientation; walls of a wing that
// meets it at another angle are then neither on the grid's axes nor slopes, and go to the
// complementary mesh. Here the building is cut by a vertical plane of its own frame into the main
// part and the wing, each is converted in its own frame (the whole mesh deciding what is inside),
// and a root block with two cells along the cut joins them: one redirects to the main part, the
// other to the wing with the format's free yaw. Each cell clips its block (docs/FORMAT.md,
// "Redirection record"), so the parts may overlap across the cut and the cut decides who shows what.
#pragma once

#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include <converter/align.hpp>
#include <nut/hierarchy.hpp>
#include <scene/obj.hpp>

namespace nut::converter {

// Where a building aligned to its frame is cut, and how its wing is turned.
struct WingCut {
  std::uint16_t yaw = 0;   // the wing's orientation in the building's frame, format yaw steps
  int axis = 0;            // 0 (x) or 2 (z): the cut plane is axis = atM
  double atM = 0;
  bool wingAbove = true;   // the wing lies at coordinates above atM
  double wingShare = 0;    // share of the walls (area projected on vertical planes) turned with
                           // the wing and on its side of the cut
};

// The wing of a mesh in its building's aligned frame: the orientation more than the angle
// tolerance off the frame's axes gathering the most wall area (none when that lies within two
// tolerances of the axes: survey noise, not a wing), and the cut along x or z that puts
// the most wall area on the side of its orientation (walls of neither orientation count for
// neither side). The cut lies two tolerances beyond the main part's last wall, so that walls on
// the cut stay in the main part. None when the wing's walls on its side are below `minShare` of
// the walls, or the cut leaves no wing wall on one side.
std::optional<WingCut> findTurnedWing(const TriangleMesh& aligned, double angleToleranceDeg, double toleranceM, double minShare);

// The part of the mesh on one side of the plane axis = atM (above it when `keepAbove`): triangles
// across the plane are clipped to it. Positions are not shared between triangles.
TriangleMesh clipToHalfSpace(const TriangleMesh& mesh, int axis, double atM, bool keepAbove);

// Joins the main part, converted in the building's frame with its root's minimum corner at
// `mainOriginM`, and the wing, converted in `wingFrame` (relative to the building's frame) with
// its root's minimum corner at `wingOriginM` of that frame: the wing's blocks are appended to
// `main` (their materials merged), and a new root with two cells along the cut redirects to each
// part. Returns the new root's minimum corner in the building's frame. The main part lands
// exactly; the wing to the half millimetre (its offset is rounded to the format's millimetres).
glm::dvec3 joinAtCut(Hierarchy& main, const glm::dvec3& mainOriginM, const Hierarchy& wing, const YawFrame& wingFrame,
                     const glm::dvec3& wingOriginM, const WingCut& cut);

}  // namespace nut::converter
