// OBJ + MTL reading (scene/obj.hpp): one pass over the text with std::from_chars (doubles,
// locale-free), objects split at `o` / `g`, materials from `mtllib` files.
#include <scene/obj.hpp>

#include <nut/png_io.hpp>
#include <nut/polygon.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <string_view>

#include <glm/common.hpp>

namespace nut::scene {

namespace {

namespace fs = std::filesystem;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Splits text into lines and lines into whitespace-separated tokens.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}
  bool next(std::string_view& token) {
    std::size_t i = 0;
    while (i < rest_.size() && isSpace(rest_[i])) ++i;
    std::size_t j = i;
    while (j < rest_.size() && !isSpace(rest_[j])) ++j;
    token = rest_.substr(i, j - i);
    rest_.remove_prefix(j);
    return !token.empty();
  }
  // The rest of the line without surrounding blanks (names may contain spaces).
  std::string_view rest() const {
    std::string_view r = rest_;
    while (!r.empty() && isSpace(r.front())) r.remove_prefix(1);
    while (!r.empty() && isSpace(r.back())) r.remove_suffix(1);
    return r;
  }

 private:
  std::string_view rest_;
};

// A number as exporters write it: from_chars does not take a leading '+'. A number beyond the
// range of a double is read as a double would hold it: too large ("1e999") as infinity, so that it
// is refused as non-finite rather than as no number; too small ("1e-999") as zero.
bool parseDouble(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (end != token.data() + token.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    const std::size_t e = token.find_first_of("eE");
    const bool tiny = e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
    const bool negative = token.front() == '-';
    value = tiny ? 0.0 : negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    return true;
  }
  return ec == std::errc();
}

bool parseInt(std::string_view token, long long& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

std::uint8_t unitToByte(double v) {
  if (!(v > 0)) return 0;  // also NaN
  return static_cast<std::uint8_t>(std::lround(255.0 * std::min(v, 1.0)));
}

// Calls f(lineNumber, line) for every line of text.
template <typename F>
void forEachLine(const std::string& text, F&& f) {
  std::size_t start = 0;
  long long number = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    f(++number, std::string_view(text).substr(start, end - start));
    start = end + 1;
  }
}

struct MaterialTable {
  std::vector<Material> materials;
  std::vector<std::string> names;
  std::map<std::string, std::uint16_t, std::less<>> byName;
  int defaultIndex = -1;
  bool overflowed = false;  // a material past kMaxMeshMaterials was defined

  std::uint16_t add(const std::string& name, const Material& m) {
    if (auto it = byName.find(name); it != byName.end()) {
      materials[it->second] = m;  // a later definition wins, as in most viewers
      return it->second;
    }
    if (materials.size() == kMaxMeshMaterials) {
      overflowed = true;
      return 0;
    }
    materials.push_back(m);
    names.push_back(name);
    return byName[name] = static_cast<std::uint16_t>(materials.size() - 1);
  }
  std::uint16_t fallback() {
    if (defaultIndex < 0) defaultIndex = add("default", kDefaultMaterial);
    return static_cast<std::uint16_t>(defaultIndex);
  }
};

void readMtl(const fs::path& path, const MtlReader& readText, MaterialTable& table,
             std::vector<std::string>& warnings) {
  auto text = readText(path.string());
  if (!text) {
    warnings.push_back(text.error().message + "; its materials use the default grey");
    return;
  }
  std::string current;
  Material material = kDefaultMaterial;
  bool open = false;
  const auto flush = [&] {
    if (open) table.add(current, material);
  };
  forEachLine(*text, [&](long long line, std::string_view l) {
    Tokens t(l);
    std::string_view key;
    if (!t.next(key) || key.front() == '#') return;
    const auto warn = [&](const char* what) {
      warnings.push_back(path.string() + ":" + std::to_string(line) + ": " + what);
    };
    if (key == "newmtl") {
      flush();
      current = std::string(t.rest());
      material = kDefaultMaterial;
      open = true;
    } else if (key == "Kd" && open) {
      std::array<double, 3> kd{};
      std::string_view token;
      for (double& c : kd)
        if (!t.next(token) || !parseDouble(token, c) || !std::isfinite(c))
          return warn("Kd is not three numbers; ignored");
      material.r = unitToByte(kd[0]);
      material.g = unitToByte(kd[1]);
      material.b = unitToByte(kd[2]);
    } else if ((key == "d" || key == "Tr") && open) {
      std::string_view token;
      double v = 1;
      if (!t.next(token) || !parseDouble(token, v) || !std::isfinite(v))
        return warn("opacity is not a number; ignored");
      material.opacity = unitToByte(key == "d" ? v : 1.0 - v);
    }
  });
  flush();
}

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// Gives a mesh whose triangles hold file vertex indices its own compact vertex list, in order of
// first use. `slot` (file vertex -> mesh vertex) has an entry per file vertex, all kNoVertex, and
// is left so: one scratch list serves every object, so memory stays linear in the file however
// many objects it has.
void compactVertices(TriangleMesh& mesh, const std::vector<glm::dvec3>& positions, std::vector<std::uint32_t>& slot) {
  std::vector<std::uint32_t> used;  // file vertices, in mesh order
  for (auto& triangle : mesh.triangles)
    for (std::uint32_t& v : triangle) {
      if (slot[v] == kNoVertex) {
        slot[v] = static_cast<std::uint32_t>(used.size());
        used.push_back(v);
        mesh.positions.push_back(positions[v]);
      }
      v = slot[v];
    }
  for (std::uint32_t v : used) slot[v] = kNoVertex;
}

}  // namespace

namespace {

// The three coordinates of a `v` line (vertex `number`, counted from 1); an error otherwise.
std::string readVertex(Tokens& t, std::size_t number, glm::dvec3& p) {
  std::string_view token;
  for (int i = 0; i < 3; ++i) {
    if (!t.next(token))
      return "vertex " + std::to_string(number) + " has " + std::to_string(i) + " coordinates, expected 3";
    double v = 0;
    // from_chars reads "nan" and "inf"; anything else unparsable is not a number at all.
    if (!parseDouble(token, v))
      return "vertex " + std::to_string(number) + " has a coordinate that is not a number: '" + std::string(token) +
             "'";
    if (!std::isfinite(v))
      return "vertex " + std::to_string(number) + " has a non-finite coordinate '" + std::string(token) + "'";
    p[i] = v;
  }
  return {};
}

// The corners of an `f` line as indices of the `vertexCount` vertices read so far (OBJ counts
// from 1, or back from the last with negative indices), a corner that repeats the one before it
// left out; an error otherwise. A corner met again later stays: a face with a hole, joined to its
// outline by a bridge, passes twice through each end of the bridge.
std::string readFaceCorners(Tokens& t, std::size_t vertexCount, std::vector<std::uint32_t>& corners) {
  corners.clear();
  std::string_view token;
  while (t.next(token)) {
    long long index = 0;
    const std::string_view first = token.substr(0, token.find('/'));
    if (!parseInt(first, index) || index == 0) return "face corner '" + std::string(token) + "' is not a vertex index";
    const long long resolved = index < 0 ? static_cast<long long>(vertexCount) + index : index - 1;
    if (resolved < 0 || resolved >= static_cast<long long>(vertexCount))
      return "face refers to vertex " + std::to_string(index) + ", but only " + std::to_string(vertexCount) +
             " vertices precede it";
    const auto v = static_cast<std::uint32_t>(resolved);
    if (corners.empty() || corners.back() != v) corners.push_back(v);
  }
  while (corners.size() > 1 && corners.back() == corners.front()) corners.pop_back();
  return {};
}

// Whether a face has three distinct corners. readFaceCorners leaves no two neighbours equal, so
// three corners are three distinct ones (most faces: no copy).
bool hasThreeCorners(const std::vector<std::uint32_t>& corners) {
  if (corners.size() <= 3) return corners.size() == 3;
  std::vector<std::uint32_t> sorted = corners;
  std::sort(sorted.begin(), sorted.end());
  return std::unique(sorted.begin(), sorted.end()) - sorted.begin() >= 3;
}

}  // namespace

Result<ObjContents> readObj(const std::string& path, const ObjReadOptions& options) {
  auto text = readTextFile(path);
  if (!text) return text.error();
  return readObjText(*text, path, readTextFile, options);
}

Result<ObjContents> readObjText(const std::string& text, const std::string& path, const MtlReader& readMtlText,
                                const ObjReadOptions& options) {
  ObjContents out;
  out.fileBytes = text.size();
  const fs::path folder = fs::path(path).parent_path();

  // Objects split at `o` when the file has any, else at `g`.
  bool hasO = false;
  forEachLine(text, [&](long long, std::string_view l) {
    if (!hasO && l.size() >= 2 && l[0] == 'o' && isSpace(l[1])) hasO = true;
  });
  const char splitKey = hasO ? 'o' : 'g';

  MaterialTable table;
  std::vector<glm::dvec3> positions;
  std::vector<TriangleMesh> objects(1);  // triangles with file vertex indices until the end
  objects[0].name = fs::path(path).stem().string();
  std::map<std::string, std::size_t> objectByName;
  std::size_t current = 0;
  int material = -1;  // -1: none named yet
  long long droppedFaces = 0;
  std::vector<std::uint32_t> corners;
  std::vector<glm::dvec3> cornerPoints;
  std::vector<std::array<std::uint32_t, 3>> faceTriangles;
  std::string error;

  forEachLine(text, [&](long long line, std::string_view l) {
    if (!error.empty()) return;
    Tokens t(l);
    std::string_view key;
    if (!t.next(key) || key.front() == '#') return;
    const auto where = [&] { return path + ":" + std::to_string(line) + ": "; };
    if (key == "v") {
      glm::dvec3 p;
      if (error = readVertex(t, positions.size() + 1, p); !error.empty()) {
        error = where() + error;
        return;
      }
      positions.push_back(options.zUp ? glm::dvec3(p.x, p.z, -p.y) : p);
    } else if (key == "f") {
      if (error = readFaceCorners(t, positions.size(), corners); !error.empty()) {
        error = where() + error;
        return;
      }
      if (!hasThreeCorners(corners)) {
        ++droppedFaces;
        return;
      }
      if (material < 0) material = table.fallback();
      TriangleMesh& object = objects[current];
      cornerPoints.clear();
      for (std::uint32_t c : corners) cornerPoints.push_back(positions[c]);
      triangulatePolygon(cornerPoints, faceTriangles);
      for (const auto& [a, b, c] : faceTriangles) {
        object.triangles.push_back({corners[a], corners[b], corners[c]});
        object.triangleMaterial.push_back(static_cast<std::uint16_t>(material));
      }
    } else if (!options.oneMesh && key.size() == 1 && key.front() == splitKey) {
      std::string name(t.rest());
      if (name.empty()) name = objects[0].name + "_" + std::to_string(objects.size());
      auto [it, inserted] = objectByName.try_emplace(name, objects.size());
      if (inserted) {
        objects.emplace_back();
        objects.back().name = name;
      }
      current = it->second;
    } else if (key == "usemtl") {
      const std::string name(t.rest());
      if (auto it = table.byName.find(name); it != table.byName.end()) {
        material = it->second;
      } else {
        out.warnings.push_back(where() + "material '" + name + "' is not defined; using the default grey");
        material = table.fallback();
      }
    } else if (key == "mtllib") {
      // Names may not contain spaces here: several files on one line are allowed by the format.
      std::string_view token;
      while (t.next(token)) readMtl(folder / std::string(token), readMtlText, table, out.warnings);
    }
  });
  if (!error.empty()) return Error{error};
  if (table.overflowed)
    return Error{path + ": more than " + std::to_string(kMaxMeshMaterials) + " materials (the limit of a mesh)"};
  if (droppedFaces > 0)
    out.warnings.push_back(path + ": " + std::to_string(droppedFaces) +
                           " faces with fewer than 3 distinct vertices dropped");

  std::vector<std::uint32_t> slot(options.oneMesh ? 0 : positions.size(), kNoVertex);
  for (TriangleMesh& object : objects) {
    if (object.triangles.empty()) continue;
    if (!options.oneMesh) compactVertices(object, positions, slot);
    object.materials = table.materials;
    object.materialNames = table.names;
    out.objects.push_back(std::move(object));
  }
  if (out.objects.empty())
    return Error{path + ": no faces (the file has " + std::to_string(positions.size()) + " vertices)"};
  if (options.oneMesh) out.objects.front().positions = std::move(positions);  // indices as in the file
  return out;
}

Result<TriangleMesh> readObjMesh(const std::string& path, std::vector<std::string>& warnings) {
  auto contents = readObj(path, {.oneMesh = true});
  if (!contents) return contents.error();
  warnings.insert(warnings.end(), contents->warnings.begin(), contents->warnings.end());
  return std::move(contents->objects.front());
}

}  // namespace nut::scene
