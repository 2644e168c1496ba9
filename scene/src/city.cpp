// The city manifest (scene/city.hpp, docs/CITY.md).
#include <scene/city.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <nut/png_io.hpp>

namespace nut::scene {

namespace {

constexpr int kCityVersion = 1;

// A relative path that does not climb out of the manifest's folder.
bool staysInside(const std::string& path) {
  const std::filesystem::path p(path);
  if (p.empty() || p.is_absolute() || p.has_root_name()) return false;
  int depth = 0;
  for (const auto& part : p.lexically_normal()) {
    if (part == "..") --depth;
    else if (part != ".") ++depth;
    if (depth < 0) return false;
  }
  return depth > 0;
}

}  // namespace

std::string safeFileStem(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    out += keep ? c : '_';
  }
  if (out.empty() || out.front() == '.') out.insert(out.begin(), '_');
  return out;
}

std::string cityJson(const CityManifest& city) {
  nlohmann::json buildings = nlohmann::json::array();
  for (const CityBuilding& b : city.buildings) {
    nlohmann::json j = {{"name", b.name},
                        {"hni", b.hni},
                        {"position_m", {b.positionM.x, b.positionM.y, b.positionM.z}},
                        {"yaw_deg", b.yawDeg}};
    if (!b.complement.empty()) j["complement"] = b.complement;
    if (!b.complementLevels.empty()) {
      nlohmann::json levels = nlohmann::json::array();
      for (const ComplementLevel& level : b.complementLevels)
        levels.push_back({{"path", level.path}, {"error_m", level.errorM}});
      j["complement_levels"] = std::move(levels);
    }
    if (b.boundsM)
      j["bounds_m"] = {{b.boundsM->min.x, b.boundsM->min.y, b.boundsM->min.z},
                       {b.boundsM->max.x, b.boundsM->max.y, b.boundsM->max.z}};
    buildings.push_back(std::move(j));
  }
  const nlohmann::json j = {{"format", "nut-city"}, {"version", kCityVersion}, {"name", city.name}, {"units", "m"},
                            {"up", "y"}, {"buildings", buildings}};
  return j.dump(2) + "\n";
}

Status writeCityJson(const std::string& path, const CityManifest& city) { return writeTextFile(path, cityJson(city)); }

Result<CityManifest> readCityJson(const std::string& path) {
  std::ifstream file(path);
  if (!file) return Error{path + ": cannot open"};
  std::stringstream text;
  text << file.rdbuf();
  return parseCityJson(text.str(), path);
}

Result<CityManifest> parseCityJson(const std::string& text, const std::string& path) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) return Error{path + ": not valid JSON"};
  // A value's type is checked, or the value compared, before it is read: nlohmann's value() and
  // get() throw on a wrong type, and get<int>() wraps an integer beyond int's range.
  if (!j.is_object() || !j.contains("format") || j["format"] != "nut-city")
    return Error{path + ": not a nut city manifest (\"format\": \"nut-city\")"};
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"] != kCityVersion)
    return Error{path + ": unsupported version (this reader knows version " + std::to_string(kCityVersion) + ")"};
  if (!j.contains("buildings") || !j["buildings"].is_array()) return Error{path + ": \"buildings\" must be an array"};
  if (j.contains("name") && !j["name"].is_string()) return Error{path + ": \"name\" must be a string"};
  CityManifest city;
  city.name = j.value("name", "");
  int index = 0;
  for (const nlohmann::json& b : j["buildings"]) {
    const std::string where = path + ": building " + std::to_string(index++);
    if (!b.is_object()) return Error{where + ": not an object"};
    CityBuilding out;
    if (!b.contains("name") || !b["name"].is_string()) return Error{where + ": \"name\" must be a string"};
    out.name = b["name"].get<std::string>();
    if (!b.contains("hni") || !b["hni"].is_string() || !staysInside(b["hni"].get<std::string>()))
      return Error{where + " (" + out.name + "): \"hni\" must be a relative path inside the manifest's folder"};
    out.hni = b["hni"].get<std::string>();
    if (b.contains("complement")) {
      if (!b["complement"].is_string() || !staysInside(b["complement"].get<std::string>()))
        return Error{where + " (" + out.name + "): \"complement\" must be a relative path inside the manifest's folder"};
      out.complement = b["complement"].get<std::string>();
    }
    if (b.contains("complement_levels")) {
      const std::string levelsError = where + " (" + out.name +
                                      "): \"complement_levels\" must be objects with a \"path\" inside the "
                                      "manifest's folder and an \"error_m\" of at least 0, increasing, beside a "
                                      "\"complement\"";
      const nlohmann::json& levels = b["complement_levels"];
      if (!levels.is_array() || out.complement.empty()) return Error{levelsError};
      for (const nlohmann::json& level : levels) {
        if (!level.is_object() || !level.contains("path") || !level["path"].is_string() ||
            !staysInside(level["path"].get<std::string>()) || !level.contains("error_m") ||
            !level["error_m"].is_number() || !std::isfinite(level["error_m"].get<double>()))
          return Error{levelsError};
        const double error = level["error_m"].get<double>();
        if (error < 0 || (!out.complementLevels.empty() && error < out.complementLevels.back().errorM))
          return Error{levelsError};
        out.complementLevels.push_back({level["path"].get<std::string>(), error});
      }
    }
    if (!b.contains("position_m") || !b["position_m"].is_array() || b["position_m"].size() != 3)
      return Error{where + " (" + out.name + "): \"position_m\" must be three numbers"};
    for (int a = 0; a < 3; ++a) {
      const nlohmann::json& v = b["position_m"][static_cast<std::size_t>(a)];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        return Error{where + " (" + out.name + "): \"position_m\" must be three finite numbers"};
      out.positionM[a] = v.get<double>();
    }
    if (b.contains("yaw_deg")) {
      if (!b["yaw_deg"].is_number() || !std::isfinite(b["yaw_deg"].get<double>()))
        return Error{where + " (" + out.name + "): \"yaw_deg\" must be a finite number"};
      out.yawDeg = b["yaw_deg"].get<double>();
    }
    if (b.contains("bounds_m")) {
      const nlohmann::json& box = b["bounds_m"];
      const auto corner = [](const nlohmann::json& c, glm::dvec3& point) {
        if (!c.is_array() || c.size() != 3) return false;
        for (int a = 0; a < 3; ++a) {
          const nlohmann::json& v = c[static_cast<std::size_t>(a)];
          if (!v.is_number() || !std::isfinite(v.get<double>())) return false;
          point[a] = v.get<double>();
        }
        return true;
      };
      WorldBox bounds;
      if (!box.is_array() || box.size() != 2 || !corner(box[0], bounds.min) || !corner(box[1], bounds.max) ||
          !(bounds.min.x <= bounds.max.x && bounds.min.y <= bounds.max.y && bounds.min.z <= bounds.max.z))
        return Error{where + " (" + out.name + "): \"bounds_m\" must be two corners of three finite numbers, min <= max"};
      out.boundsM = bounds;
    }
    city.buildings.push_back(std::move(out));
  }
  return city;
}

}  // namespace nut::scene
