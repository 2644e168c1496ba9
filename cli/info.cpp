// `nut info FILE.png [--json] [--blocks] [--bytes]`: what an HNI holds and what it costs.
#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/png_encode.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
  bool blocks = false;  // one line per block
  bool bytes = false;   // PNG bytes per kind of record
};

struct BlockLine {
  int id = 0;
  glm::ivec3 cells{0}, metaPixels{0}, sizeUnits{0};
  long long redirectionCells = 0;
  bool root = false;
};

std::vector<BlockLine> blockLines(const Image& image) {
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  std::vector<BlockLine> lines;
  for (int b = 0; b < file.blockCount; ++b) {
    const TexelAddress at = view.blockAddress(file, b);
    const BlockHeader h = view.header(at);
    BlockLine line{b, h.cells, h.metaPixels, h.sizeUnits, 0, at.u == file.root.u && at.v == file.root.v};
    for (int z = 0; z < h.cells.z; ++z)
      for (int y = 0; y < h.cells.y; ++y)
        for (int x = 0; x < h.cells.x; ++x)
          line.redirectionCells += view.cell(h, {x, y, z}).g == format::kCellRedirection;
    lines.push_back(line);
  }
  return lines;
}

struct KindCost {
  PixelKind kind = PixelKind::Unused;
  long long pixels = 0;
  long long pngBytes = 0;  // what the PNG loses when these pixels are zero
};

// What each kind of record costs in the PNG: the file encoded as `nut convert` writes it, against
// the same with that kind's pixels zero. The parts overlap a little (deflate shares matches
// between them), so they need not sum to the total.
std::vector<KindCost> kindCosts(const Image& image, long long& totalBytes) {
  const std::vector<PixelKind> kinds = pixelKinds(image);
  totalBytes = static_cast<long long>(encodePng(image, nullptr, PngEffort::Smallest).size());
  std::vector<KindCost> costs;
  for (int k = 1; k < kPixelKindCount; ++k) {
    const auto kind = static_cast<PixelKind>(k);
    KindCost cost{kind, 0, 0};
    Image zeroed = image;
    for (std::size_t i = 0; i < kinds.size(); ++i)
      if (kinds[i] == kind) {
        ++cost.pixels;
        for (int c = 0; c < 4; ++c) zeroed.pixels[4 * i + static_cast<std::size_t>(c)] = 0;
      }
    if (cost.pixels == 0) continue;
    std::fprintf(stderr, "info: measuring %s\n", pixelKindName(kind));
    cost.pngBytes = totalBytes - static_cast<long long>(encodePng(zeroed, nullptr, PngEffort::Smallest).size());
    costs.push_back(cost);
  }
  return costs;
}

void printText(const InfoOptions& o, const PngFile& png, const HniStats& s) {
  std::printf("%s\n", o.path.c_str());
  if (!png.text.name.empty()) std::printf("  name          %s\n", png.text.name.c_str());
  if (!png.text.generator.empty()) std::printf("  generator     %s\n", png.text.generator.c_str());
  std::printf("  origin        %.3f %.3f %.3f %s\n", png.text.originM.x, png.text.originM.y, png.text.originM.z,
              png.text.units.c_str());
  std::printf("  image         %d x %d px, %lld bytes raw, %ju bytes PNG (%.1f:1)\n", s.width, s.height, s.bytesRaw,
              png.fileBytes, static_cast<double>(s.bytesRaw) / static_cast<double>(png.fileBytes));
  std::printf("  blocks        %d, DAG depth %d\n", s.blocks, s.dagDepth);
  std::printf("  cells         %lld (%lld solid, %lld plane, %lld redirection, %lld empty)\n", s.cells,
              s.solidCells, s.planeCells, s.redirectionCells,
              s.cells - s.solidCells - s.planeCells - s.redirectionCells);
  std::printf("  redirections  %d records\n", s.redirections);
  std::printf("  materials     %d, texture infos %d\n", s.materials, s.textures);
  std::printf("  waste         %.2f %% (%lld of %lld px unused)\n", s.wastePct,
              static_cast<long long>(s.width) * s.height - s.usedPixels, static_cast<long long>(s.width) * s.height);
  if (o.blocks) {
    std::printf("  block    cells (x y z)    size (m)                    metadata px (x y z)  redirection cells\n");
    for (const BlockLine& b : blockLines(png.image))
      std::printf("  %5d%s %4d %4d %4d   %9.3f %9.3f %9.3f   %4d %4d %4d   %lld\n", b.id, b.root ? "*" : " ", b.cells.x,
                  b.cells.y, b.cells.z, b.sizeUnits.x / 1000.0, b.sizeUnits.y / 1000.0, b.sizeUnits.z / 1000.0,
                  b.metaPixels.x, b.metaPixels.y, b.metaPixels.z, b.redirectionCells);
    std::printf("  (* the root)\n");
  }
  if (o.bytes) {
    long long total = 0;
    const std::vector<KindCost> costs = kindCosts(png.image, total);
    std::printf("  PNG bytes by record (pixels only, --png-effort smallest: %lld B; the file adds %lld B of chunks):\n",
                total, static_cast<long long>(png.fileBytes) - total);
    for (const KindCost& c : costs)
      std::printf("    %-20s %8lld px  %6lld B\n", pixelKindName(c.kind), c.pixels, c.pngBytes);
  }
}

void printJson(const InfoOptions& o, const PngFile& png, const HniStats& s) {
  nlohmann::json j = {
      {"blocks", s.blocks},
      {"cells", s.cells},
      {"solid_cells", s.solidCells},
      {"plane_cells", s.planeCells},
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
  if (o.blocks) {
    nlohmann::json list = nlohmann::json::array();
    for (const BlockLine& b : blockLines(png.image))
      list.push_back({{"id", b.id},
                      {"root", b.root},
                      {"cells", {b.cells.x, b.cells.y, b.cells.z}},
                      {"size_m", {b.sizeUnits.x / 1000.0, b.sizeUnits.y / 1000.0, b.sizeUnits.z / 1000.0}},
                      {"metadata_pixels", {b.metaPixels.x, b.metaPixels.y, b.metaPixels.z}},
                      {"redirection_cells", b.redirectionCells}});
    j["block_list"] = list;
  }
  if (o.bytes) {
    long long total = 0;
    nlohmann::json kinds = nlohmann::json::object();
    for (const KindCost& c : kindCosts(png.image, total))
      kinds[pixelKindName(c.kind)] = {{"pixels", c.pixels}, {"png_bytes", c.pngBytes}};
    j["png_bytes_by_record"] = {{"pixels_png_bytes", total}, {"kinds", kinds}};
  }
  std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void addInfoCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Print what an HNI holds: blocks, cells, sizes, waste, DAG depth");
  cmd->add_option("file", options->path, "HNI image (PNG)")->required();
  cmd->add_flag("--json", options->json,
                "Print JSON (keys: blocks, cells, redirections, materials, width, height, "
                "bytes_raw, bytes_png, waste_pct, dag_depth, ...)");
  cmd->add_flag("--blocks", options->blocks,
                "Also list every block: cells and metadata pixels per axis, size, redirection cells");
  cmd->add_flag(
      "--bytes", options->bytes,
      "Also measure what each kind of record costs in the PNG (the file re-encoded with that kind's pixels zero; "
      "a few seconds)");
  cmd->footer(
      "Examples:\n  nut info samples/hni/building.png --json\n"
      "  nut info samples/hni/building.png --blocks --bytes\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([options, &exitCode] {
    auto png = readPng(options->path);
    if (!png) {
      exitCode = fail(png.error().message, kUnreadable);
      return;
    }
    if (Status s = validate(png->image); !s) {
      exitCode = fail(options->path + ": invalid HNI: " + s.error().message, kInvalid);
      return;
    }
    const HniStats stats = computeStats(png->image);
    if (options->json)
      printJson(*options, *png, stats);
    else
      printText(*options, *png, stats);
    exitCode = kOk;
  });
}

}  // namespace nut::cli
