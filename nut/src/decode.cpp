// Decoding a validated HNI back into the editable Hierarchy (the inverse of compile()).
#include <nut/hni.hpp>

#include <algorithm>
#include <map>

#include <nut/hni_view.hpp>
#include <nut/units.hpp>

namespace nut {

Result<Hierarchy> decode(const Image& image) {
  if (Status s = validate(image); !s) return s.error();
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  std::map<std::pair<int, int>, BlockId> blockAt;
  for (int b = 0; b < file.blockCount; ++b) {
    const TexelAddress a = view.blockAddress(file, b);
    blockAt[{a.u, a.v}] = static_cast<BlockId>(b);
  }
  Hierarchy h;
  std::map<BlockId, double> lodFootprintOf;  // per redirection target
  h.root = blockAt.at({file.root.u, file.root.v});
  for (int m = 0; m < file.materialCount; ++m) h.materials.push_back(view.material(file, m));
  for (int t = 0; t < file.textureCount; ++t) h.textures.push_back(view.textureInfo(file, t));
  for (int b = 0; b < file.blockCount; ++b) {
    const BlockHeader header = view.header(view.blockAddress(file, b));
    Block block;
    block.summary = header.summary;
    for (int a = 0; a < 3; ++a) {
      const AxisView axis = view.axis(header, a);
      auto& bounds = block.boundsM[static_cast<std::size_t>(a)];
      bounds.push_back(0.0);
      for (int k = 0; k < axis.pixels; ++k)
        if (axis.meta[4 * k + 1] != 0) bounds.push_back(toMetres(readU24(axis.exact + 4 * k)));
      bounds.push_back(toMetres(header.sizeUnits[a]));
    }
    block.cells.resize(static_cast<std::size_t>(header.cells.x) * static_cast<std::size_t>(header.cells.y) *
                       static_cast<std::size_t>(header.cells.z));
    // Redirections are listed in order of first use, x fastest (what quantized() produces).
    std::map<std::pair<int, int>, std::uint32_t> recordIndex;
    for (int z = 0; z < header.cells.z; ++z)
      for (int y = 0; y < header.cells.y; ++y)
        for (int x = 0; x < header.cells.x; ++x) {
          const CellTexel t = view.cell(header, {x, y, z});
          Cell& cell = block.cell(x, y, z);
          if (t.g == format::kCellPlane) {
            const PlaneRecord r = view.planeRecord(t.planeRecord);
            PlaneCut cut;
            cut.combine = static_cast<PlaneCombine>(r.combine);
            for (std::size_t p = 0; p < static_cast<std::size_t>(r.planeCount()); ++p) {
              cut.planes[p] = decodePlane(r.planes[p]);
              if (r.surfaceMaterialCodes[p] != 0)
                cut.surfaceMaterials[p] = static_cast<std::uint16_t>(r.surfaceMaterialCodes[p] - 1);
            }
            // Cuts are listed in order of first use, equal ones once (what quantized() produces).
            auto it = std::find(block.cuts.begin(), block.cuts.end(), cut);
            if (it == block.cuts.end()) it = block.cuts.insert(block.cuts.end(), cut);
            cell = Cell::planeCell(static_cast<std::uint32_t>(it - block.cuts.begin()), r.material, r.texture);
          } else if (t.g >= format::kCellFirstSolid) {
            cell = Cell::solidCell(Solid{static_cast<std::uint8_t>(t.g - format::kCellFirstSolid)}, t.material, t.texture);
          } else if (t.g == format::kCellRedirection) {
            auto [it, inserted] = recordIndex.try_emplace({t.redirection.u, t.redirection.v},
                                                          static_cast<std::uint32_t>(block.redirections.size()));
            if (inserted) {
              const RedirectionRecord r = view.redirection(t.redirection);
              Redirection red;
              red.target = blockAt.at({r.target.u, r.target.v});
              red.offsetM = glm::dvec3(toMetres(r.offsetUnits.x), toMetres(r.offsetUnits.y), toMetres(r.offsetUnits.z));
              red.rotation = {r.cubeRotation, r.yaw};
              red.wrap = {(r.wrap & format::kWrapX) != 0, (r.wrap & format::kWrapY) != 0, (r.wrap & format::kWrapZ) != 0};
              block.redirections.push_back(red);
              lodFootprintOf[red.target] = lodFootprintM(r.lodCode);  // validate(): all records agree
            }
            cell = Cell::redirect(it->second);
          }
        }
    h.blocks.push_back(std::move(block));
  }
  for (const auto& [target, footprintM] : lodFootprintOf) h.blocks[target].lodFootprintM = footprintM;
  return h;
}

}  // namespace nut
