// The grammar language (grammar/grammar.hpp): both surface forms give the same rules, the papers'
// grammars parse as printed (samples/grammars/), every kind of mistake is one error naming
// file:line:column, and no mutation of a sample crashes or hangs the parser.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <grammar/grammar.hpp>
#include <nut/png_io.hpp>

namespace nut::grammar {
namespace {

std::string samplePath(const std::string& name) {
  return std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + name + ".grammar";
}

// Two terminals the small grammars below end in.
const std::string kTerminals = "B -> Mat(Color, 0, 1, 0, 0, 1)\nC -> Generate {Quad}\n";

void expectSameParts(const Rule& a, const Rule& b) {
  EXPECT_EQ(a.op, b.op);
  EXPECT_EQ(a.axis, b.axis);
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    EXPECT_EQ(a.parts[i].rule, b.parts[i].rule) << "part " << i;
    EXPECT_EQ(a.parts[i].relative, b.parts[i].relative) << "part " << i;
    EXPECT_EQ(a.parts[i].size.low, b.parts[i].size.low) << "part " << i;
    EXPECT_EQ(a.parts[i].size.high, b.parts[i].size.high) << "part " << i;
  }
}

TEST(GrammarParse, BothFormsGiveTheSameRules) {
  const std::pair<std::string, std::string> pairs[] = {
      {"A->SplitY(Abs, 3.0, B, Rel, 1.0, C, Rel, 2, B)", "A -> SubdivideY {3.0 : B, 1r : C, 2r : B}"},
      {"A->SplitX(-1, 0.5, C, 1, 1, B)", "A -> SubdivideX {0.5 : C, 1r : B}"},
      {"A->RepeatX(2.5, B)", "A -> RepeatX {2.5 : B}"},
      {"A->RandUni(0, B, C)", "A -> RandomRule {B, C}"},
      {"A->Rand(0, 0.25, B, 0.75, C)", "A -> RandomRule {0.25 : B, 0.75 : C}"},
      {"A->Layer(B, C)", "A -> Layer {B, C}"},
  };
  for (const auto& [call, brace] : pairs) {
    auto a = parseGrammar(call + "\n" + kTerminals, "call", "A");
    auto b = parseGrammar(brace + "\n" + kTerminals, "brace", "A");
    ASSERT_TRUE(a.ok()) << a.error().message;
    ASSERT_TRUE(b.ok()) << b.error().message;
    SCOPED_TRACE(call + "  vs  " + brace);
    expectSameParts(*a->find("A"), *b->find("A"));
    EXPECT_EQ(a->start, "A");
  }
}

TEST(GrammarParse, TheFacadePapersFigure12AsPrinted) {
  auto g = readGrammar(samplePath("krecklau_figure12"));
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(g->start, "S");
  EXPECT_EQ(g->rules.size(), 20u);
  ASSERT_TRUE(g->size.has_value());
  EXPECT_EQ(*g->size, glm::dvec3(15, 12, 0));

  const Rule& assets = *g->find("Assets");
  EXPECT_EQ(assets.op, Op::Split);
  EXPECT_EQ(assets.axis, 1);
  ASSERT_EQ(assets.parts.size(), 3u);
  EXPECT_FALSE(assets.parts[0].relative);
  EXPECT_EQ(assets.parts[0].size.low, 3.0);
  EXPECT_EQ(assets.parts[0].rule, "BottomFloor");
  EXPECT_TRUE(assets.parts[1].relative);
  EXPECT_EQ(assets.parts[2].size.low, 2.5);
  EXPECT_EQ(assets.parts[2].at.line, 15);  // the split spans three lines

  const Rule& window = *g->find("WindowMat");
  EXPECT_EQ(window.op, Op::Random);
  EXPECT_EQ(window.level, 1);
  EXPECT_EQ(window.parts.size(), 3u);
  const MaterialSpec& fitted = g->find("WindowMat1")->material;
  EXPECT_EQ(fitted.textureName, "window1");
  EXPECT_FALSE(fitted.repeated);
  EXPECT_TRUE(g->find("Wall2")->material.repeated);
  EXPECT_EQ(g->find("Skip")->op, Op::Skip);
  EXPECT_EQ(g->find("MiddleSeedStored")->op, Op::Repeat);
}

TEST(GrammarParse, ThePgaThesisGrammarsAsPrinted) {
  const std::pair<const char*, std::size_t> samples[] = {
      {"pga_simple_house", 8}, {"pga_random_windows", 8}, {"pga_random_rule", 20}};
  for (const auto& [name, rules] : samples) {
    auto g = readGrammar(samplePath(name));
    ASSERT_TRUE(g.ok()) << g.error().message;
    EXPECT_EQ(g->start, "First") << name;
    EXPECT_EQ(g->rules.size(), rules) << name;
    EXPECT_EQ(g->find("First")->op, Op::ComponentSplit) << name;
  }
  auto windows = readGrammar(samplePath("pga_random_windows"));
  ASSERT_TRUE(windows.ok());
  const Scalar tile = windows->find("FacadeX")->parts[0].size;
  EXPECT_TRUE(tile.random());
  EXPECT_EQ(tile.low, 0.3);
  EXPECT_EQ(tile.high, 0.5);

  auto facades = readGrammar(samplePath("pga_random_rule"));
  ASSERT_TRUE(facades.ok());
  const Rule& choice = *facades->find("FacadeX");
  EXPECT_EQ(choice.op, Op::Random);
  ASSERT_EQ(choice.parts.size(), 5u);
  EXPECT_DOUBLE_EQ(choice.parts[0].size.low, 0.2);  // no probabilities given: uniform
  EXPECT_EQ(facades->find("Balcony")->op, Op::Extrude);
  EXPECT_EQ(facades->find("BalconyOutside")->axis, 2);
}

TEST(GrammarParse, ConstantsDirectivesCommentsAndEmptySuccessors) {
  auto g = parseGrammar(
      "// a comment\n"
      "Floor = 3.0   # metres\n"
      "@start Top\n"
      "@size 10, 9\n"
      "Top → SubdivideY {Floor : B, 1r : Gap};\n"
      "Gap -> ComponentSplit {Empty, C, Discard}\n" +
          kTerminals,
      "consts");
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(g->start, "Top");
  EXPECT_EQ(g->find("Top")->parts[0].size.low, 3.0);
  EXPECT_EQ(*g->size, glm::dvec3(10, 9, 0));
  auto chosen = parseGrammar("A -> Layer {B}\nD -> Layer {C}\n" + kTerminals, "start", "D");
  ASSERT_TRUE(chosen.ok()) << chosen.error().message;
  EXPECT_EQ(chosen->start, "D");
}

// Each mistake, alone in an otherwise good grammar, gives one line naming where and what.
TEST(GrammarParse, EveryMistakeNamesFileLineAndColumn) {
  // start: the start rule given, or "" to have the parser find it.
  struct Case {
    std::string text, message, start = "A";
  };
  const Case cases[] = {
      {"A->SplitY(Abs, 3.0 B)\n", "g:1:20: expected ',', found 'B'"},
      {"A->SplitY(Abs, 3.0, B, Rel, 1, C\nD -> Layer {B}\n", "g:2:1: expected ',', found 'D'"},
      {"A -> SubdivideY {1r : B, 2r : Nowhere}\n", "g:1:31: no rule 'Nowhere' (A names it)"},
      {"A -> Layer {B}\nA -> Layer {C}\n", "g:2:1: rule 'A' is defined twice (first on line 1)"},
      {"A -> Layer {B}\nD -> Layer {C}\n", "g: several rules are named by no other: A (line 1), D (line 2)", ""},
      {"A -> Layer {B, D}\nD -> SubdivideX {1r : E}\nE -> Layer {D}\n", "g:2:1: rule 'D' never reaches a terminal (D -> E -> D)"},
      {"A -> SubdivideX {-1 : B}\n", "g:1:18: a size must be positive"},
      {"A->Rand(0, 0.5, B, 0.25, C)\n", "g:1:4: Rand's weights add up to 0.750000, not 1"},
      {"A->Mat(Color, 0, 1.5, 0, 0, 1)\n", "g:1:18: expected a number in [0, 1]"},
      {"A->Intrusion(0.3, B, C, B, C)\n", "g:1:4: Intrusion takes 6 parameters, found 5"},
      {"A->Twist(1, B)\n", "g:1:4: unknown operator 'Twist' in the call form"},
      {"A -> Generate {Sphere}\n", "g:1:6: Generate takes {Quad} or {Box}"},
      {"A -> Layer {B} $\n", "g:1:16: unexpected '$'"},
      {"A -> RepeatX {2r : B}\n", "g:1:15: a repeat size is in metres, not relative"},
      {"@size 0, 3\nA -> Layer {B}\n", "g:1:7: @size must be positive"},
      {"A -> Layer {B}\n@start Q\n", "g:2:8: no start rule 'Q'", ""},
  };
  for (const auto& [text, message, start] : cases) {
    auto g = parseGrammar(text + kTerminals, "g", start);
    ASSERT_FALSE(g.ok()) << text;
    EXPECT_EQ(g.error().message.find('\n'), std::string::npos) << g.error().message;
    EXPECT_EQ(g.error().message.rfind(message, 0), 0u) << "got:      " << g.error().message << "\nexpected: " << message;
  }
}

// Random edits of every sample (bytes replaced, deleted, duplicated, lines swapped) parse or fail
// with one error line; none crashes, and all of them together take well under a second each.
TEST(GrammarParse, MutatedSamplesNeverCrashOrHang) {
  std::mt19937 rng(12345);
  const std::string alphabet = "()[]{},:;=>@-r.0123456789 \n\tAbsRelRandMatSplitXYRepeat#/\xe2\x86\x92";
  for (const char* name : {"krecklau_figure12", "pga_simple_house", "pga_random_windows", "pga_random_rule"}) {
    auto text = readTextFile(samplePath(name));
    ASSERT_TRUE(text.ok());
    int accepted = 0, refused = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int n = 0; n < 3000; ++n) {
      std::string t = *text;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !t.empty(); ++e) {
        const std::size_t at = rng() % t.size();
        switch (rng() % 3) {
          case 0: t[at] = alphabet[rng() % alphabet.size()]; break;
          case 1: t.erase(at, 1 + rng() % 8); break;
          default: t.insert(at, t.substr(rng() % t.size(), 1 + rng() % 16)); break;
        }
      }
      auto g = parseGrammar(t, "mutant");
      if (g.ok()) {
        ++accepted;
        ASSERT_NE(g->find(g->start), nullptr);
      } else {
        ++refused;
        ASSERT_EQ(g.error().message.find('\n'), std::string::npos) << g.error().message;
      }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %d mutants accepted, %d refused, %.2f s\n", name, accepted, refused, seconds);
    EXPECT_GT(refused, 0);
    EXPECT_LT(seconds, 30.0);
  }
}

}  // namespace
}  // namespace nut::grammar
