// Neighbouring buildings as one hierarchy (converter/district.hpp).
#include <converter/district.hpp>

#include <converter/assemble.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>

#include <glm/mat3x3.hpp>

#include <nut/format.hpp>
#include <nut/hni.hpp>
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

  // Adds the blocks of building `index` (a valid hierarchy) that `start`, its root or a block under
  // it, reaches.
  Result<BlockId> addBuilding(const Hierarchy& h, std::size_t index, BlockId start) {
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
    return add(h, start);
  }

  std::size_t blocksSeen() const { return seen_; }
  std::size_t blocksMerged() const { return merged_; }

 private:
  BlockId add(const Hierarchy& h, BlockId id) {
    if (added_[id]) return *added_[id];
    Block b = h.blocks[id];
    for (Redirection& r : b.redirections) r.target = add(h, r.target);
    renumberMaterials(b, materials_);
    for (Cell& c : b.cells)
      if (c.hasMaterial() && c.texture != 0) c.texture = textures_[c.texture - 1u];
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

namespace {

// A building of the district on the ground: its box and its root's position, in whole millimetres
// from the district's origin, its root block and its turn.
struct PlacedRoot {
  std::array<Units, 3> lo, hi, position;
  BlockId root = 0;
  Rotation turn;
  // Where a building's root is only a frame (one cell redirecting, turned, to its grid: a
  // converted building turned about the vertical), the district redirects to the grid itself: the
  // root's own record, moved by the root's position. Zero otherwise.
  glm::dvec3 frameOffsetM{0.0};
};

// The redirection of h's root when the root is a frame the district can skip: one cell, a
// redirection that does not tile (tiling would fill the district's larger cell), and the building
// placed unturned (a turn would have to be composed with the record's).
std::optional<Redirection> skippableFrame(const Hierarchy& h, double yawDeg) {
  const Block& root = h.blocks[h.root];
  if (yawDeg != 0.0 || root.cells.size() != 1 || root.cells[0].kind != CellKind::Redirection) return std::nullopt;
  const Redirection& r = root.redirections[root.cells[0].redirection];
  if (r.wrap[0] || r.wrap[1] || r.wrap[2]) return std::nullopt;
  return r;
}

// The blocks over the buildings' roots: each block cuts the ground along x or z between buildings,
// so that every building is one cell and each cell redirects to a building or to the next block
// down (a k-d tree with as many cuts per block as there are gaps). Where no line on the ground
// separates the buildings (four boxes turning around a fifth), one block of cells bounded by every
// box side holds them.
class RootTree {
 public:
  RootTree(Hierarchy& h, const std::vector<PlacedRoot>& buildings, Units top)
      : h_(h), buildings_(buildings), top_(top) {}

  // The block over `members`, spanning lo..hi on the ground ((x, z), millimetres).
  Result<BlockId> node(const std::vector<std::size_t>& members, const std::array<Units, 2>& lo,
                       const std::array<Units, 2>& hi) {
    std::array<std::vector<Slab>, 2> slabs{slabsAlong(members, 0, lo[0]), slabsAlong(members, 2, lo[1])};
    const int axis = slabs[1].size() > slabs[0].size() ? 1 : 0;
    if (slabs[axis].size() < 2) return grid(members, lo, hi);
    const std::size_t along = axis == 0 ? 0 : 2, across = axis == 0 ? 2 : 0;
    Block b;
    b.boundsM[1] = {0.0, toMetres(top_)};
    b.boundsM[across] = {0.0, toMetres(hi[1 - axis] - lo[1 - axis])};
    for (const Slab& slab : slabs[axis]) b.boundsM[along].push_back(toMetres(slab.start - lo[axis]));
    b.boundsM[along].push_back(toMetres(hi[axis] - lo[axis]));
    for (std::size_t k = 0; k < slabs[axis].size(); ++k) {
      const Slab& slab = slabs[axis][k];
      std::array<Units, 2> cellLo = lo, cellHi = hi;
      cellLo[axis] = slab.start;
      if (k + 1 < slabs[axis].size()) cellHi[axis] = slabs[axis][k + 1].start;
      b.cells.push_back(Cell::redirect(static_cast<std::uint32_t>(b.redirections.size())));
      if (slab.members.size() == 1) {
        b.redirections.push_back(redirectionTo(slab.members.front(), cellLo));
        continue;
      }
      auto child = node(slab.members, cellLo, cellHi);
      if (!child) return child.error();
      b.redirections.push_back(Redirection{*child, glm::dvec3(0.0), Rotation{}, {false, false, false}});
    }
    return h_.addBlock(std::move(b));
  }

 private:
  // Buildings side by side along an axis, and where their cell starts.
  struct Slab {
    Units start = 0;
    std::vector<std::size_t> members;
  };

  // The members in runs along axis a, a cut after each run that no box crosses; the first slab
  // starts at lo, the next where the previous run ends (the gap between goes to the later one).
  std::vector<Slab> slabsAlong(std::vector<std::size_t> members, std::size_t a, Units lo) const {
    std::sort(members.begin(), members.end(), [&](std::size_t i, std::size_t j) {
      return buildings_[i].lo[a] != buildings_[j].lo[a] ? buildings_[i].lo[a] < buildings_[j].lo[a] : i < j;
    });
    std::vector<Slab> slabs{{lo, {}}};
    Units runEnd = lo;
    for (std::size_t i : members) {
      if (!slabs.back().members.empty() && buildings_[i].lo[a] >= runEnd) slabs.push_back({runEnd, {}});
      slabs.back().members.push_back(i);
      runEnd = std::max(runEnd, buildings_[i].hi[a]);
    }
    return slabs;
  }

  // Building i's root, from a cell whose minimum corner on the ground is cellLo.
  Redirection redirectionTo(std::size_t i, const std::array<Units, 2>& cellLo) const {
    const PlacedRoot& b = buildings_[i];
    const glm::dvec3 offset(toMetres(b.position[0] - cellLo[0]), toMetres(b.position[1]),
                            toMetres(b.position[2] - cellLo[1]));
    return Redirection{b.root, offset + b.frameOffsetM, b.turn, {false, false, false}};
  }

  // One block whose boundaries are every member box's sides: the cells of a box redirect to its
  // building, each with the offset of the building's root from the cell.
  Result<BlockId> grid(const std::vector<std::size_t>& members, const std::array<Units, 2>& lo,
                       const std::array<Units, 2>& hi) {
    std::vector<Units> xs{lo[0], hi[0]}, zs{lo[1], hi[1]};
    for (std::size_t i : members) {
      xs.insert(xs.end(), {buildings_[i].lo[0], buildings_[i].hi[0]});
      zs.insert(zs.end(), {buildings_[i].lo[2], buildings_[i].hi[2]});
    }
    xs = distinct(xs);
    zs = distinct(zs);
    Block b;
    for (Units x : xs) b.boundsM[0].push_back(toMetres(x - lo[0]));
    b.boundsM[1] = {0.0, toMetres(top_)};
    for (Units z : zs) b.boundsM[2].push_back(toMetres(z - lo[1]));
    b.cells.assign((xs.size() - 1) * (zs.size() - 1), Cell::empty());
    std::vector<std::size_t> owner(b.cells.size());
    for (std::size_t i : members)
      for (std::size_t x = indexOf(xs, buildings_[i].lo[0]); x < indexOf(xs, buildings_[i].hi[0]); ++x)
        for (std::size_t z = indexOf(zs, buildings_[i].lo[2]); z < indexOf(zs, buildings_[i].hi[2]); ++z) {
          const std::size_t c = b.cellIndex(static_cast<int>(x), 0, static_cast<int>(z));
          Cell& cell = b.cells[c];
          if (cell.kind != CellKind::Empty)
            return Error{"building " + std::to_string(i) + " overlaps building " + std::to_string(owner[c]) +
                         " on the ground"};
          owner[c] = i;
          cell = Cell::redirect(static_cast<std::uint32_t>(b.redirections.size()));
          b.redirections.push_back(redirectionTo(i, {xs[x], zs[z]}));
        }
    return h_.addBlock(std::move(b));
  }

  Hierarchy& h_;
  const std::vector<PlacedRoot>& buildings_;
  Units top_;
};

}  // namespace

Result<District> mergeDistrict(const std::vector<PlacedHierarchy>& buildings) {
  if (buildings.empty()) return Error{"a district needs at least one building"};
  District d;
  BlockMerger merger(d.hierarchy);
  std::vector<PlacedRoot> placed(buildings.size());
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const Hierarchy& h = *buildings[i].hierarchy;
    if (Status valid = checkHierarchy(h); !valid)
      return Error{"building " + std::to_string(i) + ": " + valid.error().message};
    const std::optional<Redirection> frame = skippableFrame(h, buildings[i].yawDeg);
    auto root = merger.addBuilding(h, i, frame ? frame->target : h.root);
    if (!root) return root.error();
    placed[i].root = *root;
    placed[i].turn = frame ? frame->rotation : yawRotation(buildings[i].yawDeg);
    if (frame) placed[i].frameOffsetM = frame->offsetM;
  }
  d.buildingBlocks = merger.blocksSeen();
  d.mergedBlocks = merger.blocksMerged();

  // The buildings' boxes in whole millimetres from the district's origin, as the format keeps them.
  std::array<Units, 3> origin{INT64_MAX, INT64_MAX, INT64_MAX}, extent{INT64_MIN, INT64_MIN, INT64_MIN};
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const PlacedHierarchy& b = buildings[i];
    const WorldBox box = placedRootBox(*b.hierarchy, b.positionM, b.yawDeg);
    for (std::size_t a = 0; a < 3; ++a) {
      placed[i].lo[a] = toUnits(box.min[static_cast<int>(a)]);
      placed[i].hi[a] = toUnits(box.max[static_cast<int>(a)]);
      placed[i].position[a] = toUnits(b.positionM[static_cast<int>(a)]);
      origin[a] = std::min(origin[a], placed[i].lo[a]);
      extent[a] = std::max(extent[a], placed[i].hi[a]);
    }
  }
  for (PlacedRoot& b : placed)
    for (std::size_t a = 0; a < 3; ++a) {
      b.lo[a] -= origin[a];
      b.hi[a] -= origin[a];
      b.position[a] -= origin[a];
    }
  std::vector<std::size_t> all(buildings.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  RootTree tree(d.hierarchy, placed, std::max<Units>(1, extent[1] - origin[1]));
  auto root = tree.node(all, {0, 0}, {extent[0] - origin[0], extent[2] - origin[2]});
  if (!root) return root.error();
  d.hierarchy.root = *root;
  // A block of many buildings side by side may have more cells, or narrower ones, than one
  // metadata array indexes: split them where the format needs it.
  if (auto split = splitBlocks(d.hierarchy); !split) return split.error();
  d.originM = {toMetres(origin[0]), toMetres(origin[1]), toMetres(origin[2])};
  d.boundsM = {d.originM, d.originM + d.hierarchy.blocks[d.hierarchy.root].sizeM()};
  return d;
}

std::vector<std::vector<std::size_t>> districtGroups(const std::vector<WorldBox>& boxes, double sideM,
                                                     const glm::dvec2& cornerM) {
  // A box on the ground in whole millimetres: x0, z0, x1, z1.
  using Footprint = std::array<Units, 4>;
  const auto footprintOf = [](const WorldBox& b) {
    return Footprint{toUnits(b.min.x), toUnits(b.min.z), toUnits(b.max.x), toUnits(b.max.z)};
  };
  const auto overlap = [](const Footprint& a, const Footprint& b) {
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
  };
  std::map<std::pair<long long, long long>, std::vector<std::vector<std::size_t>>> squares;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const glm::dvec3 centre = boxes[i].centre();
    auto& groups = squares[{std::llround(std::floor((centre.x - cornerM.x) / sideM)),
                            std::llround(std::floor((centre.z - cornerM.y) / sideM))}];
    const Footprint mine = footprintOf(boxes[i]);
    const auto fits = [&](const std::vector<std::size_t>& group) {
      return std::none_of(group.begin(), group.end(),
                          [&](std::size_t j) { return overlap(mine, footprintOf(boxes[j])); });
    };
    auto group = std::find_if(groups.begin(), groups.end(), fits);
    if (group == groups.end()) group = groups.insert(groups.end(), std::vector<std::size_t>{});
    group->push_back(i);
  }
  std::vector<std::vector<std::size_t>> out;
  for (auto& [square, groups] : squares)
    for (std::vector<std::size_t>& group : groups) out.push_back(std::move(group));
  return out;
}

namespace {

void compileHalves(const std::vector<PlacedHierarchy>& buildings, const std::vector<std::size_t>& members,
                   const std::string& suffix, std::vector<CompiledDistrict>& out, std::optional<Error>& error) {
  std::vector<PlacedHierarchy> placed;
  for (std::size_t i : members) placed.push_back(buildings[i]);
  auto district = mergeDistrict(placed);
  auto image = district ? compile(district->hierarchy) : Result<Image>(district.error());
  if (!image && members.size() > 1) {
    // Over one HNI's limits (its metadata region, most often): each half on its own.
    const std::size_t half = members.size() / 2;
    compileHalves(buildings,
                  std::vector<std::size_t>(members.begin(), members.begin() + static_cast<std::ptrdiff_t>(half)),
                  suffix + "a", out, error);
    if (!error)
      compileHalves(buildings,
                    std::vector<std::size_t>(members.begin() + static_cast<std::ptrdiff_t>(half), members.end()),
                    suffix + "b", out, error);
    return;
  }
  if (image)
    if (Status s = validate(*image); !s) image = Error{"the compiled HNI does not validate: " + s.error().message};
  if (!image) {
    error = image.error();
    return;
  }
  out.push_back(CompiledDistrict{members, suffix, std::move(*district), std::move(*image)});
}

}  // namespace

Result<std::vector<CompiledDistrict>> compileDistrict(const std::vector<PlacedHierarchy>& buildings,
                                                      const std::vector<std::size_t>& members) {
  std::vector<CompiledDistrict> out;
  std::optional<Error> error;
  compileHalves(buildings, members, "", out, error);
  if (error) return *error;
  return out;
}

}  // namespace nut::converter
