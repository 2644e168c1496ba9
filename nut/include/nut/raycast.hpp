// nut/raycast.hpp — the CPU reference ray caster over an encoded HNI (paper section 6).
//
// It reads the image through HniView with the lookups the GLSL shader makes: NUT traversal (the
// boundary a step reaches is the one the shader reads through the j numbers, taken from a table
// read once per block), redirection landing (record, ray transform, lower header, landing cell by
// random access), a fixed-size stack to return to parents, wrapping, the 69 solids, plane cells
// (version 3), translucent cells that tint and continue, level of detail from visual summaries,
// and an iteration cap. It computes in float, as the shader does; the exact path (exact_path.hpp) is the
// double-precision ground truth it is tested against. docs/RENDERING.md defines the output.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/hierarchy.hpp>
#include <nut/hni_view.hpp>
#include <nut/image.hpp>

namespace nut {

enum class Lookup { Heuristic, Exact };

struct RayCastOptions {
  Lookup lookup = Lookup::Heuristic;
  // Stop descending into a redirection cell whose projected size is below this many pixels and
  // use the visual summary of the face hit instead. 0 = full detail.
  double lodPx = 0.0;
  // Cell steps and landings per ray; a ray that reaches the cap ends with kCappedColour.
  int maxIterations = 512;
  // Level of detail from measured error (--lod auto): draw a redirection's target as its visual
  // summary where one pixel spans more than the footprint its record carries (version 2 files).
  bool lodAuto = false;
  // Draw each opaque hit in the colour of the iterations its ray took (nut/heat_map.hpp), unshaded
  // and untinted; rays that reach no opaque surface are drawn as usual.
  bool heatMap = false;
  // renderHni traces each tile's rays together on the CPU's SIMD lanes (traceMany) instead of one
  // at a time with trace(), the reference. Both give the same image to the bit; the packets are
  // slower on the CPUs measured (docs/BENCHMARKS.md, "Packets").
  bool packets = false;
};

// Levels of the traversal stack: deeper redirections are drawn as their visual summary.
inline constexpr int kMaxStackDepth = 32;
// The colour of a ray that reached the iteration cap (magenta: never a building colour).
inline constexpr std::array<std::uint8_t, 3> kCappedColour{255, 0, 255};

// What one ray found.
struct RayResult {
  bool hit = false;                                  // an opaque surface (or LOD summary) was reached
  double distanceM = 0.0;                            // along the ray to that surface
  glm::dvec3 normal{0.0};                            // world unit normal there, facing the ray
  std::array<std::uint8_t, 3> colour = kBackground;  // shaded, translucent tints composited
  int iterations = 0;
  bool capped = false;
};

struct RayPacketTables;

// A prepared HNI: the image (kept by reference) and its block headers, decoded once.
class HniRayCaster {
 public:
  // The image must be valid (validate()); originM is the world position of the root block origin,
  // and worldFromRoot turns the root block's axes into the world's (a rotation: a city manifest's
  // yaw_deg, docs/CITY.md), about that origin.
  // rootBlock renders another block of the file alone, as its root (level-of-detail measurement).
  HniRayCaster(const Image& image, const glm::dvec3& originM, const glm::dmat3& worldFromRoot = glm::dmat3(1.0),
               std::optional<BlockId> rootBlock = std::nullopt);

  // World bounding box of the root block (of its turned corners).
  WorldBox bounds() const;
  const glm::dvec3& originM() const { return originM_; }

  // One ray: world origin and unit direction; pixelAngle is the angle one pixel subtends (radians),
  // used only for level of detail.
  RayResult trace(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle,
                  const RayCastOptions& options) const;

  // Many rays traced together (raycast_packet.cpp): each lane of the widest SIMD unit the CPU has
  // (Google Highway, chosen at run time) walks one ray and takes the next when its ray ends. Empty
  // cells and redirections are walked on the lanes; a ray that meets anything else (a surface, a
  // level-of-detail summary, the iteration cap) is handed to trace()'s walk where it stands, as is
  // each of the last rays when too few remain to fill a quarter of the lanes. originsM holds one
  // origin per ray, or one for all. results[i] is, to the bit,
  // trace(originsM[i], directions[i], pixelAngle, options).
  void traceMany(std::span<const glm::dvec3> originsM, std::span<const glm::dvec3> directions, double pixelAngle,
                 const RayCastOptions& options, std::span<RayResult> results) const;

  // A block header decoded once, with its axis views (the shader re-reads these at each landing)
  // and each axis's boundaries b_0 = 0 .. b_W = D in units, as the heuristic and the exact
  // lookups place them, read once by following the j numbers from boundary to boundary as the
  // shader's steps do: a step of this caster takes its new boundary from the table.
  struct Block {
    BlockHeader header;
    std::array<AxisView, 3> axes;
    std::array<std::vector<float>, 3> heuristicBounds, exactBounds;
    const std::uint8_t* bottomRow;  // data pixel of cell (0, 0, 0): rows run upwards from here
    std::ptrdiff_t rowBytes;
    const std::uint8_t* cellTexel(const glm::ivec3& c) const {
      return bottomRow + 4 * (c.x + c.z * header.cells.x) - rowBytes * c.y;
    }
  };

 private:
  // A redirection record decoded once: the casters read it at every landing.
  struct Redirect {
    glm::mat3 rotation;  // target frame -> cell frame
    glm::vec3 offset;    // units
    int target = 0;      // index into blocks_
    std::uint8_t wrap = 0;
    bool unrotated = true;   // most redirections: the ray needs no transform, only the offset
    float lodFootprint = 0;  // units; 0 = none
  };

  // A plane cell record decoded once, in float and units like the traversal.
  struct PlaneCell {
    std::array<glm::vec3, 2> normals;  // unit, in the block's frame
    std::array<float, 2> offsets;      // units
    PlaneCombine combine;
    std::uint16_t material;                      // the box's sides
    std::array<std::uint16_t, 2> surfaceMaterials;  // each plane's surface
  };

  // One ray's traversal (ray_walk.hpp), with the lookup's boundaries.
  template <Lookup mode>
  class Walk;
  friend struct RayPackets;  // the packet caster's access to the tables and the walk
  int blockAt(TexelAddress header) const;
  void addPlaneCell(std::uint32_t packedRecord);

  const Image& image_;
  HniView view_;
  glm::dvec3 originM_;
  glm::dmat3 rootFromWorld_;  // the transpose of worldFromRoot: rays into the root's frame
  glm::mat3 worldFromRoot_;   // the root level's rotation to the world, as each ray starts it
  std::vector<Block> blocks_;
  std::vector<int> blockByHeader_;  // 256 * v + u -> index into blocks_, or -1
  std::vector<Redirect> redirects_;
  std::vector<int> redirectByRecord_;  // 256 * v + u -> index into redirects_, or -1
  std::vector<PlaneCell> planeCells_;
  std::unordered_map<std::uint32_t, int> planeCellByRecord_;  // packed record address -> planeCells_
  std::vector<Material> materials_;    // the material table, decoded once like the headers
  int root_ = 0;
  FileRecord file_;
  std::shared_ptr<const RayPacketTables> packetTables_;  // the above, flattened for SIMD gathers
};

struct RenderOutput {
  Image colour;                    // RGBA8, alpha 255
  std::vector<float> distanceM;    // per pixel, +infinity where nothing was hit
  std::vector<float> windowDepth;  // per pixel in [0, 1], 1 where nothing was hit
  std::vector<std::uint16_t> iterations;
};

struct RenderStats {
  double seconds = 0;
  double raysPerSecond = 0;
  double iterationsMean = 0;
  int iterationsMax = 0;
  double cappedPct = 0;
  int threads = 0;
};

// One ray of a renderer: world origin, unit direction and the angle one pixel subtends.
using RayFunction = std::function<RayResult(const glm::dvec3& originM, const glm::dvec3& direction, double pixelAngle)>;

// Renders every pixel of the camera's image with `threads` threads (0 = all cores), in 16x16 tiles
// handed out in order, by casting its ray with `trace`; the output does not depend on the thread
// count.
RenderOutput renderRays(const Camera& camera, const RayFunction& trace, int threads = 0, RenderStats* stats = nullptr);

// renderRays with the caster.
RenderOutput renderHni(const HniRayCaster& caster, const Camera& camera, const RayCastOptions& options, int threads = 0,
                       RenderStats* stats = nullptr);

}  // namespace nut
