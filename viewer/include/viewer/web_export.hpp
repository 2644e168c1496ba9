// viewer/web_export.hpp — `nut-viewer --export-web DIR`: the browser viewer (web/, docs/WEB.md)
// written into a folder, usually a city's, so that any static web server there serves it.
#pragma once

#include <span>
#include <string>

#include <nut/error.hpp>
#include <viewer/shader_library.hpp>

namespace nut::viewer {

// The files of web/, embedded at build time (cmake/embed_text_files.cmake).
struct EmbeddedWebFile {
  const char* path;  // relative to web/, e.g. "js/main.js"
  const char* text;
};
std::span<const EmbeddedWebFile> embeddedWebFiles();

// The text of js/generated.js: the ray caster (both lookups) and the mesh program assembled as
// GLSL ES 3.00 from the same sources as the desktop programs, with each file's first line for
// error messages, the format constants the page reads HNI headers with, and the pixels a
// complement level's error may span (scene::kMeshLevelErrorPx).
Result<std::string> generatedWebModule(const ShaderLibrary& library);

// Writes web/ and js/generated.js under `dir` (created if missing), each file whole (a temporary
// sibling renamed into place). Returns the number of files written.
Result<int> exportWeb(const std::string& dir, const ShaderLibrary& library);

}  // namespace nut::viewer
