// The finite-element mesh of a structure's free blocks: every free block
// must be a hexahedron (8 corners, 6 quadrilateral faces); it becomes one
// trilinear element, or a grid of them by splitting its parametric cube
// evenly: refine along each edge direction, or more where an element size
// asks for it (a long lintel then gets many elements along its length and
// few through its depth, instead of elements as long as refine allows). Blocks keep their own nodes: nodes of different blocks never merge,
// contact ties them (fea.hpp). Support blocks are not meshed; they are the
// fixed ground.
#pragma once

#include <array>
#include <vector>

#include "core/types.hpp"
#include "fea/hex_element.hpp"
#include "structure/structure.hpp"

namespace ashlar {

// A point of a block's body given by weights on mesh nodes (the trilinear
// interpolation inside the element that contains it).
struct NodeWeights {
  std::vector<int> nodes;
  std::vector<double> weights;  // sum to 1
};

// Elements along each edge of a block when a script does not say.
inline constexpr int kDefaultRefine = 1;

class FeaMesh {
public:
  // Throws InvalidArgument naming the block when a free block is not a
  // hexahedron or its trilinear map folds (a non-convex or twisted block),
  // and for refine outside [1, 64]. element_size (m, 0 = none): each block
  // edge direction gets at least ceil(mean edge length / element_size)
  // divisions, at most 256.
  FeaMesh(const Structure& structure, int refine = kDefaultRefine, double element_size = 0.0);

  // Divisions of the block along its parametric directions xi, eta, zeta.
  const std::array<int, 3>& divisions(int block) const { return divisions_[block]; }
  const std::vector<Vec3>& nodes() const { return nodes_; }             // m
  const std::vector<std::array<int, 8>>& elements() const { return elements_; }
  int node_block(int node) const { return node_block_[node]; }          // 0-based block
  int element_block(int element) const { return element_block_[element]; }
  // -1 for support blocks.
  int first_node(int block) const { return first_node_[block]; }
  int first_element(int block) const { return first_element_[block]; }
  bool meshed(int block) const { return first_node_[block] >= 0; }
  // The block's corners in hexahedron order (hex_element.hpp).
  const HexNodes& corners(int block) const { return corners_[block]; }
  HexNodes element_nodes(int element) const;
  // Nodes of the block on its boundary surface.
  std::vector<int> surface_nodes(int block) const;
  // Interpolation weights of point p (on or in the block, within round-off).
  NodeWeights locate(int block, const Vec3& p) const;

private:
  int node_index(int block, int i, int j, int k) const;

  std::vector<std::array<int, 3>> divisions_;  // per block; zero for supports
  std::vector<Vec3> nodes_;
  std::vector<std::array<int, 8>> elements_;
  std::vector<int> node_block_, element_block_;
  std::vector<int> first_node_, first_element_;
  std::vector<HexNodes> corners_;  // per block; unset for supports
};

// The 8 corners of a hexahedral block in hexahedron order. Throws
// InvalidArgument (naming `what`) unless the block has 8 vertices and 6
// quadrilateral faces joined like a cube's.
HexNodes hexahedron_corners(const Block& block, const std::string& what);

}  // namespace ashlar
