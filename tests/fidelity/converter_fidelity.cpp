// Rendering and comparison of conversions against their source (converter_fidelity.hpp).
#include "converter_fidelity.hpp"

#include <limits>

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

namespace nut::converter::testing {

namespace {

constexpr int kThreshold = 8;

Camera viewFrom(const WorldBox& box, int width, int height, const glm::dvec3& from) {
  Camera c = fitCamera(box, width, height);
  const double distance = glm::length(c.eye - c.target);
  c.eye = c.target + distance * glm::normalize(from);
  return c;
}

}  // namespace

meshref::TriangleMesh toTriangleMesh(const Mesh& mesh) {
  meshref::TriangleMesh out;
  out.positions = mesh.positions;
  out.triangles = mesh.triangles;
  out.triangleMaterial.assign(mesh.triangleMaterial.begin(), mesh.triangleMaterial.end());
  for (std::size_t m = 0; m < mesh.materials.size(); ++m)
    out.materials.push_back({m < mesh.materialNames.size() ? mesh.materialNames[m] : std::to_string(m), mesh.materials[m]});
  out.bounds = mesh.bounds();
  return out;
}

std::vector<Camera> fidelityViews(const WorldBox& box, int width, int height) {
  return {fitCamera(box, width, height), viewFrom(box, width, height, {-0.7, 0.35, -1.0}),
          viewFrom(box, width, height, {0.25, 1.6, 0.35}), viewFrom(box, width, height, {1.0, 0.12, -0.45})};
}

Image renderConversions(const std::vector<const Conversion*>& conversions, const Camera& camera) {
  Image out(camera.width, camera.height);
  std::vector<float> nearest(static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height),
                             std::numeric_limits<float>::infinity());
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    out.pixels[i] = kBackground[0];
    out.pixels[i + 1] = kBackground[1];
    out.pixels[i + 2] = kBackground[2];
    out.pixels[i + 3] = 255;
  }
  const auto keepNearer = [&](const Image& colour, const std::vector<float>& distance) {
    for (std::size_t p = 0; p < nearest.size(); ++p)
      if (distance[p] < nearest[p]) {
        nearest[p] = distance[p];
        for (int c = 0; c < 3; ++c) out.pixels[4 * p + static_cast<std::size_t>(c)] = colour.pixels[4 * p + static_cast<std::size_t>(c)];
      }
  };
  for (const Conversion* conversion : conversions) {
    const HniRayCaster caster(conversion->image, conversion->originM);
    const RenderOutput frame = renderHni(caster, camera, RayCastOptions{});
    keepNearer(frame.colour, frame.distanceM);
    if (conversion->complement.triangles.empty()) continue;
    auto renderer = meshref::EmbreeRenderer::create(toTriangleMesh(conversion->complement));
    if (!renderer) continue;
    const meshref::MeshRenderOutput mesh = renderer->render(camera);
    keepNearer(mesh.colour, mesh.distanceM);
  }
  return out;
}

Image renderMesh(const Mesh& mesh, const Camera& camera) {
  auto renderer = meshref::EmbreeRenderer::create(toTriangleMesh(mesh));
  if (!renderer) return Image(camera.width, camera.height);
  return renderer->render(camera).colour;
}

Fidelity measureFidelity(const Mesh& source, const std::vector<const Conversion*>& conversions, const std::string& stem,
                         double minPct, int width, int height) {
  Fidelity f;
  const std::vector<Camera> views = fidelityViews(source.bounds(), width, height);
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Image nut = renderConversions(conversions, views[v]);
    const Image mesh = renderMesh(source, views[v]);
    auto diff = meshref::compareImages(nut, mesh, kThreshold);
    const double within = diff ? 100.0 - diff->differingPct : 0.0;
    f.withinPct.push_back(within);
    f.worstWithinPct = std::min(f.worstWithinPct, within);
    if (within < minPct && diff) {
      const std::string base = stem + ".view" + std::to_string(v);
      (void)writePng(base + ".nut.png", nut);
      (void)writePng(base + ".mesh.png", mesh);
      (void)writePng(base + ".diff.png", diff->diff);
    }
  }
  return f;
}

}  // namespace nut::converter::testing
