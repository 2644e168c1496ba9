// viewer/offscreen.hpp — one call from a scene (HNIs placed in the world, meshes) and a camera to
// an image: what `nut render --backend gl`, `nut render-mesh --backend gl`, the image-comparison
// tests and the GL benchmark use. It owns a context of the chosen back-end, the programs, an atlas
// for the HNIs and an offscreen render target.
//
//   auto r = OffscreenRenderer::create({});                  // OSMesa, embedded shaders
//   r->addHni(png.image, png.text.originM);
//   auto frame = r->render(camera, RayCastOptions{});       // colour, window depth, distances
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>

#include <viewer/city_renderer.hpp>
#include <viewer/context.hpp>
#include <viewer/hni_renderer.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/post_process.hpp>
#include <viewer/render_target.hpp>

namespace nut::viewer {

struct OffscreenOptions {
  Backend backend = Backend::OSMesa;
  std::string shaderDirectory;  // empty: NUT_SHADER_DIR if set, else the embedded shaders
  int glslVersion = 0;          // 0: the context's
};

struct GlFrame {
  Image colour;                     // RGBA8, alpha 255, row 0 at the top
  std::vector<float> windowDepth;   // per pixel in [0, 1], 1 where nothing was drawn
  std::vector<float> distanceM;     // along each pixel's ray, +infinity where nothing was drawn
};

class OffscreenRenderer {
 public:
  static Result<std::unique_ptr<OffscreenRenderer>> create(const OffscreenOptions& options);
  ~OffscreenRenderer();

  // Adds an HNI with its root block's minimum corner at originM and its axes turned by
  // worldFromRoot (a rotation, as for nut::HniRayCaster); fails when validate() rejects the image.
  // Instances given the same shared image are validated once and take one place in the atlas (a
  // city of identical houses packs one house).
  Status addHni(std::shared_ptr<const Image> hni, const glm::dvec3& originM, const glm::dmat3& worldFromRoot = glm::dmat3(1.0));
  // The same with a copy of the image: an instance of its own.
  Status addHni(const Image& hni, const glm::dvec3& originM, const glm::dmat3& worldFromRoot = glm::dmat3(1.0));
  // Adds a mesh (world metres).
  Status addMesh(const TriangleMesh& mesh);
  // Draws a city manifest's buildings through the streaming viewer's renderer (city_renderer.hpp:
  // atlas pages, frustum culling, front-to-back order), fetched from `base` (the manifest's
  // folder) before each frame is drawn, instead of HNIs added one by one.
  void setCity(scene::CityManifest city, std::string base);

  // Anti-aliases the frames that follow with FXAA (shaders/fxaa.frag); off by default, and never
  // for frames compared with the CPU renderers, which do not anti-alias.
  Status setFxaa(bool enabled);

  // Draws the frame: clear to the background, opaque meshes, HNIs, translucent meshes, FXAA if
  // enabled; waits until the GPU has finished (so that timing it measures the rendering).
  Status draw(const Camera& camera, const RayCastOptions& options);
  // Reads back what draw() drew (distances for `camera`, which must be the one drawn).
  GlFrame read(const Camera& camera) const;
  // draw() then read().
  Result<GlFrame> render(const Camera& camera, const RayCastOptions& options);

  const Context& context() const { return *context_; }

 private:
  OffscreenRenderer() = default;
  Status prepareAtlas();
  Status prepareTargets(int width, int height);

  std::unique_ptr<Context> context_;
  ShaderLibrary library_;
  int glslVersion_ = 0;
  std::optional<HniRenderer> hniRenderer_;
  std::optional<MeshRenderer> meshRenderer_;
  std::optional<RenderTarget> target_;
  std::optional<Fxaa> fxaa_;                 // set while FXAA is enabled
  std::optional<RenderTarget> antiAliased_;  // FXAA's output, the size of target_
  std::optional<HniAtlas> atlas_;
  struct PendingHni {
    std::shared_ptr<const Image> image;
    glm::dvec3 originM;
    glm::dmat3 worldFromRoot;
  };
  std::vector<PendingHni> hnis_;
  std::unordered_set<const Image*> validated_;
  std::vector<HniInstance> instances_;
  std::vector<GpuMesh> meshes_;
  std::unique_ptr<CityRenderer> city_;
};

}  // namespace nut::viewer
