// The derivation (grammar/derive.hpp): rules applied to scopes, recursively, into interned nodes.
#include <grammar/derive.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <unordered_map>

#include <glm/mat3x3.hpp>

#include "box_frames.hpp"

namespace nut::grammar {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kOverlapM = 1e-7;     // pieces may touch; sharing more than this is an overlap
constexpr double kRecessFaceM = 0.05;  // thickness of a recess's side, floor and ceiling
constexpr long long kMaxRepeat = 100'000;

bool hasVolume(const WorldBox& b) {
  return b.max.x - b.min.x > kOverlapM && b.max.y - b.min.y > kOverlapM && b.max.z - b.min.z > kOverlapM;
}
WorldBox intersect(const WorldBox& a, const WorldBox& b) { return {glm::max(a.min, b.min), glm::min(a.max, b.max)}; }
WorldBox unite(const WorldBox& a, const WorldBox& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }
WorldBox shifted(const WorldBox& b, const glm::dvec3& d) { return {b.min + d, b.max + d}; }
int cubeIndexOf(const IMat3& m) {
  for (int i = 0; i < 24; ++i)
    if (cubeRotationMatrix(i) == m) return i;
  return -1;
}
IMat3 axesMatrix(const glm::ivec3& x, const glm::ivec3& y, const glm::ivec3& z) { return IMat3(x, y, z); }

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  std::uint64_t z = h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t hashText(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}
std::uint64_t bitsOf(double v) {
  v += 0.0;  // -0 hashes as +0, as it compares
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

struct NodeHash {
  std::size_t operator()(const Node& n) const {
    std::uint64_t h = 0;
    for (int a = 0; a < 3; ++a) h = mix(h, bitsOf(n.sizeM[a]));
    for (const Piece& p : n.pieces) {
      h = mix(h, static_cast<std::uint64_t>(p.kind) | std::uint64_t{p.material} << 8 | std::uint64_t{p.node} << 24);
      for (int a = 0; a < 3; ++a) h = mix(mix(h, bitsOf(p.region.min[a])), bitsOf(p.region.max[a]));
      for (int a = 0; a < 3; ++a) h = mix(h, bitsOf(p.offsetM[a]));
      h = mix(
          h, static_cast<std::uint64_t>(p.cube) | (p.wrap[0] ? 64 : 0) | (p.wrap[1] ? 128 : 0) | (p.wrap[2] ? 256 : 0));
    }
    return static_cast<std::size_t>(h);
  }
};

// A scope in the frame of the node being built. A quad is the face at z = origin.z (its corner at
// origin, size.z unused) with its slab behind it; a box spans [origin, origin + size].
struct Scope {
  glm::dvec3 origin{0.0};
  glm::dvec3 size{0.0};
  bool quad = true;
  double thickness = 0;       // quad: the slab's depth
  glm::dvec3 seedPoint{0.0};  // where random values are sampled (the facade paper's S_lb)
  std::uint64_t salt = 0;     // layers and faces sample apart, as the paper's i * s translation
  glm::ivec3 up{0, 1, 0};     // the world's up in this frame
  int capAxis = 1;            // box: the axis the mass grew along (ComponentSplit's top is at its end)

  WorldBox solid() const {
    if (!quad) return {origin, origin + size};
    return {origin - glm::dvec3(0, 0, thickness), origin + glm::dvec3(size.x, size.y, 0)};
  }
  Scope moved(const glm::dvec3& d) const {
    Scope s = *this;
    s.origin += d;
    s.seedPoint += d;
    return s;
  }
  Scope local() const {  // the same scope in a frame whose origin is this scope's corner
    Scope s = *this;
    s.origin = glm::dvec3(0.0);
    return s;
  }
};

struct LayerSet;

struct Context {
  std::vector<glm::dvec3> stack;     // RandStack's seeds, the last pushed last
  std::shared_ptr<LayerSet> layers;  // the innermost Layer's layers, or none
  int layer = 0;                     // the one being derived
  glm::dvec3 toLayer{0.0};           // this frame's origin in the Layer's frame
};

// What a Layer operator starts: its layers, each derived over the Layer's whole scope when a Skip
// first shows it.
struct LayerSet {
  const Rule* rule = nullptr;
  Scope scope;    // in the Layer's frame
  Context outer;  // the context the Layer was applied in
  std::vector<bool> derived;
  std::vector<std::optional<Piece>> content;
};

class Deriver {
 public:
  Deriver(const Grammar& g, const DeriveOptions& o) : g_(g), o_(o) {}

  Result<Derivation> run() {
    const Rule* start = g_.find(g_.start);
    if (!start) return Error{g_.file + ": no start rule"};
    const std::optional<glm::dvec3> size = o_.sizeM ? o_.sizeM : g_.size;
    if (!size)
      return Error{g_.file + ": no start scope: give --size W,H (a facade) or W,H,D (a mass), or @size in the file"};
    if (!(size->x > 0 && size->y > 0 && size->z >= 0) || !std::isfinite(size->x + size->y + size->z))
      return Error{g_.file + ": the start scope must have a positive width and height"};
    if (!(o_.wallM > 0)) return Error{g_.file + ": the wall thickness must be positive"};
    Scope s;
    s.size = *size;
    s.quad = size->z == 0;
    s.thickness = o_.wallM;
    std::vector<Piece> top;
    if (Status st = place(start->name, start->at, s, Context{}, top); !st) return st.error();
    auto root = finish(*start, std::move(top), glm::dvec3(0.0), 0, std::nullopt);
    if (!root) return root.error();
    if (!*root) return Error{at(*start) + "the grammar derives nothing from the start rule '" + start->name + "'"};
    // The root is a node shown whole: a box, a tiled node or a clipped one gets a node around it.
    Piece piece = **root;
    const bool whole = piece.kind == Piece::Kind::Node && piece.cube == 0 && piece.wrap == std::array<bool, 3>{} &&
                       piece.region == WorldBox{piece.offsetM, piece.offsetM + d_.nodes[piece.node].sizeM};
    if (!whole) {
      const WorldBox region = piece.region;
      piece.region = shifted(region, -region.min);
      if (piece.kind == Piece::Kind::Node) piece.offsetM -= region.min;
      piece = intern({region.size(), {piece}}, region, region.min, 0);
    }
    d_.root = piece;
    d_.shapes = shapes_;
    return std::move(d_);
  }

 private:
  std::string at(const Rule& r) const {
    return g_.file + ":" + std::to_string(r.at.line) + ":" + std::to_string(r.at.column) + ": rule '" + r.name + "': ";
  }

  // Applies the rule `name` to s, adding what it makes to `out` (pieces in s's frame). Rules that
  // cut their scope build a node of their own, so that alike results are shared.
  Status place(const std::string& name, const Position& where, const Scope& s, const Context& c,
               std::vector<Piece>& out) {
    if (isEmptyName(name)) return Ok{};
    const Rule* r = g_.find(name);
    if (!r)
      return Error{g_.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": no rule '" +
                   name + "'"};
    if (++shapes_ > o_.maxShapes)
      return Error{at(*r) + "the derivation exceeds " + std::to_string(o_.maxShapes) + " shapes"};
    switch (r->op) {
      case Op::Split:
      case Op::Repeat:
      case Op::Layer:
      case Op::Intrusion:
      case Op::ComponentSplit: {
        Context inner = c;
        inner.toLayer += s.origin;
        std::vector<Piece> pieces;
        if (Status st = apply(*r, s.local(), inner, pieces); !st) return st;
        auto piece = finish(*r, std::move(pieces), s.origin, 0, std::nullopt);
        if (!piece) return piece.error();
        if (*piece) out.push_back(**piece);
        return Ok{};
      }
      default: return apply(*r, s, c, out);
    }
  }

  // Places the rule `name` on a face (or a turned mass) whose frame is turned by `axes` and has
  // its origin at `faceOrigin` in the frame of scope s; what shows is clipped to `clip` (face frame).
  Status placeFace(const Rule& parent, const std::string& name, const Position& where, const Scope& face,
                   const Scope& s, const Context& c, const IMat3& axes, const glm::dvec3& faceOrigin,
                   const WorldBox& clip, std::vector<Piece>& out) {
    std::vector<Piece> pieces;
    Context inner;
    inner.stack = c.stack;  // faces keep the seeds but start without layers
    Scope turnedFace = face;
    turnedFace.up = transposed(axes) * s.up;
    if (Status st = place(name, where, turnedFace, inner, pieces); !st) return st;
    auto piece = finish(parent, std::move(pieces), faceOrigin, cubeIndexOf(axes), clip);
    if (!piece) return piece.error();
    if (*piece) out.push_back(**piece);
    return Ok{};
  }

  Status apply(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    switch (r.op) {
      case Op::Split: return split(r, s, c, out);
      case Op::Repeat: return repeat(r, s, c, out);
      case Op::Random: {
        const double u = random(r, s, c, r.level);
        double sum = 0;
        for (const Part& p : r.parts) sum += p.size.low;
        double acc = 0;
        for (const Part& p : r.parts) {
          acc += p.size.low / sum;
          if (u < acc || &p == &r.parts.back()) return place(p.rule, p.at, s, c, out);
        }
        return Ok{};
      }
      case Op::RandStack: {
        Context inner = c;
        inner.stack.push_back(s.seedPoint);
        return place(r.parts[0].rule, r.parts[0].at, s, inner, out);
      }
      case Op::Layer: return layer(r, s, c, out);
      case Op::Skip: return skip(s, c, r.level, out);
      case Op::SkipMask: return skip(s, c, r.level, out);  // no mask textures: every bit reads 0
      case Op::Intrusion: return intrusion(r, s, c, out);
      case Op::Material: {
        if (r.material.usage != Usage::Color) return skip(s, c, 0, out);  // a normal or specular map only
        auto m = material(r);
        if (!m) return m.error();
        out.push_back(terminal(s, *m));
        return Ok{};
      }
      case Op::Generate: {
        auto m = addMaterial(namedMaterial(r.name), r.name);
        if (!m) return Error{at(r) + m.error().message};
        out.push_back(terminal(s, *m));
        return Ok{};
      }
      case Op::Discard: return Ok{};
      case Op::ComponentSplit: return componentSplit(r, s, c, out);
      case Op::Extrude: return extrude(r, s, c, out);
      case Op::Translate: return place(r.parts[0].rule, r.parts[0].at, s.moved(r.vector), c, out);
      case Op::Scale: {
        // CGA's s(): the scope gets this size in metres, about its centre (a facade keeps its slab).
        Scope scaled = s;
        const glm::dvec3 size = s.quad ? glm::dvec3(r.vector.x, r.vector.y, 0.0) : r.vector;
        scaled.origin += 0.5 * (s.size - size);
        scaled.size = size;
        return place(r.parts[0].rule, r.parts[0].at, scaled, c, out);
      }
    }
    return Ok{};
  }

  // A terminal: the scope's solid in one material; a facade's shows its +z side.
  static Piece terminal(const Scope& s, std::uint16_t material) {
    Piece p{Piece::Kind::Box, s.solid(), material};
    if (s.quad) p.front = 4;
    return p;
  }

  // A uniform value in [0, 1): the seed, the rule, and the seed point the level names (0: this
  // scope's corner; l: the l-th last RandStack; beyond the stack: the start scope's corner).
  double random(const Rule& r, const Scope& s, const Context& c, int level) const {
    glm::dvec3 point = s.seedPoint;
    if (level > 0)
      point = level <= static_cast<int>(c.stack.size()) ? c.stack[c.stack.size() - static_cast<std::size_t>(level)]
                                                        : glm::dvec3(0.0);
    std::uint64_t h = mix(mix(o_.seed, hashText(r.name)), level > 0 ? 0 : s.salt);
    for (int a = 0; a < 3; ++a) h = mix(h, static_cast<std::uint64_t>(std::llround(point[a] * 1000.0)));
    return static_cast<double>(h >> 11) * 0x1p-53;
  }
  double draw(const Rule& r, const Scope& s, const Context& c, const Scalar& v, int part) const {
    if (!v.random()) return v.low;
    Scope salted = s;
    salted.salt = mix(s.salt, 1000 + static_cast<std::uint64_t>(part));
    return v.low + (v.high - v.low) * random(r, salted, c, 0);
  }

  Status checkAxis(const Rule& r, const Scope& s) const {
    if (s.quad && r.axis == 2)
      return Error{at(r) + "a split or repeat along z needs a mass (a box scope); this scope is a facade"};
    return Ok{};
  }

  Status split(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    if (Status st = checkAxis(r, s); !st) return st;
    const double length = s.size[r.axis];
    std::vector<double> sizes;
    double absolute = 0, relative = 0;
    for (std::size_t i = 0; i < r.parts.size(); ++i) {
      sizes.push_back(draw(r, s, c, r.parts[i].size, static_cast<int>(i)));
      (r.parts[i].relative ? relative : absolute) += sizes.back();
    }
    if (absolute > length * (1 + 1e-9) + 1e-9)
      return Error{at(r) + "parts of " + metres(absolute) + " do not fit a scope of " + metres(length) + " along " +
                   "xyz"[r.axis]};
    // Relative parts share what the absolute ones leave (the facade paper's equation 1); without
    // any, the absolute ones are stretched to fill the scope.
    const double scaleAbsolute = relative > 0 ? 1.0 : length / absolute;
    const double scaleRelative = relative > 0 ? (length - absolute) / relative : 0.0;
    double position = 0;
    for (std::size_t i = 0; i < r.parts.size(); ++i) {
      const double extent = sizes[i] * (r.parts[i].relative ? scaleRelative : scaleAbsolute);
      const double end = i + 1 == r.parts.size() ? length : position + extent;
      if (end - position > 0) {
        Scope part = s;
        part.origin[r.axis] += position;
        part.seedPoint[r.axis] += position;
        part.size[r.axis] = end - position;
        if (Status st = place(r.parts[i].rule, r.parts[i].at, part, c, out); !st) return st;
      }
      position = end;
    }
    return Ok{};
  }

  // Tiles of about the part's size. Each tile is built in its own frame; tiles that came out alike
  // become one placement that tiles its node (the format's wrap), or one box.
  Status repeat(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    if (Status st = checkAxis(r, s); !st) return st;
    const double length = s.size[r.axis];
    const double wanted = draw(r, s, c, r.parts[0].size, 0);
    // The nearest whole number of tiles, halves rounded up also when the division lands a hair
    // below the half (16 - 4.8 is 11.199999999999999 in doubles: 3.5 tiles of 3.2 m are 4).
    const double count = std::max(1.0, std::floor(length / wanted + 0.5 + 1e-9));
    if (count > kMaxRepeat)
      return Error{at(r) + "a repeat of " + metres(wanted) + " over " + metres(length) + " makes more than " +
                   std::to_string(kMaxRepeat) + " tiles"};
    const int n = static_cast<int>(count);
    const double pitch = length / n;
    std::vector<std::optional<Piece>> tiles;
    for (int i = 0; i < n; ++i) {
      Scope tile = s;
      tile.origin[r.axis] += i * pitch;
      tile.seedPoint[r.axis] += i * pitch;
      tile.size[r.axis] = pitch;
      Context inner = c;
      inner.toLayer += tile.origin;
      std::vector<Piece> pieces;
      if (Status st = place(r.parts[0].rule, r.parts[0].at, tile.local(), inner, pieces); !st) return st;
      auto piece = finish(r, std::move(pieces), tile.origin, 0, std::nullopt);
      if (!piece) return piece.error();
      tiles.push_back(*piece);
    }
    if (auto merged = mergeTiles(tiles, r.axis, pitch)) {
      out.push_back(*merged);
      return Ok{};
    }
    for (const auto& t : tiles)
      if (t) out.push_back(*t);
    return Ok{};
  }

  static std::optional<Piece> mergeTiles(const std::vector<std::optional<Piece>>& tiles, int axis, double pitch) {
    if (tiles.size() < 2 || !tiles[0]) return std::nullopt;
    const Piece& first = *tiles[0];
    Piece merged = first;
    const double tolerance = 1e-9 * std::max(1.0, pitch * static_cast<double>(tiles.size()));
    for (std::size_t i = 1; i < tiles.size(); ++i) {
      if (!tiles[i]) return std::nullopt;
      const Piece& t = *tiles[i];
      if (t.kind != first.kind || t.material != first.material || t.node != first.node || t.cube != first.cube ||
          t.wrap != first.wrap)
        return std::nullopt;
      glm::dvec3 step(0.0);
      step[axis] = pitch * static_cast<double>(i);
      const WorldBox expected = shifted(first.region, step);
      if (glm::any(glm::greaterThan(glm::abs(t.region.min - expected.min), glm::dvec3(tolerance))) ||
          glm::any(glm::greaterThan(glm::abs(t.region.max - expected.max), glm::dvec3(tolerance))))
        return std::nullopt;
      if (t.kind == Piece::Kind::Node &&
          glm::any(glm::greaterThan(glm::abs(t.offsetM - first.offsetM - step), glm::dvec3(tolerance))))
        return std::nullopt;
      merged.region = unite(merged.region, t.region);
    }
    // A box's tiles merge when they touch; a node's when each shows the whole node and its
    // extent along the repeat is the pitch, so that the format's wrap reproduces them.
    if (first.region.max[axis] - first.region.min[axis] < pitch * (1 - 1e-9)) return std::nullopt;
    if (first.kind == Piece::Kind::Node) {
      if (first.wrap != std::array<bool, 3>{}) return std::nullopt;
      const IMat3 m = cubeRotationMatrix(first.cube);
      int nodeAxis = 0;
      for (int a = 0; a < 3; ++a)
        if (m[a][axis] != 0) nodeAxis = a;  // column a is the image of the node's axis a
      merged.wrap[static_cast<std::size_t>(nodeAxis)] = true;
    }
    return merged;
  }

  Status layer(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    const std::size_t n = r.parts.size();
    auto set = std::make_shared<LayerSet>();
    set->rule = &r;
    set->scope = s;
    set->outer = c;
    set->derived.assign(n, false);
    set->content.assign(n, std::nullopt);
    Context top = c;
    top.layers = set;
    top.layer = static_cast<int>(n) - 1;
    top.toLayer = glm::dvec3(0.0);
    Scope scope = s;
    scope.salt = mix(s.salt, n);
    return place(r.parts[n - 1].rule, r.parts[n - 1].at, scope, top, out);
  }

  // This scope shows the layer `level + 1` below the current one, over the Layer's whole scope,
  // clipped to this scope's solid.
  Status skip(const Scope& s, const Context& c, int level, std::vector<Piece>& out) {
    if (!c.layers) return Ok{};
    const int below = c.layer - 1 - level;
    if (below < 0) return Ok{};
    LayerSet& set = *c.layers;
    const auto index = static_cast<std::size_t>(below);
    if (!set.derived[index]) {
      set.derived[index] = true;
      Context inner = set.outer;
      inner.layers = c.layers;
      inner.layer = below;
      inner.toLayer = glm::dvec3(0.0);
      Scope scope = set.scope;
      scope.salt = mix(scope.salt, index + 1);
      std::vector<Piece> pieces;
      const Part& part = set.rule->parts[index];
      if (Status st = place(part.rule, part.at, scope.local(), inner, pieces); !st) return st;
      auto piece = finish(*set.rule, std::move(pieces), scope.origin, 0, std::nullopt);
      if (!piece) return piece.error();
      set.content[index] = *piece;
    }
    if (!set.content[index]) return Ok{};
    Piece p = *set.content[index];
    p.region = intersect(shifted(p.region, -c.toLayer), s.solid());
    if (p.kind == Piece::Kind::Node) p.offsetM -= c.toLayer;
    if (hasVolume(p.region)) out.push_back(p);
    return Ok{};
  }

  // A recess behind the face: air to the depth, five faces of their own (left, right, floor,
  // ceiling, back). The sides own the corners; floor and ceiling lie between them.
  Status intrusion(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    if (!s.quad) return Error{at(r) + "Intrusion needs a facade (a quad scope); this scope is a mass"};
    const double v = r.depth, w = s.size.x, h = s.size.y;
    if (!(v < s.thickness))
      return Error{at(r) + "a recess of " + metres(v) + " needs a wall thicker than that; the wall is " +
                   metres(s.thickness) + " (--wall)"};
    const double f = std::min({kRecessFaceM, w / 4, h / 4});
    const glm::dvec3 o = s.origin;
    const auto face = [&](int i, double fw, double fh, double thickness) {
      Scope q;
      q.size = {fw, fh, 0};
      q.thickness = thickness;
      q.seedPoint = s.seedPoint;
      q.salt = mix(s.salt, 100 + static_cast<std::uint64_t>(i));
      return q;
    };
    const WorldBox all{glm::dvec3(-kInf), glm::dvec3(kInf)};
    const WorldBox between{{f, -kInf, -kInf}, {w - f, kInf, kInf}};
    const std::array<const Part*, 5> p{&r.parts[0], &r.parts[1], &r.parts[2], &r.parts[3], &r.parts[4]};
    Status st = placeFace(r, p[0]->rule, p[0]->at, face(0, v, h, f), s, c, axesMatrix({0, 0, -1}, {0, 1, 0}, {1, 0, 0}),
                          o + glm::dvec3(f, 0, 0), all, out);
    if (st)
      st = placeFace(r, p[1]->rule, p[1]->at, face(1, v, h, f), s, c, axesMatrix({0, 0, 1}, {0, 1, 0}, {-1, 0, 0}),
                     o + glm::dvec3(w - f, 0, -v), all, out);
    if (st)
      st = placeFace(r, p[2]->rule, p[2]->at, face(2, w, v, f), s, c, axesMatrix({1, 0, 0}, {0, 0, -1}, {0, 1, 0}),
                     o + glm::dvec3(0, f, 0), between, out);
    if (st)
      st = placeFace(r, p[3]->rule, p[3]->at, face(3, w, v, f), s, c, axesMatrix({1, 0, 0}, {0, 0, 1}, {0, -1, 0}),
                     o + glm::dvec3(0, h - f, -v), between, out);
    if (st)
      st = placeFace(r, p[4]->rule, p[4]->at, face(4, w, h, s.thickness - v), s, c, IMat3(1), o + glm::dvec3(0, 0, -v),
                     all, out);
    return st;
  }

  // The six faces of a mass, each a facade whose slab lies inside the mass (the walls). The top is
  // the face at the end of the axis the mass grew along (a building's roof, the front of a mass
  // extruded from a wall), the bottom the one opposite, the sides the other four. Of the sides,
  // the pair across the axis after the cap axis owns the corners; top and bottom lie between them.
  Status componentSplit(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    if (s.quad) return Error{at(r) + "ComponentSplit needs a mass (a box scope); this scope is a facade"};
    const glm::dvec3 n = s.size, o = s.origin;
    const double t = std::min(o_.wallM, std::min({n.x, n.y, n.z}) / 4);
    struct Face {
      int axis, side;
      IMat3 axes;
      glm::dvec3 corner;
      double width, height;
    };
    // Each face's frame: x along the face, y up the face, z its outward normal.
    const Face faces[] = {
        {2, +1, IMat3(1), {0, 0, n.z}, n.x, n.y},
        {2, -1, axesMatrix({-1, 0, 0}, {0, 1, 0}, {0, 0, -1}), {n.x, 0, 0}, n.x, n.y},
        {0, +1, axesMatrix({0, 0, -1}, {0, 1, 0}, {1, 0, 0}), {n.x, 0, n.z}, n.z, n.y},
        {0, -1, axesMatrix({0, 0, 1}, {0, 1, 0}, {-1, 0, 0}), {0, 0, 0}, n.z, n.y},
        {1, +1, axesMatrix({1, 0, 0}, {0, 0, -1}, {0, 1, 0}), {0, n.y, n.z}, n.x, n.z},
        {1, -1, axesMatrix({1, 0, 0}, {0, 0, 1}, {0, -1, 0}), {0, 0, 0}, n.x, n.z},
    };
    const int cap = s.capAxis, owner = (s.capAxis + 1) % 3;
    for (int i = 0; i < 6; ++i) {
      const Face& f = faces[i];
      const Part& part = f.axis == cap ? r.parts[f.side > 0 ? 0 : 1] : r.parts[2];
      WorldBox clip{glm::dvec3(-kInf), glm::dvec3(kInf)};
      if (f.axis == cap)
        clip = {{t, t, -kInf}, {f.width - t, f.height - t, kInf}};
      else if (f.axis != owner)
        clip = {{t, -kInf, -kInf}, {f.width - t, kInf, kInf}};
      Scope q;
      q.size = {f.width, f.height, 0};
      q.thickness = t;
      q.seedPoint = s.seedPoint + f.corner;
      q.salt = mix(s.salt, 200 + static_cast<std::uint64_t>(i));
      if (Status st = placeFace(r, part.rule, part.at, q, s, c, f.axes, o + f.corner, clip, out); !st) return st;
    }
    return Ok{};
  }

  // A mass on the face, as deep as the part says. On a wall it keeps the face's frame (z out); on
  // a horizontal face it stands upright (its y along the normal), as a building's parts do.
  Status extrude(const Rule& r, const Scope& s, const Context& c, std::vector<Piece>& out) {
    if (!s.quad) return Error{at(r) + "Extrude needs a facade (a quad scope); this scope is a mass"};
    const double depth = r.parts[0].size.low;
    Scope box = s;
    box.quad = false;
    box.size.z = depth;
    box.capAxis = 2;
    if (s.up != glm::ivec3(0, 0, 1)) return place(r.parts[0].rule, r.parts[0].at, box, c, out);
    box.origin = glm::dvec3(0.0);
    box.size = {s.size.x, depth, s.size.y};
    box.capAxis = 1;
    const IMat3 upright = axesMatrix({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
    const WorldBox all{glm::dvec3(-kInf), glm::dvec3(kInf)};
    return placeFace(r, r.parts[0].rule, r.parts[0].at, box, s, c, upright, s.origin + glm::dvec3(0, s.size.y, 0), all,
                     out);
  }

  // The pieces of one rule application, built in a frame with its origin at `origin` and turned
  // by cube rotation `cube` in the parent's frame, as one piece of the parent: a box when they are
  // one box, else an interned node of their bounding box. Empty when nothing shows.
  Result<std::optional<Piece>> finish(const Rule& r, std::vector<Piece> pieces, const glm::dvec3& origin, int cube,
                                      const std::optional<WorldBox>& clip) {
    std::vector<Piece> kept;
    for (Piece& p : pieces) {
      if (clip) p.region = intersect(p.region, *clip);
      if (hasVolume(p.region)) kept.push_back(std::move(p));
    }
    if (kept.empty()) return std::optional<Piece>{};
    if (const auto overlap = firstOverlap(kept))
      return Error{at(r) + "two of its shapes overlap (" + describe(kept[overlap->first].region) + " and " +
                   describe(kept[overlap->second].region) + "); a grid cell holds one"};
    const IMat3 m = cubeRotationMatrix(cube);
    if (kept.size() == 1 && kept[0].kind == Piece::Kind::Box) {
      kept[0].region = turned(kept[0].region, m, origin);
      kept[0].front = static_cast<std::int8_t>(turnedSide(kept[0].front, m));
      return std::optional<Piece>{kept[0]};
    }
    if (kept.size() == 1 && cube == 0) {
      kept[0].region = shifted(kept[0].region, origin);
      kept[0].offsetM += origin;
      return std::optional<Piece>{kept[0]};
    }
    WorldBox bounds = kept[0].region;
    for (const Piece& p : kept) bounds = unite(bounds, p.region);
    Node node{bounds.size(), {}};
    for (Piece& p : kept) {
      p.region = shifted(p.region, -bounds.min);
      if (p.kind == Piece::Kind::Node) p.offsetM -= bounds.min;
      node.pieces.push_back(std::move(p));
    }
    return std::optional<Piece>{
        intern(std::move(node), turned(bounds, m, origin), origin + glm::dvec3(glm::dmat3(m) * bounds.min), cube)};
  }

  // Two pieces whose regions share volume, if any: a sweep along the axis where the pieces start
  // at the most places (a split's or a repeat's axis), so that n pieces in a row cost n log n.
  static std::optional<std::pair<std::size_t, std::size_t>> firstOverlap(const std::vector<Piece>& pieces) {
    int axis = 0;
    std::size_t most = 0;
    for (int a = 0; a < 3; ++a) {
      std::vector<double> starts;
      for (const Piece& p : pieces) starts.push_back(p.region.min[a]);
      std::sort(starts.begin(), starts.end());
      const auto distinct = static_cast<std::size_t>(std::unique(starts.begin(), starts.end()) - starts.begin());
      if (distinct > most) most = distinct, axis = a;
    }
    std::vector<std::size_t> order(pieces.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return pieces[a].region.min[axis] < pieces[b].region.min[axis]; });
    for (std::size_t i = 0; i < order.size(); ++i)
      for (std::size_t j = i + 1; j < order.size(); ++j) {
        const WorldBox &a = pieces[order[i]].region, &b = pieces[order[j]].region;
        if (b.min[axis] >= a.max[axis] - kOverlapM) break;
        if (hasVolume(intersect(a, b)))
          return std::make_pair(std::min(order[i], order[j]), std::max(order[i], order[j]));
      }
    return std::nullopt;
  }

  Piece intern(Node node, const WorldBox& region, const glm::dvec3& offset, int cube) {
    auto [it, added] = ids_.try_emplace(std::move(node), static_cast<NodeId>(d_.nodes.size()));
    if (added) d_.nodes.push_back(it->first);
    Piece p;
    p.kind = Piece::Kind::Node;
    p.region = region;
    p.node = it->second;
    p.offsetM = offset;
    p.cube = cube;
    return p;
  }

  Result<std::uint16_t> material(const Rule& r) {
    const MaterialSpec& m = r.material;
    Material out;
    std::string name;
    if (m.texture == 0 && m.textureName.empty()) {
      const auto byte = [](double v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
      };
      out = {byte(m.values[0]), byte(m.values[1]), byte(m.values[2]), byte(m.values[3]), 0};
      if (out.opacity == 0) out.opacity = 1;  // a fully clear colour would be no colour at all; keep a trace
      name = r.name;
    } else {
      name = m.textureName.empty() ? "texture" + std::to_string(std::abs(m.texture)) : m.textureName;
      out = namedMaterial(name);
    }
    auto index = addMaterial(out, name);
    if (!index) return Error{at(r) + index.error().message};
    return *index;
  }

  Result<std::uint16_t> addMaterial(const Material& m, const std::string& name) {
    const auto key = std::make_pair(name, std::array<int, 5>{m.r, m.g, m.b, m.opacity, m.reflectance});
    if (auto it = materialIndex_.find(key); it != materialIndex_.end()) return it->second;
    if (d_.materials.size() >= kMaxMeshMaterials)
      return Error{"more than " + std::to_string(kMaxMeshMaterials) + " materials"};
    const auto index = static_cast<std::uint16_t>(d_.materials.size());
    d_.materials.push_back(m);
    d_.materialNames.push_back(name);
    materialIndex_.emplace(key, index);
    return index;
  }

  static std::string metres(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g m", v);
    return text;
  }
  static std::string describe(const WorldBox& b) {
    char text[160];
    std::snprintf(text, sizeof text, "[%.3g, %.3g] x [%.3g, %.3g] x [%.3g, %.3g]", b.min.x, b.max.x, b.min.y, b.max.y,
                  b.min.z, b.max.z);
    return text;
  }

  const Grammar& g_;
  const DeriveOptions& o_;
  Derivation d_;
  long long shapes_ = 0;
  std::unordered_map<Node, NodeId, NodeHash> ids_;
  std::map<std::pair<std::string, std::array<int, 5>>, std::uint16_t> materialIndex_;
};

bool contains(const std::string& name, const char* word) {
  std::string lower = name;
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return lower.find(word) != std::string::npos;
}

}  // namespace

Material namedMaterial(const std::string& name) {
  struct Tone {
    const char* word;
    int r, g, b;
  };
  // The first word the name contains picks the tone; order matters ("WindowWall" is a wall).
  static const Tone tones[] = {{"wall", 214, 198, 170},  {"column", 196, 184, 160},  {"side", 214, 198, 170},
                               {"window", 64, 88, 118},  {"glass", 90, 130, 160},    {"door", 112, 72, 46},
                               {"roof", 150, 70, 55},    {"top", 120, 118, 112},     {"balcony", 178, 178, 184},
                               {"ledge", 232, 226, 214}, {"cornice", 232, 226, 214}, {"ground", 150, 140, 130},
                               {"air", 190, 195, 200},   {"tower", 170, 160, 150}};
  const std::uint64_t h = hashText(name);
  int r = 80 + static_cast<int>(h % 150), g = 80 + static_cast<int>((h >> 8) % 150),
      b = 80 + static_cast<int>((h >> 16) % 150);
  for (const Tone& t : tones)
    if (contains(name, t.word)) {
      // Names of one kind (Wall1, Wall2) differ by a shade, so variants stay visible.
      const int shade = static_cast<int>((h >> 24) % 5) * 12 - 24;
      r = t.r + shade, g = t.g + shade, b = t.b + shade;
      break;
    }
  const auto byte = [](int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); };
  return {byte(r), byte(g), byte(b), 255, 0};
}

Result<Derivation> derive(const Grammar& g, const DeriveOptions& options) { return Deriver(g, options).run(); }

}  // namespace nut::grammar
