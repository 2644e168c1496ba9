// cli/render_scene.hpp — what `nut render` draws: one HNI, or every building of a city manifest
// (docs/CITY.md: its HNI placed and turned as the manifest says, and its complementary mesh), plus
// the meshes named by --mesh; and the world box of their content, which the default camera fits.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <meshref/obj.hpp>
#include <meshref/scene_render.hpp>
#include <nut/camera.hpp>
#include <nut/png_io.hpp>

namespace nut::cli {

struct RenderScene {
  std::vector<PngFile> files;                  // each HNI file once, in the order first named
  std::vector<meshref::PlacedHni> hnis;        // the placed HNIs, in the manifest's order
  std::vector<std::size_t> hniFiles;           // per placed HNI, its file
  std::vector<meshref::TriangleMesh> meshes;   // complementary meshes, then --mesh files
  WorldBox bounds;                             // solid content of the HNIs and the meshes' vertices

  struct LoadedHni {
    std::size_t file;
    WorldBox contentFromOrigin;  // its solid content relative to its root's origin, unturned
  };
  std::map<std::string, LoadedHni> loaded;     // by absolute path

  std::vector<const meshref::TriangleMesh*> meshPointers() const;
};

// Loads the scene; `input` is an HNI (PNG) or a city manifest (a .json file). On failure prints one
// error line naming the file (and the building) and returns the exit code (commands.hpp), else 0.
int loadRenderScene(const std::string& input, const std::vector<std::string>& meshPaths, RenderScene& scene);

}  // namespace nut::cli
