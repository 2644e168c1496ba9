// converter/convert.hpp — the whole mesh-to-NUT conversion (paper section 5) as one call, and its
// report: check and repair the mesh, yaw alignment (align.hpp), solid conversion (solid.hpp), block
// extraction (blocks.hpp), splitting to the format's limits (assemble.hpp), compilation to an HNI
// image.
// docs/CONVERTER.md describes each step and the report's fields.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include <converter/blocks.hpp>
#include <converter/mesh_check.hpp>
#include <converter/solid.hpp>
#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/hni.hpp>
#include <nut/image.hpp>
#include <nut/png_encode.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>

namespace nut::converter {

struct ConvertOptions {
  // What the converter keeps where it converts a building two ways (plane cells or not, a wing in
  // its own frame or not): the smaller files (PNG and gzipped complement GLB), or the larger share
  // of the surface the HNI shows. MostSurface also converts an open mesh as the body under its
  // sheets (sheets.hpp), the sheets drawn as complementary mesh: LoD2 roofs overhanging their
  // walls then become cells, while the files grow (the mesh of a LoD2 house is small).
  enum class Objective { SmallestFiles, MostSurface };
  Objective objective = Objective::SmallestFiles;
  SolidOptions solid;
  BlockOptions blocks;
  CompileOptions compile;
  // Convert a building that is not axis-aligned in its own frame, turned back by a yaw redirection
  // (align.hpp). Not with manual blocks, whose boxes are world boxes.
  bool alignYaw = true;
  // Build the hierarchy from the grid in the axis order whose cells compress best, with a root
  // that turns it back (axis_order.hpp). Not with manual blocks.
  bool axisOrder = true;
  // Convert a wing turned against the rest of the building in a frame of its own, when that
  // makes the files smaller (wings.hpp). Not with manual blocks.
  bool turnedWings = true;
  // Progress of the current phase: its name and the fraction done (0..1). Called from the
  // calling thread only.
  std::function<void(std::string_view phase, double fraction)> progress;
};

struct PhaseTiming {
  std::string name;
  double seconds = 0;
};

// One way of building the hierarchy that the converter tried (convert.cpp keeps the smallest).
struct VariantReport {
  std::string name;            // "none", "repeats", "repeats+splits"
  int blocks = 0;
  long long bytesRaw = 0;      // the compiled image
  long long bytesPngQuick = 0; // its PNG at PngEffort::Quick
  long long bytesPng = 0;      // at PngEffort::Small (the file written uses Smallest); 0 when not
                               // judged: its quick PNG was too far above the smallest
  double seconds = 0;          // building, compiling and encoding it
  std::string error;           // why it could not be compiled, if it could not
};

// A wing turned against the rest of its building (wings.hpp), when one was found.
struct WingReport {
  bool found = false;
  bool applied = false;             // converted in its own frame: preferred (ConvertOptions::objective)
  double yawDeg = 0;                // its orientation in the building's frame
  int axis = 0;                     // the cut plane, axis = cutM in the building's frame
  double cutM = 0;
  double wallShare = 0;             // share of the walls turned with it, on its side of the cut
  std::uint64_t bytesWithout = 0;   // HNI (PngEffort::Small) + complementary mesh (meshopt + gzip)
  std::uint64_t bytesWith = 0;      // the same, converted in two parts
  std::array<int, 3> cells{};       // the wing's grid, when applied
  int blocks = 0;                   // the wing's blocks, when applied
};

// Sheets peeled off an open mesh's body (sheets.hpp), when there were any.
struct SheetReport {
  bool found = false;
  bool applied = false;       // converted as the body: preferred (ConvertOptions::objective)
  bool bodyClosed = false;    // the body is a closed surface (at the tolerance)
  std::size_t triangles = 0;  // the sheets' triangles, drawn as complementary mesh
  double areaM2 = 0;
  std::size_t cutTriangles = 0;     // input triangles cut along a free edge lying in them
  std::size_t hiddenTriangles = 0;  // inside the body: dropped
  std::uint64_t bytesWith = 0;      // PNG + gzipped complement GLB, converted as the body
  std::uint64_t bytesWithout = 0;   // the same, converted as it is
  double nutShareWith = 0;          // the share of the surface the HNI shows, converted as the body
  double nutShareWithout = 0;       // the same, converted as it is
};

struct ConvertReport {
  std::string name;
  std::size_t inputTriangles = 0;
  MeshCheck check;  // of the input
  SheetReport sheets;
  // Converted as a closed surface: the input, or the body left once sheets were peeled off.
  bool closedSurface() const { return check.closedSurface || (sheets.applied && sheets.bodyClosed); }
  std::string insideTest;         // how occupancy was decided, in words
  double yawDeg = 0;              // the building's dominant orientation about +y (align.hpp)
  bool yawApplied = false;        // converted in that frame and wrapped in a yaw redirection
  WingReport wing;
  int axisOrderCube = 0;          // the variant kept turned the grid by this rotation (0: none)
  bool hiddenCellsFilled = false; // the variant kept started from the grid with hidden cells filled (hidden_cells.hpp)
  SolidStats solid;
  BlockStats blocks;
  std::string blockMode;              // the variant kept
  std::vector<VariantReport> variants;
  int splitBlocks = 0;            // blocks added to stay within the format's per-axis limits
  int sharedAxes = 0;             // block axes refined to share a metadata item (share_axes.hpp)
  HniStats hni;
  std::uintmax_t pngBytes = 0;    // set by writeConversion
  std::size_t complementTriangles = 0;
  glm::dvec3 originM{0.0};
  std::vector<PhaseTiming> phases;
  std::vector<std::string> warnings;
  double seconds() const;
};

struct Conversion {
  Hierarchy hierarchy;
  Image image;
  glm::dvec3 originM{0.0};  // world position of the root block's minimum corner
  TriangleMesh complement;          // faces the HNI does not show, world coordinates
  ConvertReport report;
};

// Converts one building. The mesh is repaired in place first (mesh_check.hpp). Errors: nothing
// usable (no triangles after removing degenerate ones), a grid too large for memory, or an
// HNI beyond the format's limits; each message names the building.
Result<Conversion> convertMesh(TriangleMesh mesh, const ConvertOptions& options = {});

// The PNG text chunks `nut convert` writes with the HNI: the building's name, the generator and
// the world origin.
HniText hniText(const Conversion& conversion);

// Writes a complementary mesh atomically: a binary glTF compressed with meshoptimizer when the path
// ends in .glb (mesh_size.hpp's meshoptGlb: 16-bit positions over the mesh's bounds), else OBJ + MTL.
Status writeComplement(const std::string& path, const TriangleMesh& mesh);

// Writes up to `levels` coarser levels of a complementary mesh (meshLevels, converter/mesh_lod.hpp)
// beside PATH as writeComplement does, named by inserting ".lodK" before its extension
// (a.complement.glb: a.complement.lod1.glb, ...). Returns their file names and errors, finest first.
Result<std::vector<scene::ComplementLevel>> writeComplementLevels(const std::string& path, const TriangleMesh& mesh,
                                                                  int levels);

// Writes the HNI (PNG with hniText in its text chunks) and, when complementPath is not empty, the
// complementary mesh (writeComplement), both atomically. Sets report.pngBytes. PngEffort::Small
// writes in a few milliseconds what Smallest (Zopfli) writes 5-15 % smaller in about a second per
// 150 KB of pixels.
Status writeConversion(Conversion& conversion, const std::string& pngPath, const std::string& complementPath,
                       PngEffort effort = PngEffort::Smallest);

// The report as JSON (docs/CONVERTER.md, "Report").
std::string reportJson(const ConvertReport& report);

}  // namespace nut::converter
