// The mesh reference renderer over Embree 3: one static scene of triangles; primary rays one at a
// time, in packets or as a stream (EmbreeRays), one rtcIntersect1 more per translucent face
// passed; shaded with nut::shade.
#include <meshref/embree_renderer.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include <nut/render_loop.hpp>

namespace nut::meshref {

using scene::MeshHit;

namespace {

constexpr float kFloatInfinity = std::numeric_limits<float>::infinity();

// What a ray has composited so far on its way through translucent faces.
struct LayerWalk {
  Composite composite;
  double lastLayerM = -1.0;
};

// A ray for Embree from `origin` (in Embree's frame) along `direction`, beyond tNear, no hit yet.
RTCRayHit firstRay(const glm::dvec3& origin, const glm::dvec3& direction, float tNear) {
  RTCRayHit rayHit;
  rayHit.ray.org_x = static_cast<float>(origin.x);
  rayHit.ray.org_y = static_cast<float>(origin.y);
  rayHit.ray.org_z = static_cast<float>(origin.z);
  rayHit.ray.tnear = tNear;
  rayHit.ray.dir_x = static_cast<float>(direction.x);
  rayHit.ray.dir_y = static_cast<float>(direction.y);
  rayHit.ray.dir_z = static_cast<float>(direction.z);
  rayHit.ray.time = 0.0f;
  rayHit.ray.tfar = kFloatInfinity;
  rayHit.ray.mask = ~0u;
  rayHit.ray.id = 0;
  rayHit.ray.flags = 0;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rayHit;
}

// Lane `lane` of a packet's answer, as the one-ray answer the shading reads.
template <typename Packet>
RTCRayHit laneOf(const Packet& packet, int lane) {
  RTCRayHit rayHit;
  rayHit.ray.tfar = packet.ray.tfar[lane];
  rayHit.hit.geomID = packet.hit.geomID[lane];
  rayHit.hit.primID = packet.hit.primID[lane];
  rayHit.hit.Ng_x = packet.hit.Ng_x[lane];
  rayHit.hit.Ng_y = packet.hit.Ng_y[lane];
  rayHit.hit.Ng_z = packet.hit.Ng_z[lane];
  return rayHit;
}

RTCIntersectContext coherentContext() {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return context;
}
}  // namespace

struct EmbreeRenderer::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string firstError;            // from Embree's error callback
  glm::dvec3 centre{0.0};            // world position of the origin of Embree's frame
  WorldBox bounds;
  // Per triangle, in double: the unit normal (zero for a degenerate face) and the plane offset
  // dot(normal, vertex - centre), so hit distances and shading do not inherit float rounding.
  std::vector<glm::dvec3> normals;
  std::vector<double> planeOffsets;
  std::vector<Material> materials;   // per triangle
  double buildSeconds = 0;

  // The ray's answer from Embree's first hit on it, going on one ray at a time past translucent
  // faces. The origin is in Embree's frame.
  MeshHit fromFirstHit(const glm::dvec3& origin, const glm::dvec3& direction, RTCRayHit rayHit) const;
  // Adds one hit to the walk; true when it ends the ray (an opaque face), with `result` set.
  bool addHit(const glm::dvec3& origin, const glm::dvec3& direction, const RTCRayHit& rayHit, LayerWalk& walk,
              MeshHit& result) const;
  // The primary rays of the tile's pixels x0 <= x < x1, y0 <= y < y1 (row 0 first) as packets of
  // kWide x kHigh pixels, each answer handed to store(x, y, hit).
  template <typename Packet, int kWide, int kHigh, typename Store>
  void tracePackets(const glm::dvec3& origin, const RayGenerator& generator, int x0, int y0, int x1, int y1,
                    const Store& store) const;
  // The same as one stream of rays (at most one tile).
  template <typename Store>
  void traceStream(const glm::dvec3& origin, const RayGenerator& generator, int x0, int y0, int x1, int y1,
                   const Store& store) const;

  Scene() = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

Result<EmbreeRenderer> EmbreeRenderer::create(const TriangleMesh& mesh) {
  const auto start = std::chrono::steady_clock::now();
  auto s = std::make_unique<Scene>();
  s->device = rtcNewDevice(nullptr);
  if (!s->device) return Error{"embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")"};
  rtcSetDeviceErrorFunction(
      s->device,
      [](void* user, RTCError, const char* message) {
        auto* scene = static_cast<Scene*>(user);
        if (scene->firstError.empty()) scene->firstError = message ? message : "unknown error";
      },
      s.get());

  s->bounds = mesh.bounds();
  s->centre = s->bounds.centre();
  const std::size_t triangleCount = mesh.triangles.size();
  s->normals.resize(triangleCount);
  s->planeOffsets.resize(triangleCount);
  s->materials.resize(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3 a = mesh.positions[tri[0]] - s->centre, b = mesh.positions[tri[1]] - s->centre,
                     c = mesh.positions[tri[2]] - s->centre;
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    s->normals[t] = length > 0 ? n / length : glm::dvec3(0.0);
    s->planeOffsets[t] = glm::dot(s->normals[t], a);
    s->materials[t] = mesh.materials[mesh.triangleMaterial[t]];
  }

  s->scene = rtcNewScene(s->device);
  // Robust traversal: no ray slips through the shared edge of two triangles of a closed surface.
  rtcSetSceneFlags(s->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), triangleCount));
  if (vertices && indices) {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::dvec3 p = mesh.positions[v] - s->centre;
      vertices[3 * v] = static_cast<float>(p.x);
      vertices[3 * v + 1] = static_cast<float>(p.y);
      vertices[3 * v + 2] = static_cast<float>(p.z);
    }
    for (std::size_t t = 0; t < triangleCount; ++t)
      for (std::size_t k = 0; k < 3; ++k) indices[3 * t + k] = mesh.triangles[t][k];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(s->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(s->scene);
  if (rtcGetDeviceError(s->device) != RTC_ERROR_NONE || !s->firstError.empty())
    return Error{"embree: cannot build the scene: " + (s->firstError.empty() ? std::string("unknown error") : s->firstError)};
  s->buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return EmbreeRenderer(std::move(s));
}

EmbreeRenderer::EmbreeRenderer(std::unique_ptr<Scene> scene) : scene_(std::move(scene)) {}
EmbreeRenderer::EmbreeRenderer(EmbreeRenderer&&) noexcept = default;
EmbreeRenderer& EmbreeRenderer::operator=(EmbreeRenderer&&) noexcept = default;
EmbreeRenderer::~EmbreeRenderer() = default;

WorldBox EmbreeRenderer::bounds() const { return scene_->bounds; }

double EmbreeRenderer::buildSeconds() const { return scene_->buildSeconds; }

bool EmbreeRenderer::Scene::addHit(const glm::dvec3& origin, const glm::dvec3& direction, const RTCRayHit& rayHit,
                                   LayerWalk& walk, MeshHit& result) const {
  const std::uint32_t triangle = rayHit.hit.primID;
  glm::dvec3 normal = normals[triangle];
  double distanceM = rayHit.ray.tfar;
  const double facing = glm::dot(normal, direction);
  if (std::abs(facing) > 1e-9) {
    distanceM = (planeOffsets[triangle] - glm::dot(normal, origin)) / facing;
  } else if (normal == glm::dvec3(0.0)) {
    // Degenerate in double but not after rounding to float: Embree's own normal is all there is.
    normal = glm::normalize(glm::dvec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z));
  }
  const Material& m = materials[triangle];
  const auto colour = shade({m.r, m.g, m.b}, normal, direction);
  if (m.opacity == 255) {
    result.hit = true;
    result.distanceM = distanceM;
    result.normal = glm::dot(normal, direction) > 0 ? -normal : normal;
    result.triangle = triangle;
    result.colour = walk.composite.finish(colour);
    return true;
  }
  // A translucent surface is one layer even where the ray meets it twice at the same distance
  // (the shared edge of two triangles, a duplicated face, or the same face again after rounding).
  if (distanceM > walk.lastLayerM + 1e-6 * std::max(1.0, distanceM)) {
    walk.composite.add(colour, m.opacity / 255.0);
    walk.lastLayerM = distanceM;
  }
  return false;
}

MeshHit EmbreeRenderer::Scene::fromFirstHit(const glm::dvec3& origin, const glm::dvec3& direction,
                                            RTCRayHit rayHit) const {
  MeshHit result;
  LayerWalk walk;
  for (int layer = 1; rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID; ++layer) {
    if (addHit(origin, direction, rayHit, walk, result)) return result;
    if (layer == kMaxTranslucentLayers) break;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const float tNear = std::nextafter(rayHit.ray.tfar, kFloatInfinity);
    rayHit = firstRay(origin, direction, tNear);
    rtcIntersect1(scene, &context, &rayHit);
  }
  result.colour = walk.composite.finish(kBackground);
  return result;
}

template <typename Packet, int kWide, int kHigh, typename Store>
void EmbreeRenderer::Scene::tracePackets(const glm::dvec3& origin, const RayGenerator& generator, int x0, int y0,
                                         int x1, int y1, const Store& store) const {
  constexpr int kLanes = kWide * kHigh;
  static_assert(kLanes == 8 || kLanes == 16);
  for (int by = y0; by < y1; by += kHigh)
    for (int bx = x0; bx < x1; bx += kWide) {
      Packet packet;
      alignas(64) std::array<int, kLanes> valid;  // Embree reads the mask with aligned vector loads
      std::array<glm::dvec3, kLanes> directions;
      for (int lane = 0; lane < kLanes; ++lane) {
        const int x = bx + lane % kWide, y = by + lane / kWide;
        valid[lane] = x < x1 && y < y1 ? -1 : 0;
        directions[lane] = valid[lane] ? generator.direction(x, y) : glm::dvec3(0, 0, 1);
        // The lane gets the floats firstRay would give the ray alone.
        const RTCRayHit one = firstRay(origin, directions[lane], 0.0f);
        float* const floats[] = {packet.ray.org_x, packet.ray.org_y, packet.ray.org_z, packet.ray.dir_x,
                                 packet.ray.dir_y, packet.ray.dir_z, packet.ray.tnear, packet.ray.tfar,
                                 packet.ray.time};
        const float values[] = {one.ray.org_x, one.ray.org_y, one.ray.org_z, one.ray.dir_x, one.ray.dir_y,
                                one.ray.dir_z, one.ray.tnear, one.ray.tfar, one.ray.time};
        for (std::size_t f = 0; f < std::size(floats); ++f) floats[f][lane] = values[f];
        packet.ray.mask[lane] = one.ray.mask;
        packet.ray.id[lane] = one.ray.id;
        packet.ray.flags[lane] = one.ray.flags;
        packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
      }
      RTCIntersectContext context = coherentContext();
      if constexpr (kLanes == 8)
        rtcIntersect8(valid.data(), scene, &context, &packet);
      else
        rtcIntersect16(valid.data(), scene, &context, &packet);
      for (int lane = 0; lane < kLanes; ++lane)
        if (valid[lane])
          store(bx + lane % kWide, by + lane / kWide, fromFirstHit(origin, directions[lane], laneOf(packet, lane)));
    }
}

template <typename Store>
void EmbreeRenderer::Scene::traceStream(const glm::dvec3& origin, const RayGenerator& generator, int x0, int y0, int x1,
                                        int y1, const Store& store) const {
  std::array<RTCRayHit, kRenderTile * kRenderTile> stream;
  std::array<glm::dvec3, kRenderTile * kRenderTile> directions;
  unsigned count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++count) {
      directions[count] = generator.direction(x, y);
      stream[count] = firstRay(origin, directions[count], 0.0f);
    }
  RTCIntersectContext context = coherentContext();
  rtcIntersect1M(scene, &context, stream.data(), count, sizeof(RTCRayHit));
  count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++count) store(x, y, fromFirstHit(origin, directions[count], stream[count]));
}

MeshHit EmbreeRenderer::trace(const glm::dvec3& originM, const glm::dvec3& direction) const {
  // The subtraction happens in double: world coordinates may be near 10^6 m (city origins).
  const glm::dvec3 origin = originM - scene_->centre;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayHit = firstRay(origin, direction, 0.0f);
  rtcIntersect1(scene_->scene, &context, &rayHit);
  return scene_->fromFirstHit(origin, direction, rayHit);
}

MeshRenderOutput EmbreeRenderer::render(const Camera& camera, int threads, MeshRenderStats* stats,
                                        EmbreeRays rays) const {
  const auto start = std::chrono::steady_clock::now();
  MeshRenderOutput out;
  out.colour = Image(camera.width, camera.height);
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
  out.distanceM.assign(pixels, std::numeric_limits<float>::infinity());
  const RayGenerator generator(camera);
  const glm::dvec3 origin = camera.eye - scene_->centre;
  const auto store = [&](int x, int y, const MeshHit& h) {
    std::uint8_t* p = out.colour.at(x, y);
    p[0] = h.colour[0], p[1] = h.colour[1], p[2] = h.colour[2], p[3] = 255;
    if (h.hit)
      out.distanceM[static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x)] =
          static_cast<float>(h.distanceM);
  };
  const int count = forEachTile(camera.width, camera.height, threads, [&](int x0, int y0, int x1, int y1) {
    switch (rays) {
      case EmbreeRays::Single:
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) store(x, y, trace(camera.eye, generator.direction(x, y)));
        break;
      case EmbreeRays::Packet8:
        scene_->tracePackets<RTCRayHit8, 4, 2>(origin, generator, x0, y0, x1, y1, store);
        break;
      case EmbreeRays::Packet16:
        scene_->tracePackets<RTCRayHit16, 4, 4>(origin, generator, x0, y0, x1, y1, store);
        break;
      case EmbreeRays::Stream:
        scene_->traceStream(origin, generator, x0, y0, x1, y1, store);
        break;
    }
  });
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->raysPerSecond = static_cast<double>(pixels) / stats->seconds;
    stats->threads = count;
  }
  return out;
}

Result<std::unique_ptr<const scene::MeshTracer>> traceMeshes(const std::vector<const TriangleMesh*>& meshes) {
  auto merged = mergeMeshes(meshes);
  if (!merged) return merged.error();
  if (merged->triangles.empty()) return std::unique_ptr<const scene::MeshTracer>();
  auto renderer = EmbreeRenderer::create(*merged);
  if (!renderer) return renderer.error();
  return std::unique_ptr<const scene::MeshTracer>(std::make_unique<EmbreeRenderer>(std::move(*renderer)));
}

}  // namespace nut::meshref
