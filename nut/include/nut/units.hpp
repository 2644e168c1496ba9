// nut/units.hpp — conversion between the API's metres and the encoding's integers: millimetres,
// and the log-coded level-of-detail footprint of redirection records.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <nut/format.hpp>

namespace nut {

// Nearest encoding unit (ties away from zero). Callers check the range before encoding.
inline std::int64_t toUnits(double metres) {
  return std::llround(metres / format::kMetresPerUnit);
}
inline double toMetres(std::int64_t units) {
  return static_cast<double>(units) * format::kMetresPerUnit;
}
// The metre value the encoding keeps for `metres`.
inline double snapToUnits(double metres) { return toMetres(toUnits(metres)); }

// Level-of-detail footprint code (docs/FORMAT.md, redirection record): 0 = none, else the footprint
// is 2^((c - kLodCodeOneMetre) / kLodCodesPerOctave) metres, 3.9 mm to 245 m.
inline double lodFootprintM(std::uint8_t code) {
  if (code == 0) return 0.0;
  return std::exp2(static_cast<double>(code - format::kLodCodeOneMetre) / format::kLodCodesPerOctave);
}
// The code of the smallest footprint at least `metres`, clamped to 1..255 (rounding up only ever
// keeps a summary out); 0 when metres is not positive. lodCode(lodFootprintM(c)) == c.
inline std::uint8_t lodCode(double metres) {
  if (!(metres > 0.0)) return 0;
  const double exact = format::kLodCodeOneMetre + format::kLodCodesPerOctave * std::log2(metres);
  return static_cast<std::uint8_t>(std::clamp(std::ceil(exact - 1e-9), 1.0, 255.0));
}

}  // namespace nut
