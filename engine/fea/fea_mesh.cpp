#include "fea/fea_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace ashlar {

HexNodes hexahedron_corners(const Block& block, const std::string& what) {
  const std::vector<FaceLoop>& faces = block.faces();
  const auto not_hexahedron = [&](const std::string& why) {
    return InvalidArgument(what + " is not a hexahedron (" + why +
                           "): the FEA meshes each block as 8-node hexahedra; build it with 8 "
                           "corners and 6 four-sided faces. Of the model library's blocks these are not: a "
                           "dome's keystone (give the dome an oculus), a staggered dome's voussoirs (use bond = "
                           "\"stacked\"), an arch bridge's abutments, L-shaped to back the spandrels (use "
                           "spandrel = false), and a wall's bricks cut around an arch head (use a lintel)");
  };
  if (block.vertices().size() != 8)
    throw not_hexahedron(std::to_string(block.vertices().size()) + " vertices");
  if (faces.size() != 6) throw not_hexahedron(std::to_string(faces.size()) + " faces");
  for (const FaceLoop& face : faces)
    if (face.size() != 4) throw not_hexahedron("a face with " + std::to_string(face.size()) + " corners");
  // Edges from the faces; in a cube every corner has exactly 3 neighbours.
  std::array<std::vector<int>, 8> neighbours;
  for (const FaceLoop& face : faces)
    for (int e = 0; e < 4; ++e) {
      const int p = face[e], q = face[(e + 1) % 4];
      if (std::find(neighbours[p].begin(), neighbours[p].end(), q) == neighbours[p].end()) {
        neighbours[p].push_back(q);
        neighbours[q].push_back(p);
      }
    }
  for (const auto& n : neighbours)
    if (n.size() != 3) throw not_hexahedron("a corner joined to " + std::to_string(n.size()) + " edges");
  // Bottom: the first face, reversed so that it runs counter-clockwise seen
  // from inside; each top corner is the bottom corner's neighbour off that face.
  const FaceLoop& bottom = faces[0];
  HexNodes corners;
  std::array<int, 8> index{};
  for (int a = 0; a < 4; ++a) {
    const int v = bottom[3 - a];
    index[a] = v;
    int up = -1;
    for (int n : neighbours[v])
      if (std::find(bottom.begin(), bottom.end(), n) == bottom.end()) up = n;
    if (up < 0) throw not_hexahedron("its faces are not joined like a cube's");
    index[a + 4] = up;
  }
  std::array<int, 8> sorted = index;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw not_hexahedron("its faces are not joined like a cube's");
  for (int a = 0; a < 8; ++a) corners[a] = block.vertices()[index[a]];
  return corners;
}

FeaMesh::FeaMesh(const Structure& structure, int refine, double element_size) {
  if (refine < 1 || refine > 64)
    throw InvalidArgument("refine: expected a whole number from 1 to 64, got " + std::to_string(refine));
  if (!(std::isfinite(element_size) && element_size >= 0))
    throw InvalidArgument("element_size: expected a finite number >= 0 (m), got " + std::to_string(element_size));
  const int n = structure.size();
  first_node_.assign(n, -1);
  first_element_.assign(n, -1);
  corners_.resize(n);
  divisions_.assign(n, {0, 0, 0});
  for (int b = 0; b < n; ++b) {
    if (structure.is_support(b)) continue;
    const std::string label = structure.label(b);
    corners_[b] = hexahedron_corners(structure.block(b), label);
    if (!(hex_min_jacobian(corners_[b]) > 0))
      throw InvalidArgument(label + " is a hexahedron whose trilinear map folds (a corner's "
                            "Jacobian is not positive): its faces are twisted or it is not convex");
    std::array<int, 3>& d = divisions_[b];
    for (int axis = 0; axis < 3; ++axis) {
      d[axis] = refine;
      if (element_size > 0) {
        // The four edges along this parametric direction, averaged.
        double length = 0;
        for (int a = 0; a < 8; ++a)
          if (kHexCorners[a][axis] < 0) {
            std::array<int, 3> far = kHexCorners[a];
            far[axis] = 1;
            const int other = static_cast<int>(std::find(kHexCorners.begin(), kHexCorners.end(), far) - kHexCorners.begin());
            length += 0.25 * (corners_[b][other] - corners_[b][a]).norm();
          }
        d[axis] = std::clamp(static_cast<int>(std::ceil(length / element_size - 1e-9)), refine, 256);
      }
    }
    first_node_[b] = static_cast<int>(nodes_.size());
    first_element_[b] = static_cast<int>(elements_.size());
    for (int k = 0; k <= d[2]; ++k)
      for (int j = 0; j <= d[1]; ++j)
        for (int i = 0; i <= d[0]; ++i) {
          const Vec3 xi(-1.0 + 2.0 * i / d[0], -1.0 + 2.0 * j / d[1], -1.0 + 2.0 * k / d[2]);
          nodes_.push_back(hex_point(corners_[b], xi));
          node_block_.push_back(b);
        }
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j)
        for (int i = 0; i < d[0]; ++i) {
          std::array<int, 8> element;
          for (int a = 0; a < 8; ++a)
            element[a] = node_index(b, i + (kHexCorners[a][0] + 1) / 2, j + (kHexCorners[a][1] + 1) / 2,
                                    k + (kHexCorners[a][2] + 1) / 2);
          elements_.push_back(element);
          element_block_.push_back(b);
        }
  }
}

int FeaMesh::node_index(int block, int i, int j, int k) const {
  const std::array<int, 3>& d = divisions_[block];
  return first_node_[block] + i + (d[0] + 1) * (j + (d[1] + 1) * k);
}

HexNodes FeaMesh::element_nodes(int element) const {
  HexNodes corners;
  for (int a = 0; a < 8; ++a) corners[a] = nodes_[elements_[element][a]];
  return corners;
}

std::vector<int> FeaMesh::surface_nodes(int block) const {
  std::vector<int> surface;
  const std::array<int, 3>& d = divisions_[block];
  for (int k = 0; k <= d[2]; ++k)
    for (int j = 0; j <= d[1]; ++j)
      for (int i = 0; i <= d[0]; ++i)
        if (i == 0 || i == d[0] || j == 0 || j == d[1] || k == 0 || k == d[2])
          surface.push_back(node_index(block, i, j, k));
  return surface;
}

NodeWeights FeaMesh::locate(int block, const Vec3& p) const {
  const Vec3 xi = hex_parametric(corners_[block], p);
  // The sub-element's map is the block's trilinear map on a parametric
  // sub-cube, so interpolating in its local coordinates is exact.
  int cell[3];
  Vec3 local;
  for (int axis = 0; axis < 3; ++axis) {
    const int count = divisions_[block][axis];
    const double t = (std::clamp(xi[axis], -1.0, 1.0) + 1.0) * 0.5 * count;
    cell[axis] = std::min(static_cast<int>(std::floor(t)), count - 1);
    local[axis] = 2.0 * (t - cell[axis]) - 1.0;
  }
  const std::array<double, 8> shape = hex_shape(local);
  NodeWeights weights;
  double total = 0;
  for (int a = 0; a < 8; ++a) {
    if (std::abs(shape[a]) < 1e-12) continue;
    weights.nodes.push_back(node_index(block, cell[0] + (kHexCorners[a][0] + 1) / 2,
                                       cell[1] + (kHexCorners[a][1] + 1) / 2,
                                       cell[2] + (kHexCorners[a][2] + 1) / 2));
    weights.weights.push_back(shape[a]);
    total += shape[a];
  }
  for (double& w : weights.weights) w /= total;
  return weights;
}

}  // namespace ashlar
