// Statistics of an HNI computed from its records (what `nut info` prints). The covered pixels are
// counted from the records' own extents, independently of how compile() packed them.
#include <nut/hni.hpp>

#include <nut/hni_view.hpp>

namespace nut {

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

  std::vector<bool> covered(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height), false);
  const auto cover = [&](TexelAddress a, int w, int h) {
    for (int v = a.v; v < a.v + h; ++v)
      for (int u = a.u; u < a.u + w; ++u)
        covered[static_cast<std::size_t>(v) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(u)] = true;
  };
  cover({0, 0}, format::kFileRecordPixels, 1);
  const int tablePixels = (file.blockCount + 1) / 2;
  cover(file.blockTable, std::min(tablePixels, format::kBlockTablePixelsPerRow),
        (tablePixels + format::kBlockTablePixelsPerRow - 1) / format::kBlockTablePixelsPerRow);
  for (int m = 0; m < file.materialCount; ++m)
    cover({file.materials.u + format::kMaterialPixels * (m % file.materialsPerRow), file.materials.v + m / file.materialsPerRow},
          format::kMaterialPixels, 1);
  for (int t = 0; t < file.textureCount; ++t)
    cover({file.textures.u + format::kTextureInfoPixels * (t % file.texturesPerRow), file.textures.v + t / file.texturesPerRow},
          format::kTextureInfoPixels, 1);
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader h = view.header(view.blockAddress(file, b));
    cover(view.blockAddress(file, b), format::kHeaderPixels, 1);
    for (int a = 0; a < 3; ++a) cover(h.meta[static_cast<std::size_t>(a)], h.metaPixels[a], 2);
    cover(h.data, h.cells.x * h.cells.z, h.cells.y);
    for (int z = 0; z < h.cells.z; ++z)
      for (int y = 0; y < h.cells.y; ++y)
        for (int x = 0; x < h.cells.x; ++x) {
          const CellTexel t = view.cell(h, {x, y, z});
          ++s.cells;
          if (t.g >= format::kCellFirstSolid) ++s.solidCells;
          if (t.g == format::kCellRedirection) {
            ++s.redirectionCells;
            cover(t.redirection, format::kRedirectionPixels, 1);
          }
        }
  }
  for (bool c : covered) s.usedPixels += c;
  s.wastePct = 100.0 * (1.0 - static_cast<double>(s.usedPixels) / static_cast<double>(image.width * image.height));
  if (auto h = decode(image)) s.dagDepth = dagDepth(*h);
  return s;
}

}  // namespace nut
