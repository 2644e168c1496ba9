// Seeded random hierarchies for property tests: every feature of the model (all solids, textures,
// rotations, wrapping, shared sub-blocks), always a valid DAG (blocks redirect to higher ids only).
#pragma once

#include <cstdint>

#include <nut/hierarchy.hpp>

namespace nut::testing {

struct RandomHierarchyOptions {
  int minBlocks = 1, maxBlocks = 12;
  int maxCellsPerAxis = 8;
  double minCellM = 0.01, maxCellM = 4.0;
};

Hierarchy randomHierarchy(std::uint64_t seed, const RandomHierarchyOptions& options = {});

}  // namespace nut::testing
