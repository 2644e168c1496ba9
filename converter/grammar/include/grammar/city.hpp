// grammar/city.hpp — cities of distinct buildings (`nut city`, docs/CITY.md): which source (a
// building grammar, or a converted sample) each building comes from, with which seed and size, on
// which lot of which street it stands, and a grammar's building compiled and placed there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <grammar/compile.hpp>
#include <grammar/grammar.hpp>
#include <nut/camera.hpp>
#include <nut/error.hpp>

namespace nut::grammar {

// A building of the plan: source `source` (a grammar derived with `seed` from a start scope of
// `sizeM`, or a sample stretched to `sizeM`), centred on its lot and turned by yawDeg (0 or 180:
// its front towards its street).
struct PlannedBuilding {
  std::size_t source = 0;
  std::uint64_t seed = 0;
  glm::dvec3 sizeM{0.0};
  glm::dvec2 lotCentreM{0.0};  // on the ground: world x, z
  double yawDeg = 0;
};

// Where the lots are. Both layouts have streets along +x, 16 m wide, and between two streets a
// block of two rows of lots back to back, 20 m deep, each building facing its street.
enum class CityLayout {
  // A row runs up to 240 m before the next row starts; a lot is the building's width plus 4 m.
  Streets,
  // A square city, as the NUT paper's: ceil(sqrt(count)) lots of 30 m to a row, and a 16 m cross
  // street after every 8 lots.
  Grid,
};

// Each source's size (a grammar's @size, which it must have) is scaled per building by 0.8 to
// 1.25 in width and depth and 0.7 to 1.6 in height; sources are taken in turn. Deterministic in
// (sources' sizes, count, seed, layout); the layout changes where buildings stand, not what they are.
std::vector<PlannedBuilding> planCity(const std::vector<glm::dvec3>& sourceSizesM, std::size_t count,
                                      std::uint64_t seed, CityLayout layout = CityLayout::Streets);

// The height planCity draws for a building of a source sourceSizeM tall, drawn again from `seed`.
// A retry varies with it a building whose only variation is its size (a converted sample): the
// width and depth stay, so the building still fits its lot.
double redrawHeight(double sourceHeightM, std::uint64_t seed);

// Where a building whose root block is rootSizeM stands on its lot: centred on it, turned by the
// plan's yaw, its root's origin at height groundY. The size is taken to whole millimetres, as the
// HNI stores it.
struct LotPlacement {
  glm::dvec3 positionM{0.0};  // world position of the root block's origin
  double yawDeg = 0;
  WorldBox boundsM;           // of the placed root block
};
LotPlacement placeOnLot(const glm::dvec3& rootSizeM, double groundY, const PlannedBuilding& plan);

// A planned building compiled (with compileGrammar's lod), and where its root block's origin
// stands in the world. A start scope the grammar cannot fill (parts that do not fit) is redrawn
// from the building's seed, up to 8 times, and then the grammar's own @size is used.
struct CityBuilding {
  CompiledGrammar compiled;
  LotPlacement placement;
};
Result<CityBuilding> buildCityBuilding(const Grammar& g, const PlannedBuilding& plan,
                                       const std::optional<LodMeasureOptions>& lod = std::nullopt);

}  // namespace nut::grammar
