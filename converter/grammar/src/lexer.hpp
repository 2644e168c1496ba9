// The grammar's tokens: words, numbers (a trailing 'r' marks a relative size), the arrow ("->" or
// "→"), punctuation; comments (# and //) and blanks skipped, each token with its line and column.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <grammar/grammar.hpp>

namespace nut::grammar {

struct Token {
  enum class Kind { Word, Number, Arrow, Punct, End };
  Kind kind = Kind::End;
  std::string text;      // as written
  double number = 0;     // Number
  bool relative = false; // Number written with a trailing 'r'
  char punct = 0;        // Punct: one of ( ) { } , : ; = > @
  Position at;
};

// The tokens of `text`, ending with one End token; an error names the file, line and column of a
// character no token starts with.
Result<std::vector<Token>> tokenize(std::string_view text, const std::string& file);

// "file:line:column: " for messages.
std::string where(const std::string& file, const Position& at);

}  // namespace nut::grammar
