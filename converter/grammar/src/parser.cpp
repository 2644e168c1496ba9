// Grammar text to rules (grammar.hpp): statements, the two surface forms, and each operator's
// parameters turned into one Rule whichever form wrote it.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <nut/png_io.hpp>

#include "check.hpp"
#include "lexer.hpp"

namespace nut::grammar {

namespace {

// A parameter as written, before its operator gives it a meaning.
struct Arg {
  enum class Kind { Number, Word, Texture, Range, Vector };
  Kind kind = Kind::Number;
  Position at;
  double number = 0, high = 0;  // Number (and Range's low), Range's high
  bool relative = false;        // "1r"
  std::string word;             // Word; Texture's name
  char textureMode = 0;         // ':' (Rep:name) or '>' (Fit>name)
  std::string texturePrefix;    // "Rep", "Fit"
  glm::dvec3 vector{0.0};
};

// A brace item: `value : Rule` or `Rule`.
struct Item {
  std::optional<Arg> value;
  std::string rule;
  Position ruleAt;
};

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string file) : tokens_(std::move(tokens)), file_(std::move(file)) {}

  Result<Grammar> run() {
    Grammar g;
    g.file = file_;
    while (peek().kind != Token::Kind::End) {
      if (Status s = statement(g); !s) return s.error();
    }
    return g;
  }

  const std::string& fileStart() const { return fileStart_; }
  Position fileStartAt() const { return fileStartAt_; }

 private:
  const Token& peek(std::size_t ahead = 0) const { return tokens_[std::min(next_ + ahead, tokens_.size() - 1)]; }
  const Token& take() { return tokens_[std::min(next_++, tokens_.size() - 1)]; }
  bool isPunct(char c, std::size_t ahead = 0) const {
    return peek(ahead).kind == Token::Kind::Punct && peek(ahead).punct == c;
  }
  Error expected(const std::string& what) const {
    return Error{where(file_, peek().at) + "expected " + what + ", found '" + peek().text + "'"};
  }
  Status expect(char c) {
    if (!isPunct(c)) return expected(std::string{'\'', c, '\''});
    take();
    return Ok{};
  }
  Error error(const Position& at, const std::string& message) const { return Error{where(file_, at) + message}; }

  Status statement(Grammar& g) {
    if (isPunct('@')) return directive(g);
    if (peek().kind != Token::Kind::Word) return expected("a rule name");
    const Token name = take();
    if (isPunct('=')) {
      take();
      if (peek().kind != Token::Kind::Number || peek().relative) return expected("a number");
      if (constants_.count(name.text)) return error(name.at, "constant '" + name.text + "' is defined twice");
      constants_[name.text] = take().number;
      return Ok{};
    }
    if (peek().kind != Token::Kind::Arrow) return expected("'->' or '='");
    take();
    if (peek().kind != Token::Kind::Word) return expected("an operator");
    const Token op = take();
    Rule rule;
    rule.name = name.text;
    rule.at = name.at;
    Status made = Ok{};
    if (isPunct('(')) {
      auto args = callArgs();
      if (!args) return args.error();
      made = fromCall(rule, op, *args);
    } else if (isPunct('{')) {
      auto items = braceItems();
      if (!items) return items.error();
      made = fromBraces(rule, op, *items);
    } else {
      made = fromBare(rule, op);
    }
    if (!made) return made;
    if (isPunct(';')) take();
    g.rules.push_back(std::move(rule));
    return Ok{};
  }

  Status directive(Grammar& g) {
    take();
    if (peek().kind != Token::Kind::Word) return expected("'start' or 'size' after '@'");
    const Token key = take();
    if (key.text == "start") {
      if (peek().kind != Token::Kind::Word) return expected("a rule name");
      fileStartAt_ = peek().at;
      fileStart_ = take().text;
      return Ok{};
    }
    if (key.text != "size") return error(key.at, "unknown directive '@" + key.text + "' (@start, @size)");
    std::vector<double> size;
    const Position at = peek().at;
    do {
      if (!size.empty()) take();
      auto v = number();
      if (!v) return v.error();
      size.push_back(*v);
    } while (isPunct(','));
    if (size.size() < 2 || size.size() > 3) return error(at, "@size takes W, H (a facade) or W, H, D (a mass)");
    for (double s : size)
      if (!(s > 0)) return error(at, "@size must be positive");
    g.size = glm::dvec3(size[0], size[1], size.size() == 3 ? size[2] : 0.0);
    return Ok{};
  }

  // A number, or a named constant.
  Result<double> number() {
    if (peek().kind == Token::Kind::Number && !peek().relative) return take().number;
    if (peek().kind == Token::Kind::Word) {
      if (auto it = constants_.find(peek().text); it != constants_.end()) {
        take();
        return it->second;
      }
    }
    return expected("a number");
  }

  Result<std::vector<Arg>> callArgs() {
    take();  // (
    std::vector<Arg> args;
    if (isPunct(')')) {
      take();
      return args;
    }
    while (true) {
      Arg a;
      a.at = peek().at;
      if (peek().kind == Token::Kind::Number) {
        a.kind = Arg::Kind::Number;
        a.relative = peek().relative;
        a.number = take().number;
      } else if (peek().kind == Token::Kind::Word) {
        a.word = take().text;
        if ((isPunct(':') || isPunct('>')) && peek(1).kind == Token::Kind::Word) {
          a.kind = Arg::Kind::Texture;
          a.textureMode = take().punct;
          a.texturePrefix = a.word;
          a.word = take().text;
        } else if (auto it = constants_.find(a.word); it != constants_.end()) {
          a.kind = Arg::Kind::Number;
          a.number = it->second;
        } else {
          a.kind = Arg::Kind::Word;
        }
      } else {
        return expected("a number or a name");
      }
      args.push_back(std::move(a));
      if (isPunct(')')) {
        take();
        return args;
      }
      if (Status s = expect(','); !s) return s.error();
    }
  }

  Result<std::vector<Item>> braceItems() {
    take();  // {
    std::vector<Item> items;
    while (!isPunct('}')) {
      if (!items.empty())
        if (Status s = expect(','); !s) return s.error();
      Item item;
      const bool hasValue =
          peek().kind == Token::Kind::Number || isPunct('(') ||
          (peek().kind == Token::Kind::Word && (isPunct(':', 1) || (peek().text == "Rand" && isPunct('(', 1))));
      if (hasValue) {
        auto value = braceValue();
        if (!value) return value.error();
        item.value = *value;
        if (Status s = expect(':'); !s) return s.error();
      }
      if (peek().kind != Token::Kind::Word) return expected("a rule name");
      item.ruleAt = peek().at;
      item.rule = take().text;
      items.push_back(std::move(item));
    }
    take();  // }
    return items;
  }

  // 1.5, 2r, Rand(0.3, 0.5), (0, 2.5, 0) or a constant's name.
  Result<Arg> braceValue() {
    Arg a;
    a.at = peek().at;
    if (peek().kind == Token::Kind::Number) {
      a.relative = peek().relative;
      a.number = a.high = take().number;
      return a;
    }
    if (isPunct('(')) {
      take();
      a.kind = Arg::Kind::Vector;
      for (int k = 0; k < 3; ++k) {
        if (k > 0)
          if (Status s = expect(','); !s) return s.error();
        auto v = number();
        if (!v) return v.error();
        a.vector[k] = *v;
      }
      if (Status s = expect(')'); !s) return s.error();
      return a;
    }
    if (peek().text == "Rand" && isPunct('(', 1)) {
      take();
      take();
      a.kind = Arg::Kind::Range;
      auto low = number();
      if (!low) return low.error();
      if (Status s = expect(','); !s) return s.error();
      auto high = number();
      if (!high) return high.error();
      if (Status s = expect(')'); !s) return s.error();
      if (!(*low <= *high)) return error(a.at, "Rand(low, high) needs low <= high");
      a.number = *low;
      a.high = *high;
      return a;
    }
    auto v = number();
    if (!v) return v.error();
    a.number = a.high = *v;
    return a;
  }

  // ---- the call form ----

  Status fromCall(Rule& r, const Token& op, const std::vector<Arg>& args) {
    const std::string& o = op.text;
    const auto count = [&](std::size_t n) -> Status {
      if (args.size() != n)
        return error(op.at, o + " takes " + std::to_string(n) + " parameters, found " + std::to_string(args.size()));
      return Ok{};
    };
    if (o == "SplitX" || o == "SplitY") {
      r.op = Op::Split;
      r.axis = o.back() == 'X' ? 0 : 1;
      if (args.empty() || args.size() % 3 != 0)
        return error(op.at,
                     o + " takes triples (Abs|Rel, size, Rule), found " + std::to_string(args.size()) + " parameters");
      for (std::size_t i = 0; i < args.size(); i += 3) {
        const Arg& policy = args[i];
        const bool abs = policy.kind == Arg::Kind::Word && policy.word == "Abs";
        const bool rel = policy.kind == Arg::Kind::Word && policy.word == "Rel";
        const bool signedPolicy = policy.kind == Arg::Kind::Number && (policy.number == -1 || policy.number == 1);
        if (!abs && !rel && !signedPolicy) return error(policy.at, "expected Abs or Rel (or -1 / 1)");
        auto size = positive(args[i + 1], "a split size");
        if (!size) return size.error();
        auto rule = ruleName(args[i + 2]);
        if (!rule) return rule.error();
        Part p = *rule;
        p.relative = rel || (signedPolicy && policy.number == 1);
        p.size = {*size, *size};
        r.parts.push_back(std::move(p));
      }
      return Ok{};
    }
    if (o == "RepeatX" || o == "RepeatY") {
      if (Status s = count(2); !s) return s;
      r.op = Op::Repeat;
      r.axis = o.back() == 'X' ? 0 : 1;
      auto size = positive(args[0], "a repeat size");
      if (!size) return size.error();
      auto rule = ruleName(args[1]);
      if (!rule) return rule.error();
      r.parts.push_back(*rule);
      r.parts.back().size = {*size, *size};
      return Ok{};
    }
    if (o == "Rand" || o == "RandUni") {
      r.op = Op::Random;
      if (args.size() < 2) return error(op.at, o + " takes a seed level and at least one rule");
      auto level = count0(args[0], "the seed level");
      if (!level) return level.error();
      r.level = *level;
      const bool weighted = o == "Rand";
      if (weighted && (args.size() - 1) % 2 != 0)
        return error(op.at, "Rand takes (level, weight, Rule, weight, Rule, ...)");
      double sum = 0;
      for (std::size_t i = 1; i < args.size(); i += weighted ? 2 : 1) {
        double weight = 1.0 / static_cast<double>(args.size() - 1);  // RandUni
        if (weighted) {
          auto w = positive(args[i], "a weight");
          if (!w) return w.error();
          weight = *w;
        }
        auto rule = ruleName(args[i + (weighted ? 1 : 0)]);
        if (!rule) return rule.error();
        r.parts.push_back(*rule);
        r.parts.back().size = {weight, weight};
        sum += weight;
      }
      if (weighted && std::abs(sum - 1.0) > 1e-6)
        return error(op.at, "Rand's weights add up to " + std::to_string(sum) + ", not 1");
      return Ok{};
    }
    if (o == "RandStack") {
      if (Status s = count(1); !s) return s;
      r.op = Op::RandStack;
      return rulesFrom(r, args);
    }
    if (o == "Layer") {
      if (args.empty()) return error(op.at, "Layer takes at least one rule");
      r.op = Op::Layer;
      return rulesFrom(r, args);
    }
    if (o == "Skip") {
      if (Status s = count(1); !s) return s;
      r.op = Op::Skip;
      auto level = count0(args[0], "the number of layers skipped");
      if (!level) return level.error();
      r.level = *level;
      return Ok{};
    }
    if (o == "SkipMask") {
      if (Status s = count(3); !s) return s;
      r.op = Op::SkipMask;
      auto m = count0(args[0], "the mask"), l0 = count0(args[1], "l0"), l1 = count0(args[2], "l1");
      if (!m) return m.error();
      if (!l0) return l0.error();
      if (!l1) return l1.error();
      r.mask = *m, r.level = *l0, r.level1 = *l1;
      return Ok{};
    }
    if (o == "Intrusion") {
      if (Status s = count(6); !s) return s;
      r.op = Op::Intrusion;
      auto depth = positive(args[0], "the intrusion depth");
      if (!depth) return depth.error();
      r.depth = *depth;
      return rulesFrom(r, std::vector<Arg>(args.begin() + 1, args.end()));
    }
    if (o == "Mat" || o == "MatAlpha") return material(r, op, args);
    return error(op.at, "unknown operator '" + o +
                            "' in the call form (SplitX, SplitY, RepeatX, RepeatY, Rand, RandUni, "
                            "RandStack, Layer, Skip, SkipMask, Intrusion, Mat, MatAlpha)");
  }

  Status material(Rule& r, const Token& op, const std::vector<Arg>& args) {
    const bool alpha = op.text == "MatAlpha";
    const std::size_t n = alpha ? 11 : 6;
    if (args.size() != n)
      return error(op.at,
                   op.text + " takes " + std::to_string(n) + " parameters, found " + std::to_string(args.size()));
    r.op = Op::Material;
    MaterialSpec& m = r.material;
    const Arg& usage = args[0];
    if (usage.kind == Arg::Kind::Word && (usage.word == "Color" || usage.word == "Colour"))
      m.usage = Usage::Color;
    else if (usage.kind == Arg::Kind::Word && usage.word == "Normal")
      m.usage = Usage::Normal;
    else if (usage.kind == Arg::Kind::Word && usage.word == "Specular")
      m.usage = Usage::Specular;
    else if (usage.kind == Arg::Kind::Number && (usage.number == 1 || usage.number == 2 || usage.number == 3))
      m.usage = static_cast<Usage>(static_cast<int>(usage.number) - 1);
    else
      return error(usage.at, "expected Color, Normal or Specular (or 1, 2, 3)");
    const Arg& texture = args[1];
    if (texture.kind == Arg::Kind::Texture) {
      const bool rep = texture.texturePrefix == "Rep" && texture.textureMode == ':';
      const bool fit = texture.texturePrefix == "Fit" && texture.textureMode == '>';
      if (!rep && !fit) return error(texture.at, "a texture is written Rep:name (repeated) or Fit>name (fitted)");
      m.textureName = texture.word;
      m.repeated = rep;
    } else if (texture.kind == Arg::Kind::Number && texture.number == std::floor(texture.number)) {
      m.texture = static_cast<int>(texture.number);
      m.repeated = m.texture < 0;
    } else {
      return error(texture.at, "expected 0 (a constant colour), a texture number, Rep:name or Fit>name");
    }
    for (int k = 0; k < 4; ++k) {
      auto v = unit(args[2 + static_cast<std::size_t>(k)]);
      if (!v) return v.error();
      m.values[static_cast<std::size_t>(k)] = *v;
    }
    if (alpha) {
      std::array<double, 5> a{};
      for (int k = 0; k < 5; ++k) {
        const Arg& arg = args[6 + static_cast<std::size_t>(k)];
        if (k == 0) {
          if (arg.kind != Arg::Kind::Number || arg.number != std::floor(arg.number))
            return error(arg.at, "expected the alpha texture's number (0: constant alpha)");
          a[0] = arg.number;
          continue;
        }
        auto v = unit(arg);
        if (!v) return v.error();
        a[static_cast<std::size_t>(k)] = *v;
      }
      m.alpha = a;
    }
    return Ok{};
  }

  // ---- the brace form ----

  Status fromBraces(Rule& r, const Token& op, const std::vector<Item>& items) {
    const std::string& o = op.text;
    const auto rulesOnly = [&](std::size_t n) -> Status {
      if (n != 0 && items.size() != n)
        return error(op.at, o + " takes " + std::to_string(n) + " rules, found " + std::to_string(items.size()));
      if (items.empty()) return error(op.at, o + " takes at least one rule");
      for (const Item& item : items) {
        if (item.value) return error(item.value->at, o + " takes rule names only");
        r.parts.push_back({item.rule, item.ruleAt});
      }
      return Ok{};
    };
    if (o == "Generate") {
      r.op = Op::Generate;
      if (items.size() != 1 || items[0].value || (items[0].rule != "Quad" && items[0].rule != "Box"))
        return error(op.at, "Generate takes {Quad} or {Box}");
      r.shape = items[0].rule == "Quad" ? Shape::Quad : Shape::Box;
      return Ok{};
    }
    if (o == "SubdivideX" || o == "SubdivideY" || o == "SubdivideZ" || o == "RepeatX" || o == "RepeatY" ||
        o == "RepeatZ") {
      const bool repeat = o[0] == 'R';
      r.op = repeat ? Op::Repeat : Op::Split;
      r.axis = o.back() - 'X';
      if (items.empty() || (repeat && items.size() != 1))
        return error(op.at, o + (repeat ? " takes one {size : Rule}" : " takes {size : Rule, ...}"));
      for (const Item& item : items) {
        if (!item.value || (item.value->kind != Arg::Kind::Number && item.value->kind != Arg::Kind::Range))
          return error(item.ruleAt,
                       o + " needs a size before each rule (1.5 : Rule, 2r : Rule or Rand(lo, hi) : Rule)");
        const Arg& v = *item.value;
        if (!(v.number > 0)) return error(v.at, "a size must be positive");
        if (repeat && v.relative) return error(v.at, "a repeat size is in metres, not relative");
        Part p{item.rule, item.ruleAt, v.relative, {v.number, v.kind == Arg::Kind::Range ? v.high : v.number}};
        r.parts.push_back(std::move(p));
      }
      return Ok{};
    }
    if (o == "RandomRule") {
      r.op = Op::Random;
      if (items.empty()) return error(op.at, "RandomRule takes at least one rule");
      const bool weighted = items[0].value.has_value();
      double sum = 0;
      for (const Item& item : items) {
        if (item.value.has_value() != weighted)
          return error(item.ruleAt, "RandomRule gives every rule a probability or none");
        double w = 1.0 / static_cast<double>(items.size());
        if (weighted) {
          if (item.value->kind != Arg::Kind::Number || item.value->relative || !(item.value->number > 0))
            return error(item.value->at, "a probability is a number in (0, 1]");
          w = item.value->number;
        }
        sum += w;
        r.parts.push_back({item.rule, item.ruleAt, false, {w, w}});
      }
      if (weighted && std::abs(sum - 1.0) > 1e-6)
        return error(op.at, "RandomRule's probabilities add up to " + std::to_string(sum) + ", not 1");
      return Ok{};
    }
    if (o == "ComponentSplit") {
      r.op = Op::ComponentSplit;
      return rulesOnly(3);
    }
    if (o == "Extrude" || o == "ExtrudeZ") {  // the thesis's complex house writes ExtrudeZ
      r.op = Op::Extrude;
      if (items.size() != 1 || !items[0].value || items[0].value->kind != Arg::Kind::Number ||
          items[0].value->relative || !(items[0].value->number > 0))
        return error(op.at, "Extrude takes {depth : Rule} with a positive depth in metres");
      r.parts.push_back({items[0].rule, items[0].ruleAt, false, {items[0].value->number, items[0].value->number}});
      return Ok{};
    }
    if (o == "Translate" || o == "Scale") {
      r.op = o == "Translate" ? Op::Translate : Op::Scale;
      if (items.size() != 1 || !items[0].value || items[0].value->kind != Arg::Kind::Vector)
        return error(op.at, o + " takes {(x, y, z) : Rule}");
      r.vector = items[0].value->vector;
      if (r.op == Op::Scale && !(r.vector.x > 0 && r.vector.y > 0 && r.vector.z > 0))
        return error(items[0].value->at, "a scale must be positive on every axis");
      r.parts.push_back({items[0].rule, items[0].ruleAt});
      return Ok{};
    }
    if (o == "Layer" || o == "RandStack") {
      r.op = o == "Layer" ? Op::Layer : Op::RandStack;
      return rulesOnly(o == "Layer" ? 0 : 1);
    }
    return error(op.at, "unknown operator '" + o +
                            "' in the brace form (Generate, SubdivideX/Y/Z, RepeatX/Y/Z, RandomRule, "
                            "ComponentSplit, Extrude, ExtrudeZ, Translate, Scale, Layer, RandStack)");
  }

  Status fromBare(Rule& r, const Token& op) {
    if (op.text == "Discard" || op.text == "Empty") {
      r.op = Op::Discard;
      return Ok{};
    }
    return error(op.at, "operator '" + op.text + "' needs its parameters in ( ) or { }");
  }

  // ---- parameters ----

  Result<double> positive(const Arg& a, const std::string& what) const {
    if (a.kind != Arg::Kind::Number || a.relative) return error(a.at, "expected " + what + " (a number)");
    if (!(a.number > 0)) return error(a.at, what + " must be positive");
    return a.number;
  }
  Result<int> count0(const Arg& a, const std::string& what) const {
    if (a.kind != Arg::Kind::Number || a.relative || a.number < 0 || a.number != std::floor(a.number) || a.number > 1e6)
      return error(a.at, what + " must be a whole number >= 0");
    return static_cast<int>(a.number);
  }
  Result<double> unit(const Arg& a) const {
    if (a.kind != Arg::Kind::Number || a.relative || a.number < 0 || a.number > 1)
      return error(a.at, "expected a number in [0, 1]");
    return a.number;
  }
  Result<Part> ruleName(const Arg& a) const {
    if (a.kind != Arg::Kind::Word) return error(a.at, "expected a rule name");
    return Part{a.word, a.at};
  }
  Status rulesFrom(Rule& r, const std::vector<Arg>& args) const {
    for (const Arg& a : args) {
      auto part = ruleName(a);
      if (!part) return part.error();
      r.parts.push_back(*part);
    }
    return Ok{};
  }

  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::string file_;
  std::map<std::string, double, std::less<>> constants_;
  std::string fileStart_;
  Position fileStartAt_;
};

}  // namespace

const Rule* Grammar::find(const std::string& name) const {
  for (const Rule& r : rules)
    if (r.name == name) return &r;
  return nullptr;
}

bool isEmptyName(const std::string& name) { return name == "Empty" || name == "Discard"; }

Result<Grammar> parseGrammar(const std::string& text, const std::string& file, const std::string& start) {
  auto tokens = tokenize(text, file);
  if (!tokens) return tokens.error();
  Parser parser(std::move(*tokens), file);
  auto grammar = parser.run();
  if (!grammar) return grammar.error();
  if (Status s = checkGrammar(*grammar, start.empty() ? parser.fileStart() : start, parser.fileStartAt()); !s)
    return s.error();
  return grammar;
}

Result<Grammar> readGrammar(const std::string& path, const std::string& start) {
  auto text = readTextFile(path);
  if (!text) return text.error();
  return parseGrammar(*text, path, start);
}

}  // namespace nut::grammar
