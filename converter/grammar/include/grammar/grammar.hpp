// grammar/grammar.hpp — facade and building grammars as the papers print them, parsed and checked
// into one rule model (docs/GRAMMAR.md has the language).
//
// One parser reads two surface forms, and a rule means the same whichever form wrote it:
//   call form (Krecklau and Kobbelt's facade textures):  Tile->SplitX(Rel, 1, Wall, Abs, 1.2, Window, Rel, 1, Wall)
//   brace form (the PGA thesis):                         Tile -> SubdivideX {1r : Wall, 1.2 : Window, 1r : Wall}
// Checking names every problem by file:line:column: a syntax error, an operator with the wrong
// parameters, a parameter out of range, a successor no rule defines, a start rule that is not
// unique, a rule that never reaches a terminal.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/error.hpp>

namespace nut::grammar {

struct Position {
  int line = 0, column = 0;  // from 1
};

// A number, or a random range Rand(lo, hi) resolved with the seed at compile time.
struct Scalar {
  double low = 0, high = 0;
  bool random() const { return low != high; }
};

enum class Op {
  Split,           // SplitX/Y (call), SubdivideX/Y/Z (brace): parts of absolute or relative size
  Repeat,          // RepeatX/Y/Z: tiles of about the size of parts[0]
  Random,          // Rand, RandUni (call), RandomRule (brace): one part, chosen by weight
  RandStack,       // RandStack: the scope's seed on the stack, then parts[0]
  Layer,           // Layer: parts overlaid, the last on top
  Skip,            // Skip(l): this scope shows the l-th layer below
  SkipMask,        // SkipMask(m, l0, l1)
  Intrusion,       // Intrusion(depth, left, right, bottom, top, back): a recess of five faces
  Material,        // Mat, MatAlpha: a terminal with a colour (or a texture) and opacity
  Generate,        // Generate {Quad|Box}: a terminal, the scope's face or box
  Discard,         // Discard, Empty: a terminal that leaves nothing
  ComponentSplit,  // ComponentSplit {top, bottom, sides}: the faces of a mass
  Extrude,         // Extrude {depth : R}: a mass on the scope's face
  Translate,       // Translate {(x, y, z) : R}
  Scale,           // Scale {(x, y, z) : R}
};

enum class Shape { Quad, Box };
enum class Usage { Color, Normal, Specular };

// Mat(usage, m1, ..., m5) and MatAlpha(..., a1, ..., a5). m1 = 0: the constant colour
// (m2, m3, m4) with opacity m5; a texture name (Fit>name fitted, Rep:name repeated) or a texture
// number (m1 > 0 fitted, m1 < 0 repeated) with the rectangle or offset and scale m2..m5.
struct MaterialSpec {
  Usage usage = Usage::Color;
  int texture = 0;          // 0: none; the texture's number, negative when repeated
  std::string textureName;  // when given by name
  bool repeated = false;    // Rep:name / m1 < 0
  std::array<double, 4> values{};               // m2..m5
  std::optional<std::array<double, 5>> alpha;   // MatAlpha's a1..a5
};

// A successor: the rule it names, with the size, weight or nothing its operator gives it.
struct Part {
  std::string rule;
  Position at;             // of the rule's name
  bool relative = false;   // Split: a relative size ("Rel, v" or "vr")
  Scalar size;             // Split, Repeat, Extrude: metres (or a relative weight); Random: the weight
};

struct Rule {
  std::string name;
  Position at;
  Op op = Op::Discard;
  int axis = 0;            // Split, Repeat: 0 x, 1 y, 2 z
  std::vector<Part> parts;
  int level = 0;           // Random, Skip: the seed level l; SkipMask: l0
  int level1 = 0;          // SkipMask: l1
  int mask = 0;            // SkipMask: m
  double depth = 0;        // Intrusion
  glm::dvec3 vector{0.0};  // Translate, Scale
  Shape shape = Shape::Quad;
  MaterialSpec material;
};

struct Grammar {
  std::string file;
  std::vector<Rule> rules;              // in the order written
  std::string start;                    // the start rule
  std::optional<glm::dvec3> size;       // from `@size W, H[, D]`; z = 0 for a facade
  const Rule* find(const std::string& name) const;
};

// Parses and checks grammar text; `file` names it in errors. The start rule is `start` if given,
// else the file's `@start`, else the one rule no other rule names.
Result<Grammar> parseGrammar(const std::string& text, const std::string& file, const std::string& start = {});

// Reads and parses a grammar file.
Result<Grammar> readGrammar(const std::string& path, const std::string& start = {});

// A successor name that needs no rule: the empty terminal (what Discard leaves).
bool isEmptyName(const std::string& name);

}  // namespace nut::grammar
