// `nut grammar IN.grammar -o OUT.png`: compiles a facade or building grammar into an HNI
// (grammar/compile.hpp), and optionally the derivation's own mesh and a JSON report.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include <grammar/compile.hpp>
#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

struct GrammarCliOptions {
  std::string input, output, start, size, mesh, report, meshFaces = "solid";
  std::uint64_t seed = 0;
  double wallM = 0.3;
  bool lod = false, quiet = false;
};

Result<glm::dvec3> parseSize(const std::string& text) {
  double v[3] = {0, 0, 0};
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail);
  if (n != 2 && n != 3) return Error{"--size '" + text + "': expected W,H (a facade) or W,H,D (a mass) in metres"};
  for (int i = 0; i < n; ++i)
    if (!(v[i] > 0 && v[i] < 1e6)) return Error{"--size '" + text + "': every size must be positive and under 1000 km"};
  return glm::dvec3(v[0], v[1], n == 3 ? v[2] : 0.0);
}

int run(const GrammarCliOptions& o) {
  grammar::DeriveOptions options;
  options.seed = o.seed;
  options.wallM = o.wallM;
  if (!o.size.empty()) {
    auto size = parseSize(o.size);
    if (!size) return fail(size.error().message, kUsage);
    options.sizeM = *size;
  }
  auto text = readTextFile(o.input);
  if (!text) return fail(text.error().message, kUnreadable);
  auto g = grammar::parseGrammar(*text, o.input, o.start);
  if (!g) return fail(g.error().message, kInvalid);
  auto compiled = grammar::compileGrammar(*g, options, o.lod ? std::optional<LodMeasureOptions>(LodMeasureOptions{})
                                                             : std::nullopt);
  if (!compiled) return fail(compiled.error().message, kInvalid);

  HniText hniText;
  hniText.name = std::filesystem::path(o.input).stem().string();
  hniText.generator = "nut grammar";
  hniText.originM = compiled->originM;
  if (Status s = writeHni(o.output, compiled->image, hniText); !s) return fail(s.error().message, kUnreadable);
  std::error_code ec;
  const auto pngBytes = std::filesystem::file_size(o.output, ec);

  std::size_t triangles = 0;
  if (!o.mesh.empty()) {
    auto mesh = grammar::derivationMesh(
        compiled->derivation, o.meshFaces == "fronts" ? grammar::MeshFaces::Fronts : grammar::MeshFaces::Solid);
    if (!mesh) return fail(o.input + ": " + mesh.error().message, kInvalid);
    mesh->name = hniText.name;
    triangles = mesh->triangles.size();
    if (Status s = writeObj(o.mesh, *mesh); !s) return fail(s.error().message, kUnreadable);
  }
  const HniStats stats = computeStats(compiled->image);
  if (!o.report.empty()) {
    nlohmann::json report = {{"grammar", o.input},
                             {"start", g->start},
                             {"seed", o.seed},
                             {"wall_m", o.wallM},
                             {"origin_m", {compiled->originM.x, compiled->originM.y, compiled->originM.z}},
                             {"shapes", compiled->derivation.shapes},
                             {"nodes", compiled->derivation.nodes.size()},
                             {"blocks", stats.blocks},
                             {"cells", stats.cells},
                             {"redirections", stats.redirections},
                             {"materials", stats.materials},
                             {"dag_depth", stats.dagDepth},
                             {"image", {stats.width, stats.height}},
                             {"png_bytes", pngBytes},
                             {"seconds",
                              {{"derive", compiled->deriveSeconds},
                               {"compile", compiled->compileSeconds},
                               {"lod", compiled->lodSeconds}}}};
    if (o.lod) {
      nlohmann::json footprints = nlohmann::json::array();
      for (const Block& block : compiled->hierarchy.blocks) footprints.push_back(block.lodFootprintM);
      report["lod_footprint_m"] = footprints;  // per block id; 0 = never drawn as its summary
    }
    if (!o.mesh.empty()) report["mesh"] = {{"file", o.mesh}, {"faces", o.meshFaces}, {"triangles", triangles}};
    if (Status s = writeTextFile(o.report, report.dump(2) + "\n"); !s) return fail(s.error().message, kUnreadable);
  }
  if (!o.quiet)
    std::fprintf(stderr,
                 "grammar: %s: %lld shapes, %zu distinct, %d blocks; wrote %s (%dx%d, %ju bytes PNG) in %.3f s\n",
                 o.input.c_str(), compiled->derivation.shapes, compiled->derivation.nodes.size(), stats.blocks,
                 o.output.c_str(), stats.width, stats.height, static_cast<std::uintmax_t>(pngBytes),
                 compiled->deriveSeconds + compiled->compileSeconds + compiled->lodSeconds);
  return kOk;
}

}  // namespace

void addGrammarCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<GrammarCliOptions>();
  CLI::App* cmd = app.add_subcommand("grammar", "Compile a facade or building grammar into an HNI (docs/GRAMMAR.md)");
  cmd->add_option("input", o->input, "Grammar file, in the call form or the brace form")->required();
  cmd->add_option("-o,--output", o->output, "Output HNI")->required()->check(outputExtension(".png", "an HNI (PNG)"));
  cmd->add_option("--seed", o->seed, "Seed of the random choices: the same seed gives the same HNI")
      ->capture_default_str();
  cmd->add_option("--size", o->size,
                  "Start scope: W,H (a facade) or W,H,D (a mass) in metres; default: the file's @size");
  cmd->add_option("--start", o->start, "Start rule; default: the file's @start, else the one rule no other names");
  cmd->add_option("--wall", o->wallM, "Thickness of a facade's wall and of a mass's walls (metres)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 10.0));
  cmd->add_option("--mesh", o->mesh, "Also write the derivation's own geometry as OBJ + MTL (the reference)")
      ->check(outputExtension(".obj", "OBJ"));
  cmd->add_option("--mesh-faces", o->meshFaces,
                  "solid: every box closed (what the HNI shows); fronts: a facade's terminal as its front quad, as a "
                  "shape-grammar system emits it")
      ->check(CLI::IsMember({"solid", "fronts"}))
      ->capture_default_str();
  cmd->add_option("--report", o->report, "Write a JSON report (shapes, blocks, bytes, timings)")
      ->check(outputExtension(".json", "JSON"));
  cmd->add_flag("--lod", o->lod,
                "Measure each block's level of detail (its summary against its full render) and store it: "
                "a version 2 HNI that `nut render --lod auto` draws with fewer steps far away");
  cmd->add_flag("--quiet", o->quiet, "No summary on stderr");
  cmd->footer(
      "Examples:\n  nut grammar samples/grammars/krecklau_figure12.grammar -o facade.png --seed 7\n"
      "  nut grammar samples/grammars/pga_simple_house.grammar -o house.png --mesh house.obj --report house.json\n"
      "  nut grammar samples/grammars/pga_complex_house.grammar -o house.png --lod\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
