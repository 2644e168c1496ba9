// converter/winding.hpp — the generalized winding number of a triangle mesh (Jacobson et al.
// 2013), evaluated fast with a bounding volume hierarchy and far-field expansions (Barill et al.
// 2018, "Fast winding numbers for soups and clouds").
//
// w(q) = (1 / 4 pi) * sum over triangles of the signed solid angle the triangle subtends at q.
// For a closed, outward-oriented mesh it is 1 inside and 0 outside; for the open, overlapping,
// non-manifold meshes real buildings are, it degrades smoothly (about 1/2 next to a hole), so
// "inside" is w >= 1/2 once the mesh faces outwards (mesh_check.hpp). It has no special cases
// at edges or vertices: a query point is never misclassified because it lines up with an edge,
// which is what makes ray parity fragile.
//
// Near triangles are summed exactly (Van Oosterom-Strackee solid angle, one atan2 per leaf of the
// tree); a node of the tree whose bounding sphere is far away (distance > beta * radius) is
// replaced by its second-order expansion (Barill 2018 use orders up to two), which is exact for
// the node's summed area vector and for its first and second moments. Second order at beta 2.2
// is more accurate than first order at beta 3 (5 cm from Ingolstadt's faces, max |fast - exact|
// 0.0034 against 0.0058) and sums a third fewer triangles exactly (977 against 1,436
// a query there, with one atan2 per leaf of up to 12 instead of one per triangle): a query takes
// half the time. `bench/winding_bench` measures time and error.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace nut::converter {

class WindingNumber {
 public:
  // Builds the tree; positions and triangles are copied (relative to `centre` for precision).
  WindingNumber(const std::vector<glm::dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                double beta = 2.2);

  // The generalized winding number at the world point q. Thread-safe.
  double operator()(const glm::dvec3& q) const;

  // The exact sum over every triangle (no tree, one atan2 per triangle): the reference for tests.
  double exact(const glm::dvec3& q) const;

  // Triangles after long ones were split for the tree (what exact() sums).
  std::size_t triangleCount() const { return triangles_.size(); }

 private:
  // What a query reads of every node it visits; the expansion only when the node is far.
  struct Node {
    glm::dvec3 centre;    // area-weighted centroid of the node's triangles
    double farSquared;    // (beta * radius)^2, radius of the sphere about centre holding every corner
    std::uint32_t first;  // leaf: first triangle in triangles_; inner: left child (right = left + 1)
    std::uint32_t count;  // leaf: number of triangles; inner: 0
  };
  // The far-field expansion about a node's centre p~ (winding.cpp derives it): with r = p~ - q and
  // d = |r|, the node's solid angle is about
  //   (N . r + tr M) / d^3 - (3 r^T M r + 3/2 g . r) / d^5 + 15/2 C[r, r, r] / d^7.
  struct Expansion {
    glm::dvec3 areaVector;           // N: sum of area times unit normal
    double trace;                    // tr M, M = sum of area * (centroid - p~) * normal^T
    std::array<double, 6> moment;    // r^T M r's coefficients: xx yy zz xy xz yz
    glm::dvec3 secondTrace;          // g
    std::array<double, 10> second;   // C[r, r, r]'s: xxx yyy zzz xxy xxz yyx yyz zzx zzy xyz
  };
  struct Triangle {
    glm::dvec3 a, b, c;
  };

  void fill(std::uint32_t slot, std::uint32_t first, std::uint32_t count, std::vector<glm::dvec3>& centroids);

  glm::dvec3 origin_;
  double beta_;
  std::vector<Triangle> triangles_;  // in tree order, relative to origin_
  std::vector<Node> nodes_;
  std::vector<Expansion> expansions_;  // per node
};

// The exact winding number at q of some triangles of a mesh (one atan2 per triangle, no tree):
// for a handful of triangles, where building a tree would cost more than it saves.
double exactWindingNumber(const std::vector<glm::dvec3>& positions, std::span<const std::array<std::uint32_t, 3>> triangles,
                          const glm::dvec3& q);

}  // namespace nut::converter
