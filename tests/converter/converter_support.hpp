// What the converter tests share besides the fidelity measure (converter_fidelity.hpp): the test
// output folder, conversions that fail the test, and counts over a conversion.
#pragma once

#include <string>

#include <converter/convert.hpp>
#include <nut/solids.hpp>
#include <scene/obj.hpp>

#include "converter_fidelity.hpp"

namespace nut::converter::testing {

// The test output folder for a group of tests (created).
std::string outputDir(const std::string& group);

// convertMesh, failing the current test (and returning an empty conversion) when it fails.
Conversion convertOrFail(const TriangleMesh& mesh, const ConvertOptions& options = {});

// The share of the mesh's surface shown by grid cells.
double nutFraction(const Conversion& c);

// Cells of the HNI in one solid group (every block, as stored).
int cellsOf(const Conversion& c, SolidGroup group);

}  // namespace nut::converter::testing
