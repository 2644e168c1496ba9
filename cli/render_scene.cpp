// Loading what `nut render` draws (render_scene.hpp).
#include "render_scene.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <glm/common.hpp>

#include <converter/city.hpp>
#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

void include(WorldBox& bounds, const glm::dvec3& p) {
  bounds.min = glm::min(bounds.min, p);
  bounds.max = glm::max(bounds.max, p);
}

// Reads, checks and places one HNI; `where` names it in errors (the file, or the manifest's
// building). The manifest's position is the one used; the file's own origin is the same when the
// converter wrote both (docs/CITY.md). A file placed several times is read once: its instances
// share the image (and the ray caster, meshref::SceneRenderer).
int addHni(RenderScene& scene, const std::string& path, const std::string& where, const glm::dvec3* positionM,
           double yawDeg) {
  const std::string key = std::filesystem::absolute(path).lexically_normal().string();
  auto loaded = scene.loaded.find(key);
  if (loaded == scene.loaded.end()) {
    auto png = readPng(path);
    if (!png) return fail(png.error().message, kUnreadable);
    if (Status s = validate(png->image); !s) return fail(where + ": invalid HNI: " + s.error().message, kInvalid);
    const glm::dvec3 origin = positionM ? *positionM : png->text.originM;
    auto hierarchy = decode(png->image);
    auto content = hierarchy ? contentBounds(*hierarchy, origin) : Result<WorldBox>(hierarchy.error());
    if (!content) return fail(where + ": " + content.error().message, kInvalid);
    scene.files.push_back(std::move(*png));
    const RenderScene::LoadedHni file{scene.files.size() - 1, {content->min - origin, content->max - origin}};
    loaded = scene.loaded.emplace(key, file).first;
  }
  const std::size_t index = loaded->second.file;
  const glm::dvec3 origin = positionM ? *positionM : scene.files[index].text.originM;
  const WorldBox& content = loaded->second.contentFromOrigin;
  const glm::dmat3 turn = meshref::yawRotation(yawDeg);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner(c & 1 ? content.max.x : content.min.x, c & 2 ? content.max.y : content.min.y,
                            c & 4 ? content.max.z : content.min.z);
    include(scene.bounds, origin + turn * corner);
  }
  scene.hniFiles.push_back(index);
  scene.hnis.push_back({nullptr, origin, turn});
  return kOk;
}

int addMesh(RenderScene& scene, const std::string& path) {
  auto mesh = meshref::readObj(path);
  if (!mesh) return fail(mesh.error().message, kInvalid);
  for (const std::string& warning : mesh->warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  include(scene.bounds, mesh->bounds.min);
  include(scene.bounds, mesh->bounds.max);
  scene.meshes.push_back(std::move(*mesh));
  return kOk;
}

bool isManifest(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".json";
}

}  // namespace

std::vector<const meshref::TriangleMesh*> RenderScene::meshPointers() const {
  std::vector<const meshref::TriangleMesh*> out;
  for (const meshref::TriangleMesh& m : meshes) out.push_back(&m);
  return out;
}

int loadRenderScene(const std::string& input, const std::vector<std::string>& meshPaths, RenderScene& scene) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  scene.bounds = {glm::dvec3(kInfinity), glm::dvec3(-kInfinity)};
  if (isManifest(input)) {
    auto city = converter::readCityJson(input);
    if (!city) return fail(city.error().message, kInvalid);
    if (city->buildings.empty()) return fail(input + ": the manifest lists no buildings", kInvalid);
    const std::filesystem::path folder = std::filesystem::path(input).parent_path();
    for (std::size_t i = 0; i < city->buildings.size(); ++i) {
      const converter::CityBuilding& b = city->buildings[i];
      const std::string where = input + ": building " + std::to_string(i) + " (" + b.name + ")";
      if (int code = addHni(scene, (folder / b.hni).string(), where, &b.positionM, b.yawDeg); code != kOk) return code;
      if (!b.complement.empty())
        if (int code = addMesh(scene, (folder / b.complement).string()); code != kOk) return code;
    }
  } else if (int code = addHni(scene, input, input, nullptr, 0.0); code != kOk) {
    return code;
  }
  for (const std::string& path : meshPaths)
    if (int code = addMesh(scene, path); code != kOk) return code;
  for (std::size_t i = 0; i < scene.hnis.size(); ++i) scene.hnis[i].image = &scene.files[scene.hniFiles[i]].image;
  return kOk;
}

}  // namespace nut::cli
