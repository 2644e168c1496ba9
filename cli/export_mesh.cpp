// `nut export-mesh IN.png -o OUT.obj`: the HNI's solid as a triangle mesh (OBJ + MTL), so that any
// mesh tool can show it or compare against it. The geometry rules are nut/mesh_export.hpp.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

struct ExportMeshOptions {
  std::string input, output;
  MeshExportOptions mesh;
};

int run(const ExportMeshOptions& o) {
  auto png = readPng(o.input);
  if (!png) return fail(png.error().message, kUnreadable);
  auto hierarchy = decode(png->image);  // validates first
  if (!hierarchy) return fail(o.input + ": invalid HNI: " + hierarchy.error().message, kInvalid);
  auto mesh = exportMesh(*hierarchy, png->text.originM, o.mesh);
  if (!mesh) return fail(o.input + ": " + mesh.error().message, kInvalid);
  if (Status s = writeObj(o.output, *mesh); !s) return fail(s.error().message, kUnreadable);
  std::vector<bool> used(hierarchy->materials.size(), false);
  for (std::uint16_t m : mesh->triangleMaterial) used[m] = true;
  std::fprintf(stderr, "export-mesh: wrote %s (%zu triangles, %zu vertices, %zu materials used, tolerance %g m)\n",
               o.output.c_str(), mesh->triangles.size(), mesh->positions.size(),
               static_cast<std::size_t>(std::count(used.begin(), used.end(), true)), o.mesh.toleranceM);
  return kOk;
}

}  // namespace

void addExportMeshCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<ExportMeshOptions>();
  CLI::App* cmd = app.add_subcommand("export-mesh", "Export an HNI's solid cells as a triangle mesh (OBJ + MTL)");
  cmd->add_option("input", o->input, "HNI image (PNG)")->required();
  cmd->add_option("-o,--output", o->output, "Output mesh (OBJ); the materials go beside it as .mtl")
      ->required()
      ->check(outputExtension(".obj", "OBJ"));
  // CLI::PositiveNumber's message prints the whole double range; say it plainly.
  const auto positive = [](const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    return *end == '\0' && value > 0 ? std::string() : "must be a positive number, got " + text;
  };
  cmd->add_option("--tolerance", o->mesh.toleranceM,
                  "Largest distance between a curved surface and its triangles (metres)")
      ->default_val(o->mesh.toleranceM)
      ->check(positive);
  cmd->add_option("--max-triangles", o->mesh.maxTriangles, "Fail rather than write more triangles than this")
      ->default_val(o->mesh.maxTriangles)
      ->check(positive);
  cmd->footer("Example:\n  nut export-mesh samples/hni/building.png -o building.obj --tolerance 0.002\n\n" +
              std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
