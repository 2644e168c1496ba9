// nut/summary.hpp — visual summaries: one colour per block side for level of detail (paper 4.1).
#pragma once

#include <vector>

#include <nut/hierarchy.hpp>

namespace nut {

// For every block, the area-weighted colour of what is seen looking at each side (+x, -x, +y, -y,
// +z, -z) from outside along the axis, and the covered fraction in alpha. A block's own summary
// is used when set. The hierarchy must pass checkHierarchy().
std::vector<VisualSummary> computeSummaries(const Hierarchy& h);

}  // namespace nut
