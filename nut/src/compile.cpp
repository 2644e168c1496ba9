// HNI compilation (paper 4.4): every record of the hierarchy becomes a rectangle, MaxRects
// best-area-fit packs them over a search of image widths, and the records are written where the
// packer put them. Records addressed with 8 bits are kept inside the 256x256 metadata region.
#include <nut/hni.hpp>

#include <climits>
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

// A redirection record as encoded; equal keys share one record.
using RecordKey = std::tuple<BlockId, std::int64_t, std::int64_t, std::int64_t, std::uint8_t,
                             std::uint8_t, std::uint16_t>;

struct BlockPlan {
  std::array<AxisIndex, 3> axes;
  std::vector<int> records;  // global record index of each of the block's redirections
  std::array<int, 3> metaItem{};  // the packed metadata item each axis uses (items are shared)
  int dataItem = 0;               // the packed data component (shared by blocks with equal cells)
};

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
    key.push_back(k);
  }
  return key;
}

// What each packed rectangle holds.
enum class ItemKind { BlockTable, Header, Metadata, Data, Records, Materials, Textures };
struct ItemInfo {
  ItemKind kind;
  int block = 0;  // Header
  int first = 0;  // Records: first record index in the chunk
};

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

}  // namespace

Result<Image> compile(const Hierarchy& h, const CompileOptions& options) {
  if (Status s = checkHierarchy(h); !s) return s.error();
  if (h.blocks.size() > 0xffff) return Error{"more than 65535 blocks"};
  if (h.materials.size() > static_cast<std::size_t>(format::kMaxMaterials))
    return Error{std::to_string(h.materials.size()) + " materials exceed the limit of 65536"};
  if (h.textures.size() > static_cast<std::size_t>(format::kMaxTextureInfos))
    return Error{std::to_string(h.textures.size()) + " texture infos exceed the limit of 255"};

  // Per block: metadata arrays of the millimetre boundaries, and global redirection records.
  std::vector<BlockPlan> plans(h.blocks.size());
  std::vector<RecordKey> records;
  std::map<RecordKey, int> recordIndex;
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    const std::string where = "block " + std::to_string(b);
    for (int a = 0; a < 3; ++a) {
      const std::string axisWhere = where + " axis " + axisName(a);
      std::vector<std::int64_t> bounds;
      for (double m : block.boundsM[a]) bounds.push_back(toUnits(m));
      if (auto size = lengthUnits(block.boundsM[a].back(), axisWhere + " size"); !size) return size.error();
      for (std::size_t i = 1; i < bounds.size(); ++i)
        if (bounds[i] <= bounds[i - 1])
          return Error{axisWhere + ": cell " + std::to_string(i - 1) + " is narrower than 1 mm"};
      auto index = buildAxisIndexWithin(bounds, options.heuristicToleranceM);
      if (!index) return Error{axisWhere + ": " + index.error().message};
      plans[b].axes[static_cast<std::size_t>(a)] = std::move(*index);
    }
    const int dataWidth = block.cellCount(0) * block.cellCount(2);
    if (dataWidth > format::kMaxImageSize)
      return Error{where + ": data component " + std::to_string(dataWidth) + " px wide (n_x * n_z) exceeds " +
                   std::to_string(format::kMaxImageSize)};
    // Only redirections some cell uses get a record (decode() could not find the others).
    plans[b].records.assign(block.redirections.size(), -1);
    for (const Cell& cell : block.cells) {
      if (cell.kind != CellKind::Redirection || plans[b].records[cell.redirection] >= 0) continue;
      const Redirection& red = block.redirections[cell.redirection];
      std::array<std::int64_t, 3> offset{};
      for (int a = 0; a < 3; ++a) {
        auto o = offsetUnits(red.offsetM[a], where + " redirection " + std::to_string(cell.redirection));
        if (!o) return o.error();
        offset[static_cast<std::size_t>(a)] = *o;
      }
      const auto wrap = static_cast<std::uint8_t>((red.wrap[0] ? format::kWrapX : 0) |
                                                  (red.wrap[1] ? format::kWrapY : 0) |
                                                  (red.wrap[2] ? format::kWrapZ : 0));
      const RecordKey key{red.target, offset[0], offset[1], offset[2], wrap, red.rotation.cube, red.rotation.yaw};
      auto [it, inserted] = recordIndex.try_emplace(key, static_cast<int>(records.size()));
      if (inserted) records.push_back(key);
      plans[b].records[cell.redirection] = it->second;
    }
  }
  if (records.size() > 0xffff) return Error{"more than 65535 distinct redirection records"};
  const std::vector<VisualSummary> summaries = computeSummaries(h);

  // One rectangle per record group; 8-bit-addressed ones stay inside the metadata region.
  std::vector<packer::Item> items;
  std::vector<ItemInfo> infos;
  const auto add = [&](ItemInfo info, int width, int height, bool metadataRegion) {
    // Only 8-bit-addressed records carry a limit: the packer treats any limit as "region first",
    // and the bin itself already bounds everything to the 4096 px image limit.
    const int limit = metadataRegion ? format::kMetadataRegion : INT_MAX;
    items.push_back({static_cast<int>(items.size()), width, height, limit, limit});
    infos.push_back(info);
  };
  const auto rowsOf = [](int count, int perRow) { return (count + perRow - 1) / perRow; };
  const int tablePixels = rowsOf(static_cast<int>(h.blocks.size()), format::kBlockTableEntriesPerPixel);
  add({ItemKind::BlockTable}, std::min(tablePixels, format::kBlockTablePixelsPerRow),
      rowsOf(tablePixels, format::kBlockTablePixelsPerRow), true);
  // Equal metadata arrays (any blocks, any axes) and equal data components are stored once: the
  // headers address records, and nothing says two may not address the same one.
  std::map<std::string, int> metaItems;
  std::map<std::vector<std::int64_t>, int> dataItems;
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    const int bi = static_cast<int>(b);
    BlockPlan& plan = plans[b];
    add({ItemKind::Header, bi}, format::kHeaderPixels, 1, true);
    for (int a = 0; a < 3; ++a) {
      const AxisIndex& index = plan.axes[static_cast<std::size_t>(a)];
      auto [it, inserted] = metaItems.try_emplace(encodedItem(index), static_cast<int>(items.size()));
      if (inserted) add({ItemKind::Metadata}, index.pixels(), 2, true);
      plan.metaItem[static_cast<std::size_t>(a)] = it->second;
    }
    auto [it, inserted] = dataItems.try_emplace(dataKey(block, plan), static_cast<int>(items.size()));
    if (inserted) add({ItemKind::Data}, block.cellCount(0) * block.cellCount(2), block.cellCount(1), false);
    plan.dataItem = it->second;
  }
  for (int first = 0; first < static_cast<int>(records.size()); first += format::kRedirectionsPerItem) {
    const int count = std::min(format::kRedirectionsPerItem, static_cast<int>(records.size()) - first);
    add({ItemKind::Records, 0, first}, count * format::kRedirectionPixels, 1, true);
  }
  const int materialCount = static_cast<int>(h.materials.size());
  const int materialsPerRow = std::min(materialCount, format::kMaterialsPerRow);
  if (materialCount > 0)
    add({ItemKind::Materials}, materialsPerRow * format::kMaterialPixels,
        rowsOf(materialCount, format::kMaterialsPerRow), false);
  const int textureCount = static_cast<int>(h.textures.size());
  const int texturesPerRow = std::min(textureCount, format::kTextureInfosPerRow);
  if (textureCount > 0)
    add({ItemKind::Textures}, texturesPerRow * format::kTextureInfoPixels,
        rowsOf(textureCount, format::kTextureInfosPerRow), false);

  const packer::Rect fileRecord{0, 0, format::kFileRecordPixels, 1};
  packer::Options packOptions;
  packOptions.reserved = std::span<const packer::Rect>(&fileRecord, 1);
  // Best-area-fit first, then best-short-side-fit and bottom-left where they pack tighter: shared
  // records and one-pixel metadata items leave fewer small rectangles to fill gaps, and the other
  // rules recover what that costs (docs/BENCHMARKS.md, packing).
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

  // Where each record landed.
  std::vector<packer::Rect> itemAt(items.size());
  for (const packer::Placement& p : layout->placements) itemAt[static_cast<std::size_t>(p.id)] = p.rect;
  std::vector<packer::Rect> headerAt(h.blocks.size()), dataAt(h.blocks.size());
  std::vector<std::array<packer::Rect, 3>> metaAt(h.blocks.size());
  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    for (std::size_t a = 0; a < 3; ++a) metaAt[b][a] = itemAt[static_cast<std::size_t>(plans[b].metaItem[a])];
    dataAt[b] = itemAt[static_cast<std::size_t>(plans[b].dataItem)];
  }
  std::vector<TexelAddress> recordAt(records.size());
  packer::Rect tableAt, materialsAt, texturesAt;
  for (const packer::Placement& p : layout->placements) {
    const ItemInfo& info = infos[static_cast<std::size_t>(p.id)];
    const auto b = static_cast<std::size_t>(info.block);
    switch (info.kind) {
      case ItemKind::BlockTable: tableAt = p.rect; break;
      case ItemKind::Header: headerAt[b] = p.rect; break;
      case ItemKind::Metadata:
      case ItemKind::Data: break;  // placed above, per block
      case ItemKind::Materials: materialsAt = p.rect; break;
      case ItemKind::Textures: texturesAt = p.rect; break;
      case ItemKind::Records:
        for (int r = info.first; r < std::min(info.first + format::kRedirectionsPerItem,
                                              static_cast<int>(records.size())); ++r)
          recordAt[static_cast<std::size_t>(r)] = {p.rect.x + (r - info.first) * format::kRedirectionPixels, p.rect.y};
        break;
    }
  }

  Image image(layout->width, layout->height);
  // File record.
  std::uint8_t* p = image.at(format::kFileMagic, 0);
  p[0] = format::kMagic[0], p[1] = format::kMagic[1], p[2] = format::kMagic[2], p[3] = format::kVersion;
  p = image.at(format::kFileRoot, 0);
  p[0] = static_cast<std::uint8_t>(headerAt[h.root].x), p[1] = static_cast<std::uint8_t>(headerAt[h.root].y);
  writeU16(p + 2, static_cast<std::uint32_t>(h.blocks.size()));
  p = image.at(format::kFileMaterials, 0);
  writeU24(p, materialCount > 0 ? packAddress(materialsAt.x, materialsAt.y) : 0);
  p[3] = static_cast<std::uint8_t>(materialsPerRow);
  p = image.at(format::kFileCounts, 0);
  writeU16(p, static_cast<std::uint32_t>(materialCount));
  writeU16(p + 2, static_cast<std::uint32_t>(records.size()));
  p = image.at(format::kFileTextures, 0);
  writeU24(p, textureCount > 0 ? packAddress(texturesAt.x, texturesAt.y) : 0);
  p[3] = static_cast<std::uint8_t>(texturesPerRow);
  p = image.at(format::kFileBlockTable, 0);
  p[0] = static_cast<std::uint8_t>(textureCount);
  p[1] = static_cast<std::uint8_t>(tableAt.x), p[2] = static_cast<std::uint8_t>(tableAt.y), p[3] = 0;

  for (std::size_t b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    const packer::Rect& at = headerAt[b];
    // Block table entry.
    const int pixel = static_cast<int>(b) / format::kBlockTableEntriesPerPixel;
    std::uint8_t* entry = image.at(tableAt.x + pixel % format::kBlockTablePixelsPerRow,
                                   tableAt.y + pixel / format::kBlockTablePixelsPerRow) +
                          2 * (b % format::kBlockTableEntriesPerPixel);
    entry[0] = static_cast<std::uint8_t>(at.x), entry[1] = static_cast<std::uint8_t>(at.y);
    // Header.
    for (int s = 0; s < 6; ++s) {
      const Rgba8 c = summaries[b][static_cast<std::size_t>(s)];
      std::uint8_t* q = image.at(at.x + format::kHeaderSummary + s, at.y);
      q[0] = c.r, q[1] = c.g, q[2] = c.b, q[3] = c.a;
    }
    for (int a = 0; a < 3; ++a) {
      std::uint8_t* q = image.at(at.x + format::kHeaderSize + a, at.y);
      writeU24(q, plans[b].axes[static_cast<std::size_t>(a)].sizeUnits);
      q[3] = static_cast<std::uint8_t>(block.cellCount(a) - 1);
    }
    const std::uint32_t data = packAddress(dataAt[b].x, dataAt[b].y);
    const auto& meta = metaAt[b];
    std::uint8_t* q = image.at(at.x + format::kHeaderMetaSizes, at.y);
    for (int a = 0; a < 3; ++a) q[a] = static_cast<std::uint8_t>(meta[static_cast<std::size_t>(a)].width - 1);
    q[3] = static_cast<std::uint8_t>(data);
    q = image.at(at.x + format::kHeaderMetaXY, at.y);
    q[0] = static_cast<std::uint8_t>(meta[0].x), q[1] = static_cast<std::uint8_t>(meta[0].y);
    q[2] = static_cast<std::uint8_t>(meta[1].x), q[3] = static_cast<std::uint8_t>(meta[1].y);
    q = image.at(at.x + format::kHeaderMetaZ, at.y);
    q[0] = static_cast<std::uint8_t>(meta[2].x), q[1] = static_cast<std::uint8_t>(meta[2].y);
    writeU16(q + 2, data >> 8);
    // Metadata arrays.
    for (int a = 0; a < 3; ++a) {
      const packer::Rect& r = meta[static_cast<std::size_t>(a)];
      encodeAxisIndex(plans[b].axes[static_cast<std::size_t>(a)], image.at(r.x, r.y), image.at(r.x, r.y + 1));
    }
    // Data component: z tiled along x, top cell row first.
    const int nx = block.cellCount(0), ny = block.cellCount(1), nz = block.cellCount(2);
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const Cell& cell = block.cell(x, y, z);
          std::uint8_t* d = image.at(dataAt[b].x + x + z * nx, dataAt[b].y + ny - 1 - y);
          if (cell.kind == CellKind::Solid) {
            writeU16(d, cell.material);
            d[2] = cell.texture;
            d[3] = static_cast<std::uint8_t>(format::kCellFirstSolid + cell.solid.index);
          } else if (cell.kind == CellKind::Redirection) {
            const TexelAddress r = recordAt[static_cast<std::size_t>(plans[b].records[cell.redirection])];
            d[0] = static_cast<std::uint8_t>(r.u), d[1] = static_cast<std::uint8_t>(r.v);
            d[3] = format::kCellRedirection;
          }
        }
  }
  // Redirection records.
  for (std::size_t r = 0; r < records.size(); ++r) {
    const auto& [target, ox, oy, oz, wrap, cube, yaw] = records[r];
    const TexelAddress at = recordAt[r];
    const std::int64_t offset[3] = {ox, oy, oz};
    for (int a = 0; a < 3; ++a) writeU24(image.at(at.u + a, at.v), static_cast<std::uint32_t>(offset[a]) & 0xffffff);
    image.at(at.u, at.v)[3] = wrap;
    image.at(at.u + 1, at.v)[3] = cube;
    std::uint8_t* q = image.at(at.u + 3, at.v);
    q[0] = static_cast<std::uint8_t>(headerAt[target].x), q[1] = static_cast<std::uint8_t>(headerAt[target].y);
    writeU16(q + 2, yaw);
  }
  // Materials and texture infos, row-major in their rectangles.
  for (int m = 0; m < materialCount; ++m) {
    const Material& mat = h.materials[static_cast<std::size_t>(m)];
    std::uint8_t* q = image.at(materialsAt.x + format::kMaterialPixels * (m % format::kMaterialsPerRow),
                               materialsAt.y + m / format::kMaterialsPerRow);
    q[0] = mat.r, q[1] = mat.g, q[2] = mat.b, q[3] = mat.opacity, q[4] = mat.reflectance;
  }
  for (int t = 0; t < textureCount; ++t) {
    const TextureInfo& tex = h.textures[static_cast<std::size_t>(t)];
    std::uint8_t* q = image.at(texturesAt.x + format::kTextureInfoPixels * (t % format::kTextureInfosPerRow),
                               texturesAt.y + t / format::kTextureInfosPerRow);
    for (int a = 0; a < 3; ++a) {
      auto o = offsetUnits(tex.offsetM[a], "texture info " + std::to_string(t));
      if (!o) return o.error();
      writeU24(q + 4 * a, static_cast<std::uint32_t>(*o) & 0xffffff);
    }
    q[3] = static_cast<std::uint8_t>(tex.textureId), q[7] = static_cast<std::uint8_t>(tex.textureId >> 8);
  }
  return image;
}

}  // namespace nut
