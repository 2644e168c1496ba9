// HNI compilation (paper 4.4) in four steps: plan (each block's metadata arrays and the distinct
// redirection records), list (one rectangle per record group, equal ones shared), pack (MaxRects
// over a search of image widths, 8-bit-addressed records inside the 256x256 metadata region), and
// write every record where the packer put it.
#include <nut/hni.hpp>

#include <array>
#include <climits>
#include <compare>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include <packer/maxrects.hpp>

#include <nut/format.hpp>
#include <nut/hni_view.hpp>
#include <nut/metadata.hpp>
#include <nut/summary.hpp>
#include <nut/units.hpp>

namespace nut {

namespace {

const char* axisName(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

void writeU24(std::uint8_t* p, std::uint32_t value) {
  p[0] = static_cast<std::uint8_t>(value);
  p[1] = static_cast<std::uint8_t>(value >> 8);
  p[2] = static_cast<std::uint8_t>(value >> 16);
}
void writeU16(std::uint8_t* p, std::uint32_t value) {
  p[0] = static_cast<std::uint8_t>(value);
  p[1] = static_cast<std::uint8_t>(value >> 8);
}
std::uint32_t packAddress(int u, int v) { return static_cast<std::uint32_t>(u | v << 12); }
int rowsOf(int count, int perRow) { return (count + perRow - 1) / perRow; }

Result<std::int64_t> lengthUnits(double metres, const std::string& where) {
  const std::int64_t u = toUnits(metres);
  if (u < 1 || u > format::kMaxLengthUnits)
    return Error{where + ": " + std::to_string(metres) + " m is outside the encodable range (0.001 to " +
                 std::to_string(toMetres(format::kMaxLengthUnits)) + " m)"};
  return u;
}

Result<std::int64_t> offsetUnits(double metres, const std::string& where) {
  const std::int64_t u = toUnits(metres);
  if (u < format::kMinOffsetUnits || u > format::kMaxOffsetUnits)
    return Error{where + ": offset " + std::to_string(metres) + " m is outside +-" +
                 std::to_string(toMetres(format::kMaxOffsetUnits)) + " m"};
  return u;
}

// ---- Plan: what each block needs, before anything is placed.

// A redirection record as encoded; equal keys share one record.
struct RecordKey {
  BlockId target = 0;
  std::array<std::int64_t, 3> offset{};  // millimetres
  std::uint8_t wrap = 0, cube = 0;
  std::uint16_t yaw = 0;
  friend auto operator<=>(const RecordKey&, const RecordKey&) = default;
};

// A plane cell record as encoded; equal keys share one record.
struct PlaneRecordKey {
  std::array<EncodedPlane, 2> planes{};  // the second is zero for one plane
  std::array<std::uint16_t, 2> surfaceMaterialCodes{};  // 0: the record's material, k: material k - 1
  PlaneCombine combine = PlaneCombine::One;
  std::uint16_t material = 0;
  std::uint8_t texture = 0;
  int pixels() const { return format::kPlaneRecordHeadPixels + format::kPixelsPerPlane * planeCount(combine); }
  friend auto operator<=>(const PlaneRecordKey&, const PlaneRecordKey&) = default;
};

struct BlockPlan {
  std::array<AxisIndex, 3> axes;
  std::vector<int> records;       // global record index of each of the block's redirections
  // Global plane record index per (cut, material, texture) the block's plane cells use.
  std::map<std::tuple<std::uint32_t, std::uint16_t, std::uint8_t>, int> planeRecords;
  std::array<int, 3> metaItem{};  // the listed metadata item each axis uses (items are shared)
  int dataItem = 0;               // the listed data component (shared by blocks with equal cells)
};

struct Plan {
  std::vector<BlockPlan> blocks;
  std::vector<RecordKey> records;
  std::vector<PlaneRecordKey> planeRecords;
  std::vector<std::array<std::int64_t, 3>> textureOffsets;
};

int planeRecordOf(const BlockPlan& plan, const Cell& cell) {
  return plan.planeRecords.at({cell.cut, cell.material, cell.texture});
}

Result<AxisIndex> planAxis(const Block& block, int a, const CompileOptions& options, const std::string& where) {
  std::vector<std::int64_t> bounds;
  for (double m : block.boundsM[a]) bounds.push_back(toUnits(m));
  if (auto size = lengthUnits(block.boundsM[a].back(), where + " size"); !size) return size.error();
  for (std::size_t i = 1; i < bounds.size(); ++i)
    if (bounds[i] <= bounds[i - 1]) return Error{where + ": cell " + std::to_string(i - 1) + " is narrower than 1 mm"};
  auto index = buildAxisIndexWithin(bounds, options.heuristicToleranceM);
  if (!index) return Error{where + ": " + index.error().message};
  return std::move(*index);
}

Result<RecordKey> recordKey(const Redirection& red, const std::string& where) {
  RecordKey key{red.target, {}, 0, red.rotation.cube, red.rotation.yaw};
  for (std::size_t a = 0; a < 3; ++a) {
    auto o = offsetUnits(red.offsetM[a], where);
    if (!o) return o.error();
    key.offset[a] = *o;
  }
  key.wrap = static_cast<std::uint8_t>((red.wrap[0] ? format::kWrapX : 0) | (red.wrap[1] ? format::kWrapY : 0) |
                                       (red.wrap[2] ? format::kWrapZ : 0));
  return key;
}

Result<Plan> planBlocks(const Hierarchy& h, const CompileOptions& options) {
  Plan plan;
  plan.blocks.resize(h.blocks.size());
  std::map<RecordKey, int> recordIndex;
  std::map<PlaneRecordKey, int> planeRecordIndex;
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    BlockPlan& blockPlan = plan.blocks[b];
    const std::string where = "block " + std::to_string(b);
    for (int a = 0; a < 3; ++a) {
      auto index = planAxis(block, a, options, where + " axis " + axisName(a));
      if (!index) return index.error();
      blockPlan.axes[static_cast<std::size_t>(a)] = std::move(*index);
    }
    const int dataWidth = block.cellCount(0) * block.cellCount(2);
    if (dataWidth > format::kMaxImageSize)
      return Error{where + ": data component " + std::to_string(dataWidth) + " px wide (n_x * n_z) exceeds " +
                   std::to_string(format::kMaxImageSize)};
    // Only redirections some cell uses get a record (decode() could not find the others).
    blockPlan.records.assign(block.redirections.size(), -1);
    for (const Cell& cell : block.cells) {
      if (cell.kind != CellKind::Redirection || blockPlan.records[cell.redirection] >= 0) continue;
      auto key =
          recordKey(block.redirections[cell.redirection], where + " redirection " + std::to_string(cell.redirection));
      if (!key) return key.error();
      auto [it, inserted] = recordIndex.try_emplace(*key, static_cast<int>(plan.records.size()));
      if (inserted) plan.records.push_back(*key);
      blockPlan.records[cell.redirection] = it->second;
    }
    for (const Cell& cell : block.cells) {
      if (cell.kind != CellKind::Plane || blockPlan.planeRecords.contains({cell.cut, cell.material, cell.texture}))
        continue;
      const PlaneCut& cut = block.cuts[cell.cut];
      PlaneRecordKey key{{}, {}, cut.combine, cell.material, cell.texture};
      for (int p = 0; p < cut.planeCount(); ++p) {
        const auto encoded = encodePlane(cut.planes[static_cast<std::size_t>(p)]);
        if (!encoded)
          return Error{where + " plane cut " + std::to_string(cell.cut) + " plane " + std::to_string(p) +
                       ": offset beyond the encodable +-33.5 km"};
        key.planes[static_cast<std::size_t>(p)] = *encoded;
        // Material indices stop at 65534 (at most 65535 materials), so the code fits a u16.
        if (const auto& m = cut.surfaceMaterials[static_cast<std::size_t>(p)])
          key.surfaceMaterialCodes[static_cast<std::size_t>(p)] = static_cast<std::uint16_t>(*m + 1);
      }
      auto [it, inserted] = planeRecordIndex.try_emplace(key, static_cast<int>(plan.planeRecords.size()));
      if (inserted) plan.planeRecords.push_back(key);
      blockPlan.planeRecords[{cell.cut, cell.material, cell.texture}] = it->second;
    }
  }
  if (plan.records.size() > 0xffff) return Error{"more than 65535 distinct redirection records"};
  for (std::size_t t = 0; t < h.textures.size(); ++t) {
    std::array<std::int64_t, 3> offset{};
    for (std::size_t a = 0; a < 3; ++a) {
      auto o = offsetUnits(h.textures[t].offsetM[a], "texture info " + std::to_string(t));
      if (!o) return o.error();
      offset[a] = *o;
    }
    plan.textureOffsets.push_back(offset);
  }
  return plan;
}

// ---- List: one rectangle per record group.

// The pixels of a metadata item (metadata row, then exact row): equal arrays share one item.
std::string encodedItem(const AxisIndex& index) {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(8 * index.pixels()));
  encodeAxisIndex(index, pixels.data(), pixels.data() + 4 * index.pixels());
  return {pixels.begin(), pixels.end()};
}

// What a data component holds, before packing decides record addresses: its size, then per cell
// kind, solid, material and texture, or the global record index. Equal keys share one component.
std::vector<std::int64_t> dataKey(const Block& block, const BlockPlan& plan) {
  std::vector<std::int64_t> key{block.cellCount(0), block.cellCount(1), block.cellCount(2)};
  key.reserve(key.size() + block.cells.size());
  for (const Cell& cell : block.cells) {
    std::int64_t k = static_cast<std::int64_t>(cell.kind);
    if (cell.kind == CellKind::Solid)
      k |= static_cast<std::int64_t>(cell.solid.index) << 8 | static_cast<std::int64_t>(cell.material) << 16 |
           static_cast<std::int64_t>(cell.texture) << 40;
    else if (cell.kind == CellKind::Redirection)
      k |= static_cast<std::int64_t>(plan.records[cell.redirection]) << 8;
    else if (cell.kind == CellKind::Plane)
      k |= static_cast<std::int64_t>(planeRecordOf(plan, cell)) << 8;
    key.push_back(k);
  }
  return key;
}

enum class ItemKind { BlockTable, Header, Metadata, Data, Records, PlaneRecord, Materials, Textures };
struct ItemInfo {
  ItemKind kind;
  int block = 0;  // Header
  int first = 0;  // Records: first record index in the chunk; PlaneRecord: its index
};

// The rectangles to pack, each with what it holds.
struct ItemList {
  std::vector<packer::Item> items;
  std::vector<ItemInfo> infos;
  int materialsPerRow = 0, texturesPerRow = 0;

  void add(ItemInfo info, int width, int height, bool metadataRegion) {
    // Only 8-bit-addressed records carry a limit: the packer treats any limit as "region first",
    // and the bin itself already bounds everything to the 4096 px image limit.
    const int limit = metadataRegion ? format::kMetadataRegion : INT_MAX;
    items.push_back({static_cast<int>(items.size()), width, height, limit, limit});
    infos.push_back(info);
  }
};

// Equal metadata arrays (any blocks, any axes) and equal data components are stored once: the
// headers address records, and nothing says two may not address the same one. Sets each block
// plan's metaItem and dataItem.
ItemList listItems(const Hierarchy& h, Plan& plan) {
  ItemList list;
  const int tablePixels = rowsOf(static_cast<int>(h.blocks.size()), format::kBlockTableEntriesPerPixel);
  list.add({ItemKind::BlockTable}, std::min(tablePixels, format::kBlockTablePixelsPerRow),
           rowsOf(tablePixels, format::kBlockTablePixelsPerRow), true);
  std::map<std::string, int> metaItems;
  std::map<std::vector<std::int64_t>, int> dataItems;
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    BlockPlan& blockPlan = plan.blocks[b];
    list.add({ItemKind::Header, static_cast<int>(b)}, format::kHeaderPixels, 1, true);
    for (std::size_t a = 0; a < 3; ++a) {
      const AxisIndex& index = blockPlan.axes[a];
      auto [it, inserted] = metaItems.try_emplace(encodedItem(index), static_cast<int>(list.items.size()));
      if (inserted) list.add({ItemKind::Metadata}, index.pixels(), 2, true);
      blockPlan.metaItem[a] = it->second;
    }
    auto [it, inserted] = dataItems.try_emplace(dataKey(block, blockPlan), static_cast<int>(list.items.size()));
    if (inserted) list.add({ItemKind::Data}, block.cellCount(0) * block.cellCount(2), block.cellCount(1), false);
    blockPlan.dataItem = it->second;
  }
  const int recordCount = static_cast<int>(plan.records.size());
  for (int first = 0; first < recordCount; first += format::kRedirectionsPerItem) {
    const int count = std::min(format::kRedirectionsPerItem, recordCount - first);
    list.add({ItemKind::Records, 0, first}, count * format::kRedirectionPixels, 1, true);
  }
  for (std::size_t r = 0; r < plan.planeRecords.size(); ++r)
    list.add({ItemKind::PlaneRecord, 0, static_cast<int>(r)}, plan.planeRecords[r].pixels(), 1, false);
  const int materialCount = static_cast<int>(h.materials.size());
  list.materialsPerRow = std::min(materialCount, format::kMaterialsPerRow);
  if (materialCount > 0)
    list.add({ItemKind::Materials}, list.materialsPerRow * format::kMaterialPixels,
             rowsOf(materialCount, format::kMaterialsPerRow), false);
  const int textureCount = static_cast<int>(h.textures.size());
  list.texturesPerRow = std::min(textureCount, format::kTextureInfosPerRow);
  if (textureCount > 0)
    list.add({ItemKind::Textures}, list.texturesPerRow * format::kTextureInfoPixels,
             rowsOf(textureCount, format::kTextureInfosPerRow), false);
  return list;
}

// ---- Pack.

Result<packer::Layout> pack(const std::vector<packer::Item>& items, const CompileOptions& options) {
  const packer::Rect fileRecord{0, 0, format::kFileRecordPixels, 1};
  packer::Options packOptions;
  packOptions.reserved = std::span<const packer::Rect>(&fileRecord, 1);
  // Best-area-fit first, then best-short-side-fit and bottom-left where they pack tighter: shared
  // records and one-pixel metadata items leave fewer small rectangles to fill gaps, and the other
  // rules recover what that costs (docs/PERFORMANCE.md, "HNI packing waste").
  const auto search = [&](packer::Options attempt) {
    std::optional<packer::Layout> best;
    for (packer::Heuristic rule :
         {packer::Heuristic::BestAreaFit, packer::Heuristic::BestShortSideFit, packer::Heuristic::BottomLeft}) {
      attempt.heuristic = rule;
      if (best) attempt.maxBoundingArea = static_cast<long long>(best->width) * best->height - 1;
      if (auto layout = packer::packSearchWidth(items, options.maxSearchWidth, format::kMaxImageSize, attempt))
        best = std::move(layout);
    }
    return best;
  };
  auto layout = search(packOptions);
  if (!layout) {
    // Large hierarchies: place the 8-bit-addressed records first so they keep the metadata region.
    packOptions.regionLimitedFirst = true;
    layout = search(packOptions);
  }
  if (!layout)
    return Error{"the records do not fit a " + std::to_string(format::kMaxImageSize) + "x" +
                 std::to_string(format::kMaxImageSize) + " image with headers and metadata arrays inside the " +
                 "256x256 metadata region; split the hierarchy into several HNIs"};
  return std::move(*layout);
}

// Where each record landed.
struct Placed {
  packer::Rect table, materials, textures;
  std::vector<packer::Rect> header, data;         // per block
  std::vector<std::array<packer::Rect, 3>> meta;  // per block and axis
  std::vector<TexelAddress> record;               // per global record
  std::vector<TexelAddress> planeRecord;          // per global plane record
};

Placed locate(const Plan& plan, const ItemList& list, const packer::Layout& layout) {
  Placed at;
  const std::size_t blockCount = plan.blocks.size();
  std::vector<packer::Rect> itemAt(list.items.size());
  for (const packer::Placement& p : layout.placements) itemAt[static_cast<std::size_t>(p.id)] = p.rect;
  at.header.resize(blockCount);
  at.data.resize(blockCount);
  at.meta.resize(blockCount);
  for (std::size_t b = 0; b < blockCount; ++b) {
    for (std::size_t a = 0; a < 3; ++a) at.meta[b][a] = itemAt[static_cast<std::size_t>(plan.blocks[b].metaItem[a])];
    at.data[b] = itemAt[static_cast<std::size_t>(plan.blocks[b].dataItem)];
  }
  const int recordCount = static_cast<int>(plan.records.size());
  at.record.resize(plan.records.size());
  at.planeRecord.resize(plan.planeRecords.size());
  for (const packer::Placement& p : layout.placements) {
    const ItemInfo& info = list.infos[static_cast<std::size_t>(p.id)];
    switch (info.kind) {
      case ItemKind::BlockTable:
        at.table = p.rect;
        break;
      case ItemKind::Header:
        at.header[static_cast<std::size_t>(info.block)] = p.rect;
        break;
      case ItemKind::Metadata:
      case ItemKind::Data:
        break;  // placed above, per block
      case ItemKind::Materials:
        at.materials = p.rect;
        break;
      case ItemKind::Textures:
        at.textures = p.rect;
        break;
      case ItemKind::PlaneRecord:
        at.planeRecord[static_cast<std::size_t>(info.first)] = {p.rect.x, p.rect.y};
        break;
      case ItemKind::Records:
        for (int r = info.first; r < std::min(info.first + format::kRedirectionsPerItem, recordCount); ++r)
          at.record[static_cast<std::size_t>(r)] = {p.rect.x + (r - info.first) * format::kRedirectionPixels, p.rect.y};
        break;
    }
  }
  return at;
}

// ---- Write.

void writeFileRecord(Image& image, const Hierarchy& h, const Plan& plan, const ItemList& list, const Placed& at) {
  const auto materialCount = static_cast<std::uint32_t>(h.materials.size());
  const auto textureCount = static_cast<std::uint32_t>(h.textures.size());
  std::uint8_t* p = image.at(format::kFileMagic, 0);
  p[0] = format::kMagic[0], p[1] = format::kMagic[1], p[2] = format::kMagic[2], p[3] = format::kVersion;
  p = image.at(format::kFileRoot, 0);
  const packer::Rect& root = at.header[h.root];
  p[0] = static_cast<std::uint8_t>(root.x), p[1] = static_cast<std::uint8_t>(root.y);
  writeU16(p + 2, static_cast<std::uint32_t>(h.blocks.size()));
  p = image.at(format::kFileMaterials, 0);
  writeU24(p, materialCount > 0 ? packAddress(at.materials.x, at.materials.y) : 0);
  p[3] = static_cast<std::uint8_t>(list.materialsPerRow);
  p = image.at(format::kFileCounts, 0);
  writeU16(p, materialCount);
  writeU16(p + 2, static_cast<std::uint32_t>(plan.records.size()));
  p = image.at(format::kFileTextures, 0);
  writeU24(p, textureCount > 0 ? packAddress(at.textures.x, at.textures.y) : 0);
  p[3] = static_cast<std::uint8_t>(list.texturesPerRow);
  p = image.at(format::kFileBlockTable, 0);
  p[0] = static_cast<std::uint8_t>(textureCount);
  p[1] = static_cast<std::uint8_t>(at.table.x), p[2] = static_cast<std::uint8_t>(at.table.y), p[3] = 0;
}

void writeBlockTableEntry(Image& image, std::size_t b, const Placed& at) {
  const int pixel = static_cast<int>(b) / format::kBlockTableEntriesPerPixel;
  std::uint8_t* entry = image.at(at.table.x + pixel % format::kBlockTablePixelsPerRow,
                                 at.table.y + pixel / format::kBlockTablePixelsPerRow) +
                        2 * (b % format::kBlockTableEntriesPerPixel);
  entry[0] = static_cast<std::uint8_t>(at.header[b].x), entry[1] = static_cast<std::uint8_t>(at.header[b].y);
}

void writeHeader(Image& image, const Block& block, const BlockPlan& blockPlan, const VisualSummary& summary,
                 const packer::Rect& header, const std::array<packer::Rect, 3>& meta, const packer::Rect& dataRect) {
  for (int s = 0; s < 6; ++s) {
    const Rgba8 c = summary[static_cast<std::size_t>(s)];
    std::uint8_t* q = image.at(header.x + format::kHeaderSummary + s, header.y);
    q[0] = c.r, q[1] = c.g, q[2] = c.b, q[3] = c.a;
  }
  for (int a = 0; a < 3; ++a) {
    std::uint8_t* q = image.at(header.x + format::kHeaderSize + a, header.y);
    writeU24(q, blockPlan.axes[static_cast<std::size_t>(a)].sizeUnits);
    q[3] = static_cast<std::uint8_t>(block.cellCount(a) - 1);
  }
  const std::uint32_t data = packAddress(dataRect.x, dataRect.y);
  std::uint8_t* q = image.at(header.x + format::kHeaderMetaSizes, header.y);
  for (std::size_t a = 0; a < 3; ++a) q[a] = static_cast<std::uint8_t>(meta[a].width - 1);
  q[3] = static_cast<std::uint8_t>(data);
  q = image.at(header.x + format::kHeaderMetaXY, header.y);
  q[0] = static_cast<std::uint8_t>(meta[0].x), q[1] = static_cast<std::uint8_t>(meta[0].y);
  q[2] = static_cast<std::uint8_t>(meta[1].x), q[3] = static_cast<std::uint8_t>(meta[1].y);
  q = image.at(header.x + format::kHeaderMetaZ, header.y);
  q[0] = static_cast<std::uint8_t>(meta[2].x), q[1] = static_cast<std::uint8_t>(meta[2].y);
  writeU16(q + 2, data >> 8);
}

// The data component: z tiled along x, top cell row first.
void writeData(Image& image, const Block& block, const BlockPlan& blockPlan, const packer::Rect& dataRect,
               const Placed& at) {
  const int nx = block.cellCount(0), ny = block.cellCount(1), nz = block.cellCount(2);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const Cell& cell = block.cell(x, y, z);
        std::uint8_t* d = image.at(dataRect.x + x + z * nx, dataRect.y + ny - 1 - y);
        if (cell.kind == CellKind::Solid) {
          writeU16(d, cell.material);
          d[2] = cell.texture;
          d[3] = static_cast<std::uint8_t>(format::kCellFirstSolid + cell.solid.index);
        } else if (cell.kind == CellKind::Redirection) {
          const TexelAddress r = at.record[static_cast<std::size_t>(blockPlan.records[cell.redirection])];
          d[0] = static_cast<std::uint8_t>(r.u), d[1] = static_cast<std::uint8_t>(r.v);
          d[3] = format::kCellRedirection;
        } else if (cell.kind == CellKind::Plane) {
          const TexelAddress r = at.planeRecord[static_cast<std::size_t>(planeRecordOf(blockPlan, cell))];
          writeU24(d, packAddress(r.u, r.v));
          d[3] = format::kCellPlane;
        }
      }
}

void writeRecord(Image& image, const RecordKey& record, TexelAddress at, const packer::Rect& targetHeader,
                 std::uint8_t targetLodCode) {
  for (int a = 0; a < 3; ++a)
    writeU24(image.at(at.u + a, at.v),
             static_cast<std::uint32_t>(record.offset[static_cast<std::size_t>(a)]) & 0xffffff);
  image.at(at.u, at.v)[3] = record.wrap;
  image.at(at.u + 1, at.v)[3] = record.cube;
  image.at(at.u + format::kRedirectionLodPixel, at.v)[3] = targetLodCode;
  std::uint8_t* q = image.at(at.u + 3, at.v);
  q[0] = static_cast<std::uint8_t>(targetHeader.x), q[1] = static_cast<std::uint8_t>(targetHeader.y);
  writeU16(q + 2, record.yaw);
}

void writePlaneRecord(Image& image, const PlaneRecordKey& record, TexelAddress at) {
  std::uint8_t* q = image.at(at.u, at.v);
  writeU16(q, record.material);
  q[2] = record.texture;
  q[3] = static_cast<std::uint8_t>(record.combine);
  for (int p = 0; p < planeCount(record.combine); ++p) {
    const EncodedPlane& e = record.planes[static_cast<std::size_t>(p)];
    const int first = at.u + format::kPlaneRecordHeadPixels + format::kPixelsPerPlane * p;
    writeU24(image.at(first, at.v), e.octX);
    writeU24(image.at(first + 1, at.v), e.octY);
    const std::uint16_t code = record.surfaceMaterialCodes[static_cast<std::size_t>(p)];
    image.at(first, at.v)[3] = static_cast<std::uint8_t>(code & 0xff);
    image.at(first + 1, at.v)[3] = static_cast<std::uint8_t>(code >> 8);
    const auto offset = static_cast<std::uint32_t>(e.offset);
    writeU24(image.at(first + 2, at.v), offset & 0xffffff);
    image.at(first + 2, at.v)[3] = static_cast<std::uint8_t>(offset >> 24);
  }
}

// Materials and texture infos, row-major in their rectangles.
void writeMaterialsAndTextures(Image& image, const Hierarchy& h, const Plan& plan, const Placed& at) {
  for (std::size_t m = 0; m < h.materials.size(); ++m) {
    const Material& mat = h.materials[m];
    const int i = static_cast<int>(m);
    std::uint8_t* q = image.at(at.materials.x + format::kMaterialPixels * (i % format::kMaterialsPerRow),
                               at.materials.y + i / format::kMaterialsPerRow);
    q[0] = mat.r, q[1] = mat.g, q[2] = mat.b, q[3] = mat.opacity, q[4] = mat.reflectance;
  }
  for (std::size_t t = 0; t < h.textures.size(); ++t) {
    const int i = static_cast<int>(t);
    std::uint8_t* q = image.at(at.textures.x + format::kTextureInfoPixels * (i % format::kTextureInfosPerRow),
                               at.textures.y + i / format::kTextureInfosPerRow);
    for (std::size_t a = 0; a < 3; ++a)
      writeU24(q + 4 * a, static_cast<std::uint32_t>(plan.textureOffsets[t][a]) & 0xffffff);
    const std::uint16_t id = h.textures[t].textureId;
    q[3] = static_cast<std::uint8_t>(id), q[7] = static_cast<std::uint8_t>(id >> 8);
  }
}

}  // namespace

Result<Image> compile(const Hierarchy& h, const CompileOptions& options) {
  if (Status s = checkHierarchy(h); !s) return s.error();
  if (h.blocks.size() > 0xffff) return Error{"more than 65535 blocks"};
  if (h.materials.size() > static_cast<std::size_t>(format::kMaxMaterials))
    return Error{std::to_string(h.materials.size()) + " materials exceed the limit of 65535"};
  if (h.textures.size() > static_cast<std::size_t>(format::kMaxTextureInfos))
    return Error{std::to_string(h.textures.size()) + " texture infos exceed the limit of 255"};

  auto planned = planBlocks(h, options);
  if (!planned) return planned.error();
  const ItemList list = listItems(h, *planned);
  auto layout = pack(list.items, options);
  if (!layout) return layout.error();
  const Placed at = locate(*planned, list, *layout);

  Image image(layout->width, layout->height);
  writeFileRecord(image, h, *planned, list, at);
  const std::vector<VisualSummary> summaries = computeSummaries(h);
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const BlockPlan& blockPlan = planned->blocks[b];
    writeBlockTableEntry(image, b, at);
    writeHeader(image, h.blocks[b], blockPlan, summaries[b], at.header[b], at.meta[b], at.data[b]);
    for (std::size_t a = 0; a < 3; ++a) {
      const packer::Rect& r = at.meta[b][a];
      encodeAxisIndex(blockPlan.axes[a], image.at(r.x, r.y), image.at(r.x, r.y + 1));
    }
    writeData(image, h.blocks[b], blockPlan, at.data[b], at);
  }
  bool anyLod = false;
  for (std::size_t r = 0; r < planned->records.size(); ++r) {
    const BlockId target = planned->records[r].target;
    const std::uint8_t lod = lodCode(h.blocks[target].lodFootprintM);
    anyLod = anyLod || lod != 0;
    writeRecord(image, planned->records[r], at.record[r], at.header[target], lod);
  }
  for (std::size_t r = 0; r < planned->planeRecords.size(); ++r)
    writePlaneRecord(image, planned->planeRecords[r], at.planeRecord[r]);
  if (!planned->planeRecords.empty())
    image.at(format::kFileMagic, 0)[3] = format::kVersionPlanes;
  else if (anyLod)
    image.at(format::kFileMagic, 0)[3] = format::kVersionLod;
  writeMaterialsAndTextures(image, h, *planned, at);
  return image;
}

}  // namespace nut
