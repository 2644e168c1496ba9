// grammar/compile.hpp — a grammar to an HNI in one call: derive, build the hierarchy, compile.
// What `nut grammar`, the tests and the benchmarks run (docs/GRAMMAR.md).
#pragma once

#include <glm/vec3.hpp>

#include <grammar/derive.hpp>
#include <grammar/grammar.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>

namespace nut::grammar {

struct CompiledGrammar {
  Derivation derivation;
  Hierarchy hierarchy;
  Image image;                // the HNI
  glm::dvec3 originM{0.0};    // world position of the root block's corner (HniText::originM)
  double deriveSeconds = 0;   // derive() and derivationHierarchy()
  double compileSeconds = 0;  // compile()
};

// derive(), derivationHierarchy() and compile(). Errors name the grammar file and the rule.
Result<CompiledGrammar> compileGrammar(const Grammar& g, const DeriveOptions& options = {});

}  // namespace nut::grammar
