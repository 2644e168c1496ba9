// converter/align.hpp — yaw alignment of buildings that are not axis-aligned (docs/CONVERTER.md,
// "Yaw alignment").
//
// The solid conversion only turns faces near an axis into cells, so a building turned by 30 degrees
// about the vertical would go almost whole to the complementary mesh. Instead its dominant
// orientation about +y is found, the mesh is turned into that frame and converted, and the result
// is wrapped in a new root block with one cell that redirects to the converted root with the
// format's free yaw (docs/FORMAT.md, "Redirection record"), which turns it back into place. The
// angle is quantized to the format's yaw step before the mesh is turned, so the rotation the
// renderer applies is exactly the one the conversion used.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>
#include <scene/obj.hpp>

namespace nut::converter {

// The building's dominant orientation about +y, in the format's yaw steps (1/65536 turn), as the
// yaw that turns an axis-aligned frame onto it, between -45 and +45 degrees. Faces count with their
// area projected onto a vertical plane (walls fully, roof pitches partly, flat faces not at all);
// the orientation is the one, modulo 90 degrees, that brings the most such area within
// `angleToleranceDeg` of an axis, refined to the area-weighted mean angle of those faces. 0 when
// that orientation lies further than the tolerance from the axes and gathers no more area than they
// do.
std::uint16_t dominantYaw(const TriangleMesh& mesh, double angleToleranceDeg);

// A yaw in steps as signed degrees, -180 < d <= 180.
double yawDegrees(std::uint16_t yaw);

// The aligned frame: world point p is aligned point inverse(R) * (p - pivot), R the yaw rotation.
struct YawFrame {
  std::uint16_t yaw = 0;
  glm::dvec3 pivotM{0.0};  // world metres; near the building so aligned coordinates stay small
};

// Turns the mesh's positions from the world into the aligned frame, and back.
void toAlignedFrame(TriangleMesh& mesh, const YawFrame& frame);
void toWorldFrame(TriangleMesh& mesh, const YawFrame& frame);

// Wraps a hierarchy converted in the aligned frame, whose root's minimum corner is at
// `alignedOriginM`, so that it shows the building in the world frame: a new root block, the world
// box of the turned old root (to the millimetre, 1 mm larger on every side), with one cell
// redirecting to the old root with the frame's yaw. Returns the world position of the new root's
// minimum corner, chosen so that the redirection's offset is whole millimetres and the building
// lands exactly where it was.
glm::dvec3 wrapInWorldFrame(Hierarchy& hierarchy, const glm::dvec3& alignedOriginM, const YawFrame& frame);

}  // namespace nut::converter
