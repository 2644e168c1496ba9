// nut/units.hpp — conversion between the API's metres and the encoding's integer millimetres.
#pragma once

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

}  // namespace nut
