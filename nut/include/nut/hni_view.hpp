// nut/hni_view.hpp — read-only access to an encoded HNI, the way the GLSL ray caster reads it.
//
// Every accessor is one or a few texel fetches relative to the HNI's origin, with the same
// decoding as the shader (docs/FORMAT.md). The view does no bounds checking: use it on images that
// validate() accepted. It works on an image of its own or on an HNI placed inside a larger atlas.
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include <nut/format.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>
#include <nut/metadata.hpp>

namespace nut {

struct TexelAddress {
  int u = 0, v = 0;
  friend bool operator==(const TexelAddress&, const TexelAddress&) = default;
};

struct FileRecord {
  int version = 0;
  TexelAddress root;
  int blockCount = 0;
  TexelAddress materials;
  int materialsPerRow = 0;
  int materialCount = 0;
  int redirectionCount = 0;
  TexelAddress textures;
  int texturesPerRow = 0;
  int textureCount = 0;
  TexelAddress blockTable;
  int flags = 0;
};

struct BlockHeader {
  VisualSummary summary;               // +x, -x, +y, -y, +z, -z
  glm::ivec3 cells{0};                 // n (W per axis)
  glm::ivec3 metaPixels{0};            // M per axis
  glm::ivec3 sizeUnits{0};             // D per axis, mm
  std::array<TexelAddress, 3> meta{};  // metadata item per axis (row 0 meta, row 1 exact)
  TexelAddress data;                   // data component corner
};

struct RedirectionRecord {
  glm::ivec3 offsetUnits{0};
  std::uint8_t wrap = 0;               // format::kWrapX | kWrapY | kWrapZ
  std::uint8_t cubeRotation = 0;
  std::uint16_t yaw = 0;
  std::uint8_t lodCode = 0;            // version 2: the target's level-of-detail footprint (units.hpp)
  TexelAddress target;                 // header of the target block
};

// A data pixel: the cell descriptor g and what it points to.
struct CellTexel {
  std::uint8_t g = 0;                  // 0 empty, 1 redirection, 2 + solid index, 71 plane cell
  std::uint16_t material = 0;          // solids
  std::uint8_t texture = 0;            // solids: 0 none, n = texture info n - 1
  TexelAddress redirection;            // redirection cells
  TexelAddress planeRecord;            // plane cells (version 3)
};

// A plane cell record (version 3).
struct PlaneRecord {
  std::uint16_t material = 0;
  std::uint8_t texture = 0;
  std::uint8_t combine = 0;            // PlaneCombine: 1 one plane, 2 both, 3 either
  std::array<EncodedPlane, 2> planes{};  // planes[1] only when combine is 2 or 3
  // Per plane, the material its surface shows as stored: 0 the record's, k material k - 1.
  std::array<std::uint16_t, 2> surfaceMaterialCodes{};
  int planeCount() const { return nut::planeCount(static_cast<PlaneCombine>(combine)); }
};

inline std::uint32_t readU24(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0] | p[1] << 8 | p[2] << 16);
}
inline std::int32_t readS24(const std::uint8_t* p) {
  const std::uint32_t u = readU24(p);
  return static_cast<std::int32_t>(u ^ 0x800000u) - 0x800000;
}
// 12-bit u and v packed into 24 bits: u in bits 0-11, v in bits 12-23.
inline TexelAddress unpackAddress(std::uint32_t packed) {
  return {static_cast<int>(packed & 0xfff), static_cast<int>(packed >> 12 & 0xfff)};
}

class HniView {
 public:
  // An HNI at (originX, originY) of an RGBA8 image whose rows are rowPixels wide.
  HniView(const std::uint8_t* pixels, int rowPixels, int originX = 0, int originY = 0)
      : pixels_(pixels), rowPixels_(rowPixels), originX_(originX), originY_(originY) {}
  explicit HniView(const Image& image) : HniView(image.pixels.data(), image.width) {}

  const std::uint8_t* texel(int u, int v) const {
    return pixels_ + (static_cast<std::size_t>(originY_ + v) * static_cast<std::size_t>(rowPixels_) +
                      static_cast<std::size_t>(originX_ + u)) * 4;
  }
  // Bytes from one image row to the next.
  std::ptrdiff_t rowBytes() const { return static_cast<std::ptrdiff_t>(rowPixels_) * 4; }
  const std::uint8_t* texel(TexelAddress a, int du = 0, int dv = 0) const {
    return texel(a.u + du, a.v + dv);
  }

  FileRecord fileRecord() const {
    FileRecord f;
    const std::uint8_t* p = texel(0, 0);
    f.version = p[3];
    p = texel(format::kFileRoot, 0);
    f.root = {p[0], p[1]};
    f.blockCount = p[2] | p[3] << 8;
    p = texel(format::kFileMaterials, 0);
    f.materials = unpackAddress(readU24(p));
    f.materialsPerRow = p[3];
    p = texel(format::kFileCounts, 0);
    f.materialCount = p[0] | p[1] << 8;
    f.redirectionCount = p[2] | p[3] << 8;
    p = texel(format::kFileTextures, 0);
    f.textures = unpackAddress(readU24(p));
    f.texturesPerRow = p[3];
    p = texel(format::kFileBlockTable, 0);
    f.textureCount = p[0];
    f.blockTable = {p[1], p[2]};
    f.flags = p[3];
    return f;
  }

  // Header address of block `index` (block ids of the Hierarchy) from the block table.
  TexelAddress blockAddress(const FileRecord& f, int index) const {
    const int pixel = index / format::kBlockTableEntriesPerPixel;
    const std::uint8_t* p = texel(f.blockTable, pixel % format::kBlockTablePixelsPerRow,
                                  pixel / format::kBlockTablePixelsPerRow);
    const int channel = 2 * (index % format::kBlockTableEntriesPerPixel);
    return {p[channel], p[channel + 1]};
  }

  BlockHeader header(TexelAddress at) const {
    BlockHeader h;
    for (int s = 0; s < 6; ++s) {
      const std::uint8_t* p = texel(at, format::kHeaderSummary + s);
      h.summary[static_cast<std::size_t>(s)] = {p[0], p[1], p[2], p[3]};
    }
    for (int a = 0; a < 3; ++a) {
      const std::uint8_t* p = texel(at, format::kHeaderSize + a);
      h.sizeUnits[a] = static_cast<int>(readU24(p));
      h.cells[a] = p[3] + 1;
    }
    const std::uint8_t* m = texel(at, format::kHeaderMetaSizes);
    const std::uint8_t* xy = texel(at, format::kHeaderMetaXY);
    const std::uint8_t* z = texel(at, format::kHeaderMetaZ);
    h.metaPixels = {m[0] + 1, m[1] + 1, m[2] + 1};
    h.meta = {TexelAddress{xy[0], xy[1]}, TexelAddress{xy[2], xy[3]}, TexelAddress{z[0], z[1]}};
    h.data = unpackAddress(static_cast<std::uint32_t>(m[3] | z[2] << 8 | z[3] << 16));
    return h;
  }

  AxisView axis(const BlockHeader& h, int a) const {
    const TexelAddress at = h.meta[static_cast<std::size_t>(a)];
    return AxisView::make(texel(at), texel(at, 0, 1), h.metaPixels[a], h.cells[a], static_cast<float>(h.sizeUnits[a]));
  }

  // The data pixel of cell c: z is tiled along u, and rows run from the top cell (y = n_y - 1)
  // down so that the data component looks upright in an image viewer.
  const std::uint8_t* cellTexel(const BlockHeader& h, const glm::ivec3& c) const {
    return texel(h.data, c.x + c.z * h.cells.x, h.cells.y - 1 - c.y);
  }
  CellTexel cell(const BlockHeader& h, const glm::ivec3& c) const {
    const std::uint8_t* p = cellTexel(h, c);
    CellTexel t;
    t.g = p[3];
    if (t.g == format::kCellRedirection) {
      t.redirection = {p[0], p[1]};
    } else if (t.g == format::kCellPlane) {
      t.planeRecord = unpackAddress(readU24(p));
    } else if (t.g >= format::kCellFirstSolid) {
      t.material = static_cast<std::uint16_t>(p[0] | p[1] << 8);
      t.texture = p[2];
    }
    return t;
  }

  // The record's planes are read only as far as its combination byte says (validate() checks the
  // byte and that the record fits the image first).
  PlaneRecord planeRecord(TexelAddress at) const {
    PlaneRecord r;
    const std::uint8_t* head = texel(at);
    r.material = static_cast<std::uint16_t>(head[0] | head[1] << 8);
    r.texture = head[2];
    r.combine = head[3];
    for (int i = 0; i < r.planeCount(); ++i) {
      const int first = format::kPlaneRecordHeadPixels + format::kPixelsPerPlane * i;
      const std::uint8_t* x = texel(at, first);
      const std::uint8_t* y = texel(at, first + 1);
      const std::uint8_t* o = texel(at, first + 2);
      const std::uint32_t offset = readU24(o) | static_cast<std::uint32_t>(o[3]) << 24;
      r.planes[static_cast<std::size_t>(i)] = {readU24(x), readU24(y), static_cast<std::int32_t>(offset)};
      r.surfaceMaterialCodes[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(x[3] | y[3] << 8);
    }
    return r;
  }

  RedirectionRecord redirection(TexelAddress at) const {
    RedirectionRecord r;
    const std::uint8_t* p0 = texel(at, 0);
    const std::uint8_t* p1 = texel(at, 1);
    const std::uint8_t* p2 = texel(at, 2);
    const std::uint8_t* p3 = texel(at, 3);
    r.offsetUnits = {readS24(p0), readS24(p1), readS24(p2)};
    r.wrap = p0[3];
    r.cubeRotation = p1[3];
    r.lodCode = p2[3];
    r.target = {p3[0], p3[1]};
    r.yaw = static_cast<std::uint16_t>(p3[2] | p3[3] << 8);
    return r;
  }

  Material material(const FileRecord& f, int index) const {
    const std::uint8_t* p = texel(f.materials, format::kMaterialPixels * (index % f.materialsPerRow),
                                  index / f.materialsPerRow);
    return {p[0], p[1], p[2], p[3], p[4]};
  }

  TextureInfo textureInfo(const FileRecord& f, int index) const {
    const std::uint8_t* p = texel(f.textures, format::kTextureInfoPixels * (index % f.texturesPerRow),
                                  index / f.texturesPerRow);
    TextureInfo t;
    t.offsetM = glm::dvec3(readS24(p), readS24(p + 4), readS24(p + 8)) * format::kMetresPerUnit;
    t.textureId = static_cast<std::uint16_t>(p[3] | p[7] << 8);
    return t;
  }

 private:
  const std::uint8_t* pixels_;
  int rowPixels_;
  int originX_, originY_;
};

}  // namespace nut
