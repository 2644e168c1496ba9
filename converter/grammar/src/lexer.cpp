// The grammar's tokens (lexer.hpp).
#include "lexer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace nut::grammar {

std::string where(const std::string& file, const Position& at) {
  return file + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": ";
}

namespace {

bool isWordStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

Result<std::vector<Token>> tokenize(std::string_view text, const std::string& file) {
  std::vector<Token> tokens;
  Position at{1, 1};
  std::size_t i = 0;
  const auto advance = [&](std::size_t n) {
    for (std::size_t k = 0; k < n && i < text.size(); ++k, ++i) {
      if (text[i] == '\n') {
        ++at.line;
        at.column = 1;
      } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
        ++at.column;  // a UTF-8 character counts once
      }
    }
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      advance(1);
    } else if (c == '#' || text.substr(i, 2) == "//") {
      while (i < text.size() && text[i] != '\n') advance(1);
    } else if (text.substr(i, 2) == "->" || text.substr(i, 3) == "\u2192") {
      tokens.push_back({Token::Kind::Arrow, "->", 0, false, 0, at});
      advance(c == '-' ? 2 : 3);
    } else if (isWordStart(c)) {
      std::size_t j = i;
      while (j < text.size() && isWordChar(text[j])) ++j;
      tokens.push_back({Token::Kind::Word, std::string(text.substr(i, j - i)), 0, false, 0, at});
      advance(j - i);
    } else if (isDigit(c) || ((c == '-' || c == '+' || c == '.') && i + 1 < text.size() &&
                              (isDigit(text[i + 1]) || text[i + 1] == '.'))) {
      const std::size_t sign = (c == '+') ? 1 : 0;  // from_chars takes '-' but not '+'
      double value = 0;
      const char* begin = text.data() + i + sign;
      const auto [end, ec] = std::from_chars(begin, text.data() + text.size(), value);
      if (ec != std::errc() || !std::isfinite(value))
        return Error{where(file, at) + "'" +
                     std::string(text.substr(i, static_cast<std::size_t>(end - text.data()) - i + 1)) +
                     "' is not a finite number"};
      std::size_t length = static_cast<std::size_t>(end - (text.data() + i));
      const bool relative = i + length < text.size() && text[i + length] == 'r' &&
                            (i + length + 1 == text.size() || !isWordChar(text[i + length + 1]));
      Token token{
          Token::Kind::Number, std::string(text.substr(i, length + (relative ? 1 : 0))), value, relative, 0, at};
      if (i + length + (relative ? 1 : 0) < text.size() && isWordChar(text[i + length + (relative ? 1 : 0)]))
        return Error{where(file, at) + "'" + token.text + text[i + length + (relative ? 1 : 0)] +
                     "...' is not a number (a rule name starts with a letter)"};
      tokens.push_back(std::move(token));
      advance(length + (relative ? 1 : 0));
    } else if (std::string_view("(){},:;=>@").find(c) != std::string_view::npos) {
      tokens.push_back({Token::Kind::Punct, std::string(1, c), 0, false, c, at});
      advance(1);
    } else {
      const unsigned char byte = static_cast<unsigned char>(c);
      return Error{where(file, at) + (byte >= 0x20 && byte < 0x7F ? "unexpected '" + std::string(1, c) + "'"
                                                                  : "unexpected byte " + std::to_string(byte))};
    }
  }
  tokens.push_back({Token::Kind::End, "end of file", 0, false, 0, at});
  return tokens;
}

}  // namespace nut::grammar
