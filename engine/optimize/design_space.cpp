#include "optimize/design_space.hpp"

#include <Eigen/SparseLU>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/error.hpp"
#include "geometry/block.hpp"
#include "geometry/polygon.hpp"

namespace ashlar {
namespace {

constexpr double kRelativeWeldTolerance = 1e-9;  // of the model size
// Newton's target for a constraint row, of its face's size: far below the
// 1e-10 planarity that designs promise, far above rounding.
constexpr double kRelativeRowTolerance = 1e-12;
// A design counts as planar when no row exceeds this many row tolerances.
constexpr double kRowSlack = 100.0;
// Constraint gradients shorter than this fraction of the longest, after
// removing their components along earlier ones, are redundant.
constexpr double kRankThreshold = 1e-9;
constexpr int kMaxNewtonIterations = 20;

std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string describe(const PositionRef& ref) {
  if (ref.block == PositionRef::kFreePoint) return "point " + std::to_string(ref.index + 1);
  return "vertex " + std::to_string(ref.index + 1) + " of block " + std::to_string(ref.block + 1);
}

std::string describe(const FaceRef& face) {
  return "face " + std::to_string(face.face + 1) + " of block " + std::to_string(face.block + 1);
}

void check_block_index(int block, const DesignPoint& design, const std::string& what) {
  const int blocks = static_cast<int>(design.block_vertices.size());
  if (block < 0 || block >= blocks) {
    throw InvalidArgument(what + ": block " + std::to_string(block + 1) +
                          " does not exist (the design has " + std::to_string(blocks) +
                          " blocks)");
  }
}

void check_position(const PositionRef& ref, const DesignPoint& design, const std::string& what) {
  if (ref.block == PositionRef::kFreePoint) {
    const int points = static_cast<int>(design.points.size());
    if (ref.index < 0 || ref.index >= points) {
      throw InvalidArgument(what + ": there is no point " + std::to_string(ref.index + 1) +
                            " (the design has " + std::to_string(points) + " points)");
    }
    return;
  }
  check_block_index(ref.block, design, what);
  const int vertices = static_cast<int>(design.block_vertices[ref.block].size());
  if (ref.index < 0 || ref.index >= vertices) {
    throw InvalidArgument(what + ": block " + std::to_string(ref.block + 1) + " has no vertex " +
                          std::to_string(ref.index + 1) + " (it has " +
                          std::to_string(vertices) + ")");
  }
}

class DisjointSets {
public:
  explicit DisjointSets(int size) : parent_(size) {
    for (int i = 0; i < size; ++i) parent_[i] = i;
  }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // True when a and b were in different sets.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

private:
  std::vector<int> parent_;
};

// Buckets points in cubic cells of side `cell` for neighbour queries in
// time proportional to the cells (or the occupied cells) they cover.
class PointGrid {
public:
  PointGrid(const Vec3& origin, double cell) : origin_(origin), cell_(cell) {}

  void insert(const Vec3& p, int id) { cells_[key(p)].push_back(id); }

  // The ids in the cells that overlap the box [lo, hi]: every point inside
  // the box, and some near it.
  void for_each_in(const Vec3& lo, const Vec3& hi, const std::function<void(int)>& visit) const {
    const Key first = key(lo), last = key(hi);
    double cells = 1.0;
    for (int axis = 0; axis < 3; ++axis) cells *= static_cast<double>(last[axis] - first[axis] + 1);
    const auto inside = [&](const Key& k) {
      for (int axis = 0; axis < 3; ++axis) {
        if (k[axis] < first[axis] || k[axis] > last[axis]) return false;
      }
      return true;
    };
    if (cells > static_cast<double>(cells_.size())) {
      for (const auto& [k, ids] : cells_) {
        if (!inside(k)) continue;
        for (int id : ids) visit(id);
      }
      return;
    }
    for (Key k = first; k[0] <= last[0]; ++k[0]) {
      for (k[1] = first[1]; k[1] <= last[1]; ++k[1]) {
        for (k[2] = first[2]; k[2] <= last[2]; ++k[2]) {
          const auto cell = cells_.find(k);
          if (cell == cells_.end()) continue;
          for (int id : cell->second) visit(id);
        }
      }
    }
  }

  void for_each_near(const Vec3& p, double radius, const std::function<void(int)>& visit) const {
    for_each_in(p - Vec3::Constant(radius), p + Vec3::Constant(radius), visit);
  }

private:
  using Key = std::array<std::int64_t, 3>;
  struct KeyHash {
    size_t operator()(const Key& k) const {
      const auto bits = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
      return static_cast<size_t>(bits(k[0]) * 73856093u ^ bits(k[1]) * 19349663u ^
                                 bits(k[2]) * 83492791u);
    }
  };
  Key key(const Vec3& p) const {
    const Vec3 q = (p - origin_) / cell_;
    return {static_cast<std::int64_t>(std::floor(q.x())), static_cast<std::int64_t>(std::floor(q.y())),
            static_cast<std::int64_t>(std::floor(q.z()))};
  }

  Vec3 origin_;
  double cell_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

// True when p lies inside the 2D polygon or within `tolerance` of its outline.
bool covers(const Loop2& polygon, const Vec2& p, double tolerance) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    const Vec2 edge = b - a;
    const double along = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    if ((a + along * edge - p).norm() <= tolerance) return true;
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * edge.x() / edge.y()) {
      inside = !inside;
    }
  }
  return inside;
}

// Two unit vectors spanning the plane with unit normal n; axis-aligned when
// n is, so that box bounds on in-plane displacements stay per coordinate.
Mat3 plane_basis(const Vec3& n) {
  int axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Vec3 first = (Vec3::Unit(axis) - n[axis] * n).normalized();
  Mat3 basis;
  basis << first, n.cross(first), n;
  return basis;
}

}  // namespace

DesignSpace::DesignSpace(std::vector<std::vector<FaceLoop>> faces, DesignPoint initial,
                         DesignConstraints constraints)
    : faces_(std::move(faces)), initial_(std::move(initial)), constraints_(std::move(constraints)) {
  check_input();
  weld();
  build_variables();
  build_constraint_rows();
  find_start();
}

void DesignSpace::check_input() const {
  const int blocks = static_cast<int>(initial_.block_vertices.size());
  if (static_cast<int>(faces_.size()) != blocks) {
    throw InvalidArgument("design: " + std::to_string(faces_.size()) + " blocks of faces but " +
                          std::to_string(blocks) + " blocks of vertices");
  }
  for (int b = 0; b < blocks; ++b) {
    const int vertices = static_cast<int>(initial_.block_vertices[b].size());
    for (int k = 0; k < vertices; ++k) {
      if (!initial_.block_vertices[b][k].allFinite()) {
        throw InvalidArgument("design: " + describe(PositionRef::vertex(b, k)) +
                              " is not finite");
      }
    }
    for (size_t f = 0; f < faces_[b].size(); ++f) {
      const FaceLoop& loop = faces_[b][f];
      const std::string face = describe(FaceRef{b, static_cast<int>(f)});
      if (loop.size() < 3) throw InvalidArgument("design: " + face + " has fewer than 3 vertices");
      for (int index : loop) {
        if (index < 0 || index >= vertices) {
          throw InvalidArgument("design: " + face + " refers to vertex " +
                                std::to_string(index + 1) + ", but the block has " +
                                std::to_string(vertices));
        }
      }
    }
  }
  for (size_t p = 0; p < initial_.points.size(); ++p) {
    if (!initial_.points[p].allFinite()) {
      throw InvalidArgument("design: " + describe(PositionRef::point(static_cast<int>(p))) +
                            " is not finite");
    }
  }

  const DesignConstraints& c = constraints_;
  if (c.weld_tolerance && !(std::isfinite(*c.weld_tolerance) && *c.weld_tolerance >= 0.0)) {
    throw InvalidArgument("weld_tolerance must be a finite number >= 0 (m), got " +
                          number(*c.weld_tolerance));
  }
  for (int block : c.fixed_blocks) check_block_index(block, initial_, "fixed_blocks");
  for (const PositionRef& ref : c.fixed) check_position(ref, initial_, "fixed");
  for (size_t g = 0; g < c.move_together.size(); ++g) {
    const std::string what = "move_together: group " + std::to_string(g + 1);
    if (c.move_together[g].empty()) throw InvalidArgument(what + " is empty");
    for (const PositionRef& ref : c.move_together[g]) check_position(ref, initial_, what);
  }
  if (c.mirror) {
    if (!c.mirror->point.allFinite()) throw InvalidArgument("mirror: the plane's point must be finite");
    if (!c.mirror->normal.allFinite() || c.mirror->normal.norm() == 0.0) {
      throw InvalidArgument("mirror: the plane's normal must be a finite, non-zero vector");
    }
  }
  for (const FaceRef& face : c.keep_normal) {
    check_block_index(face.block, initial_, "keep_normal");
    const int count = static_cast<int>(faces_[face.block].size());
    if (face.face < 0 || face.face >= count) {
      throw InvalidArgument("keep_normal: block " + std::to_string(face.block + 1) +
                            " has no face " + std::to_string(face.face + 1) + " (it has " +
                            std::to_string(count) + ")");
    }
  }
  if (!(c.max_displacement > 0.0)) {
    throw InvalidArgument("max_displacement must be a number > 0 (m) or infinite, got " +
                          number(c.max_displacement));
  }
  if (!(std::isfinite(c.min_block_volume) && c.min_block_volume >= 0.0)) {
    throw InvalidArgument("min_block_volume must be a finite number >= 0 (m^3), got " +
                          number(c.min_block_volume));
  }
}

int DesignSpace::position_index(const PositionRef& ref) const {
  if (ref.block == PositionRef::kFreePoint) return block_offset_.back() + ref.index;
  return block_offset_[ref.block] + ref.index;
}

void DesignSpace::weld() {
  std::vector<Vec3> positions;
  std::vector<PositionRef> refs;
  const int blocks = static_cast<int>(initial_.block_vertices.size());
  for (int b = 0; b < blocks; ++b) {
    block_offset_.push_back(static_cast<int>(positions.size()));
    for (size_t k = 0; k < initial_.block_vertices[b].size(); ++k) {
      positions.push_back(initial_.block_vertices[b][k]);
      refs.push_back(PositionRef::vertex(b, static_cast<int>(k)));
    }
  }
  block_offset_.push_back(static_cast<int>(positions.size()));
  for (size_t p = 0; p < initial_.points.size(); ++p) {
    positions.push_back(initial_.points[p]);
    refs.push_back(PositionRef::point(static_cast<int>(p)));
  }
  if (positions.empty()) throw InvalidArgument("design: it has no blocks and no points");

  Box3 bounds;
  for (const Vec3& p : positions) bounds.add(p);
  model_size_ = bounds.diagonal() > 0.0 ? bounds.diagonal() : 1.0;
  weld_tolerance_ = constraints_.weld_tolerance.value_or(kRelativeWeldTolerance * model_size_);

  const int count = static_cast<int>(positions.size());
  DisjointSets welded(count);
  PointGrid grid(bounds.lo, std::max(weld_tolerance_, 1e-12 * model_size_));
  for (int i = 0; i < count; ++i) {
    grid.for_each_near(positions[i], weld_tolerance_, [&](int j) {
      if ((positions[j] - positions[i]).norm() <= weld_tolerance_) welded.unite(i, j);
    });
    grid.insert(positions[i], i);
  }

  std::vector<int> node_of_root(count, -1);
  std::vector<int> members;
  node_of_position_.resize(count);
  for (int i = 0; i < count; ++i) {
    int& node = node_of_root[welded.find(i)];
    if (node < 0) {
      node = static_cast<int>(nodes_.size());
      nodes_.push_back(Node{});
      nodes_.back().example = refs[i];
      members.push_back(0);
    }
    node_of_position_[i] = node;
    nodes_[node].initial += positions[i];
    ++members[node];
  }
  for (size_t g = 0; g < nodes_.size(); ++g) nodes_[g].initial /= members[g];

  // A block whose own vertices weld together would lose a face or an edge.
  std::vector<int> vertex_in_block(nodes_.size(), -1);
  std::vector<int> block_of_mark(nodes_.size(), -1);
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < block_offset_[b + 1] - block_offset_[b]; ++k) {
      const int node = node_of_position_[block_offset_[b] + k];
      if (block_of_mark[node] == b) {
        throw InvalidArgument("welding: vertices " + std::to_string(vertex_in_block[node] + 1) +
                              " and " + std::to_string(k + 1) + " of block " +
                              std::to_string(b + 1) + " are closer than the weld tolerance (" +
                              number(weld_tolerance_) + " m)");
      }
      block_of_mark[node] = b;
      vertex_in_block[node] = k;
    }
  }
}

void DesignSpace::build_variables() {
  const int count = static_cast<int>(nodes_.size());
  DisjointSets classes(count);
  for (const auto& group : constraints_.move_together) {
    const int first = node_of_position_[position_index(group.front())];
    for (const PositionRef& ref : group) classes.unite(first, node_of_position_[position_index(ref)]);
  }
  std::vector<char> fixed_node(count, 0);
  for (int block : constraints_.fixed_blocks) {
    for (int i = block_offset_[block]; i < block_offset_[block + 1]; ++i) {
      fixed_node[node_of_position_[i]] = 1;
    }
  }
  for (const PositionRef& ref : constraints_.fixed) fixed_node[node_of_position_[position_index(ref)]] = 1;
  std::vector<char> fixed_class(count, 0);
  for (int g = 0; g < count; ++g) fixed_class[classes.find(g)] |= fixed_node[g];

  std::vector<int> partner(count, -1);
  Mat3 reflection = Mat3::Identity();
  Mat3 in_plane = Mat3::Identity();
  if (constraints_.mirror) {
    const Vec3 normal = constraints_.mirror->normal.normalized();
    const Vec3& origin = constraints_.mirror->point;
    reflection -= 2.0 * normal * normal.transpose();
    in_plane = plane_basis(normal);
    Box3 bounds;
    for (const Node& node : nodes_) bounds.add(node.initial);
    PointGrid grid(bounds.lo, std::max(weld_tolerance_, 1e-12 * model_size_));
    for (int g = 0; g < count; ++g) grid.insert(nodes_[g].initial, g);
    for (int g = 0; g < count; ++g) {
      const Vec3& p = nodes_[g].initial;
      const Vec3 image = p - 2.0 * normal.dot(p - origin) * normal;
      double nearest = weld_tolerance_;
      grid.for_each_near(image, weld_tolerance_, [&](int h) {
        const double distance = (nodes_[h].initial - image).norm();
        if (distance <= nearest) {
          nearest = distance;
          partner[g] = h;
        }
      });
      if (partner[g] < 0 && !fixed_class[classes.find(g)]) {
        throw InvalidArgument("mirror: " + describe(nodes_[g].example) + " at (" + number(p.x()) +
                              ", " + number(p.y()) + ", " + number(p.z()) +
                              ") has no mirror image across the plane");
      }
    }
    // Positions that move together have partners that move together.
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<int> anchor(count, -1);
      for (int g = 0; g < count; ++g) {
        if (partner[g] < 0) continue;
        int& first = anchor[classes.find(g)];
        if (first < 0) {
          first = g;
        } else {
          changed |= classes.unite(partner[g], partner[first]);
        }
      }
    }
    std::fill(fixed_class.begin(), fixed_class.end(), 0);
    for (int g = 0; g < count; ++g) fixed_class[classes.find(g)] |= fixed_node[g];
    for (int g = 0; g < count; ++g) {
      if (partner[g] < 0) continue;
      const int a = classes.find(g), b = classes.find(partner[g]);
      fixed_class[a] = fixed_class[b] = fixed_class[a] | fixed_class[b];
    }
  }

  std::vector<int> first_variable(count, -1);
  for (int g = 0; g < count; ++g) {
    Node& node = nodes_[g];
    const int own = classes.find(g);
    if (fixed_class[own]) continue;
    const int image = partner[g] < 0 ? own : classes.find(partner[g]);
    const int owner = std::min(own, image);
    node.variable_count = (constraints_.mirror && own == image) ? 2 : 3;
    if (first_variable[owner] < 0) {
      first_variable[owner] = variable_count_;
      variable_count_ += node.variable_count;
    }
    node.first_variable = first_variable[owner];
    if (own == image) {
      if (constraints_.mirror) node.basis = in_plane;
    } else if (own != owner) {
      node.basis = reflection;
    }
  }
}

void DesignSpace::build_constraint_rows() {
  const double magnitude = [&] {
    double largest = 0.0;
    for (const Node& node : nodes_) largest = std::max(largest, node.initial.cwiseAbs().maxCoeff());
    return largest;
  }();
  const auto at = [&](int node) -> const Vec3& { return nodes_[node].initial; };
  // Nodes in cells of about one node each, to find those lying on a face.
  const double cell = std::max(model_size_ / std::cbrt(static_cast<double>(nodes_.size())),
                               2.0 * weld_tolerance_);
  Box3 bounds;
  for (const Node& node : nodes_) bounds.add(node.initial);
  PointGrid grid(bounds.lo, cell);
  for (int g = 0; g < static_cast<int>(nodes_.size()); ++g) grid.insert(at(g), g);

  // Faces of welded blocks that share all their nodes are one constraint;
  // a kept normal wins over plain planarity.
  std::vector<FaceRef> unique_faces;
  std::vector<char> keeps_normal;
  std::set<std::vector<int>> seen;
  const auto node_loop = [&](const FaceRef& face) {
    std::vector<int> loop;
    for (int index : faces_[face.block][face.face]) {
      loop.push_back(node_of_position_[block_offset_[face.block] + index]);
    }
    return loop;
  };
  const auto add_face = [&](const FaceRef& face, bool keep) {
    std::vector<int> loop = node_loop(face);
    std::sort(loop.begin(), loop.end());
    if (!seen.insert(loop).second) return;
    unique_faces.push_back(face);
    keeps_normal.push_back(keep);
  };
  for (const FaceRef& face : constraints_.keep_normal) add_face(face, true);
  for (int b = 0; b < static_cast<int>(faces_.size()); ++b) {
    for (int f = 0; f < static_cast<int>(faces_[b].size()); ++f) add_face(FaceRef{b, f}, false);
  }

  std::vector<double> tolerances;
  std::vector<int> own_block_mark(nodes_.size(), -1);
  for (size_t u = 0; u < unique_faces.size(); ++u) {
    const FaceRef face = unique_faces[u];
    const std::vector<int> loop = node_loop(face);
    for (int i = block_offset_[face.block]; i < block_offset_[face.block + 1]; ++i) {
      own_block_mark[node_of_position_[i]] = static_cast<int>(u);
    }
    // The widest triangle of the face fixes its plane: a, the vertex
    // farthest from a, then the vertex farthest from that line.
    const int a = loop[0];
    const int far = *std::max_element(loop.begin(), loop.end(), [&](int p, int q) {
      return (at(p) - at(a)).squaredNorm() < (at(q) - at(a)).squaredNorm();
    });
    const auto area = [&](int node) { return (at(far) - at(a)).cross(at(node) - at(a)).norm(); };
    const int wide = *std::max_element(loop.begin(), loop.end(),
                                       [&](int p, int q) { return area(p) < area(q); });
    ConstraintRow row;
    row.face = face;
    row.keeps_normal = keeps_normal[u];
    row.scale = area(wide);
    if (row.keeps_normal) {
      row.normal = face_planes(initial_.block_vertices[face.block],
                               {faces_[face.block][face.face]}).front().normal;
    }
    const double tolerance = kRelativeRowTolerance * (at(far) - at(a)).norm() +
                             8.0 * std::numeric_limits<double>::epsilon() * magnitude;
    const auto add_row = [&](int node) {
      row.nodes = row.keeps_normal ? std::array<int, 4>{a, node, -1, -1}
                                   : std::array<int, 4>{a, far, wide, node};
      rows_.push_back(row);
      tolerances.push_back(tolerance);
    };
    for (int node : loop) {
      if (node != a && (row.keeps_normal || (node != far && node != wide))) add_row(node);
    }

    // Positions of other blocks (or free points) lying on the face stay on
    // it: T-junctions, a block standing inside a larger face, an anchor.
    std::vector<Vec3> corners;
    Box3 extent;
    for (int node : loop) {
      corners.push_back(at(node));
      extent.add(at(node));
    }
    const PlaneFrame frame = PlaneFrame::from_normal(at(a), newell_normal(corners).normalized());
    Loop2 outline;
    for (const Vec3& corner : corners) outline.push_back(frame.project(corner));
    const Vec3 margin = Vec3::Constant(weld_tolerance_);
    grid.for_each_in(extent.lo - margin, extent.hi + margin, [&](int node) {
      if (own_block_mark[node] == static_cast<int>(u)) return;
      if (std::abs(frame.distance(at(node))) > weld_tolerance_) return;
      if (!covers(outline, frame.project(at(node)), weld_tolerance_)) return;
      add_row(node);
    });
  }
  tolerances_ = Eigen::Map<const Eigen::VectorXd>(tolerances.data(), tolerances.size());
}

void DesignSpace::find_start() {
  start_ = Eigen::VectorXd::Zero(variable_count_);
  start_residuals_ = Eigen::VectorXd::Zero(constraint_count());
  const std::optional<Eigen::VectorXd> planar = PlanarChart(*this, start_).project(start_);
  if (!planar) {
    throw InvalidArgument("design: its faces cannot be made planar within the constraints");
  }
  start_ = *planar;
  start_residuals_ = constraint_values(start_).cwiseAbs();
  const std::string why = rejection(start_);
  if (!why.empty()) throw InvalidArgument("the initial design is not admissible: " + why);
}

Eigen::VectorXd DesignSpace::lower_bounds() const {
  return Eigen::VectorXd::Constant(variable_count_, -constraints_.max_displacement);
}

Eigen::VectorXd DesignSpace::upper_bounds() const {
  return Eigen::VectorXd::Constant(variable_count_, constraints_.max_displacement);
}

std::vector<Vec3> DesignSpace::node_positions(const Eigen::VectorXd& z) const {
  if (z.size() != variable_count_) {
    throw InvalidArgument("design variables: got " + std::to_string(z.size()) + ", expected " +
                          std::to_string(variable_count_));
  }
  std::vector<Vec3> positions;
  positions.reserve(nodes_.size());
  for (const Node& node : nodes_) {
    Vec3 p = node.initial;
    for (int k = 0; k < node.variable_count; ++k) p += node.basis.col(k) * z[node.first_variable + k];
    positions.push_back(p);
  }
  return positions;
}

DesignPoint DesignSpace::design(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  DesignPoint design;
  design.block_vertices.resize(faces_.size());
  for (size_t b = 0; b < faces_.size(); ++b) {
    for (int i = block_offset_[b]; i < block_offset_[b + 1]; ++i) {
      design.block_vertices[b].push_back(positions[node_of_position_[i]]);
    }
  }
  for (size_t i = block_offset_.back(); i < node_of_position_.size(); ++i) {
    design.points.push_back(positions[node_of_position_[i]]);
  }
  return design;
}

Eigen::VectorXd DesignSpace::reduce(const DesignPoint& gradient) const {
  const auto shape_error = [](const std::string& what) {
    return InvalidArgument("design gradient: " + what + " (it must have the design's shape)");
  };
  if (gradient.block_vertices.size() != faces_.size()) {
    throw shape_error(std::to_string(gradient.block_vertices.size()) + " blocks, expected " +
                      std::to_string(faces_.size()));
  }
  if (gradient.points.size() != initial_.points.size()) {
    throw shape_error(std::to_string(gradient.points.size()) + " points, expected " +
                      std::to_string(initial_.points.size()));
  }
  Eigen::VectorXd reduced = Eigen::VectorXd::Zero(variable_count_);
  const auto add = [&](int position, const Vec3& g) {
    const Node& node = nodes_[node_of_position_[position]];
    for (int k = 0; k < node.variable_count; ++k) reduced[node.first_variable + k] += node.basis.col(k).dot(g);
  };
  for (size_t b = 0; b < faces_.size(); ++b) {
    const auto& vertices = gradient.block_vertices[b];
    const size_t expected = block_offset_[b + 1] - block_offset_[b];
    if (vertices.size() != expected) {
      throw shape_error("block " + std::to_string(b + 1) + " has " +
                        std::to_string(vertices.size()) + " vertices, expected " +
                        std::to_string(expected));
    }
    for (size_t k = 0; k < vertices.size(); ++k) add(block_offset_[b] + static_cast<int>(k), vertices[k]);
  }
  for (size_t p = 0; p < gradient.points.size(); ++p) {
    add(block_offset_.back() + static_cast<int>(p), gradient.points[p]);
  }
  return reduced;
}

double DesignSpace::largest_move(const Eigen::VectorXd& z_from, const Eigen::VectorXd& z_to) const {
  const std::vector<Vec3> from = node_positions(z_from), to = node_positions(z_to);
  double largest = 0.0;
  for (size_t g = 0; g < from.size(); ++g) largest = std::max(largest, (to[g] - from[g]).norm());
  return largest;
}

std::string DesignSpace::rejection(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  const double bound = constraints_.max_displacement;
  if (std::isfinite(bound)) {
    for (size_t g = 0; g < nodes_.size(); ++g) {
      const double moved = (positions[g] - nodes_[g].initial).cwiseAbs().maxCoeff();
      if (moved > bound + 1e-12 * model_size_) {
        return describe(nodes_[g].example) + " moves " + number(moved) +
               " m along an axis, beyond max_displacement (" + number(bound) + " m)";
      }
    }
  }
  for (int r = 0; r < constraint_count(); ++r) {
    const double off = std::abs(row_value(rows_[r], positions, nullptr));
    if (off > kRowSlack * tolerances_[r] + start_residuals_[r]) {
      return describe(rows_[r].face) + " is not planar (a vertex " + number(off) +
             " m off its plane)";
    }
  }
  const DesignPoint candidate = design(z);
  for (size_t b = 0; b < faces_.size(); ++b) {
    const double volume = mass_properties(candidate.block_vertices[b], faces_[b]).volume;
    const std::string block = "block " + std::to_string(b + 1);
    if (volume <= 0.0) return block + " is inverted or flat (volume " + number(volume) + " m^3)";
    if (volume < constraints_.min_block_volume) {
      return block + " has volume " + number(volume) + " m^3, below min_block_volume (" +
             number(constraints_.min_block_volume) + " m^3)";
    }
  }
  return {};
}

double DesignSpace::row_value(const ConstraintRow& row, const std::vector<Vec3>& positions,
                              std::array<Vec3, 4>* gradient) const {
  const Vec3& a = positions[row.nodes[0]];
  if (row.keeps_normal) {
    if (gradient) *gradient = {-row.normal, row.normal, Vec3::Zero(), Vec3::Zero()};
    return row.normal.dot(positions[row.nodes[1]] - a);
  }
  // (i - a) . ((b - a) x (c - a)) / scale: the distance of i from the plane
  // of a, b, c while that triangle keeps its area.
  const Vec3 u = positions[row.nodes[1]] - a;
  const Vec3 v = positions[row.nodes[2]] - a;
  const Vec3 w = positions[row.nodes[3]] - a;
  if (gradient) {
    const Vec3 d_b = v.cross(w) / row.scale, d_c = w.cross(u) / row.scale,
               d_i = u.cross(v) / row.scale;
    *gradient = {-(d_b + d_c + d_i), d_b, d_c, d_i};
  }
  return w.dot(u.cross(v)) / row.scale;
}

Eigen::VectorXd DesignSpace::constraint_values(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  Eigen::VectorXd values(constraint_count());
  for (int r = 0; r < constraint_count(); ++r) values[r] = row_value(rows_[r], positions, nullptr);
  return values;
}

Eigen::SparseMatrix<double> DesignSpace::constraint_jacobian(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  std::vector<Eigen::Triplet<double>> entries;
  std::array<Vec3, 4> gradient;
  for (int r = 0; r < constraint_count(); ++r) {
    row_value(rows_[r], positions, &gradient);
    for (int k = 0; k < 4; ++k) {
      if (rows_[r].nodes[k] < 0) continue;
      const Node& node = nodes_[rows_[r].nodes[k]];
      for (int c = 0; c < node.variable_count; ++c) {
        entries.emplace_back(r, node.first_variable + c, node.basis.col(c).dot(gradient[k]));
      }
    }
  }
  Eigen::SparseMatrix<double> jacobian(constraint_count(), variable_count_);
  jacobian.setFromTriplets(entries.begin(), entries.end());
  return jacobian;
}

PlanarChart::PlanarChart(const DesignSpace& space, const Eigen::VectorXd& base) : space_(&space) {
  const Eigen::SparseMatrix<double> full = space.constraint_jacobian(base);
  Eigen::SparseMatrix<double> columns = full.transpose();
  columns.makeCompressed();
  double longest = 0.0;
  for (int r = 0; r < columns.cols(); ++r) longest = std::max(longest, columns.col(r).norm());
  if (longest > 0.0) {
    // Rows that depend on others (a face and its mirror image, faces whose
    // vertices are all fixed) would make A_b A^T singular: the QR moves the
    // columns of A_b^T it finds dependent past its rank.
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
    qr.setPivotThreshold(kRankThreshold * longest);
    qr.compute(columns);
    if (qr.info() != Eigen::Success) {
      throw InvalidArgument("design: the constraint Jacobian could not be factorised");
    }
    for (Eigen::Index k = 0; k < qr.rank(); ++k) rows_.push_back(qr.colsPermutation().indices()[k]);
    std::sort(rows_.begin(), rows_.end());
  }
  std::vector<Eigen::Triplet<double>> ones;
  tolerances_.resize(rank());
  for (int k = 0; k < rank(); ++k) {
    ones.emplace_back(k, rows_[k], 1.0);
    tolerances_[k] = space.constraint_tolerances()[rows_[k]];
  }
  selection_.resize(rank(), space.constraint_count());
  selection_.setFromTriplets(ones.begin(), ones.end());
  base_jacobian_ = selection_ * full;
}

Eigen::SparseMatrix<double> PlanarChart::jacobian(const Eigen::VectorXd& z) const {
  return selection_ * space_->constraint_jacobian(z);
}

std::optional<Eigen::VectorXd> PlanarChart::project(const Eigen::VectorXd& z) const {
  Eigen::VectorXd y = z;
  for (int iteration = 0;; ++iteration) {
    const Eigen::VectorXd residual = selection_ * space_->constraint_values(y);
    if (!residual.allFinite()) return std::nullopt;
    if (rank() == 0 || (residual.cwiseAbs() - tolerances_).maxCoeff() <= 0.0) return y;
    if (iteration == kMaxNewtonIterations) return std::nullopt;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(jacobian(y) * base_jacobian_.transpose());
    if (lu.info() != Eigen::Success) return std::nullopt;
    const Eigen::VectorXd step = lu.solve(residual);
    if (!step.allFinite()) return std::nullopt;
    y -= base_jacobian_.transpose() * step;
  }
}

Eigen::VectorXd PlanarChart::pull_back(const Eigen::VectorXd& y,
                                       const Eigen::VectorXd& gradient) const {
  if (rank() == 0) return gradient;
  const Eigen::SparseMatrix<double> at_y = jacobian(y);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(at_y * base_jacobian_.transpose());
  if (lu.info() != Eigen::Success) {
    throw GeometryError("planar chart: the constraints are singular at this design");
  }
  const Eigen::VectorXd multipliers = lu.transpose().solve(base_jacobian_ * gradient);
  return gradient - at_y.transpose() * multipliers;
}

}  // namespace ashlar
