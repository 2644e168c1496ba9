// Neighbouring buildings as one hierarchy (converter/district.hpp).
#include <converter/district.hpp>

#include <converter/assemble.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>

#include <glm/mat3x3.hpp>

#include <nut/format.hpp>
#include <nut/units.hpp>

namespace nut::converter {

namespace {

using Units = std::int64_t;

// A turn about +y as the format stores it: exact cube rotations for quarter turns.
Rotation yawRotation(double yawDeg) {
  const double turns = yawDeg / 360.0 - std::floor(yawDeg / 360.0);
  const double quarters = turns * 4.0;
  if (std::abs(quarters - std::round(quarters)) < 1e-9) {
    // 0, 90, 180, 270 degrees: the identity, x -> -z, x -> -x, x -> +z (docs/FORMAT.md's table).
    static constexpr std::array<std::uint8_t, 4> kQuarterTurns{0, 20, 2, 22};
    return Rotation{kQuarterTurns[static_cast<std::size_t>(std::lround(quarters)) % 4], 0};
  }
  return Rotation{0, static_cast<std::uint16_t>(std::lround(turns * 65536.0) % 65536)};
}

void mixHash(std::size_t& seed, std::size_t value) {
  seed ^= value + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
}

std::size_t blockHash(const Block& b) {
  std::size_t h = 0;
  for (const auto& bounds : b.boundsM) {
    mixHash(h, bounds.size());
    for (double x : bounds) mixHash(h, std::hash<double>{}(x));
  }
  for (const Cell& c : b.cells)
    mixHash(h, static_cast<std::size_t>(c.kind) | std::size_t{c.solid.index} << 8 | std::size_t{c.material} << 16 |
                   std::size_t{c.texture} << 32 | std::size_t{c.redirection} << 40);
  for (const Redirection& r : b.redirections) {
    mixHash(h, r.target);
    for (int a = 0; a < 3; ++a) mixHash(h, std::hash<double>{}(r.offsetM[a]));
  }
  return h;
}

// Adds the blocks of each building to one hierarchy, children before parents, keeping one block of
// every set of equal blocks (equal once their materials, textures and targets are renumbered).
class BlockMerger {
 public:
  explicit BlockMerger(Hierarchy& out) : out_(out) {}

  Result<BlockId> addBuilding(const Hierarchy& h, std::size_t index) {
    if (Status s = checkHierarchy(h); !s) return Error{"building " + std::to_string(index) + ": " + s.error().message};
    materials_.clear();
    for (const Material& m : h.materials) materials_.push_back(out_.addMaterial(m));
    textures_.clear();
    for (const TextureInfo& t : h.textures) {
      auto it = std::find(out_.textures.begin(), out_.textures.end(), t);
      if (it == out_.textures.end()) {
        if (out_.textures.size() >= format::kMaxTextureInfos)
          return Error{"building " + std::to_string(index) + ": more texture infos than one HNI holds"};
        it = out_.textures.insert(out_.textures.end(), t);
      }
      textures_.push_back(static_cast<std::uint8_t>(it - out_.textures.begin() + 1));
    }
    added_.assign(h.blocks.size(), std::nullopt);
    return add(h, h.root);
  }

  std::size_t blocksSeen() const { return seen_; }
  std::size_t blocksMerged() const { return merged_; }

 private:
  BlockId add(const Hierarchy& h, BlockId id) {
    if (added_[id]) return *added_[id];
    Block b = h.blocks[id];
    for (Redirection& r : b.redirections) r.target = add(h, r.target);
    for (Cell& c : b.cells) {
      if (!c.hasMaterial()) continue;
      c.material = materials_[c.material];
      if (c.texture != 0) c.texture = textures_[c.texture - 1u];
    }
    ++seen_;
    const std::size_t hash = blockHash(b);
    for (auto [it, end] = byHash_.equal_range(hash); it != end; ++it)
      if (out_.blocks[it->second] == b) {
        ++merged_;
        return *(added_[id] = it->second);
      }
    const BlockId newId = out_.addBlock(std::move(b));
    byHash_.emplace(hash, newId);
    return *(added_[id] = newId);
  }

  Hierarchy& out_;
  std::unordered_multimap<std::size_t, BlockId> byHash_;
  std::vector<std::uint16_t> materials_;
  std::vector<std::uint8_t> textures_;
  std::vector<std::optional<BlockId>> added_;
  std::size_t seen_ = 0, merged_ = 0;
};

// Sorted distinct values.
std::vector<Units> distinct(std::vector<Units> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

std::size_t indexOf(const std::vector<Units>& sorted, Units value) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), value) - sorted.begin());
}

}  // namespace

WorldBox placedRootBox(const Hierarchy& h, const glm::dvec3& positionM, double yawDeg) {
  glm::dvec3 size = h.blocks[h.root].sizeM();
  for (int a = 0; a < 3; ++a) size[a] = snapToUnits(size[a]);
  const glm::dmat3 turn = rotationMatrix(yawRotation(yawDeg));
  WorldBox box{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 local((corner & 1) ? size.x : 0.0, (corner & 2) ? size.y : 0.0, (corner & 4) ? size.z : 0.0);
    const glm::dvec3 world = positionM + turn * local;
    box.min = glm::min(box.min, world);
    box.max = glm::max(box.max, world);
  }
  return box;
}

Result<District> mergeDistrict(const std::vector<PlacedHierarchy>& buildings) {
  if (buildings.empty()) return Error{"a district needs at least one building"};
  District d;
  BlockMerger merger(d.hierarchy);
  std::vector<BlockId> roots;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    auto root = merger.addBuilding(*buildings[i].hierarchy, i);
    if (!root) return root.error();
    roots.push_back(*root);
  }
  d.buildingBlocks = merger.blocksSeen();
  d.mergedBlocks = merger.blocksMerged();

  // The buildings' boxes in whole millimetres from the district's origin, as the format keeps them.
  std::array<Units, 3> origin{INT64_MAX, INT64_MAX, INT64_MAX};
  std::vector<std::array<Units, 3>> lo(buildings.size()), hi(buildings.size()), position(buildings.size());
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const PlacedHierarchy& b = buildings[i];
    const WorldBox box = placedRootBox(*b.hierarchy, b.positionM, b.yawDeg);
    for (std::size_t a = 0; a < 3; ++a) {
      lo[i][a] = toUnits(box.min[static_cast<int>(a)]);
      hi[i][a] = toUnits(box.max[static_cast<int>(a)]);
      position[i][a] = toUnits(b.positionM[static_cast<int>(a)]);
      origin[a] = std::min(origin[a], lo[i][a]);
    }
  }
  std::vector<Units> xs{0}, zs{0};
  Units top = 1;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      lo[i][a] -= origin[a];
      hi[i][a] -= origin[a];
      position[i][a] -= origin[a];
    }
    xs.push_back(lo[i][0]);
    xs.push_back(hi[i][0]);
    zs.push_back(lo[i][2]);
    zs.push_back(hi[i][2]);
    top = std::max(top, hi[i][1]);
  }
  xs = distinct(xs);
  zs = distinct(zs);
  Block root;
  for (Units x : xs) root.boundsM[0].push_back(toMetres(x));
  root.boundsM[1] = {0.0, toMetres(top)};
  for (Units z : zs) root.boundsM[2].push_back(toMetres(z));
  root.cells.assign((xs.size() - 1) * (zs.size() - 1), Cell::empty());
  std::vector<std::size_t> owner(root.cells.size());
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const Rotation turn = yawRotation(buildings[i].yawDeg);
    for (std::size_t x = indexOf(xs, lo[i][0]); x < indexOf(xs, hi[i][0]); ++x)
      for (std::size_t z = indexOf(zs, lo[i][2]); z < indexOf(zs, hi[i][2]); ++z) {
        const std::size_t c = root.cellIndex(static_cast<int>(x), 0, static_cast<int>(z));
        Cell& cell = root.cells[c];
        if (cell.kind != CellKind::Empty)
          return Error{"building " + std::to_string(i) + " overlaps building " + std::to_string(owner[c]) +
                       " on the ground"};
        owner[c] = i;
        cell = Cell::redirect(static_cast<std::uint32_t>(root.redirections.size()));
        const glm::dvec3 offset(toMetres(position[i][0] - xs[x]), toMetres(position[i][1]),
                                toMetres(position[i][2] - zs[z]));
        root.redirections.push_back(Redirection{roots[i], offset, turn, {false, false, false}});
      }
  }
  d.hierarchy.root = d.hierarchy.addBlock(std::move(root));
  // Sides of buildings in neighbouring rows make narrow cells that one metadata array cannot
  // index over the whole district: split the root where the format needs it.
  if (auto split = splitBlocks(d.hierarchy); !split) return split.error();
  d.originM = {toMetres(origin[0]), toMetres(origin[1]), toMetres(origin[2])};
  d.boundsM = {d.originM, d.originM + d.hierarchy.blocks[d.hierarchy.root].sizeM()};
  return d;
}

}  // namespace nut::converter
