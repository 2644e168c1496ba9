// heat_map.hpp — the iteration heat-map (RayCastOptions::heatMap, `--heat-map`): where the ray
// casters spend their traversal steps, drawn as colour.
//
// An opaque hit is drawn in the colour of the traversal iterations its ray took, on a log scale
// from 0 to the iteration cap, so that the usual 5-50 iterations spread over the ramp. The GLSL
// caster draws the same ramp from generated constants (shaders/glsl_constants.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace nut {

// Evenly spaced stops: dark blue, blue, green, yellow, red (the cap itself is kCappedColour).
inline constexpr int kHeatRampStops = 5;
inline constexpr std::array<std::array<std::uint8_t, 3>, kHeatRampStops> kHeatRamp{
    {{0, 0, 96}, {0, 128, 255}, {0, 200, 80}, {255, 220, 0}, {255, 40, 0}}};

// The ramp at log2(1 + iterations) / log2(1 + maxIterations), rounded half up to the byte.
inline std::array<std::uint8_t, 3> heatColour(int iterations, int maxIterations) {
  const double scale = std::log2(1.0 + std::max(1, maxIterations));
  const double t = std::clamp(std::log2(1.0 + std::max(0, iterations)) / scale, 0.0, 1.0) * (kHeatRampStops - 1);
  const int stop = std::min(static_cast<int>(t), kHeatRampStops - 2);
  const double f = t - stop;
  std::array<std::uint8_t, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double a = kHeatRamp[static_cast<std::size_t>(stop)][i];
    const double b = kHeatRamp[static_cast<std::size_t>(stop) + 1][i];
    out[i] = static_cast<std::uint8_t>(a + (b - a) * f + 0.5);
  }
  return out;
}

}  // namespace nut
