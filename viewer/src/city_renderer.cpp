// A city manifest streamed and drawn frame by frame (viewer/city_renderer.hpp).
#include <viewer/city_renderer.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <thread>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <nut/hni_view.hpp>
#include <scene/scene.hpp>

namespace nut::viewer {

bool mayBeVisible(const WorldBox& box, const FrameView& view) {
  const Camera& camera = view.camera;
  const glm::dvec3 forward(view.rays.forward), right(view.rays.right), up(view.rays.upVector);
  std::array<glm::dvec3, 8> corners;
  for (int c = 0; c < 8; ++c)
    corners[static_cast<std::size_t>(c)] =
        glm::dvec3(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y, c & 4 ? box.max.z : box.min.z) -
        camera.eye;
  // A plane's inside is value(p) >= 0: the four sides through the eye, then near and far.
  const auto allOutside = [&](auto value) {
    return std::all_of(corners.begin(), corners.end(), [&](const glm::dvec3& p) { return value(p) < 0; });
  };
  const double tx = view.rays.tanHalfX, ty = view.rays.tanHalfY;
  return !(allOutside([&](const glm::dvec3& p) { return tx * glm::dot(p, forward) - glm::dot(p, right); }) ||
           allOutside([&](const glm::dvec3& p) { return tx * glm::dot(p, forward) + glm::dot(p, right); }) ||
           allOutside([&](const glm::dvec3& p) { return ty * glm::dot(p, forward) - glm::dot(p, up); }) ||
           allOutside([&](const glm::dvec3& p) { return ty * glm::dot(p, forward) + glm::dot(p, up); }) ||
           allOutside([&](const glm::dvec3& p) { return glm::dot(p, forward) - camera.nearM; }) ||
           allOutside([&](const glm::dvec3& p) { return camera.farM - glm::dot(p, forward); }));
}

CityRenderer::CityRenderer(const Gl& gl, const HniRenderer& hniRenderer, const MeshRenderer* meshRenderer,
                           scene::CityManifest city, std::string base, Fetch fetch, const CityRendererOptions& options)
    : gl_(&gl),
      hniRenderer_(&hniRenderer),
      meshRenderer_(meshRenderer),
      city_(std::move(city)),
      base_(std::move(base)),
      options_(options),
      pages_(gl, options.atlasPageSize, options.maxAtlasPages),
      loader_(std::move(fetch), options.loaderThreads) {
  for (const scene::CityBuilding& b : city_.buildings) {
    Building building;
    building.originM = b.positionM;
    building.worldFromRoot = scene::yawRotation(b.yawDeg);
    building.bounds = b.boundsM;
    // Without a MeshRenderer there is nothing to draw a complementary mesh with: never fetched.
    if (meshRenderer_ && !b.complement.empty()) building.complement.resize(1 + b.complementLevels.size());
    buildings_.push_back(std::move(building));
  }
}

// Finished loads join the upload queue; failures are final.
void CityRenderer::receive(CityFrameStats& stats) {
  for (LoadedHni& loaded : loader_.takeFinished()) {
    bytesStreamed_ += loaded.bytes;
    if (loaded.status)
      uploadQueue_.push_back(std::move(loaded));
    else
      fail(loaded.building, loaded.status.error().message, stats);
  }
}

// A building that failed is never drawn or requested again.
void CityRenderer::fail(std::size_t building, const std::string& message, CityFrameStats& stats) {
  Building& b = buildings_[building];
  if (b.state == State::Failed) return;
  if (b.state == State::Loaded) --loaded_;
  b.state = State::Failed;
  ++failed_;
  stats.newFailures.push_back(city_.buildings[building].name + ": " + message);
}

// A level of a building's complementary mesh onto the GPU; its box joins the building's, which
// is culled and tested as one. False when the building failed.
bool CityRenderer::addComplementLevel(LoadedHni& loaded, CityFrameStats& stats) {
  Building& b = buildings_[loaded.building];
  auto mesh = GpuMesh::upload(*gl_, *loaded.complement);
  if (!mesh) {
    fail(loaded.building, "complementary mesh: " + mesh.error().message, stats);
    return false;
  }
  const WorldBox box = mesh->bounds();
  if (!b.complementBox) b.complementBox = box;
  b.complementBox->min = glm::min(b.complementBox->min, box.min);
  b.complementBox->max = glm::max(b.complementBox->max, box.max);
  b.bounds->min = glm::min(b.bounds->min, box.min);
  b.bounds->max = glm::max(b.bounds->max, box.max);
  b.complement[loaded.complementLevel].mesh.emplace(std::move(*mesh));
  return true;
}

// The level of a building's complementary mesh the camera wants: under --lod auto the coarsest
// whose error spans under a pixel at the nearest point of the levels' box (before any level has
// arrived, of the building's box), as the cpu scene picks (scene::meshLevel).
std::size_t CityRenderer::wantedLevel(std::size_t building, const Camera& camera, bool lodAuto) const {
  const Building& b = buildings_[building];
  const std::optional<WorldBox>& box = b.complementBox ? b.complementBox : b.bounds;
  return lodAuto && box ? scene::meshLevel(city_.buildings[building].complementLevels, *box, camera) : 0;
}

std::string CityRenderer::levelLocation(std::size_t building, std::size_t level) const {
  const scene::CityBuilding& entry = city_.buildings[building];
  return base_ + "/" + (level == 0 ? entry.complement : entry.complementLevels[level - 1].path);
}

// The level to draw: the one wanted when it has arrived; else it is requested, and the nearest
// level loaded stands in (finer first), so the frame never waits for a file.
GpuMesh* CityRenderer::complementToDraw(std::size_t building, const Camera& camera, bool lodAuto) {
  Building& b = buildings_[building];
  if (b.complement.empty()) return nullptr;
  const std::size_t wanted = wantedLevel(building, camera, lodAuto);
  Building::MeshLevel& level = b.complement[wanted];
  if (level.mesh) return &*level.mesh;
  if (!level.requested) {
    loader_.request({building, "", levelLocation(building, wanted), wanted});
    level.requested = true;
    settled_ = false;
  }
  for (std::size_t k = wanted; k-- > 0;)
    if (b.complement[k].mesh) return &*b.complement[k].mesh;
  for (std::size_t k = wanted + 1; k < b.complement.size(); ++k)
    if (b.complement[k].mesh) return &*b.complement[k].mesh;
  return nullptr;
}

// Empties the page whose buildings were seen least recently, unless one of them was seen this
// frame. Returns whether a page was emptied.
bool CityRenderer::evictLeastRecentlySeenPage() {
  std::vector<std::size_t> lastSeen(static_cast<std::size_t>(pages_.pageCount()), 0);
  for (const Building& b : buildings_)
    if (b.state == State::Loaded)
      lastSeen[static_cast<std::size_t>(b.slot.page)] = std::max(lastSeen[static_cast<std::size_t>(b.slot.page)], b.lastSeen);
  const auto oldest = std::min_element(lastSeen.begin(), lastSeen.end());
  if (oldest == lastSeen.end() || *oldest >= frame_) return false;
  const int page = static_cast<int>(oldest - lastSeen.begin());
  for (Building& b : buildings_)
    if (b.state == State::Loaded && b.slot.page == page) {
      b.state = State::Unrequested;
      b.evicted = true;
      b.occluded = false;
      b.query = {};
      for (Building::MeshLevel& level : b.complement) level = {};
      b.complementBox.reset();
      --loaded_;
      ++evicted_;
    }
  pages_.clear(page);
  return true;
}

// A slice of the upload queue into the atlas: up to the per-frame bytes, at least one HNI.
void CityRenderer::upload(CityFrameStats& stats) {
  std::size_t bytes = 0;
  std::size_t taken = 0;
  for (; taken < uploadQueue_.size() && (taken == 0 || bytes < options_.uploadBytesPerFrame); ++taken) {
    LoadedHni& loaded = uploadQueue_[taken];
    Building& b = buildings_[loaded.building];
    if (!loaded.image) {
      // A level of the complement alone, for a building loaded before (dropped if evicted since).
      if (b.state == State::Loaded) addComplementLevel(loaded, stats);
      continue;
    }
    if (!pages_.fits(*loaded.image) && !evictLeastRecentlySeenPage()) {
      stats.overBudget = true;  // stays queued until the view moves on
      break;
    }
    bytes += loaded.image->pixels.size();
    auto slot = pages_.place(*loaded.image);
    if (!slot) {
      fail(loaded.building, slot.error().message, stats);
      continue;
    }
    b.slot = *slot;
    b.bounds = HniRayCaster(*loaded.image, b.originM, b.worldFromRoot).bounds();
    if (loaded.complement && !addComplementLevel(loaded, stats)) continue;
    const HniView hni(*loaded.image);
    const BlockHeader root = hni.header(hni.fileRecord().root);
    b.rootSizeM = glm::dvec3(root.sizeUnits) * format::kMetresPerUnit;
    b.summary = root.summary;
    b.state = State::Loaded;
    ++loaded_;
    ++stats.uploaded;
  }
  uploadQueue_.erase(uploadQueue_.begin(), uploadQueue_.begin() + static_cast<std::ptrdiff_t>(taken));
}

namespace {

constexpr Material kProxyGrey{175, 175, 175, 255, 0};
constexpr Material kGround{196, 198, 190, 255, 0};

// A box of eight corners (x fastest, then y, then z: corner c at bits x = c & 1, y = c & 2,
// z = c & 4), each face its material: +x, -x, +y, -y, +z, -z.
void addBox(TriangleMesh& mesh, const std::array<glm::dvec3, 8>& corner, const std::array<Material, 6>& faces) {
  // Each face's four corners, counter-clockwise seen from outside.
  static constexpr int kFace[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  for (int f = 0; f < 6; ++f) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int k = 0; k < 4; ++k) mesh.positions.push_back(corner[static_cast<std::size_t>(kFace[f][k])]);
    const auto material = static_cast<std::uint16_t>(mesh.materials.size());
    mesh.materials.push_back(faces[static_cast<std::size_t>(f)]);
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
    mesh.triangleMaterial.insert(mesh.triangleMaterial.end(), 2, material);
  }
}

std::array<glm::dvec3, 8> cornersOf(const WorldBox& box) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[static_cast<std::size_t>(i)] = {i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z};
  return c;
}

}  // namespace

// The answers of last frame's queries that have arrived; a query still in flight keeps its
// building's previous answer.
void CityRenderer::collectOcclusion() {
  for (Building& b : buildings_) {
    if (b.query.get() == 0) continue;
    GLuint available = 0;
    gl_->GetQueryObjectuiv(b.query.get(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) continue;
    GLuint passed = 0;
    gl_->GetQueryObjectuiv(b.query.get(), GL_QUERY_RESULT, &passed);
    b.occluded = passed == 0;
    b.query = {};
  }
}

namespace {

// A building's box enlarged by 1 % and 5 cm, so that its own surfaces never hide its probe.
WorldBox probeBox(const WorldBox& box) {
  const glm::dvec3 grow = 0.01 * box.size() + 0.05;
  return {box.min - grow, box.max + grow};
}

// Whether p lies in the box: an eye inside a probe box cannot test it.
bool holds(const WorldBox& box, const glm::dvec3& p) {
  return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x && p.y <= box.max.y &&
         p.z <= box.max.z;
}

}  // namespace

// After the frame: one query per building drawn (or skipped as occluded), its probe box against
// the frame's depth.
Status CityRenderer::issueOcclusionQueries(const FrameView& view, const std::vector<std::size_t>& tested) {
  TriangleMesh probes;
  std::vector<std::size_t> order;
  for (std::size_t i : tested) {
    Building& b = buildings_[i];
    if (b.query.get() != 0) continue;  // the last one has not answered yet
    addBox(probes, cornersOf(probeBox(*b.bounds)), {kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey});
    order.push_back(i);
  }
  if (order.empty()) return Ok{};
  auto gpu = GpuMesh::upload(*gl_, probes);
  if (!gpu) return gpu.error();
  constexpr GLsizei kBoxVertices = 36;
  for (std::size_t k = 0; k < order.size(); ++k) {
    Building& b = buildings_[order[k]];
    b.query = makeQuery(*gl_);
    gl_->BeginQuery(GL_ANY_SAMPLES_PASSED, b.query.get());
    meshRenderer_->probe(view, *gpu, static_cast<GLint>(k) * kBoxVertices, kBoxVertices);
    gl_->EndQuery(GL_ANY_SAMPLES_PASSED);
  }
  return Ok{};
}

Status CityRenderer::drawBoxes(const FrameView& view, const TriangleMesh& boxes) const {
  if (boxes.triangles.empty()) return Ok{};
  auto gpu = GpuMesh::upload(*gl_, boxes);
  if (!gpu) return gpu.error();
  meshRenderer_->drawOpaque(view, *gpu);
  return Ok{};
}

// Receive, cull, upload a slice and request what the view needs next; the visible buildings,
// nearest first.
std::vector<CityRenderer::Visible> CityRenderer::prepare(const FrameView& view, bool lodAuto, CityFrameStats& stats) {
  ++frame_;
  receive(stats);
  const Camera& camera = view.camera;
  std::vector<Visible> visible;
  for (std::size_t i = 0; i < buildings_.size(); ++i) {
    const Building& b = buildings_[i];
    if (b.state == State::Failed) continue;
    if (options_.frustumCulling && b.bounds && !mayBeVisible(*b.bounds, view)) {
      ++stats.culledByFrustum;
      continue;
    }
    // Distance of a building from the eye: to its box's centre, else to its origin.
    const glm::dvec3 centre = b.bounds ? b.bounds->centre() : b.originM;
    visible.push_back({i, glm::length(centre - camera.eye)});
    buildings_[i].lastSeen = frame_;
  }
  std::stable_sort(visible.begin(), visible.end(), [](const Visible& a, const Visible& b) { return a.distance < b.distance; });
  upload(stats);

  // The nearest visible buildings not yet asked for go to the loaders, as many as they may hold.
  std::size_t outstanding = loader_.outstanding();
  for (const Visible& v : visible) {
    Building& b = buildings_[v.building];
    if (b.state == State::Loaded) continue;
    ++stats.waiting;
    if (b.state != State::Unrequested || outstanding >= options_.maxOutstanding) continue;
    // The image with the level of its complement the camera wants now.
    LoadRequest request{v.building, base_ + "/" + city_.buildings[v.building].hni, "", 0};
    if (!b.complement.empty()) {
      request.complementLevel = wantedLevel(v.building, camera, lodAuto);
      request.complement = levelLocation(v.building, request.complementLevel);
      b.complement[request.complementLevel].requested = true;
    }
    loader_.request(std::move(request));
    b.state = State::Requested;
    refetched_ += b.evicted ? 1 : 0;
    ++outstanding;
  }
  settled_ = stats.waiting == 0 && uploadQueue_.empty() && loader_.outstanding() == 0;
  return visible;
}

Status CityRenderer::streamIn(const Camera& camera, double timeoutSeconds) {
  const FrameView view(camera);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
  while (true) {
    CityFrameStats stats;
    prepare(view, false, stats);
    if (settled_) return Ok{};
    if (std::chrono::steady_clock::now() > deadline)
      return Error{"the city did not stream in within " + std::to_string(timeoutSeconds) + " s"};
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

Status CityRenderer::drawFrame(const Camera& camera, const RayCastOptions& options, CityFrameStats& stats) {
  stats = {};
  const FrameView view(camera);
  const bool occlusion = options_.occlusionCulling && meshRenderer_;
  if (occlusion) collectOcclusion();
  const std::vector<Visible> visible = prepare(view, options.lodAuto, stats);

  // Boxes first, which the depth test then keeps in front of what is ray-cast behind them: the
  // ground, the proxies of what is still streaming in, and the far buildings as their summaries.
  TriangleMesh boxes;
  std::vector<bool> summarised(buildings_.size(), false);
  if (meshRenderer_) {
    if (options_.ground && !buildings_.empty()) {
      WorldBox all{glm::dvec3(1e300), glm::dvec3(-1e300)};
      for (const Building& b : buildings_) {
        const WorldBox box = b.bounds ? *b.bounds : WorldBox{b.originM, b.originM};
        all.min = glm::min(all.min, box.min);
        all.max = glm::max(all.max, box.max);
      }
      const double margin = 0.5 * glm::length(all.size()) + 100.0;
      const WorldBox ground{{all.min.x - margin, all.min.y - 0.1, all.min.z - margin},
                            {all.max.x + margin, all.min.y, all.max.z + margin}};
      addBox(boxes, cornersOf(ground), {kGround, kGround, kGround, kGround, kGround, kGround});
    }
    for (const Visible& v : visible) {
      const Building& b = buildings_[v.building];
      if (b.state != State::Loaded && options_.proxies && b.bounds) {
        addBox(boxes, cornersOf(*b.bounds), {kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey, kProxyGrey});
        ++stats.proxies;
      }
      const double largest = std::max({b.rootSizeM.x, b.rootSizeM.y, b.rootSizeM.z});
      if (b.state == State::Loaded && options_.summaryBelowPx > 0 &&
          largest < options_.summaryBelowPx * std::max(v.distance, 1e-3) * view.pixelAngle) {
        std::array<glm::dvec3, 8> corner;
        for (int c = 0; c < 8; ++c)
          corner[static_cast<std::size_t>(c)] =
              b.originM + b.worldFromRoot * (b.rootSizeM * glm::dvec3(c & 1 ? 1 : 0, c & 2 ? 1 : 0, c & 4 ? 1 : 0));
        std::array<Material, 6> faces;
        for (int f = 0; f < 6; ++f) {
          const Rgba8 colour = b.summary[static_cast<std::size_t>(f)];
          faces[static_cast<std::size_t>(f)] = {colour.r, colour.g, colour.b, 255, 0};
        }
        addBox(boxes, corner, faces);
        summarised[v.building] = true;
        ++stats.asSummary;
      }
    }
    if (Status s = drawBoxes(view, boxes); !s) return s;
  }

  // One instanced draw per page, pages in the order of their nearest building; within a page
  // nearest first, so that early depth rejection spares what lies behind.
  std::vector<std::vector<HniInstance>> perPage(static_cast<std::size_t>(pages_.pageCount()));
  std::vector<int> pageOrder;
  std::vector<std::size_t> tested;    // the buildings this frame's occlusion queries test
  std::vector<GpuMesh*> meshes;       // the complementary meshes of those drawn, at their levels
  const auto add = [&](std::size_t i) {
    if (summarised[i]) return;
    const Building& b = buildings_[i];
    const bool testable = occlusion && !holds(probeBox(*b.bounds), camera.eye);
    if (testable) tested.push_back(i);
    if (testable && b.occluded) {
      ++stats.culledByOcclusion;
      return;
    }
    if (GpuMesh* mesh = complementToDraw(i, camera, options.lodAuto)) {
      meshes.push_back(mesh);
      stats.complementTriangles += mesh->triangleCount();
    }
    auto& instances = perPage[static_cast<std::size_t>(b.slot.page)];
    if (instances.empty()) pageOrder.push_back(b.slot.page);
    instances.push_back({b.slot.origin, b.originM, b.worldFromRoot});
    ++stats.drawn;
  };
  if (options_.frontToBack) {
    for (const Visible& v : visible)
      if (buildings_[v.building].state == State::Loaded) add(v.building);
  } else {
    std::vector<std::size_t> inOrder;
    for (const Visible& v : visible)
      if (buildings_[v.building].state == State::Loaded) inOrder.push_back(v.building);
    std::sort(inOrder.begin(), inOrder.end());
    for (std::size_t i : inOrder) add(i);
  }
  // Opaque meshes before the HNIs and translucent ones after, as OffscreenRenderer draws a scene.
  for (const GpuMesh* mesh : meshes) meshRenderer_->drawOpaque(view, *mesh);
  for (int page : pageOrder)
    hniRenderer_->draw(view, pages_.page(page), perPage[static_cast<std::size_t>(page)], options);
  for (GpuMesh* mesh : meshes) meshRenderer_->drawTranslucent(view, *mesh);
  if (occlusion)
    if (Status s = issueOcclusionQueries(view, tested); !s) return s;

  stats.known = buildings_.size();
  stats.loaded = loaded_;
  stats.failed = failed_;
  stats.bytesStreamed = bytesStreamed_;
  stats.atlasBytes = pages_.bytes();
  stats.evicted = evicted_;
  stats.refetched = refetched_;
  if (const GLenum error = gl_->GetError(); error != GL_NO_ERROR) return Error{"GL frame: " + glErrorName(error)};
  return Ok{};
}

}  // namespace nut::viewer
