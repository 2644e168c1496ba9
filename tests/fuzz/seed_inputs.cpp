// The fuzz targets' generated seeds (seed_inputs.hpp).
#include "seed_inputs.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>

#include "../random_hierarchy.hpp"
#include "frame.hpp"
#include "obj_input.hpp"

namespace nut::fuzz {

namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = NUT_SOURCE_DIR;

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The regular files of a folder, sorted by name (the corpus test runs them in a fixed order).
std::vector<fs::path> filesIn(const fs::path& folder) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) return files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

Result<std::vector<SeedInput>> hniSeeds() {
  std::vector<SeedInput> seeds;
  for (std::uint64_t seed = 0; seed < 32; ++seed) {
    auto image = compile(testing::randomHierarchy(seed));
    if (!image) return Error{"random hierarchy " + std::to_string(seed) + ": " + image.error().message};
    seeds.push_back({"random" + std::to_string(seed), frame(*image)});
  }
  // Version 3 files: half the solid cells plane cells.
  testing::RandomHierarchyOptions planes;
  planes.planeCellShare = 0.5;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    auto image = compile(testing::randomHierarchy(seed, planes));
    if (!image) return Error{"random hierarchy with plane cells " + std::to_string(seed) + ": " + image.error().message};
    seeds.push_back({"planes" + std::to_string(seed), frame(*image)});
  }
  for (const fs::path& path : filesIn(kSourceDir / "samples/hni")) {
    auto png = readPng(path.string());
    if (!png) return png.error();
    seeds.push_back({path.stem().string(), frame(png->image)});
  }
  return seeds;
}

std::vector<SeedInput> objSeeds() {
  std::vector<SeedInput> seeds;
  for (const char* folder : {"samples/obj", "tests/data"})
    for (const fs::path& path : filesIn(kSourceDir / folder)) {
      if (path.extension() != ".obj") continue;
      const fs::path mtl = fs::path(path).replace_extension(".mtl");
      const std::string obj = fileText(path);
      seeds.push_back({path.stem().string(), bytesOf(fs::exists(mtl) ? joinObjInput(obj, fileText(mtl)) : obj)});
    }
  return seeds;
}

std::vector<SeedInput> glbSeeds() {
  std::vector<SeedInput> seeds;
  for (const fs::path& path : filesIn(kSourceDir / "tests/data"))
    if (path.extension() == ".glb") seeds.push_back({path.filename().string(), bytesOf(fileText(path))});
  return seeds;
}

std::vector<SeedInput> citySeeds() {
  scene::CityManifest city{"street", {}};
  city.buildings.push_back({"house", "house.png", "house.complement.obj", {12.5, 0, -3.25}, 90});
  city.buildings.push_back({"tower 2", "towers/tower_2.png", "", {1234567.125, 10, 7654321.5}, -33.75});
  std::vector<SeedInput> seeds{{"writer", bytesOf(scene::cityJson(city))}};
  city.buildings.clear();
  seeds.push_back({"writer-empty", bytesOf(scene::cityJson(city))});
  return seeds;
}

std::vector<SeedInput> grammarSeeds() {
  std::vector<SeedInput> seeds;
  for (const fs::path& path : filesIn(kSourceDir / "samples/grammars"))
    if (path.extension() == ".grammar") seeds.push_back({path.stem().string(), bytesOf(fileText(path))});
  return seeds;
}

std::vector<SeedInput> committedInputs(const std::string& folder) {
  std::vector<SeedInput> inputs;
  for (const fs::path& path : filesIn(kSourceDir / "tests/fuzz" / folder))
    if (path.filename() != "README.md") inputs.push_back({path.filename().string(), bytesOf(fileText(path))});
  return inputs;
}

}  // namespace nut::fuzz
