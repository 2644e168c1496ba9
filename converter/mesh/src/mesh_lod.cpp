// Levels of detail of a complementary mesh with OpenMesh's decimater (converter/mesh_lod.hpp).
#include <converter/mesh_lod.hpp>

#include <cmath>
#include <limits>
#include <map>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace nut::converter {

namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// The mesh in OpenMesh's form, positions relative to `origin` (city coordinates near 10^6 m keep
// their precision in the quadrics), with each face's material, and the faces it would not take.
struct Decimatable {
  OmMesh mesh;
  OpenMesh::FPropHandleT<std::uint16_t> material;
  std::vector<std::size_t> keptAside;  // triangles of the input
};

Decimatable decimatable(const TriangleMesh& in, const glm::dvec3& origin) {
  // OpenMesh reports each face it refuses on its error stream; they are kept aside, not errors.
  static const bool quiet = [] {
    omerr().disable();
    return true;
  }();
  (void)quiet;
  Decimatable d;
  d.mesh.add_property(d.material);
  // Equal positions are one vertex, so that the decimater sees the surface connected.
  std::map<std::array<double, 3>, OmMesh::VertexHandle> vertexAt;
  std::vector<OmMesh::VertexHandle> handles(in.positions.size());
  for (std::size_t v = 0; v < in.positions.size(); ++v) {
    const glm::dvec3 p = in.positions[v] - origin;
    auto [it, added] = vertexAt.try_emplace({p.x, p.y, p.z});
    if (added) it->second = d.mesh.add_vertex(OmMesh::Point(p.x, p.y, p.z));
    handles[v] = it->second;
  }
  for (std::size_t t = 0; t < in.triangles.size(); ++t) {
    const auto& tri = in.triangles[t];
    const OmMesh::VertexHandle a = handles[tri[0]], b = handles[tri[1]], c = handles[tri[2]];
    const OmMesh::FaceHandle f = a == b || b == c || a == c ? OmMesh::FaceHandle() : d.mesh.add_face(a, b, c);
    if (!f.is_valid()) {
      d.keptAside.push_back(t);
      continue;
    }
    d.mesh.property(d.material, f) = in.triangleMaterial[t];
  }
  // Vertices between materials stay, and so do the outlines of colour regions.
  d.mesh.request_vertex_status();
  d.mesh.request_edge_status();
  d.mesh.request_face_status();
  d.mesh.request_face_normals();
  d.mesh.update_face_normals();
  for (const OmMesh::VertexHandle v : d.mesh.vertices()) {
    int first = -1;
    for (const OmMesh::FaceHandle f : d.mesh.vf_range(v)) {
      const int m = d.mesh.property(d.material, f);
      if (first < 0) first = m;
      if (m != first) d.mesh.status(v).set_locked(true);
    }
  }
  return d;
}

// The decimated mesh back in world coordinates, with the faces kept aside.
TriangleMesh triangleMesh(const Decimatable& d, const TriangleMesh& in, const glm::dvec3& origin) {
  TriangleMesh out;
  out.name = in.name;
  out.materials = in.materials;
  out.materialNames = in.materialNames;
  std::vector<std::uint32_t> index(d.mesh.n_vertices(), 0);
  for (const OmMesh::VertexHandle v : d.mesh.vertices()) {
    const OmMesh::Point& p = d.mesh.point(v);
    index[static_cast<std::size_t>(v.idx())] = static_cast<std::uint32_t>(out.positions.size());
    out.positions.push_back(origin + glm::dvec3(p[0], p[1], p[2]));
  }
  for (const OmMesh::FaceHandle f : d.mesh.faces()) {
    std::array<std::uint32_t, 3> tri{};
    std::size_t k = 0;
    for (const OmMesh::VertexHandle v : d.mesh.fv_range(f)) tri[k++] = index[static_cast<std::size_t>(v.idx())];
    out.triangles.push_back(tri);
    out.triangleMaterial.push_back(d.mesh.property(d.material, f));
  }
  for (const std::size_t t : d.keptAside) {
    std::array<std::uint32_t, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      tri[k] = static_cast<std::uint32_t>(out.positions.size());
      out.positions.push_back(in.positions[in.triangles[t][k]]);
    }
    out.triangles.push_back(tri);
    out.triangleMaterial.push_back(in.triangleMaterial[t]);
  }
  return out;
}

using Kernel = CGAL::Simple_cartesian<double>;
using CgalTriangle = Kernel::Triangle_3;
using Tree = CGAL::AABB_tree<
    CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>>>;

// The mesh's surface for distance queries (CGAL's AABB tree), positions relative to `origin`.
struct Surface {
  std::vector<CgalTriangle> triangles;
  Tree tree;
  Surface(const TriangleMesh& mesh, const glm::dvec3& origin) {
    for (const auto& t : mesh.triangles) {
      const auto point = [&](std::uint32_t v) {
        const glm::dvec3 q = mesh.positions[v] - origin;
        return Kernel::Point_3(q.x, q.y, q.z);
      };
      const Kernel::Point_3 a = point(t[0]), b = point(t[1]), c = point(t[2]);
      if (!CGAL::collinear(a, b, c)) triangles.emplace_back(a, b, c);
    }
    tree.insert(triangles.begin(), triangles.end());
    tree.accelerate_distance_queries();
  }
  double distance(const Kernel::Point_3& p) const { return std::sqrt(tree.squared_distance(p)); }
};

// Keeps each new face on the mesh's surface: every face a collapse makes has its centroid and
// edge midpoints within the tolerance of the original surface (the Hausdorff module checks the
// removed vertices against the new faces, not the new faces against the surface, which a face
// grown over a window's hole or past a roof's outline breaks). A vertex on the boundary moves only
// along it, and a collapse must leave a face around the kept vertex, so no small piece vanishes.
template <class MeshT>
class ModStayOnSurfaceT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModStayOnSurfaceT, MeshT, StayOnSurface);
  explicit ModStayOnSurfaceT(MeshT& mesh) : Base(mesh, true) {}
  void set(const Surface* surface, double toleranceM) { surface_ = surface, tolerance_ = toleranceM; }

  float collapse_priority(const CollapseInfo& ci) override {
    const Mesh& mesh = Base::mesh();
    if (mesh.is_boundary(ci.v0) && !mesh.is_boundary(mesh.edge_handle(ci.v0v1))) return Base::ILLEGAL_COLLAPSE;
    bool faceLeft = false;
    for (const OmMesh::FaceHandle f : mesh.vf_range(ci.v1)) faceLeft = faceLeft || (f != ci.fl && f != ci.fr);
    for (const OmMesh::FaceHandle f : mesh.vf_range(ci.v0)) {
      if (f == ci.fl || f == ci.fr) continue;
      faceLeft = true;
      // The face as it will be: v0 moved onto v1.
      std::array<OmMesh::Point, 3> corner;
      std::size_t k = 0;
      for (const OmMesh::VertexHandle v : mesh.fv_range(f)) corner[k++] = mesh.point(v == ci.v0 ? ci.v1 : v);
      const auto far = [&](const OmMesh::Point& p) {
        return surface_->distance(Kernel::Point_3(p[0], p[1], p[2])) > tolerance_;
      };
      if (far((corner[0] + corner[1] + corner[2]) / 3.0) || far(0.5 * (corner[0] + corner[1])) ||
          far(0.5 * (corner[1] + corner[2])) || far(0.5 * (corner[2] + corner[0])))
        return Base::ILLEGAL_COLLAPSE;
    }
    return faceLeft ? Base::LEGAL_COLLAPSE : Base::ILLEGAL_COLLAPSE;
  }

 private:
  const Surface* surface_ = nullptr;
  double tolerance_ = 0;
};

TriangleMesh decimated(const TriangleMesh& in, const glm::dvec3& origin, double toleranceM) {
  Decimatable d = decimatable(in, origin);
  OpenMesh::Decimater::DecimaterT<OmMesh> decimater(d.mesh);
  OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
  OpenMesh::Decimater::ModHausdorffT<OmMesh>::Handle hausdorff;
  OpenMesh::Decimater::ModNormalFlippingT<OmMesh>::Handle flipping;
  ModStayOnSurfaceT<OmMesh>::Handle stayOnSurface;
  decimater.add(quadric);
  decimater.add(hausdorff);
  decimater.add(flipping);
  decimater.add(stayOnSurface);
  // A kept vertex within the tolerance of every original face plane around the removed one (the
  // quadric is the sum of squared distances to them): no collapse across a wall's edge.
  decimater.module(quadric).set_max_err(toleranceM * toleranceM, false);
  decimater.module(hausdorff).set_tolerance(toleranceM);
  const Surface surface(in, origin);
  decimater.module(stayOnSurface).set(&surface, toleranceM);
  if (!decimater.initialize()) return in;
  decimater.decimate();
  d.mesh.garbage_collection();
  return triangleMesh(d, in, origin);
}

}  // namespace

std::vector<glm::dvec3> surfaceSamples(const TriangleMesh& mesh) {
  std::vector<glm::dvec3> samples;
  samples.reserve(7 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    samples.insert(samples.end(), {a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (a + b + c) / 3.0});
  }
  return samples;
}

double surfaceDistance(const TriangleMesh& from, const TriangleMesh& to) {
  if (from.triangles.empty()) return 0.0;
  const glm::dvec3 origin = from.bounds().min;
  const Surface surface(to, origin);
  if (surface.triangles.empty()) return std::numeric_limits<double>::infinity();
  double worst = 0;
  for (const glm::dvec3& p : surfaceSamples(from)) {
    const glm::dvec3 q = p - origin;
    worst = std::max(worst, surface.distance(Kernel::Point_3(q.x, q.y, q.z)));
  }
  return worst;
}

std::vector<MeshLevel> meshLevels(const TriangleMesh& mesh, const MeshLodOptions& options) {
  std::vector<MeshLevel> levels;
  if (mesh.triangles.empty()) return levels;
  const glm::dvec3 origin = mesh.bounds().min;
  std::size_t previous = mesh.triangles.size();
  double tolerance = options.firstToleranceM;
  for (int k = 0; k < options.maxLevels; ++k, tolerance *= options.factor) {
    TriangleMesh level = decimated(mesh, origin, tolerance);
    if (static_cast<double>(level.triangles.size()) > kLevelShrink * static_cast<double>(previous)) continue;
    previous = level.triangles.size();
    const double error = std::max(surfaceDistance(mesh, level), surfaceDistance(level, mesh));
    levels.push_back({std::move(level), error});
  }
  return levels;
}

}  // namespace nut::converter
