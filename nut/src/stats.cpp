// Statistics of an HNI computed from its records (what `nut info` prints), and which record each
// pixel belongs to. Both come from the records' own extents, independently of how compile()
// packed them.
#include <nut/hni.hpp>

#include <nut/hni_view.hpp>

namespace nut {

const char* pixelKindName(PixelKind kind) {
  switch (kind) {
    case PixelKind::Unused: return "unused";
    case PixelKind::FileRecord: return "file record";
    case PixelKind::BlockTable: return "block table";
    case PixelKind::Header: return "block headers";
    case PixelKind::MetadataRow: return "metadata rows";
    case PixelKind::ExactRow: return "exact rows";
    case PixelKind::DataComponent: return "data components";
    case PixelKind::RedirectionRecord: return "redirection records";
    case PixelKind::Material: return "materials";
    case PixelKind::TextureInfo: return "texture infos";
    case PixelKind::PlaneRecord: return "plane cell records";
  }
  return "?";
}

std::vector<PixelKind> pixelKinds(const Image& image) {
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  std::vector<PixelKind> kinds(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height), PixelKind::Unused);
  const auto mark = [&](TexelAddress a, int w, int h, PixelKind kind) {
    for (int v = a.v; v < a.v + h; ++v)
      for (int u = a.u; u < a.u + w; ++u) kinds[static_cast<std::size_t>(v) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(u)] = kind;
  };
  mark({0, 0}, format::kFileRecordPixels, 1, PixelKind::FileRecord);
  const int tablePixels = (file.blockCount + 1) / 2;
  for (int p = 0; p < tablePixels; ++p)
    mark({file.blockTable.u + p % format::kBlockTablePixelsPerRow, file.blockTable.v + p / format::kBlockTablePixelsPerRow}, 1, 1,
         PixelKind::BlockTable);
  for (int m = 0; m < file.materialCount; ++m)
    mark({file.materials.u + format::kMaterialPixels * (m % file.materialsPerRow), file.materials.v + m / file.materialsPerRow},
         format::kMaterialPixels, 1, PixelKind::Material);
  for (int t = 0; t < file.textureCount; ++t)
    mark({file.textures.u + format::kTextureInfoPixels * (t % file.texturesPerRow), file.textures.v + t / file.texturesPerRow},
         format::kTextureInfoPixels, 1, PixelKind::TextureInfo);
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader h = view.header(view.blockAddress(file, b));
    mark(view.blockAddress(file, b), format::kHeaderPixels, 1, PixelKind::Header);
    for (int a = 0; a < 3; ++a) {
      mark(h.meta[static_cast<std::size_t>(a)], h.metaPixels[a], 1, PixelKind::MetadataRow);
      mark({h.meta[static_cast<std::size_t>(a)].u, h.meta[static_cast<std::size_t>(a)].v + 1}, h.metaPixels[a], 1, PixelKind::ExactRow);
    }
    mark(h.data, h.cells.x * h.cells.z, h.cells.y, PixelKind::DataComponent);
    for (int z = 0; z < h.cells.z; ++z)
      for (int y = 0; y < h.cells.y; ++y)
        for (int x = 0; x < h.cells.x; ++x) {
          const CellTexel t = view.cell(h, {x, y, z});
          if (t.g == format::kCellRedirection)
            mark(t.redirection, format::kRedirectionPixels, 1, PixelKind::RedirectionRecord);
          if (t.g != format::kCellPlane) continue;
          const int planes = view.planeRecord(t.planeRecord).planeCount();
          mark(t.planeRecord, format::kPlaneRecordHeadPixels + format::kPixelsPerPlane * planes, 1,
               PixelKind::PlaneRecord);
        }
  }
  return kinds;
}

HniStats computeStats(const Image& image) {
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  HniStats s;
  s.blocks = file.blockCount;
  s.redirections = file.redirectionCount;
  s.materials = file.materialCount;
  s.textures = file.textureCount;
  s.width = image.width;
  s.height = image.height;
  s.bytesRaw = static_cast<long long>(image.width) * image.height * 4;
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader h = view.header(view.blockAddress(file, b));
    for (int z = 0; z < h.cells.z; ++z)
      for (int y = 0; y < h.cells.y; ++y)
        for (int x = 0; x < h.cells.x; ++x) {
          const CellTexel t = view.cell(h, {x, y, z});
          ++s.cells;
          s.solidCells += t.g >= format::kCellFirstSolid && t.g <= format::kCellLastSolid;
          s.planeCells += t.g == format::kCellPlane;
          s.redirectionCells += t.g == format::kCellRedirection;
        }
  }
  for (PixelKind k : pixelKinds(image)) s.usedPixels += k != PixelKind::Unused;
  s.wastePct = 100.0 * (1.0 - static_cast<double>(s.usedPixels) / static_cast<double>(image.width * image.height));
  if (auto h = decode(image)) s.dagDepth = dagDepth(*h);
  return s;
}

}  // namespace nut
