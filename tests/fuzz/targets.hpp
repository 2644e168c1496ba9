// The fuzz targets, one function each: a libFuzzer binary calls one of them for every input
// (libfuzzer_entry.cpp), and the plain corpus test calls each over its seeds and regressions.
// Each returns 0, and calls abort() when an input breaks what it checks.
#pragma once

#include <cstddef>
#include <cstdint>

namespace nut::fuzz {

// Bytes as an HNI (frame.hpp) through validate, decode and compile (hni_fuzz.cpp).
int hniInput(const std::uint8_t* data, std::size_t size);
// Bytes as an OBJ, with an optional MTL part, through the OBJ reader (obj_fuzz.cpp).
int objInput(const std::uint8_t* data, std::size_t size);
// Bytes as a binary glTF file through the GLB reader (glb_fuzz.cpp).
int glbInput(const std::uint8_t* data, std::size_t size);
// Bytes as a city.json through the manifest reader (city_fuzz.cpp).
int cityInput(const std::uint8_t* data, std::size_t size);
// Bytes as an HNI (frame.hpp) through validate and, when valid, the CPU ray caster (render_fuzz.cpp).
int renderInput(const std::uint8_t* data, std::size_t size);
// Bytes as a grammar through the grammar parser and its checks (grammar_fuzz.cpp).
int grammarInput(const std::uint8_t* data, std::size_t size);

}  // namespace nut::fuzz
