// The mesh reference renderer over Embree 3: one static scene of triangles, one rtcIntersect1 per
// pixel (and one more per translucent face passed), shaded with nut::shade.
#include <meshref/embree_renderer.hpp>

#include <algorithm>
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

MeshHit EmbreeRenderer::trace(const glm::dvec3& originM, const glm::dvec3& direction) const {
  const Scene& s = *scene_;
  // The subtraction happens in double: world coordinates may be near 10^6 m (city origins).
  const glm::dvec3 origin = originM - s.centre;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  MeshHit result;
  Composite composite;
  float tNear = 0.0f;
  double lastLayerM = -1.0;
  for (int layer = 0; layer < kMaxTranslucentLayers; ++layer) {
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
    rtcIntersect1(s.scene, &context, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;

    const std::uint32_t triangle = rayHit.hit.primID;
    glm::dvec3 normal = s.normals[triangle];
    double distanceM = rayHit.ray.tfar;
    const double facing = glm::dot(normal, direction);
    if (std::abs(facing) > 1e-9) {
      distanceM = (s.planeOffsets[triangle] - glm::dot(normal, origin)) / facing;
    } else if (normal == glm::dvec3(0.0)) {
      // Degenerate in double but not after rounding to float: Embree's own normal is all there is.
      normal = glm::normalize(glm::dvec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z));
    }
    const Material& m = s.materials[triangle];
    const auto colour = shade({m.r, m.g, m.b}, normal, direction);
    if (m.opacity == 255) {
      result.hit = true;
      result.distanceM = distanceM;
      result.normal = glm::dot(normal, direction) > 0 ? -normal : normal;
      result.triangle = triangle;
      result.colour = composite.finish(colour);
      return result;
    }
    // A translucent surface is one layer even where the ray meets it twice at the same distance
    // (the shared edge of two triangles, a duplicated face, or the same face again after rounding).
    if (distanceM > lastLayerM + 1e-6 * std::max(1.0, distanceM)) {
      composite.add(colour, m.opacity / 255.0);
      lastLayerM = distanceM;
    }
    tNear = std::nextafter(rayHit.ray.tfar, kFloatInfinity);
  }
  result.colour = composite.finish(kBackground);
  return result;
}

MeshRenderOutput EmbreeRenderer::render(const Camera& camera, int threads, MeshRenderStats* stats) const {
  const auto start = std::chrono::steady_clock::now();
  MeshRenderOutput out;
  out.colour = Image(camera.width, camera.height);
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
  out.distanceM.assign(pixels, std::numeric_limits<float>::infinity());
  const RayGenerator rays(camera);
  const int count = forEachPixelInTiles(camera.width, camera.height, threads, [&](int x, int y) {
    const MeshHit h = trace(camera.eye, rays.direction(x, y));
    std::uint8_t* p = out.colour.at(x, y);
    p[0] = h.colour[0], p[1] = h.colour[1], p[2] = h.colour[2], p[3] = 255;
    if (h.hit)
      out.distanceM[static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x)] =
          static_cast<float>(h.distanceM);
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
