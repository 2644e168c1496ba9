// converter/winding.hpp — the generalized winding number of a triangle mesh (Jacobson et al.
// 2013), evaluated fast with a bounding volume hierarchy and far-field expansions (Barill et al.
// 2018, "Fast winding numbers for soups and clouds").
//
// w(q) = (1 / 4 pi) * sum over triangles of the signed solid angle the triangle subtends at q.
// For a closed, outward-oriented mesh it is 1 inside and 0 outside; for the open, overlapping,
// non-manifold meshes real buildings are, it degrades smoothly (about 1/2 next to a hole), so
// "inside" is |w| >= 1/2. It has no special cases at edges or vertices: a query point is never
// misclassified because it lines up with an edge, which is what makes ray parity fragile.
//
// Near triangles are summed exactly (Van Oosterom-Strackee solid angle); a node of the tree whose
// bounding sphere is far away (distance > beta * radius) is replaced by its first-order expansion,
// which is exact for the dipole and the first moment of the node's area-weighted normals.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace nut::converter {

class WindingNumber {
 public:
  // Builds the tree; positions and triangles are copied (relative to `centre` for precision).
  WindingNumber(const std::vector<glm::dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                double beta = 3.0);

  // The generalized winding number at the world point q. Thread-safe.
  double operator()(const glm::dvec3& q) const;

  // The exact sum over every triangle (no tree): the reference for tests.
  double exact(const glm::dvec3& q) const;

 private:
  struct Node {
    glm::dvec3 centre;    // area-weighted centroid of the node's triangles
    double radius = 0;    // of the sphere about centre holding every corner
    glm::dvec3 normal;    // sum of area vectors (area times unit normal)
    glm::dmat3 moment;    // sum of area * (centroid - centre) * normal^T
    std::uint32_t first;  // leaf: first triangle in order_; inner: left child (right = left + 1)
    std::uint32_t count;  // leaf: number of triangles; inner: 0
  };
  struct Triangle {
    glm::dvec3 a, b, c;
  };

  void fill(std::uint32_t slot, std::uint32_t first, std::uint32_t count, std::vector<glm::dvec3>& centroids);

  glm::dvec3 origin_;
  double beta_;
  std::vector<Triangle> triangles_;  // in tree order, relative to origin_
  std::vector<Node> nodes_;
};

}  // namespace nut::converter
