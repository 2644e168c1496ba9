// viewer/city_renderer.hpp — a city manifest streamed and drawn frame by frame: the buildings the
// camera can see are requested nearest first from the loader threads, uploaded into atlas pages in
// bounded slices per frame, and ray-cast front to back, one instanced draw per page. The frame
// never waits for a file. What each frame skips is counted (docs/VIEWER.md).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>

#include <viewer/atlas_pages.hpp>
#include <viewer/city_loader.hpp>
#include <viewer/frame_view.hpp>
#include <viewer/gl_object.hpp>
#include <viewer/hni_renderer.hpp>
#include <viewer/mesh_renderer.hpp>

namespace nut::viewer {

struct CityRendererOptions {
  bool frustumCulling = true;
  // Occlusion culling (needs a MeshRenderer): each frame, every drawn building's box, enlarged by
  // 1 % and 5 cm, is depth-tested against the finished frame in an occlusion query; a building
  // none of whose box passed is skipped the next frame, and tested again after it. A building
  // whose box holds the eye is always drawn.
  bool occlusionCulling = true;
  bool frontToBack = true;
  // Boxes (drawn when the renderer has a MeshRenderer): a visible building not loaded yet as its
  // box in a neutral grey (the manifest's bounds_m); a loaded building whose largest side spans
  // fewer than summaryBelowPx pixels as its root block with each face its visual summary's colour
  // (0: never); and a ground plane under the city.
  bool proxies = true;
  double summaryBelowPx = 0;
  bool ground = false;
  int loaderThreads = 2;
  std::size_t maxOutstanding = 16;                 // requests in the loaders' hands at once
  std::size_t uploadBytesPerFrame = 4u << 20;      // at least one HNI a frame is uploaded
  // The memory budget: pages of atlasPageSize^2 texels (4 bytes each), at most maxAtlasPages.
  // When they are full, the page whose buildings were seen least recently is emptied (its
  // buildings go back to unloaded, fetched again when seen), never one seen this frame.
  int atlasPageSize = 4096;
  int maxAtlasPages = 16;
};

struct CityFrameStats {
  std::size_t known = 0;           // buildings in the manifest
  std::size_t loaded = 0;          // in the atlas
  std::size_t failed = 0;          // missing, unreadable, corrupt or invalid: never drawn
  std::size_t drawn = 0;           // ray-cast this frame
  std::size_t culledByFrustum = 0; // outside the view (known boxes only)
  std::size_t culledByOcclusion = 0;  // in the view, hidden in the last frame that tested it
  std::size_t waiting = 0;         // visible, not loaded yet
  std::size_t proxies = 0;         // of those, drawn as their box
  std::size_t asSummary = 0;       // loaded, drawn as their summary box
  std::size_t complementTriangles = 0;  // of the complementary meshes drawn, at the levels drawn
  std::size_t uploaded = 0;        // HNIs uploaded this frame
  std::size_t evicted = 0;         // buildings whose page was emptied, so far
  std::size_t refetched = 0;       // requests, so far, for buildings evicted before
  bool overBudget = false;         // this frame could not upload: every page holds what it sees
  std::size_t bytesStreamed = 0;   // fetched so far
  std::size_t atlasBytes = 0;
  std::vector<std::string> newFailures;  // this frame's, one message each
};

class CityRenderer {
 public:
  // `base` is the manifest's folder (or URL prefix): a building's location is base + "/" + hni.
  // `meshRenderer` draws the complementary meshes, proxies, summaries and ground, and probes
  // for occlusion; without one none of these are drawn or fetched.
  CityRenderer(const Gl& gl, const HniRenderer& hniRenderer, const MeshRenderer* meshRenderer, scene::CityManifest city,
               std::string base, Fetch fetch, const CityRendererOptions& options);

  // Takes what the loaders finished, uploads a slice, requests what the camera needs next and
  // draws into the bound framebuffer (its depth test and blending as HniRenderer::draw).
  Status drawFrame(const Camera& camera, const RayCastOptions& options, CityFrameStats& stats);

  // Streams in what the camera sees without drawing (a single image: `nut render --backend gl`),
  // waiting at most timeoutSeconds.
  Status streamIn(const Camera& camera, double timeoutSeconds);

  // No building left to load that the last frame could see, and nothing in the loaders' hands.
  bool settled() const { return settled_; }

  // The culling and order switches may change between frames (the viewer's overlay).
  void setFrustumCulling(bool on) { options_.frustumCulling = on; }
  void setFrontToBack(bool on) { options_.frontToBack = on; }
  void setOcclusionCulling(bool on) { options_.occlusionCulling = on; }
  void setSummaryBelowPx(double px) { options_.summaryBelowPx = px; }

 private:
  enum class State { Unrequested, Requested, Loaded, Failed };
  struct Building {
    State state = State::Unrequested;
    std::size_t lastSeen = 0;  // the last frame (from 1) that found it visible
    bool evicted = false;      // loaded once and evicted since
    glm::dvec3 originM{0.0};
    glm::dmat3 worldFromRoot{1.0};
    std::optional<WorldBox> bounds;  // the manifest's until loaded, then the image's
    AtlasSlot slot;
    glm::dvec3 rootSizeM{0.0};       // once loaded: the root block's size and summary
    VisualSummary summary{};
    // When the manifest names a complementary mesh (and there is a MeshRenderer): its levels, 0 the
    // mesh itself and k its k-th coarser level (complement_levels), each fetched when a frame first
    // wants it, and the box of those loaded (world metres).
    struct MeshLevel {
      std::optional<GpuMesh> mesh;
      bool requested = false;
    };
    std::vector<MeshLevel> complement;
    std::optional<WorldBox> complementBox;
    GlObject query;                  // its occlusion query, while one is in flight
    bool occluded = false;           // the last query's answer
  };
  struct Visible {
    std::size_t building;
    double distance;  // from the eye
  };
  std::vector<Visible> prepare(const FrameView& view, bool lodAuto, CityFrameStats& stats);
  void receive(CityFrameStats& stats);
  void fail(std::size_t building, const std::string& message, CityFrameStats& stats);
  bool addComplementLevel(LoadedHni& loaded, CityFrameStats& stats);
  std::size_t wantedLevel(std::size_t building, const Camera& camera, bool lodAuto) const;
  std::string levelLocation(std::size_t building, std::size_t level) const;
  GpuMesh* complementToDraw(std::size_t building, const Camera& camera, bool lodAuto);
  Status drawBoxes(const FrameView& view, const TriangleMesh& boxes) const;
  void collectOcclusion();
  Status issueOcclusionQueries(const FrameView& view, const std::vector<std::size_t>& drawn);
  void upload(CityFrameStats& stats);
  bool evictLeastRecentlySeenPage();

  const Gl* gl_;
  const HniRenderer* hniRenderer_;
  const MeshRenderer* meshRenderer_;
  scene::CityManifest city_;
  std::string base_;
  CityRendererOptions options_;
  std::vector<Building> buildings_;
  std::vector<LoadedHni> uploadQueue_;  // decoded, waiting for their frame's slice
  AtlasPages pages_;
  CityLoader loader_;
  std::size_t bytesStreamed_ = 0, loaded_ = 0, failed_ = 0, evicted_ = 0, refetched_ = 0, frame_ = 0;
  bool settled_ = false;
};

// Whether any part of the box may lie in the camera's view (its four side planes and near and
// far): false only when all eight corners are outside one plane.
bool mayBeVisible(const WorldBox& box, const FrameView& view);

}  // namespace nut::viewer
