// shaders/embedded.hpp — the GLSL sources of shaders/, embedded into the binary at build time.
//
// The build turns every file of shaders/ (and format_constants.glsl, generated from the C++
// constants by glsl_constants.cpp) into a string literal; nut::viewer::ShaderLibrary assembles
// programs from them, or from the files on disk during development.
#pragma once

#include <span>

namespace nut::shaders {

struct EmbeddedShader {
  const char* name;    // file name, e.g. "hni_raycast.frag"
  const char* source;  // the file's text
};

std::span<const EmbeddedShader> embeddedShaders();

}  // namespace nut::shaders
