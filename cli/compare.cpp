// `nut compare A.png B.png`: how far two renders of the same view are apart (RMS, PSNR, share of
// differing pixels), with an optional diff picture. Thin over nut::compareImages.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

namespace {

struct CompareOptions {
  std::string a, b, diff;
  int threshold = 8, reduce = 1;
  bool json = false;
};

int run(const CompareOptions& o) {
  auto a = readPng(o.a, PngKind::Render);
  if (!a) return fail(a.error().message, kUnreadable);
  auto b = readPng(o.b, PngKind::Render);
  if (!b) return fail(b.error().message, kUnreadable);
  if (o.reduce > 1) {
    auto reduced = boxFilter(a->image, o.reduce);
    if (!reduced) return fail(o.a + ": " + reduced.error().message, kInvalid);
    a->image = std::move(*reduced);
  }
  auto d = nut::compareImages(a->image, b->image, o.threshold);
  if (!d) return fail(d.error().message, kInvalid);
  if (!o.diff.empty())
    if (Status s = writePng(o.diff, d->diff); !s) return fail(s.error().message, kUnreadable);
  const bool identical = std::isinf(d->psnr);
  if (o.json) {
    nlohmann::json j = {{"a", o.a},
                        {"b", o.b},
                        {"width", d->width},
                        {"height", d->height},
                        {"rms", d->rms},
                        {"psnr", nullptr},
                        {"max_difference", d->maxDifference},
                        {"pixels", d->pixels},
                        {"differing", d->differing},
                        {"differing_pct", d->differingPct},
                        {"threshold", d->threshold}};
    if (!identical) j["psnr"] = d->psnr;
    if (!o.diff.empty()) j["diff"] = o.diff;
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf("compare: %s vs %s, %dx%d\n", o.a.c_str(), o.b.c_str(), d->width, d->height);
  if (identical)
    std::printf("rms 0  psnr inf  max difference 0\n");
  else
    std::printf("rms %.4f  psnr %.2f dB  max difference %d\n", d->rms, d->psnr, d->maxDifference);
  std::printf("differing %.4f%% (%lld of %lld pixels differ by more than %d in some channel)\n", d->differingPct,
              static_cast<long long>(d->differing), static_cast<long long>(d->pixels), d->threshold);
  if (!o.diff.empty()) std::printf("diff: wrote %s\n", o.diff.c_str());
  return kOk;
}

}  // namespace

void addCompareCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd =
      app.add_subcommand("compare", "Compare two images of the same size (e.g. an HNI render and a mesh render)");
  cmd->add_option("a", o->a, "First image (PNG)")->required();
  cmd->add_option("b", o->b, "Second image (PNG)")->required();
  cmd->add_option("--diff", o->diff, "Write a difference picture (PNG), see below")
      ->check(outputExtension(".png", "PNG"));
  cmd->add_option("--threshold", o->threshold, "A pixel differs when some channel differs by more than this (0..255)")
      ->default_val(8)
      ->check(CLI::Range(0, 255));
  cmd->add_option("--reduce", o->reduce,
                  "Box-filter the first image by N x N pixels first: a reference rendered at N times the size "
                  "becomes a supersampled one")
      ->default_val(1)
      ->check(CLI::Range(1, 16));
  cmd->add_flag("--json", o->json, "Print the numbers as JSON");
  cmd->footer(
      "Numbers (over R, G, B on the 0..255 scale; alpha is ignored):\n"
      "  rms            root mean square of the channel differences\n"
      "  psnr           20 log10(255 / rms) dB; \"inf\" when the images are identical (JSON: null)\n"
      "  max difference the largest channel difference of any pixel\n"
      "  differing      pixels whose largest channel difference exceeds --threshold, and their share in %\n"
      "JSON keys: a, b, width, height, rms, psnr, max_difference, pixels, differing, differing_pct, threshold[, "
      "diff].\n\n"
      "Diff picture: equal pixels show A in faded grey; pixels that differ by 1..threshold are blue, by more\n"
      "than the threshold red (both brighter as the difference grows; red is full from 64 up).\n"
      "The exit code is 0 whenever the comparison ran; differences are reported, not failed.\n\n"
      "Example:\n  nut render building.png -o hni.png && nut render-mesh building.obj -o mesh.png\n"
      "  nut compare hni.png mesh.png --diff diff.png --threshold 8\n"
      "  nut compare ref-1280x720.png lod-320x180.png --reduce 4   # against a 4x4 supersampled reference\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
