// Helpers of the converter tests (converter_support.hpp).
#include "converter_support.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace nut::converter::testing {

std::string outputDir(const std::string& group) { return nut::testing::testOutputDir(group).string(); }

Conversion convertOrFail(const TriangleMesh& mesh, const ConvertOptions& options) {
  auto c = convertMesh(mesh, options);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return c.ok() ? std::move(*c) : Conversion{};
}

double nutFraction(const Conversion& c) { return c.report.solid.nutAreaM2 / c.report.solid.areaM2; }

int cellsOf(const Conversion& c, SolidGroup group) {
  int count = 0;
  for (const Block& block : c.hierarchy.blocks)
    for (const Cell& cell : block.cells) count += cell.kind == CellKind::Solid && solidGroup(cell.solid) == group;
  return count;
}

}  // namespace nut::converter::testing
