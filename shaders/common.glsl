// common.glsl — what every program shares: the shading of docs/RENDERING.md.
//
// References: Kuang et al. 2013, section 6 (rendering); docs/RENDERING.md "Shading", which every
// renderer of the project follows (nut/camera.hpp shade() is the C++ original). Programs are
// assembled as: #version, format_constants.glsl (generated from the C++ constants), this file,
// then the program's own files (nut::viewer::ShaderLibrary).

const float kInfinity = uintBitsToFloat(0x7F800000u);

// albedo x (ambient + (1 - ambient) max(0, n.l)) with the normal turned to face the viewer, on
// sRGB bytes (0..255) without linearisation, rounded half up to the byte.
vec3 shade(vec3 albedo, vec3 normal, vec3 rayDirection) {
  if (dot(normal, rayDirection) > 0.0) normal = -normal;
  float light = kAmbient + (1.0 - kAmbient) * max(0.0, dot(normal, kLightDirection));
  return floor(min(vec3(255.0), albedo * light) + 0.5);
}

// The iteration heat-map (nut/heat_map.hpp heatColour): the ramp at log2(1 + iterations) over
// log2(1 + maxIterations), rounded half up to the byte.
vec3 heatColour(int iterations, int maxIterations) {
  float scale = log2(1.0 + float(max(1, maxIterations)));
  float t = clamp(log2(1.0 + float(max(0, iterations))) / scale, 0.0, 1.0) * float(kHeatRamp.length() - 1);
  int stop = min(int(t), kHeatRamp.length() - 2);
  return floor(mix(kHeatRamp[stop], kHeatRamp[stop + 1], t - float(stop)) + 0.5);
}
