// Rendering and comparison of conversions against their source (converter_fidelity.hpp).
#include "converter_fidelity.hpp"

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/scene_render.hpp>

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

std::vector<Camera> fidelityViews(const WorldBox& box, int width, int height) {
  return {fitCamera(box, width, height), viewFrom(box, width, height, {-0.7, 0.35, -1.0}),
          viewFrom(box, width, height, {0.25, 1.6, 0.35}), viewFrom(box, width, height, {1.0, 0.12, -0.45})};
}

Image renderConversions(const std::vector<const Conversion*>& conversions, const Camera& camera) {
  std::vector<scene::PlacedHni> hnis;
  std::vector<TriangleMesh> complements;
  for (const Conversion* conversion : conversions) {
    hnis.push_back({&conversion->image, conversion->originM, glm::dmat3(1.0)});
    if (!conversion->complement.triangles.empty()) complements.push_back(conversion->complement);
  }
  std::vector<const TriangleMesh*> meshes;
  for (const TriangleMesh& m : complements) meshes.push_back(&m);
  auto tracer = meshref::traceMeshes(meshes);
  if (!tracer) return Image(camera.width, camera.height);  // all black: the comparison fails
  const scene::SceneRenderer scene(hnis, std::move(*tracer));
  return scene.render(camera, RayCastOptions{}).colour;
}

Image renderMesh(const TriangleMesh& mesh, const Camera& camera) {
  auto renderer = meshref::EmbreeRenderer::create(mesh);
  if (!renderer) return Image(camera.width, camera.height);
  return renderer->render(camera).colour;
}

Fidelity measureFidelity(const TriangleMesh& source, const std::vector<const Conversion*>& conversions, const std::string& stem,
                         double minPct, int width, int height) {
  Fidelity f;
  const std::vector<Camera> views = fidelityViews(source.bounds(), width, height);
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Image nut = renderConversions(conversions, views[v]);
    const Image mesh = renderMesh(source, views[v]);
    auto diff = nut::compareImages(nut, mesh, kThreshold);
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
