// Loading a scene (scene/scene.hpp).
#include <scene/scene.hpp>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>

#include <glm/common.hpp>

#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <scene/city.hpp>
#include <scene/mesh_file.hpp>

namespace nut::scene {

glm::dmat3 yawRotation(double degrees) {
  const double r = degrees * std::numbers::pi / 180;
  const double c = std::cos(r), s = std::sin(r);
  return glm::dmat3(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));  // columns
}

std::vector<const TriangleMesh*> Scene::meshPointers() const {
  std::vector<const TriangleMesh*> out;
  for (const TriangleMesh& m : meshes) out.push_back(&m);
  return out;
}

double meshLevelErrorAllowedM(const WorldBox& box, const Camera& camera) {
  const double pixelAngle = 2.0 * std::tan(0.5 * camera.fovYDeg * std::numbers::pi / 180.0) / camera.height;
  const double distance = glm::length(camera.eye - glm::clamp(camera.eye, box.min, box.max));
  return kMeshLevelErrorPx * distance * pixelAngle;
}

std::vector<const TriangleMesh*> Scene::meshPointers(const Camera& camera) const {
  std::vector<const TriangleMesh*> out;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const std::size_t level = meshLevel(coarser[i], meshes[i].bounds(), camera);
    out.push_back(level == 0 ? &meshes[i] : &coarser[i][level - 1].mesh);
  }
  return out;
}

namespace {

void include(WorldBox& bounds, const glm::dvec3& p) {
  bounds.min = glm::min(bounds.min, p);
  bounds.max = glm::max(bounds.max, p);
}

bool isManifest(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".json";
}

class Loader {
 public:
  explicit Loader(LoadFailure* failure) : failure_(failure) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    scene_.bounds = {glm::dvec3(kInfinity), glm::dvec3(-kInfinity)};
  }

  // Reads, checks and places one HNI; `where` names it in errors (the file, or the manifest's
  // building). The manifest's position is the one used; the file's own origin is the same when the
  // converter wrote both (docs/CITY.md).
  Status addHni(const std::string& path, const std::string& where, const glm::dvec3* positionM, double yawDeg) {
    const std::string key = std::filesystem::absolute(path).lexically_normal().string();
    auto loaded = loaded_.find(key);
    if (loaded == loaded_.end()) {
      auto png = readPng(path);
      if (!png) return fail(png.error().message, LoadFailure::unreadable);
      if (Status s = validate(png->image); !s) return fail(where + ": invalid HNI: " + s.error().message);
      const glm::dvec3 origin = positionM ? *positionM : png->text.originM;
      auto hierarchy = decode(png->image);
      auto content = hierarchy ? contentBounds(*hierarchy, origin) : Result<WorldBox>(hierarchy.error());
      if (!content) return fail(where + ": " + content.error().message);
      scene_.files.push_back(std::move(*png));
      const LoadedHni file{scene_.files.size() - 1, {content->min - origin, content->max - origin}};
      loaded = loaded_.emplace(key, file).first;
    }
    const std::size_t index = loaded->second.file;
    const glm::dvec3 origin = positionM ? *positionM : scene_.files[index].text.originM;
    const WorldBox& content = loaded->second.contentFromOrigin;
    const glm::dmat3 turn = yawRotation(yawDeg);
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner(c & 1 ? content.max.x : content.min.x, c & 2 ? content.max.y : content.min.y,
                              c & 4 ? content.max.z : content.min.z);
      include(scene_.bounds, origin + turn * corner);
    }
    hniFiles_.push_back(index);
    scene_.hnis.push_back({nullptr, origin, turn});
    return Ok{};
  }

  // A mesh and its coarser levels (files and errors, finest first).
  Status addMesh(const std::string& path, const std::vector<std::pair<std::string, double>>& levels = {}) {
    auto mesh = readMeshFile(path, scene_.warnings);
    if (!mesh) return fail(mesh.error().message);
    const WorldBox box = mesh->bounds();
    include(scene_.bounds, box.min);
    include(scene_.bounds, box.max);
    std::vector<CoarserMesh> coarser;
    for (const auto& [levelPath, errorM] : levels) {
      auto level = readMeshFile(levelPath, scene_.warnings);
      if (!level) return fail(level.error().message);
      coarser.push_back({std::move(*level), errorM});
    }
    scene_.meshes.push_back(std::move(*mesh));
    scene_.coarser.push_back(std::move(coarser));
    return Ok{};
  }

  // The scene, its HNIs pointing at their images (which stay where they are when it moves).
  Scene finish() {
    for (std::size_t i = 0; i < scene_.hnis.size(); ++i) scene_.hnis[i].image = &scene_.files[hniFiles_[i]].image;
    return std::move(scene_);
  }

  Error fail(std::string message, LoadFailure kind = LoadFailure::invalid) {
    if (failure_) *failure_ = kind;
    return Error{std::move(message)};
  }

 private:
  struct LoadedHni {
    std::size_t file;
    WorldBox contentFromOrigin;  // its solid content relative to its root's origin, unturned
  };
  Scene scene_;
  std::vector<std::size_t> hniFiles_;       // per placed HNI, its file
  std::map<std::string, LoadedHni> loaded_;  // by absolute path
  LoadFailure* failure_;
};

}  // namespace

Result<Scene> loadScene(const std::string& input, const std::vector<std::string>& meshPaths, LoadFailure* failure) {
  Loader loader(failure);
  if (isManifest(input)) {
    auto city = readCityJson(input);
    if (!city) return loader.fail(city.error().message);
    if (city->buildings.empty()) return loader.fail(input + ": the manifest lists no buildings");
    const std::filesystem::path folder = std::filesystem::path(input).parent_path();
    for (std::size_t i = 0; i < city->buildings.size(); ++i) {
      const CityBuilding& b = city->buildings[i];
      const std::string where = input + ": building " + std::to_string(i) + " (" + b.name + ")";
      if (Status s = loader.addHni((folder / b.hni).string(), where, &b.positionM, b.yawDeg); !s) return s.error();
      std::vector<std::pair<std::string, double>> levels;
      for (const ComplementLevel& level : b.complementLevels)
        levels.emplace_back((folder / level.path).string(), level.errorM);
      if (!b.complement.empty())
        if (Status s = loader.addMesh((folder / b.complement).string(), levels); !s) return s.error();
    }
  } else if (Status s = loader.addHni(input, input, nullptr, 0.0); !s) {
    return s.error();
  }
  for (const std::string& path : meshPaths)
    if (Status s = loader.addMesh(path); !s) return s.error();
  return loader.finish();
}

}  // namespace nut::scene
