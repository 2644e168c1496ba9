// OBJ + MTL reading through tinyobjloader, into the triangle mesh the reference renderer draws.
//
// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "1.0x") as 0 without a word, so a
// broken vertex would move silently to the origin. A first pass over the `v` lines therefore checks
// every coordinate itself and reports the line; tinyobjloader then parses the same text.
#include <meshref/obj.hpp>

#include <nut/png_io.hpp>
#include <nut/polygon.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include <glm/common.hpp>

#include <tiny_obj_loader.h>

namespace nut::meshref {

namespace {

// Separates tokens; '\r' too, so that files with CRLF line ends read the same.
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Checks the first three coordinates of every `v` line: each must be a finite number.
Status checkVertexLines(const std::string& path, const std::string& text) {
  std::size_t lineStart = 0;
  long long line = 0, vertex = 0;
  while (lineStart < text.size()) {
    std::size_t lineEnd = text.find('\n', lineStart);
    if (lineEnd == std::string::npos) lineEnd = text.size();
    ++line;
    const char* p = text.data() + lineStart;
    const char* end = text.data() + lineEnd;
    lineStart = lineEnd + 1;
    while (p < end && isSpace(*p)) ++p;
    if (end - p < 2 || p[0] != 'v' || (p[1] != ' ' && p[1] != '\t')) continue;  // not a position (vn, vt, f, ...)
    ++vertex;
    p += 1;
    const std::string where = path + ":" + std::to_string(line) + ": vertex " + std::to_string(vertex);
    for (int i = 0; i < 3; ++i) {
      while (p < end && isSpace(*p)) ++p;
      const char* tokenEnd = p;
      while (tokenEnd < end && !isSpace(*tokenEnd)) ++tokenEnd;
      if (p == tokenEnd) return Error{where + " has " + std::to_string(i) + " coordinates, expected 3"};
      const std::string token(p, tokenEnd);
      // from_chars does not take a leading '+', which some exporters write.
      const char* number = (*p == '+') ? p + 1 : p;
      double value = 0;
      const auto [stop, ec] = std::from_chars(number, tokenEnd, value);
      if (ec == std::errc::result_out_of_range || (ec == std::errc() && stop == tokenEnd && !std::isfinite(value)))
        return Error{where + " has a non-finite coordinate '" + token + "'"};
      if (ec != std::errc() || stop != tokenEnd) return Error{where + " has a coordinate that is not a number: '" + token + "'"};
      p = tokenEnd;
    }
  }
  return Ok{};
}

std::uint8_t unitToByte(double v) {
  if (!(v > 0)) return 0;  // also NaN
  return static_cast<std::uint8_t>(std::lround(255.0 * std::min(v, 1.0)));
}

// tinyobjloader's warnings are lines ending in '\n'; each becomes "<file>: <line>".
void addWarnings(const std::string& path, const std::string& text, std::vector<std::string>& out) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) out.push_back(path + ": " + line);
}

}  // namespace

Result<TriangleMesh> readObj(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{path + ": is a directory, not an OBJ file"};
  auto read = readTextFile(path);
  if (!read) return read.error();
  const std::string& text = *read;
  if (Status s = checkVertexLines(path, text); !s) return s.error();

  // MTL files are looked up beside the OBJ file.
  std::string baseDir = std::filesystem::path(path).parent_path().string();
  if (baseDir.empty()) baseDir = ".";
  tinyobj::MaterialFileReader materialReader(baseDir);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> objMaterials;
  std::string warnings, errors;
  std::istringstream stream(std::move(text));
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &objMaterials, &warnings, &errors, &stream, &materialReader,
                                       /*triangulate=*/false, /*default_vcols_fallback=*/false);
  TriangleMesh mesh;
  addWarnings(path, warnings, mesh.warnings);
  if (!parsed || !errors.empty()) {
    const std::string first = errors.substr(0, errors.find('\n'));
    return Error{path + ": " + (first.empty() ? std::string("cannot parse") : first)};
  }

  const std::size_t vertexCount = attrib.vertices.size() / 3;
  mesh.positions.reserve(vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v)
    mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);

  for (const tinyobj::material_t& m : objMaterials) {
    Material material;
    material.r = unitToByte(m.diffuse[0]);
    material.g = unitToByte(m.diffuse[1]);
    material.b = unitToByte(m.diffuse[2]);
    material.opacity = unitToByte(m.dissolve);
    mesh.materials.push_back({m.name, material});
  }
  // Faces without a (known) material share one default entry, added only when needed.
  std::uint32_t defaultMaterial = std::numeric_limits<std::uint32_t>::max();

  std::vector<bool> used(vertexCount, false);
  std::vector<std::uint32_t> corners;
  std::vector<glm::dvec3> cornerPoints;
  std::vector<std::array<std::uint32_t, 3>> faceTriangles;
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t first = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      corners.clear();
      for (std::size_t k = 0; k < n; ++k) {
        const int index = shape.mesh.indices[first + k].vertex_index;
        if (index < 0 || static_cast<std::size_t>(index) >= vertexCount)
          return Error{path + ": a face of '" + shape.name + "' refers to vertex " + std::to_string(index + 1) +
                       ", but the file has " + std::to_string(vertexCount) + " vertices"};
        // A corner that repeats the one before it is left out, as the converter's reader does.
        if (corners.empty() || corners.back() != static_cast<std::uint32_t>(index))
          corners.push_back(static_cast<std::uint32_t>(index));
        used[static_cast<std::size_t>(index)] = true;
      }
      while (corners.size() > 1 && corners.back() == corners.front()) corners.pop_back();
      first += n;
      if (corners.size() < 3) continue;
      const int id = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      std::uint32_t material = 0;
      if (id >= 0 && static_cast<std::size_t>(id) < objMaterials.size()) {
        material = static_cast<std::uint32_t>(id);
      } else {
        if (defaultMaterial == std::numeric_limits<std::uint32_t>::max()) {
          defaultMaterial = static_cast<std::uint32_t>(mesh.materials.size());
          mesh.materials.push_back({"default", kDefaultMeshMaterial});
        }
        material = defaultMaterial;
      }
      // Non-convex faces too (an L-shaped floor), as the converter reads them (nut/polygon.hpp).
      cornerPoints.clear();
      for (std::uint32_t c : corners) cornerPoints.push_back(mesh.positions[c]);
      triangulatePolygon(cornerPoints, faceTriangles);
      for (const auto& [a, b, c] : faceTriangles) {
        mesh.triangles.push_back({corners[a], corners[b], corners[c]});
        mesh.triangleMaterial.push_back(material);
      }
    }
  }
  if (mesh.triangles.empty()) return Error{path + ": no faces (the file has " + std::to_string(vertexCount) + " vertices)"};

  mesh.bounds.min = glm::dvec3(std::numeric_limits<double>::infinity());
  mesh.bounds.max = -mesh.bounds.min;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (!used[v]) continue;
    mesh.bounds.min = glm::min(mesh.bounds.min, mesh.positions[v]);
    mesh.bounds.max = glm::max(mesh.bounds.max, mesh.positions[v]);
  }
  return mesh;
}

}  // namespace nut::meshref
