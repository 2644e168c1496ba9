// A city manifest streamed and drawn frame by frame (viewer/city_renderer.hpp).
#include <viewer/city_renderer.hpp>

#include <algorithm>
#include <array>

#include <glm/geometric.hpp>

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

CityRenderer::CityRenderer(const Gl& gl, const HniRenderer& hniRenderer, scene::CityManifest city, std::string base,
                           Fetch fetch, const CityRendererOptions& options)
    : gl_(&gl),
      hniRenderer_(&hniRenderer),
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
    buildings_.push_back(building);
  }
}

// Finished loads join the upload queue; failures are final.
void CityRenderer::receive(CityFrameStats& stats) {
  for (LoadedHni& loaded : loader_.takeFinished()) {
    bytesStreamed_ += loaded.bytes;
    if (loaded.image) {
      uploadQueue_.push_back(std::move(loaded));
      continue;
    }
    buildings_[loaded.building].state = State::Failed;
    ++failed_;
    stats.newFailures.push_back(city_.buildings[loaded.building].name + ": " + loaded.image.error().message);
  }
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
    if (!pages_.fits(*loaded.image) && !evictLeastRecentlySeenPage()) {
      stats.overBudget = true;  // stays queued until the view moves on
      break;
    }
    bytes += loaded.image->pixels.size();
    auto slot = pages_.place(*loaded.image);
    if (!slot) {
      b.state = State::Failed;
      ++failed_;
      stats.newFailures.push_back(city_.buildings[loaded.building].name + ": " + slot.error().message);
      continue;
    }
    b.slot = *slot;
    b.bounds = HniRayCaster(*loaded.image, b.originM, b.worldFromRoot).bounds();
    b.state = State::Loaded;
    ++loaded_;
    ++stats.uploaded;
  }
  uploadQueue_.erase(uploadQueue_.begin(), uploadQueue_.begin() + static_cast<std::ptrdiff_t>(taken));
}

Status CityRenderer::drawFrame(const Camera& camera, const RayCastOptions& options, CityFrameStats& stats) {
  stats = {};
  ++frame_;
  receive(stats);
  const FrameView view(camera);
  // Distance of a building from the eye: to its box's centre, else to its origin.
  struct Visible {
    std::size_t building;
    double distance;
  };
  std::vector<Visible> visible;
  for (std::size_t i = 0; i < buildings_.size(); ++i) {
    const Building& b = buildings_[i];
    if (b.state == State::Failed) continue;
    if (options_.frustumCulling && b.bounds && !mayBeVisible(*b.bounds, view)) {
      ++stats.culledByFrustum;
      continue;
    }
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
    loader_.request(v.building, base_ + "/" + city_.buildings[v.building].hni);
    b.state = State::Requested;
    refetched_ += b.evicted ? 1 : 0;
    ++outstanding;
  }

  // One instanced draw per page, pages in the order of their nearest building; within a page
  // nearest first, so that early depth rejection spares what lies behind.
  std::vector<std::vector<HniInstance>> perPage(static_cast<std::size_t>(pages_.pageCount()));
  std::vector<int> pageOrder;
  const auto add = [&](const Building& b) {
    auto& instances = perPage[static_cast<std::size_t>(b.slot.page)];
    if (instances.empty()) pageOrder.push_back(b.slot.page);
    instances.push_back({b.slot.origin, b.originM, b.worldFromRoot});
    ++stats.drawn;
  };
  if (options_.frontToBack) {
    for (const Visible& v : visible)
      if (buildings_[v.building].state == State::Loaded) add(buildings_[v.building]);
  } else {
    std::vector<std::size_t> inOrder;
    for (const Visible& v : visible)
      if (buildings_[v.building].state == State::Loaded) inOrder.push_back(v.building);
    std::sort(inOrder.begin(), inOrder.end());
    for (std::size_t i : inOrder) add(buildings_[i]);
  }
  for (int page : pageOrder)
    hniRenderer_->draw(view, pages_.page(page), perPage[static_cast<std::size_t>(page)], options);

  stats.known = buildings_.size();
  stats.loaded = loaded_;
  stats.failed = failed_;
  stats.bytesStreamed = bytesStreamed_;
  stats.atlasBytes = pages_.bytes();
  stats.evicted = evicted_;
  stats.refetched = refetched_;
  settled_ = stats.waiting == 0 && uploadQueue_.empty() && loader_.outstanding() == 0;
  if (const GLenum error = gl_->GetError(); error != GL_NO_ERROR) return Error{"GL frame: " + glErrorName(error)};
  return Ok{};
}

}  // namespace nut::viewer
