// Seeded random hierarchies for property tests: every feature of the model (all solids, plane
// cells when asked, textures, rotations, wrapping, shared sub-blocks), always a valid DAG (blocks
// redirect to higher ids only).
#pragma once

#include <cstdint>

#include <nut/hierarchy.hpp>

namespace nut::testing {

struct RandomHierarchyOptions {
  int minBlocks = 1, maxBlocks = 12;
  int maxCellsPerAxis = 8;
  double minCellM = 0.01, maxCellM = 4.0;
  // The share of solid cells made plane cells (version 3), cut by one of a few planes through
  // their block at random angles (one or two planes, both or either). 0 draws nothing for them,
  // so the hierarchies of every seed stay what they were before plane cells existed.
  double planeCellShare = 0.0;
};

Hierarchy randomHierarchy(std::uint64_t seed, const RandomHierarchyOptions& options = {});

}  // namespace nut::testing
