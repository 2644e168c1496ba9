// A grammar to an HNI (grammar/compile.hpp).
#include <grammar/compile.hpp>

#include <chrono>

#include <nut/hni.hpp>

namespace nut::grammar {

Result<CompiledGrammar> compileGrammar(const Grammar& g, const DeriveOptions& options,
                                       const std::optional<LodMeasureOptions>& lod) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point from) {
    return std::chrono::duration<double>(Clock::now() - from).count();
  };
  CompiledGrammar out;
  const auto start = Clock::now();
  auto derivation = derive(g, options);
  if (!derivation) return derivation.error();
  out.derivation = std::move(*derivation);
  auto hierarchy = derivationHierarchy(out.derivation, out.originM);
  if (!hierarchy) return Error{g.file + ": " + hierarchy.error().message};
  out.hierarchy = std::move(*hierarchy);
  out.deriveSeconds = seconds(start);
  const auto compiling = Clock::now();
  auto image = compile(out.hierarchy);
  if (!image) return Error{g.file + ": " + image.error().message};
  out.image = std::move(*image);
  out.compileSeconds = seconds(compiling);
  if (lod) {
    const auto measuring = Clock::now();
    measureLevelOfDetail(out.hierarchy, out.image, *lod);
    auto withLod = compile(out.hierarchy);
    if (!withLod) return Error{g.file + ": " + withLod.error().message};
    out.image = std::move(*withLod);
    out.lodSeconds = seconds(measuring);
  }
  return out;
}

}  // namespace nut::grammar
