// The derivation as triangles (grammar/derive.hpp, derivationMesh): the DAG expanded into world
// boxes, tiles and clips applied, and each box's six faces emitted but for the ones two opaque
// boxes share exactly.
#include <grammar/derive.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/mat3x3.hpp>

#include "box_frames.hpp"

namespace nut::grammar {

namespace {

constexpr std::size_t kMaxBoxes = 5'000'000;  // 60 M triangles before culling: refused instead

struct SolidBox {
  WorldBox box;
  std::uint16_t material = 0;
  int front = -1;  // the world side a facade's terminal shows (Piece::front), -1 for a mass's box
};

bool hasVolume(const WorldBox& b) { return b.max.x > b.min.x && b.max.y > b.min.y && b.max.z > b.min.z; }

// Every solid box of piece p, placed in the world by rotation r and offset t, inside `clip`.
Status collect(const Derivation& d, const Piece& p, const IMat3& r, const glm::dvec3& t, const WorldBox& clip,
               std::vector<SolidBox>& out) {
  const WorldBox region = turned(p.region, r, t);
  const WorldBox shown{glm::max(region.min, clip.min), glm::min(region.max, clip.max)};
  if (!hasVolume(shown)) return Ok{};
  if (p.kind == Piece::Kind::Box) {
    if (out.size() >= kMaxBoxes) return Error{"the derivation has more than " + std::to_string(kMaxBoxes) + " boxes"};
    out.push_back({shown, p.material, turnedSide(p.front, r)});
    return Ok{};
  }
  const Node& node = d.nodes.at(p.node);
  const IMat3 nodeRotation = r * cubeRotationMatrix(p.cube);
  const glm::dvec3 nodeOrigin = t + glm::dmat3(r) * p.offsetM;
  // The tiles of wrapped axes that meet what shows: the shown box in the node's frame.
  const WorldBox local =
      turned({shown.min - nodeOrigin, shown.max - nodeOrigin}, transposed(nodeRotation), glm::dvec3(0.0));
  std::array<long long, 3> first{}, last{};
  for (int a = 0; a < 3; ++a) {
    if (!p.wrap[static_cast<std::size_t>(a)]) continue;
    first[a] = static_cast<long long>(std::floor(local.min[a] / node.sizeM[a]));
    last[a] = static_cast<long long>(std::ceil(local.max[a] / node.sizeM[a])) - 1;
  }
  for (long long kz = first[2]; kz <= last[2]; ++kz)
    for (long long ky = first[1]; ky <= last[1]; ++ky)
      for (long long kx = first[0]; kx <= last[0]; ++kx) {
        const glm::dvec3 step =
            glm::dvec3(static_cast<double>(kx), static_cast<double>(ky), static_cast<double>(kz)) * node.sizeM;
        const glm::dvec3 tileOrigin = nodeOrigin + glm::dmat3(nodeRotation) * step;
        for (const Piece& q : node.pieces)
          if (Status s = collect(d, q, nodeRotation, tileOrigin, shown, out); !s) return s;
      }
  return Ok{};
}

// A face of a box: the axis it is normal to, the side (+1 or -1), its plane and rectangle.
using FaceKey = std::tuple<int, double, double, double, double, double>;  // axis, plane, u0, u1, v0, v1

}  // namespace

Result<TriangleMesh> derivationMesh(const Derivation& d, MeshFaces faces) {
  std::vector<SolidBox> boxes;
  const WorldBox everywhere{glm::dvec3(-HUGE_VAL), glm::dvec3(HUGE_VAL)};
  if (Status s = collect(d, d.root, IMat3(1), glm::dvec3(0.0), everywhere, boxes); !s) return s.error();

  // A face is dropped when an opaque box has the same rectangle on the other side of the plane.
  std::map<FaceKey, std::array<int, 2>> sides;  // per face: how many opaque boxes on its - and + side
  const auto keyOf = [](const WorldBox& b, int axis, int side) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    return FaceKey{axis, side > 0 ? b.max[axis] : b.min[axis], b.min[u], b.max[u], b.min[v], b.max[v]};
  };
  for (const SolidBox& b : boxes) {
    if (d.materials[b.material].opacity != 255) continue;
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {-1, 1}) ++sides[keyOf(b.box, axis, side)][side > 0 ? 1 : 0];
  }

  TriangleMesh mesh;
  mesh.materials = d.materials;
  mesh.materialNames = d.materialNames;
  std::map<std::array<double, 3>, std::uint32_t> welded;
  const auto vertex = [&](const glm::dvec3& p) {
    auto [it, added] = welded.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(mesh.positions.size()));
    if (added) mesh.positions.push_back(p);
    return it->second;
  };
  for (const SolidBox& b : boxes) {
    const bool opaque = d.materials[b.material].opacity == 255;
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {-1, 1}) {
        if (faces == MeshFaces::Fronts && b.front >= 0 && b.front != 2 * axis + (side > 0 ? 0 : 1)) continue;
        if (opaque) {
          const auto& count = sides.at(keyOf(b.box, axis, side));
          if (count[0] == 1 && count[1] == 1) continue;  // an inner face of two touching boxes
        }
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        glm::dvec3 c[4];
        for (int k = 0; k < 4; ++k) {
          c[k][axis] = side > 0 ? b.box.max[axis] : b.box.min[axis];
          c[k][u] = (k == 1 || k == 2) ? b.box.max[u] : b.box.min[u];
          c[k][v] = (k >= 2) ? b.box.max[v] : b.box.min[v];
        }
        // Counter-clockwise seen from outside: u then v turns about +axis.
        std::array<std::uint32_t, 4> i{vertex(c[0]), vertex(c[1]), vertex(c[2]), vertex(c[3])};
        if (side < 0) std::swap(i[1], i[3]);
        mesh.triangles.push_back({i[0], i[1], i[2]});
        mesh.triangles.push_back({i[0], i[2], i[3]});
        mesh.triangleMaterial.insert(mesh.triangleMaterial.end(), 2, b.material);
      }
  }
  return mesh;
}

}  // namespace nut::grammar
