// Fuzz target grammar_fuzz: arbitrary bytes as a grammar must never crash or hang the parser or
// the compiler; an error is one line naming the file, and an accepted grammar is whole: its start
// rule exists, every successor is a rule or the empty name, and every size and weight is positive.
// An accepted grammar is then derived (at most 20,000 shapes, a 10 m x 10 m facade when it gives
// no size), and a derivation that succeeds compiles to an HNI that validate() accepts.
#include <string>

#include <grammar/compile.hpp>
#include <grammar/grammar.hpp>
#include <nut/hni.hpp>

#include "require.hpp"
#include "targets.hpp"

namespace nut::fuzz {

int grammarInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = "fuzz.grammar";
  auto g = grammar::parseGrammar(std::string(reinterpret_cast<const char*>(data), size), path);
  if (!g) {
    NUT_FUZZ_REQUIRE(g.error().message.rfind(path, 0) == 0);
    NUT_FUZZ_REQUIRE(g.error().message.find('\n') == std::string::npos);
    return 0;
  }
  NUT_FUZZ_REQUIRE(g->find(g->start) != nullptr);
  for (const grammar::Rule& r : g->rules)
    for (const grammar::Part& p : r.parts) {
      NUT_FUZZ_REQUIRE(g->find(p.rule) != nullptr || grammar::isEmptyName(p.rule));
      if (r.op == grammar::Op::Split || r.op == grammar::Op::Repeat || r.op == grammar::Op::Extrude ||
          r.op == grammar::Op::Random)
        NUT_FUZZ_REQUIRE(p.size.low > 0 && p.size.low <= p.size.high);
    }
  grammar::DeriveOptions options;
  options.maxShapes = 20'000;
  if (!g->size) options.sizeM = glm::dvec3(10, 10, 0);
  auto compiled = grammar::compileGrammar(*g, options);
  if (!compiled) {
    NUT_FUZZ_REQUIRE(compiled.error().message.rfind(path, 0) == 0);
    NUT_FUZZ_REQUIRE(compiled.error().message.find('\n') == std::string::npos);
    return 0;
  }
  NUT_FUZZ_REQUIRE(validate(compiled->image).ok());
  return 0;
}

}  // namespace nut::fuzz
