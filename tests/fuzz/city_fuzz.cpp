// Fuzz target city_fuzz: arbitrary bytes as a city.json must never crash the manifest reader; an
// error names the file, and an accepted manifest's every path stays inside its folder (checked
// here independently: joined to a folder and normalised, it still lies below that folder) and its
// every number is finite.
#include <cmath>
#include <filesystem>
#include <string>

#include <scene/city.hpp>

#include "require.hpp"
#include "targets.hpp"

namespace nut::fuzz {

namespace {

bool staysBelowFolder(const std::string& relative) {
  const std::filesystem::path folder = "/manifest-folder";
  const std::string normal = (folder / relative).lexically_normal().string();
  const std::string prefix = folder.string() + "/";
  return normal.size() > prefix.size() && normal.rfind(prefix, 0) == 0;
}

}  // namespace

int cityInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = "fuzz/city.json";
  auto city = scene::parseCityJson(std::string(reinterpret_cast<const char*>(data), size), path);
  if (!city) {
    NUT_FUZZ_REQUIRE(city.error().message.rfind(path, 0) == 0);
    return 0;
  }
  for (const scene::CityBuilding& b : city->buildings) {
    NUT_FUZZ_REQUIRE(staysBelowFolder(b.hni));
    NUT_FUZZ_REQUIRE(b.complement.empty() || staysBelowFolder(b.complement));
    for (int a = 0; a < 3; ++a) NUT_FUZZ_REQUIRE(std::isfinite(b.positionM[a]));
    NUT_FUZZ_REQUIRE(std::isfinite(b.yawDeg));
  }
  return 0;
}

}  // namespace nut::fuzz
