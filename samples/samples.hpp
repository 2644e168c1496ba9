// samples/samples.hpp — the hand-built sample hierarchies that make_samples writes as HNIs.
#pragma once

#include <nut/hierarchy.hpp>

namespace samples {

// A facade whose window bay repeats 8 x 5 times through one wrapping redirection (paper Fig. 3a).
nut::Hierarchy buildFacadeSample();
// A four-storey mixed-use building with a hipped roof, of many blocks (compare paper Fig. 12).
nut::Hierarchy buildBuildingSample();
// Every one of the 69 solids in a cabinet, plus a pavilion and a gatehouse built from them.
nut::Hierarchy buildSolidsSample();
// One small asymmetric block shown by each of the 24 cube rotations, on a 6 x 4 grid.
nut::Hierarchy buildRotationsSample();

}  // namespace samples
