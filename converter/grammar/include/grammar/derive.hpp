// grammar/derive.hpp — a grammar applied to its start scope: the derivation, as a DAG of shapes
// that the HNI and the reference mesh are both made from (docs/GRAMMAR.md, "Compilation").
//
// Every scope is a box. A facade scope (a quad) is the slab behind its face: the face lies in the
// scope's z = 0 plane, the outward normal is +z, and the wall's solid fills z in [-thickness, 0].
// Splits, repeats, layers and recesses cut scopes into parts; terminals (Mat, Generate) fill their
// scope's solid with a material; Discard, Empty and a Skip with no layer below leave air.
//
// Identical results are one node: a node is the content of one rule application in its own frame,
// and nodes are interned by value, so the ten windows of a floor that came out alike are one node
// placed ten times, and a repeat whose tiles are alike is one placement that tiles its node.
// Random choices are made here, from `--seed` and the scope's corner (the facade paper's noise at
// S_lb), so the HNI and the mesh show the same choices.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <grammar/grammar.hpp>
#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::grammar {

using NodeId = std::uint32_t;

// One piece of a node's content, in the node's frame. The regions of a node's pieces do not
// overlap, which is what lets every cell of the node's grid hold one of them.
struct Piece {
  enum class Kind : std::uint8_t { Box, Node };
  Kind kind = Kind::Box;
  WorldBox region;             // Box: the solid; Node: what of the placed node shows (its clip)
  std::uint16_t material = 0;  // Box: index into Derivation::materials
  NodeId node = 0;             // Node: placed with its frame's origin at offsetM, turned by the
  glm::dvec3 offsetM{0.0};     //   cube rotation `cube` (hierarchy.hpp), and tiled along the
  int cube = 0;                //   node's axes whose `wrap` is set (all zero for a box, so that
                               //   alike boxes compare equal wherever they were made)
  std::array<bool, 3> wrap{};
  // Box: the side a facade's terminal shows, 2 * axis + (0 for +, 1 for -) in this frame (the
  // order of VisualSummary); -1 for a mass's box, which shows every side.
  std::int8_t front = -1;
  friend bool operator==(const Piece&, const Piece&) = default;
};

struct Node {
  glm::dvec3 sizeM{0.0};  // the frame spans [0, sizeM]
  std::vector<Piece> pieces;
  friend bool operator==(const Node&, const Node&) = default;
};

struct Derivation {
  std::vector<Node> nodes;  // a node's pieces name only nodes before it
  Piece root;               // in world metres: the start scope's corner is the world origin
  std::vector<Material> materials;
  std::vector<std::string> materialNames;  // parallel: the rule or texture each comes from
  long long shapes = 0;                    // rule applications
};

struct DeriveOptions {
  std::uint64_t seed = 0;
  std::optional<glm::dvec3> sizeM;  // the start scope; z = 0 for a facade. Default: the file's @size
  double wallM = 0.3;               // thickness of a facade's slab and of a mass's walls
  long long maxShapes = 2'000'000;  // a grammar that derives more is refused, naming the rule
};

// Applies g from its start rule. Errors name the rule and its line: a size that cannot fit its
// scope, an operator on the wrong kind of scope, a recess deeper than the wall, shapes that
// overlap, too many shapes.
Result<Derivation> derive(const Grammar& g, const DeriveOptions& options = {});

// The material a name stands for when the grammar gives no colour (Generate, textures without
// images): a tone by what the name says it is (window, wall, roof, door, ...), shaded by the name
// itself so that Wall1 and Wall2 differ.
Material namedMaterial(const std::string& name);

enum class MeshFaces {
  Solid,   // every box closed, but for the faces two opaque boxes share: what the HNI shows
  Fronts,  // a facade's terminal as its front face only (two triangles), a mass's box whole:
           // what a CGA-style system emits for Generate {Quad}
};

// The derivation as triangles. Solid is the reference the HNI is compared with; Fronts is the
// lighter geometry a shape-grammar system would emit, the peer for sizes.
Result<TriangleMesh> derivationMesh(const Derivation& d, MeshFaces faces = MeshFaces::Solid);

// The derivation as a NUT hierarchy: a block per node (its grid the union of its pieces'
// boundaries), boxes as solid cells, placed nodes as redirections, then the shared passes that fit
// the format's limits. `originM` receives the world position of the root block's corner.
Result<Hierarchy> derivationHierarchy(const Derivation& d, glm::dvec3& originM);

}  // namespace nut::grammar
