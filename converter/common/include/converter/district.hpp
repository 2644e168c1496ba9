// converter/district.hpp — neighbouring buildings as one hierarchy: blocks over their ground plan
// whose cells redirect to each building where it stands, over the buildings' blocks merged, equal
// blocks stored once. `nut city --pack-atlases` and `nut convert --pack-atlases` write a district
// as one HNI this way (docs/CITY.md, "Districts"): one file and one atlas rectangle instead of one
// per building, and a block that many buildings share (a window, a storey) is stored once.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>

namespace nut::converter {

// A building as a city manifest places it (docs/CITY.md): its root block's origin at positionM,
// turned by yawDeg about +y through it.
struct PlacedHierarchy {
  const Hierarchy* hierarchy = nullptr;
  glm::dvec3 positionM{0.0};
  double yawDeg = 0;
};

struct District {
  Hierarchy hierarchy;
  glm::dvec3 originM{0.0};  // world position of the root block's minimum corner
  WorldBox boundsM;         // of the root block
  std::size_t buildingBlocks = 0;  // the buildings' blocks before merging
  std::size_t mergedBlocks = 0;    // of them, equal to a block stored already
};

// The root spans the buildings' world boxes. It and the blocks under it cut the ground between
// buildings (a k-d tree, cuts along x or z at every gap), so that each building is one cell,
// redirecting to its root turned by its yaw (a cube rotation for multiples of 90 degrees, the
// format's yaw otherwise); where no line separates a group of boxes, one block bounded by all their
// sides holds them. A root that is only a frame (one cell redirecting to the building's grid) of a
// building placed unturned is not stored: the cell redirects to the grid. Positions are taken to
// the millimetre, as the format stores them. Blocks are split where the format's per-axis limits
// need it (assemble.hpp). Errors: no buildings, two buildings whose boxes overlap on the ground,
// and whatever checkHierarchy finds in a building; each names the building by its index.
Result<District> mergeDistrict(const std::vector<PlacedHierarchy>& buildings);

// The side of a district on the ground (`--pack-atlases` of `nut city` and `nut convert`).
inline constexpr double kDistrictSideM = 256.0;

// Buildings grouped into districts: squares of sideM on the ground, one corner of them at
// cornerM (x, z), by the centre of each world box, squares in the order of their (x, z) index.
// Within a square a building whose box overlaps a member of a group on the ground (neighbours
// converted from one mesh share a wall, and each box holds it) joins the square's next group, so
// that every group merges. Overlap is judged on boxes taken to the millimetre, as mergeDistrict
// takes them: boxes that touch do not overlap.
std::vector<std::vector<std::size_t>> districtGroups(const std::vector<WorldBox>& boxes, double sideM,
                                                     const glm::dvec2& cornerM);

// A district as one HNI: the members (indices into the buildings given), the suffix its file name
// takes when a district was halved ("" when whole; "a", "b", "ab", ...), the merged hierarchy and
// its compiled image, which validates.
struct CompiledDistrict {
  std::vector<std::size_t> members;
  std::string suffix;
  District district;
  Image image;
};

// The members merged (mergeDistrict) and compiled as one HNI or, while they do not fit one (its
// metadata region holds every block's header and record), each half on its own, along their
// order. Errors: mergeDistrict's, and an HNI that does not compile or validate even for one
// building.
Result<std::vector<CompiledDistrict>> compileDistrict(const std::vector<PlacedHierarchy>& buildings,
                                                      const std::vector<std::size_t>& members);

// The world box of h's root block placed at positionM and turned by yawDeg about +y through it.
WorldBox placedRootBox(const Hierarchy& h, const glm::dvec3& positionM, double yawDeg);

}  // namespace nut::converter
