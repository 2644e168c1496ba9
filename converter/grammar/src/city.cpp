// Cities of distinct buildings from building grammars (grammar/city.hpp).
#include <grammar/city.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/common.hpp>

#include <nut/units.hpp>

namespace nut::grammar {

namespace {

constexpr double kStreetWidthM = 16.0;
constexpr double kRowDepthM = 20.0;
constexpr double kRowLengthM = 240.0;
constexpr double kLotGapM = 4.0;
constexpr double kGridLotM = 30.0;
constexpr int kGridLotsBetweenCrossStreets = 8;
constexpr int kSizeRedraws = 8;

// The start scope of a building: the grammar's @size scaled per axis.
glm::dvec3 drawSize(const glm::dvec3& base, std::mt19937_64& random) {
  std::uniform_real_distribution<double> footprint(0.8, 1.25), height(0.7, 1.6);
  const double width = footprint(random), tall = height(random), depth = footprint(random);
  return {base.x * width, base.y * tall, base.z * depth};
}

// The centre of a row of lots (world z): row 2k faces the street before its block (-z), row 2k + 1
// the one after it (+z).
double rowCentreZ(int row) {
  const int block = row / 2;
  return kStreetWidthM + block * (2 * kRowDepthM + kStreetWidthM) + (row % 2 == 1 ? 1.5 : 0.5) * kRowDepthM;
}

}  // namespace

std::vector<PlannedBuilding> planCity(const std::vector<glm::dvec3>& sourceSizesM, std::size_t count,
                                      std::uint64_t seed, CityLayout layout) {
  std::vector<PlannedBuilding> plan;
  if (sourceSizesM.empty()) return plan;
  std::mt19937_64 random(seed);
  const auto lotsPerGridRow = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  int row = 0;
  double along = 0;
  for (std::size_t i = 0; i < count; ++i) {
    PlannedBuilding b;
    b.source = i % sourceSizesM.size();
    b.seed = random();
    b.sizeM = drawSize(sourceSizesM[b.source], random);
    if (layout == CityLayout::Grid) {
      const std::size_t column = i % lotsPerGridRow;
      row = static_cast<int>(i / lotsPerGridRow);
      const double crossStreets = static_cast<double>(column / kGridLotsBetweenCrossStreets) * kStreetWidthM;
      b.lotCentreM = {(static_cast<double>(column) + 0.5) * kGridLotM + crossStreets, rowCentreZ(row)};
    } else {
      const double lot = b.sizeM.x + kLotGapM;
      if (along + lot > kRowLengthM && along > 0) {
        ++row;
        along = 0;
      }
      b.lotCentreM = {along + lot / 2, rowCentreZ(row)};
      along += lot;
    }
    b.yawDeg = row % 2 == 1 ? 180.0 : 0.0;
    plan.push_back(b);
  }
  return plan;
}

double redrawHeight(double sourceHeightM, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  return drawSize({1.0, sourceHeightM, 1.0}, random).y;
}

Result<CityBuilding> buildCityBuilding(const Grammar& g, const PlannedBuilding& plan,
                                       const std::optional<LodMeasureOptions>& lod) {
  DeriveOptions options;
  options.seed = plan.seed;
  options.sizeM = plan.sizeM;
  std::mt19937_64 redraw(plan.seed);
  auto compiled = compileGrammar(g, options, lod);
  for (int attempt = 0; !compiled && attempt < kSizeRedraws; ++attempt) {
    options.sizeM = drawSize(g.size.value_or(plan.sizeM), redraw);
    compiled = compileGrammar(g, options, lod);
  }
  if (!compiled) {
    options.sizeM = g.size;
    compiled = compileGrammar(g, options, lod);
  }
  if (!compiled) return compiled.error();
  CityBuilding out;
  out.compiled = std::move(*compiled);
  out.placement = placeOnLot(out.compiled.hierarchy.blocks[out.compiled.hierarchy.root].sizeM(),
                             out.compiled.originM.y, plan);
  return out;
}

LotPlacement placeOnLot(const glm::dvec3& rootSizeM, double groundY, const PlannedBuilding& plan) {
  // The size as encoded (whole millimetres), which is what a renderer of the HNI places.
  glm::dvec3 size = rootSizeM;
  for (int a = 0; a < 3; ++a) size[a] = snapToUnits(size[a]);
  // The root block's box, centred on the lot: world = position + Yaw * local, and a turn of 0 or
  // 180 degrees about y maps the box's centre (S / 2) to (+-S.x / 2, S.y / 2, +-S.z / 2).
  LotPlacement out;
  out.yawDeg = plan.yawDeg;
  const double sign = plan.yawDeg == 0.0 ? 1.0 : -1.0;
  out.positionM = {plan.lotCentreM.x - sign * size.x / 2, groundY, plan.lotCentreM.y - sign * size.z / 2};
  const glm::dvec3 farCorner = out.positionM + glm::dvec3(sign * size.x, size.y, sign * size.z);
  out.boundsM = {glm::min(out.positionM, farCorner), glm::max(out.positionM, farCorner)};
  return out;
}

}  // namespace nut::grammar
