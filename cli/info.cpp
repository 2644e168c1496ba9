// `nut info FILE.png [--json]`: what an HNI holds and what it costs.
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
};

void printText(const InfoOptions& o, const PngFile& png, const HniStats& s) {
  std::printf("%s\n", o.path.c_str());
  if (!png.text.name.empty()) std::printf("  name          %s\n", png.text.name.c_str());
  if (!png.text.generator.empty()) std::printf("  generator     %s\n", png.text.generator.c_str());
  std::printf("  origin        %.3f %.3f %.3f %s\n", png.text.originM.x, png.text.originM.y, png.text.originM.z,
              png.text.units.c_str());
  std::printf("  image         %d x %d px, %lld bytes raw, %ju bytes PNG (%.1f:1)\n", s.width, s.height, s.bytesRaw,
              png.fileBytes, static_cast<double>(s.bytesRaw) / static_cast<double>(png.fileBytes));
  std::printf("  blocks        %d, DAG depth %d\n", s.blocks, s.dagDepth);
  std::printf("  cells         %lld (%lld solid, %lld redirection, %lld empty)\n", s.cells, s.solidCells,
              s.redirectionCells, s.cells - s.solidCells - s.redirectionCells);
  std::printf("  redirections  %d records\n", s.redirections);
  std::printf("  materials     %d, texture infos %d\n", s.materials, s.textures);
  std::printf("  waste         %.2f %% (%lld of %lld px unused)\n", s.wastePct,
              static_cast<long long>(s.width) * s.height - s.usedPixels, static_cast<long long>(s.width) * s.height);
}

void printJson(const PngFile& png, const HniStats& s) {
  const nlohmann::json j = {
      {"blocks", s.blocks},
      {"cells", s.cells},
      {"solid_cells", s.solidCells},
      {"redirection_cells", s.redirectionCells},
      {"redirections", s.redirections},
      {"materials", s.materials},
      {"textures", s.textures},
      {"width", s.width},
      {"height", s.height},
      {"bytes_raw", s.bytesRaw},
      {"bytes_png", png.fileBytes},
      {"waste_pct", s.wastePct},
      {"dag_depth", s.dagDepth},
      {"name", png.text.name},
      {"generator", png.text.generator},
      {"units", png.text.units},
      {"origin", {png.text.originM.x, png.text.originM.y, png.text.originM.z}},
  };
  std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void addInfoCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Print what an HNI holds: blocks, cells, sizes, waste, DAG depth");
  cmd->add_option("file", options->path, "HNI image (PNG)")->required();
  cmd->add_flag("--json", options->json, "Print JSON (keys: blocks, cells, redirections, materials, width, height, "
                                         "bytes_raw, bytes_png, waste_pct, dag_depth, ...)");
  cmd->footer("Example:\n  nut info samples/hni/building.png --json");
  cmd->callback([options, &exitCode] {
    auto png = readPng(options->path);
    if (!png) {
      std::fprintf(stderr, "error: %s\n", png.error().message.c_str());
      exitCode = kUnreadable;
      return;
    }
    if (Status s = validate(png->image); !s) {
      std::fprintf(stderr, "error: %s: invalid HNI: %s\n", options->path.c_str(), s.error().message.c_str());
      exitCode = kInvalid;
      return;
    }
    const HniStats stats = computeStats(png->image);
    if (options->json)
      printJson(*png, stats);
    else
      printText(*options, *png, stats);
    exitCode = kOk;
  });
}

}  // namespace nut::cli
