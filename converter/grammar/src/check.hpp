// The checks a parsed grammar must pass (grammar.hpp): one definition per rule, every successor
// defined, one start rule, and every rule the start reaches reaches a terminal.
#pragma once

#include <string>

#include <grammar/grammar.hpp>

namespace nut::grammar {

// Checks g and sets g.start: `start` when given (`startAt` is where the file named it, or line 0
// for the command line), else the one rule no other rule names.
Status checkGrammar(Grammar& g, const std::string& start, const Position& startAt);

}  // namespace nut::grammar
