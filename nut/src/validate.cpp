// Validation of untrusted HNI images: every rule of docs/FORMAT.md, checked with bounds-checked
// reads before any HniView accessor touches the pixels. The first failure is reported with the
// block, field and pixel it concerns.
#include <nut/hni.hpp>

#include <map>
#include <set>
#include <string>
#include <vector>

#include <nut/hni_view.hpp>
#include <nut/units.hpp>

namespace nut {

namespace {

std::string at(int u, int v) { return "pixel (" + std::to_string(u) + "," + std::to_string(v) + ")"; }
std::string at(TexelAddress a) { return at(a.u, a.v); }
const char* axisName(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

class Validator {
 public:
  explicit Validator(const Image& image) : image_(image), view_(image) {}

  Status run() {
    if (image_.width < format::kFileRecordPixels || image_.height < 1)
      return Error{"image " + std::to_string(image_.width) + "x" + std::to_string(image_.height) +
                   " is too small to hold the file record"};
    if (image_.width > format::kMaxImageSize || image_.height > format::kMaxImageSize)
      return Error{"image " + std::to_string(image_.width) + "x" + std::to_string(image_.height) +
                   " exceeds the " + std::to_string(format::kMaxImageSize) + " px limit"};
    if (image_.pixels.size() != static_cast<std::size_t>(image_.width) * static_cast<std::size_t>(image_.height) * 4)
      return Error{"pixel buffer holds " + std::to_string(image_.pixels.size()) + " bytes, expected " +
                   std::to_string(static_cast<std::size_t>(image_.width) * static_cast<std::size_t>(image_.height) * 4) +
                   " (truncated image)"};
    const std::uint8_t* magic = image_.at(0, 0);
    if (magic[0] != format::kMagic[0] || magic[1] != format::kMagic[1] || magic[2] != format::kMagic[2])
      return Error{"pixel (0,0) file record: wrong magic (not an HNI)"};
    if (magic[3] < format::kVersion || magic[3] > format::kVersionPlanes)
      return Error{"pixel (0,0) file record: unsupported version " + std::to_string(magic[3]) +
                   " (this build reads versions " + std::to_string(format::kVersion) + " to " +
                   std::to_string(format::kVersionPlanes) + ")"};
    file_ = view_.fileRecord();
    edges_.resize(static_cast<std::size_t>(file_.blockCount));
    if (Status s = checkFileRecord(); !s) return s;
    for (int b = 0; b < file_.blockCount; ++b)
      if (Status s = checkBlock(b); !s) return s;
    if (static_cast<int>(recordTargets_.size()) != file_.redirectionCount)
      return Error{"pixel (" + std::to_string(format::kFileCounts) + ",0) file record: " +
                   std::to_string(file_.redirectionCount) + " redirection records declared, " +
                   std::to_string(recordTargets_.size()) + " referenced by cells"};
    return checkAcyclic();
  }

 private:
  // Whether [u, u + w) x [v, v + h) lies in the image and, for 8-bit records, in the metadata region.
  bool inside(TexelAddress a, int w, int h, bool metadataRegion) const {
    const int maxU = metadataRegion ? std::min(image_.width, format::kMetadataRegion) : image_.width;
    const int maxV = metadataRegion ? std::min(image_.height, format::kMetadataRegion) : image_.height;
    return a.u >= 0 && a.v >= 0 && w >= 0 && h >= 0 && a.u + w <= maxU && a.v + h <= maxV;
  }

  Status checkFileRecord() {
    const std::string where = "file record";
    if (file_.blockCount < 1) return Error{"pixel (1,0) " + where + ": no blocks"};
    const int tablePixels = (file_.blockCount + 1) / 2;
    const int tableWidth = std::min(tablePixels, format::kBlockTablePixelsPerRow);
    const int tableRows = (tablePixels + format::kBlockTablePixelsPerRow - 1) / format::kBlockTablePixelsPerRow;
    if (!inside(file_.blockTable, tableWidth, tableRows, true))
      return Error{"pixel (5,0) " + where + ": block table at " + at(file_.blockTable) + " (" +
                   std::to_string(tableWidth) + "x" + std::to_string(tableRows) + ") is out of range"};
    if (file_.flags != 0) return Error{"pixel (5,0) " + where + ": reserved flags are not zero"};
    for (int b = 0; b < file_.blockCount; ++b) {
      const TexelAddress h = view_.blockAddress(file_, b);
      if (!headers_.emplace(std::make_pair(h.u, h.v), b).second)
        return Error{"block table: blocks " + std::to_string(headers_[{h.u, h.v}]) + " and " + std::to_string(b) +
                     " share the header at " + at(h)};
    }
    if (file_.blockCount % 2 == 1) {
      const int last = tablePixels - 1;
      const std::uint8_t* p = view_.texel(file_.blockTable, last % format::kBlockTablePixelsPerRow,
                                          last / format::kBlockTablePixelsPerRow);
      if (p[2] != 0 || p[3] != 0) return Error{"block table: padding after the last entry is not zero"};
    }
    if (!headers_.count({file_.root.u, file_.root.v}))
      return Error{"pixel (1,0) " + where + ": root " + at(file_.root) + " is not a block header"};
    if (file_.materialCount > 0) {
      if (file_.materialsPerRow < 1 || file_.materialsPerRow > format::kMaterialsPerRow)
        return Error{"pixel (2,0) " + where + ": " + std::to_string(file_.materialsPerRow) +
                     " materials per row is out of range"};
      const int rows = (file_.materialCount + file_.materialsPerRow - 1) / file_.materialsPerRow;
      if (!inside(file_.materials, file_.materialsPerRow * format::kMaterialPixels, rows, false))
        return Error{"pixel (2,0) " + where + ": material array at " + at(file_.materials) + " is out of range"};
      for (int m = 0; m < file_.materialCount; ++m) {
        const std::uint8_t* p = view_.texel(file_.materials, format::kMaterialPixels * (m % file_.materialsPerRow),
                                            m / file_.materialsPerRow);
        if (p[5] != 0 || p[6] != 0 || p[7] != 0)
          return Error{"material " + std::to_string(m) + ": reserved bytes are not zero"};
      }
    } else if (file_.materialsPerRow != 0 || file_.materials != TexelAddress{}) {
      return Error{"pixel (2,0) " + where + ": material array given but no materials"};
    }
    if (file_.textureCount > 0) {
      if (file_.texturesPerRow < 1 || file_.texturesPerRow > format::kTextureInfosPerRow)
        return Error{"pixel (4,0) " + where + ": " + std::to_string(file_.texturesPerRow) +
                     " texture infos per row is out of range"};
      const int rows = (file_.textureCount + file_.texturesPerRow - 1) / file_.texturesPerRow;
      if (!inside(file_.textures, file_.texturesPerRow * format::kTextureInfoPixels, rows, false))
        return Error{"pixel (4,0) " + where + ": texture-info array at " + at(file_.textures) + " is out of range"};
      for (int t = 0; t < file_.textureCount; ++t) {
        const std::uint8_t* p = view_.texel(file_.textures, format::kTextureInfoPixels * (t % file_.texturesPerRow),
                                            t / file_.texturesPerRow);
        if (p[11] != 0) return Error{"texture info " + std::to_string(t) + ": reserved byte is not zero"};
      }
    } else if (file_.texturesPerRow != 0 || file_.textures != TexelAddress{}) {
      return Error{"pixel (4,0) " + where + ": texture-info array given but no texture infos"};
    }
    return Ok{};
  }

  Status checkBlock(int b) {
    const TexelAddress h = view_.blockAddress(file_, b);
    const std::string where = "block " + std::to_string(b) + " header " + at(h);
    if (!inside(h, format::kHeaderPixels, 1, true))
      return Error{where + ": header does not fit in the metadata region"};
    const BlockHeader header = view_.header(h);
    for (int a = 0; a < 3; ++a) {
      const std::string field = where + " axis " + axisName(a);
      if (header.metaPixels[a] < header.cells[a])
        return Error{field + ": metadata array of " + std::to_string(header.metaPixels[a]) +
                     " pixels is shorter than its " + std::to_string(header.cells[a]) + " cells"};
      if (header.sizeUnits[a] < header.cells[a])
        return Error{field + ": size " + std::to_string(header.sizeUnits[a]) + " mm is less than 1 mm per cell"};
      if (!inside(header.meta[static_cast<std::size_t>(a)], header.metaPixels[a], 2, true))
        return Error{field + ": metadata array at " + at(header.meta[static_cast<std::size_t>(a)]) + " is out of range"};
      if (Status s = checkAxis(view_.axis(header, a), field); !s) return s;
    }
    const int dataWidth = header.cells.x * header.cells.z;
    if (!inside(header.data, dataWidth, header.cells.y, false))
      return Error{where + ": data component at " + at(header.data) + " (" + std::to_string(dataWidth) + "x" +
                   std::to_string(header.cells.y) + ") is out of range"};
    for (int z = 0; z < header.cells.z; ++z)
      for (int y = 0; y < header.cells.y; ++y)
        for (int x = 0; x < header.cells.x; ++x)
          if (Status s = checkCell(b, header, {x, y, z}); !s) return s;
    return Ok{};
  }

  // The metadata pixels must be exactly what buildAxisIndex() makes of the exact boundaries.
  Status checkAxis(const AxisView& axis, const std::string& field) {
    std::vector<std::int64_t> bounds{0};
    for (int k = 0; k < axis.pixels; ++k) {
      const std::uint8_t* e = axis.exact + 4 * k;
      const bool holds = axis.meta[4 * k + 1] != 0;
      if (!holds && (e[0] | e[1] | e[2]) != 0)
        return Error{field + " exact row pixel " + std::to_string(k) + ": position without a boundary"};
      if (e[3] != 0) return Error{field + " exact row pixel " + std::to_string(k) + ": reserved byte is not zero"};
      if (holds) bounds.push_back(readU24(e));
    }
    bounds.push_back(static_cast<std::int64_t>(axis.size));
    if (static_cast<int>(bounds.size()) - 1 != axis.cells)
      return Error{field + ": " + std::to_string(bounds.size() - 2) + " boundaries in the metadata array for " +
                   std::to_string(axis.cells) + " cells"};
    for (std::size_t m = 1; m < bounds.size(); ++m)
      if (bounds[m] <= bounds[m - 1])
        return Error{field + ": boundary " + std::to_string(m) + " is not after boundary " + std::to_string(m - 1)};
    return checkAxisPixels(axis, bounds, field);
  }

  // Each pixel against the rules at this M (a writer need not pick the smallest M).
  Status checkAxisPixels(const AxisView& axis, const std::vector<std::int64_t>& bounds, const std::string& field) {
    const int cells = axis.cells, pixels = axis.pixels;
    const auto size = static_cast<std::int64_t>(axis.size);
    std::vector<int> pixelOf(bounds.size(), 0);
    pixelOf.back() = pixels;
    int m = 1;
    for (int k = 0; k < pixels; ++k)
      if (axis.meta[4 * k + 1] != 0) pixelOf[static_cast<std::size_t>(m++)] = k;
    int cell = 0;
    for (int k = 0; k < pixels; ++k) {
      const std::uint8_t* p = axis.meta + 4 * k;
      const std::string px = field + " metadata pixel " + std::to_string(k);
      if (p[0] != cell) return Error{px + ": i = " + std::to_string(p[0]) + ", expected " + std::to_string(cell)};
      if (p[1] != 0) {
        // f must be the rounding of the exact boundary within this very pixel.
        const std::int64_t b = bounds[static_cast<std::size_t>(cell + 1)];
        const std::int64_t q = (2 * format::kFractionSteps * pixels * b + size) / (2 * size);
        if (q != static_cast<std::int64_t>(k) * format::kFractionSteps + p[1])
          return Error{px + ": f = " + std::to_string(p[1]) + " does not match the exact boundary " +
                       std::to_string(b) + " mm"};
      }
      const int left = pixelOf[static_cast<std::size_t>(cell)];
      const int rightBoundary = cell + (p[1] != 0 ? 2 : 1);
      const int right = std::min(pixelOf[static_cast<std::size_t>(rightBoundary)] - k, 255);
      if (p[2] != k - left || p[3] != right || (rightBoundary < cells && right + k != pixelOf[static_cast<std::size_t>(rightBoundary)]))
        return Error{px + ": j numbers (" + std::to_string(p[2]) + ", " + std::to_string(p[3]) +
                     ") do not lead to the neighbouring boundaries"};
      if (p[1] != 0) ++cell;
    }
    return Ok{};
  }

  Status checkCell(int b, const BlockHeader& header, const glm::ivec3& c) {
    const std::uint8_t* p = view_.cellTexel(header, c);
    const TexelAddress px{header.data.u + c.x + c.z * header.cells.x, header.data.v + header.cells.y - 1 - c.y};
    // Named only on failure: a large HNI has hundreds of thousands of cells, and building the name
    // of each would be most of the time validation takes.
    const auto where = [&] {
      return "block " + std::to_string(b) + " cell (" + std::to_string(c.x) + "," + std::to_string(c.y) + "," +
             std::to_string(c.z) + ") " + at(px);
    };
    const int g = p[3];
    if (g == format::kCellEmpty) {
      if (p[0] | p[1] | p[2]) return Error{where() + ": empty cell with non-zero data"};
      return Ok{};
    }
    if (g == format::kCellPlane && file_.version >= format::kVersionPlanes) return checkPlaneCell(p, where);
    if (g > format::kCellLastSolid)
      return Error{where() + ": cell descriptor g = " + std::to_string(g) + " is out of range" +
                   (g == format::kCellPlane ? " (plane cells need version 3)" : "")};
    if (g >= format::kCellFirstSolid) {
      const int material = p[0] | p[1] << 8;
      if (material >= file_.materialCount)
        return Error{where() + ": material " + std::to_string(material) + " out of range (" +
                     std::to_string(file_.materialCount) + " materials)"};
      if (p[2] > file_.textureCount)
        return Error{where() + ": texture " + std::to_string(p[2]) + " out of range (" +
                     std::to_string(file_.textureCount) + " texture infos)"};
      return Ok{};
    }
    const TexelAddress r{p[0], p[1]};
    if (p[2] != 0) return Error{where() + ": redirection cell with a non-zero texture byte"};
    if (!inside(r, format::kRedirectionPixels, 1, true))
      return Error{where() + ": redirection record at " + at(r) + " does not fit in the metadata region"};
    const RedirectionRecord record = view_.redirection(r);
    const auto rw = [&] { return "redirection record " + at(r); };
    if (record.wrap > (format::kWrapX | format::kWrapY | format::kWrapZ))
      return Error{rw() + ": tiling flags " + std::to_string(record.wrap) + " out of range"};
    if (record.cubeRotation >= format::kCubeRotationCount)
      return Error{rw() + ": rotation " + std::to_string(record.cubeRotation) + " out of range"};
    if (file_.version == format::kVersion && record.lodCode != 0)
      return Error{rw() + ": level-of-detail byte is not zero in a version 1 file"};
    const auto target = headers_.find({record.target.u, record.target.v});
    if (target == headers_.end()) return Error{rw() + ": target " + at(record.target) + " is not a block header"};
    // The footprint belongs to the target block: every record that redirects to it agrees.
    const auto [lod, first] = lodCodeByTarget_.try_emplace(target->second, record.lodCode);
    if (!first && lod->second != record.lodCode)
      return Error{rw() + ": level-of-detail code " + std::to_string(record.lodCode) + " differs from " +
                   std::to_string(lod->second) + " of another record to block " + std::to_string(target->second)};
    recordTargets_[{r.u, r.v}] = target->second;
    edges_[static_cast<std::size_t>(b)].insert(target->second);
    return Ok{};
  }

  // A plane cell's record (version 3), checked once per address.
  template <typename Where>
  Status checkPlaneCell(const std::uint8_t* p, const Where& where) {
    const TexelAddress r = unpackAddress(readU24(p));
    if (!planeRecordsChecked_.insert({r.u, r.v}).second) return Ok{};
    const std::string rw = "plane cell record " + at(r);
    if (!inside(r, format::kPlaneRecordHeadPixels, 1, false))
      return Error{where() + ": " + rw + " is outside the image"};
    const std::uint8_t combine = view_.texel(r)[3];
    if (combine < static_cast<int>(PlaneCombine::One) || combine > static_cast<int>(PlaneCombine::Either))
      return Error{rw + ": combination " + std::to_string(combine) + " is not 1, 2 or 3"};
    const PlaneRecord record = view_.planeRecord(r);
    if (!inside(r, format::kPlaneRecordHeadPixels + format::kPixelsPerPlane * record.planeCount(), 1, false))
      return Error{rw + ": " + std::to_string(record.planeCount()) + " planes do not fit in the image"};
    if (record.material >= file_.materialCount)
      return Error{rw + ": material " + std::to_string(record.material) + " out of range (" +
                   std::to_string(file_.materialCount) + " materials)"};
    if (record.texture > file_.textureCount)
      return Error{rw + ": texture " + std::to_string(record.texture) + " out of range (" +
                   std::to_string(file_.textureCount) + " texture infos)"};
    for (int i = 0; i < record.planeCount(); ++i) {
      const EncodedPlane& e = record.planes[static_cast<std::size_t>(i)];
      if (e.octX == 0 || e.octY == 0)
        return Error{rw + " plane " + std::to_string(i) + ": octahedral coordinate 0 (the range starts at 1)"};
      const std::uint16_t code = record.surfaceMaterialCodes[static_cast<std::size_t>(i)];
      if (code > file_.materialCount)
        return Error{rw + " plane " + std::to_string(i) + ": surface material " + std::to_string(code - 1) +
                     " out of range (" + std::to_string(file_.materialCount) + " materials)"};
    }
    return Ok{};
  }

  // Iterative depth-first search: a hostile file may chain thousands of blocks.
  Status checkAcyclic() {
    std::vector<int> state(edges_.size(), 0);  // 0 new, 1 on stack, 2 done
    for (int start = 0; start < file_.blockCount; ++start) {
      if (state[static_cast<std::size_t>(start)] != 0) continue;
      std::vector<std::pair<int, std::set<int>::const_iterator>> stack{{start, edges_[static_cast<std::size_t>(start)].begin()}};
      state[static_cast<std::size_t>(start)] = 1;
      while (!stack.empty()) {
        auto& [b, it] = stack.back();
        if (it == edges_[static_cast<std::size_t>(b)].end()) {
          state[static_cast<std::size_t>(b)] = 2;
          stack.pop_back();
          continue;
        }
        const int next = *it++;
        if (state[static_cast<std::size_t>(next)] == 1)
          return Error{"block " + std::to_string(b) + ": redirection to block " + std::to_string(next) +
                       " closes a cycle (the hierarchy must be a DAG)"};
        if (state[static_cast<std::size_t>(next)] == 0) {
          state[static_cast<std::size_t>(next)] = 1;
          stack.push_back({next, edges_[static_cast<std::size_t>(next)].begin()});
        }
      }
    }
    return Ok{};
  }

  const Image& image_;
  HniView view_;
  FileRecord file_;
  std::map<std::pair<int, int>, int> headers_;        // header address -> block id
  std::map<std::pair<int, int>, int> recordTargets_;  // record address -> target block
  std::map<int, std::uint8_t> lodCodeByTarget_;
  std::set<std::pair<int, int>> planeRecordsChecked_;  // target block -> the footprint code its records carry
  std::vector<std::set<int>> edges_;
};

}  // namespace

Status validate(const Image& image) { return Validator(image).run(); }

}  // namespace nut
