// A context, the programs, an atlas and a render target: scenes to images in one call.
#include <viewer/offscreen.hpp>

#include <unordered_map>

#include <packer/maxrects.hpp>

#include <nut/hni.hpp>

namespace nut::viewer {

Result<std::unique_ptr<OffscreenRenderer>> OffscreenRenderer::create(const OffscreenOptions& options) {
  std::unique_ptr<OffscreenRenderer> r(new OffscreenRenderer());
  auto context = createContext(options.backend);
  if (!context) return context.error();
  r->context_ = std::move(*context);
  r->library_ = options.shaderDirectory.empty() ? ShaderLibrary::fromEnvironment() : ShaderLibrary(options.shaderDirectory);
  r->glslVersion_ = options.glslVersion;
  const ShaderLibrary& library = r->library_;
  auto hni = HniRenderer::create(*r->context_, library, options.glslVersion);
  if (!hni) return hni.error();
  r->hniRenderer_.emplace(std::move(*hni));
  auto mesh = MeshRenderer::create(*r->context_, library, options.glslVersion);
  if (!mesh) return mesh.error();
  r->meshRenderer_.emplace(std::move(*mesh));
  return r;
}

// GL objects go before the context that owns them, deleted while it is current.
OffscreenRenderer::~OffscreenRenderer() {
  if (context_) (void)context_->makeCurrent();
  meshes_.clear();
  city_.reset();
  atlas_.reset();
  antiAliased_.reset();
  fxaa_.reset();
  target_.reset();
  meshRenderer_.reset();
  hniRenderer_.reset();
}

Status OffscreenRenderer::addHni(std::shared_ptr<const Image> hni, const glm::dvec3& originM, const glm::dmat3& worldFromRoot) {
  // The shader follows the file's addresses without checks: only a valid HNI may reach it.
  if (!validated_.contains(hni.get())) {
    if (Status s = validate(*hni); !s) return Error{"invalid HNI: " + s.error().message};
    validated_.insert(hni.get());
  }
  hnis_.push_back({std::move(hni), originM, worldFromRoot});
  atlas_.reset();  // packed again, with every HNI, at the next draw
  return Ok{};
}

Status OffscreenRenderer::addHni(const Image& hni, const glm::dvec3& originM, const glm::dmat3& worldFromRoot) {
  return addHni(std::make_shared<const Image>(hni), originM, worldFromRoot);
}

Status OffscreenRenderer::addMesh(const TriangleMesh& mesh) {
  if (Status s = context_->makeCurrent(); !s) return s;
  auto gpu = GpuMesh::upload(context_->gl(), mesh);
  if (!gpu) return gpu.error();
  meshes_.push_back(std::move(*gpu));
  return Ok{};
}

void OffscreenRenderer::setCity(scene::CityManifest city, std::string base) {
  (void)context_->makeCurrent();
  city_ = std::make_unique<CityRenderer>(context_->gl(), *hniRenderer_, nullptr, std::move(city), std::move(base),
                                         localFiles(), CityRendererOptions{});
}

// One atlas just large enough for every distinct HNI image: the packer's width search, as HNI
// compilation does.
Status OffscreenRenderer::prepareAtlas() {
  if (atlas_ || hnis_.empty()) return Ok{};
  std::vector<const Image*> distinct;
  std::unordered_map<const Image*, std::size_t> slot;  // image -> index into distinct
  std::vector<packer::Item> items;
  for (const PendingHni& h : hnis_)
    if (slot.emplace(h.image.get(), distinct.size()).second) {
      items.push_back({static_cast<int>(distinct.size()), h.image->width, h.image->height});
      distinct.push_back(h.image.get());
    }
  GLint maxSize = 0;
  context_->gl().GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const auto layout = packer::packSearchWidth(items, maxSize, maxSize);
  if (!layout) return Error{"HNI atlas: the HNIs do not fit one " + std::to_string(maxSize) + "^2 texture"};
  auto atlas = HniAtlas::create(context_->gl(), layout->width, layout->height);
  if (!atlas) return atlas.error();
  std::vector<glm::ivec2> origins(distinct.size());  // per distinct image, where the atlas holds it
  for (const packer::Placement& p : layout->placements) {
    const auto d = static_cast<std::size_t>(p.id);
    origins[d] = {p.rect.x, p.rect.y};
    if (Status s = atlas->put(*distinct[d], origins[d]); !s) return s;
  }
  instances_.clear();
  for (const PendingHni& h : hnis_) instances_.push_back({origins[slot.at(h.image.get())], h.originM, h.worldFromRoot});
  atlas_.emplace(std::move(*atlas));
  return Ok{};
}

Status OffscreenRenderer::setFxaa(bool enabled) {
  if (Status s = context_->makeCurrent(); !s) return s;
  if (!enabled) {
    fxaa_.reset();
    antiAliased_.reset();
    return Ok{};
  }
  if (fxaa_) return Ok{};
  auto fxaa = Fxaa::create(*context_, library_, glslVersion_);
  if (!fxaa) return fxaa.error();
  fxaa_.emplace(std::move(*fxaa));
  return Ok{};
}

// The frame's target, and FXAA's when enabled, at the camera's size.
Status OffscreenRenderer::prepareTargets(int width, int height) {
  const Gl& gl = context_->gl();
  for (auto* target : {&target_, &antiAliased_}) {
    if (target == &antiAliased_ && !fxaa_) continue;
    if (*target && (*target)->width() == width && (*target)->height() == height) continue;
    target->reset();
    auto created = RenderTarget::create(gl, width, height);
    if (!created) return created.error();
    target->emplace(std::move(*created));
  }
  return Ok{};
}

Status OffscreenRenderer::draw(const Camera& camera, const RayCastOptions& options) {
  if (Status s = context_->makeCurrent(); !s) return s;
  const Gl& gl = context_->gl();
  if (Status s = prepareAtlas(); !s) return s;
  if (Status s = prepareTargets(camera.width, camera.height); !s) return s;
  // A single image waits for the city's files before it draws, so that it is complete.
  constexpr double kStreamTimeoutSeconds = 600;
  if (city_)
    if (Status s = city_->streamIn(camera, kStreamTimeoutSeconds); !s) return s;
  const FrameView view(camera);
  target_->bindCleared();
  for (const GpuMesh& mesh : meshes_) meshRenderer_->drawOpaque(view, mesh);
  if (atlas_) hniRenderer_->draw(view, *atlas_, instances_, options);
  if (city_) {
    CityFrameStats stats;
    if (Status s = city_->drawFrame(camera, options, stats); !s) return s;
    if (!stats.newFailures.empty()) return Error{stats.newFailures.front()};
  }
  for (GpuMesh& mesh : meshes_) meshRenderer_->drawTranslucent(view, mesh);
  if (fxaa_) fxaa_->apply(*target_, *antiAliased_);
  gl.Finish();
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) return Error{"GL frame: " + glErrorName(error)};
  return Ok{};
}

GlFrame OffscreenRenderer::read(const Camera& camera) const {
  (void)context_->makeCurrent();  // it was current for draw(), which checked it
  GlFrame frame;
  frame.colour = (fxaa_ ? *antiAliased_ : *target_).readColour();
  frame.windowDepth = target_->readDepth();
  const FrameView view(camera);
  frame.distanceM.resize(frame.windowDepth.size());
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x);
      frame.distanceM[i] = static_cast<float>(view.distanceFromWindowDepth(x, y, frame.windowDepth[i]));
    }
  return frame;
}

Result<GlFrame> OffscreenRenderer::render(const Camera& camera, const RayCastOptions& options) {
  if (Status s = draw(camera, options); !s) return s.error();
  return read(camera);
}

}  // namespace nut::viewer
