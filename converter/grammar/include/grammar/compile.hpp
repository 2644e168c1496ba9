// grammar/compile.hpp — a grammar to an HNI in one call: derive, build the hierarchy, compile,
// and optionally measure each block's level of detail (nut/lod.hpp) and compile again with it.
// What `nut grammar`, the tests and the benchmarks run (docs/GRAMMAR.md).
#pragma once

#include <optional>

#include <glm/vec3.hpp>

#include <grammar/derive.hpp>
#include <grammar/grammar.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>
#include <nut/lod.hpp>

namespace nut::grammar {

struct CompiledGrammar {
  Derivation derivation;
  Hierarchy hierarchy;
  Image image;                // the HNI
  glm::dvec3 originM{0.0};    // world position of the root block's corner (HniText::originM)
  double deriveSeconds = 0;   // derive() and derivationHierarchy()
  double compileSeconds = 0;  // compile()
  double lodSeconds = 0;      // measureLevelOfDetail() and the second compile()
};

// derive(), derivationHierarchy() and compile(); with `lod`, also measureLevelOfDetail(), so the
// HNI carries the footprints (version 2). Errors name the grammar file and the rule.
Result<CompiledGrammar> compileGrammar(const Grammar& g, const DeriveOptions& options = {},
                                       const std::optional<LodMeasureOptions>& lod = std::nullopt);

}  // namespace nut::grammar
