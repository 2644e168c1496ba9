// scene/city.hpp — the city manifest `city.json`: which HNIs make up a street or district and
// where each one stands (docs/CITY.md has the JSON schema). `nut convert` writes one when an OBJ
// holding several objects is converted into a folder; the streaming viewer reads it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>

namespace nut::scene {

// A coarser level of a building's complementary mesh (converter/mesh_lod.hpp): the file, and the
// largest distance from the complement's surface to this level's.
struct ComplementLevel {
  std::string path;  // relative to the manifest's folder
  double errorM = 0;
};

struct CityBuilding {
  std::string name;
  std::string hni;          // path relative to the manifest's folder
  std::string complement;   // OBJ relative to the manifest's folder; empty if none
  glm::dvec3 positionM{0.0};  // world position of the HNI's root block origin (double precision)
  double yawDeg = 0;        // rotation about +y (counter-clockwise seen from above), degrees
  // World box of the placed HNI's root block, when the writer knows it: a viewer culls and draws
  // a proxy for the building before its image arrives.
  std::optional<WorldBox> boundsM;
  std::vector<ComplementLevel> complementLevels;  // finest first, errors increasing; needs a complement
};

struct CityManifest {
  std::string name;
  std::vector<CityBuilding> buildings;
};

// The manifest as JSON text (version 1), positions with 17 significant digits.
std::string cityJson(const CityManifest& city);

// Writes cityJson(city) to `path` whole (a temporary sibling, then renamed into place).
Status writeCityJson(const std::string& path, const CityManifest& city);

// Reads and checks a manifest: version, required fields, types, finite numbers, relative paths
// that stay inside the manifest's folder. Errors name the file and the building.
Result<CityManifest> readCityJson(const std::string& path);

// readCityJson on a manifest already in memory; `path` names it in errors.
Result<CityManifest> parseCityJson(const std::string& text, const std::string& path);

// A file name for an object name: letters, digits, '-', '_' and '.' kept, anything else '_',
// never empty, never starting with '.'.
std::string safeFileStem(const std::string& name);

}  // namespace nut::scene
