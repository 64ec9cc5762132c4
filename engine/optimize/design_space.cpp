#include "optimize/design_space.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>

#include "core/error.hpp"
#include "core/text.hpp"
#include "core/point_grid.hpp"
#include "core/union_find.hpp"
#include "geometry/block.hpp"
#include "geometry/polygon.hpp"
#include "optimize/planar_chart.hpp"

namespace ashlar {
namespace {

constexpr double kRelativeWeldTolerance = 1e-9;  // of the model size
// Unit normals this parallel (dot product) are parallel: about 0.08 degrees.
constexpr double kParallel = 1.0 - 1e-6;
// The projection's target for a constraint row, of its face's size: far
// below the 1e-10 planarity that designs promise, far above rounding.
constexpr double kRelativeRowTolerance = 1e-12;
// Rows weighing less than this fraction of the largest in a dependency are
// not part of it.
constexpr double kInvolved = 1e-6;

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
                          " does not exist (the design has " + std::to_string(blocks) + " blocks)");
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
                          std::to_string(ref.index + 1) + " (it has " + std::to_string(vertices) +
                          ")");
  }
}

enum class Placement { outside, on_outline, inside };

// Where p lies relative to a 2D polygon, `tolerance` counting as on it.
Placement locate(const Loop2& polygon, const Vec2& p, double tolerance) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    const Vec2 edge = b - a;
    const double along = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    if ((a + along * edge - p).norm() <= tolerance) return Placement::on_outline;
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * edge.x() / edge.y()) {
      inside = !inside;
    }
  }
  return inside ? Placement::inside : Placement::outside;
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

// Every face once (welded blocks share contact faces), with every node on it.
struct DesignSpace::FaceSet {
  std::vector<FaceRef> faces;
  std::vector<std::vector<int>> nodes;  // sorted
  std::vector<Vec3> areas;              // Newell vectors: normal times twice the area
  std::vector<char> keeps_normal;
};

DesignSpace::DesignSpace(std::vector<std::vector<FaceLoop>> faces, DesignPoint initial,
                         DesignConstraints constraints)
    : faces_(std::move(faces)), initial_(std::move(initial)), constraints_(std::move(constraints)) {
  check_input();
  weld();
  build_variables();
  position_variable_count_ = variable_count_;
  build_plane_groups();
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
        throw InvalidArgument("design: " + describe(PositionRef::vertex(b, k)) + " is not finite");
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
                          message_number(*c.weld_tolerance, kGivenValueDigits));
  }
  for (int block : c.fixed_blocks) check_block_index(block, initial_, "fixed_blocks");
  for (const PositionRef& ref : c.fixed) check_position(ref, initial_, "fixed");
  for (size_t g = 0; g < c.move_together.size(); ++g) {
    const std::string what = "move_together: group " + std::to_string(g + 1);
    if (c.move_together[g].empty()) throw InvalidArgument(what + " is empty");
    for (const PositionRef& ref : c.move_together[g]) check_position(ref, initial_, what);
  }
  if (c.mirror) {
    if (!c.mirror->point.allFinite()) {
      throw InvalidArgument("mirror: the plane's point must be finite");
    }
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
                          message_number(c.max_displacement, kGivenValueDigits));
  }
  if (!(std::isfinite(c.min_block_volume) && c.min_block_volume >= 0.0)) {
    throw InvalidArgument("min_block_volume must be a finite number >= 0 (m^3), got " +
                          message_number(c.min_block_volume, kGivenValueDigits));
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
  UnionFind welded(count);
  PointGrid grid(bounds.lo, std::max(weld_tolerance_, 1e-12 * model_size_));
  for (int i = 0; i < count; ++i) {
    grid.for_each_near(positions[i], weld_tolerance_, [&](int j) {
      if ((positions[j] - positions[i]).norm() <= weld_tolerance_) welded.join(i, j);
    });
    grid.insert(positions[i], i);
  }

  std::vector<int> node_of_root(count, -1);
  std::vector<int> members;
  node_of_position_.resize(count);
  for (int i = 0; i < count; ++i) {
    int& node = node_of_root[welded.root(i)];
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
                              message_number(weld_tolerance_, kGivenValueDigits) + " m)");
      }
      block_of_mark[node] = b;
      vertex_in_block[node] = k;
    }
  }
}

void DesignSpace::build_variables() {
  const int count = static_cast<int>(nodes_.size());
  UnionFind classes(count);
  for (const auto& group : constraints_.move_together) {
    const int first = node_of_position_[position_index(group.front())];
    for (const PositionRef& ref : group) {
      classes.join(first, node_of_position_[position_index(ref)]);
    }
  }
  std::vector<char> fixed_node(count, 0);
  for (int block : constraints_.fixed_blocks) {
    for (int i = block_offset_[block]; i < block_offset_[block + 1]; ++i) {
      fixed_node[node_of_position_[i]] = 1;
    }
  }
  for (const PositionRef& ref : constraints_.fixed) {
    fixed_node[node_of_position_[position_index(ref)]] = 1;
  }
  std::vector<char> fixed_class(count, 0);
  for (int g = 0; g < count; ++g) fixed_class[classes.root(g)] |= fixed_node[g];

  std::vector<int>& partner = partner_;
  partner.assign(count, -1);
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
      if (partner[g] < 0 && !fixed_class[classes.root(g)]) {
        throw InvalidArgument("mirror: " + describe(nodes_[g].example) + " at (" + message_number(p.x(), kGivenValueDigits) +
                              ", " + message_number(p.y(), kGivenValueDigits) + ", " + message_number(p.z(), kGivenValueDigits) +
                              ") has no mirror image across the plane");
      }
    }
    // Positions that move together have partners that move together.
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<int> anchor(count, -1);
      for (int g = 0; g < count; ++g) {
        if (partner[g] < 0) continue;
        int& first = anchor[classes.root(g)];
        if (first < 0) {
          first = g;
        } else {
          changed |= classes.join(partner[g], partner[first]);
        }
      }
    }
    std::fill(fixed_class.begin(), fixed_class.end(), 0);
    for (int g = 0; g < count; ++g) fixed_class[classes.root(g)] |= fixed_node[g];
    for (int g = 0; g < count; ++g) {
      if (partner[g] < 0) continue;
      const int a = classes.root(g), b = classes.root(partner[g]);
      fixed_class[a] = fixed_class[b] = fixed_class[a] | fixed_class[b];
    }
  }

  std::vector<int> first_variable(count, -1);
  for (int g = 0; g < count; ++g) {
    Node& node = nodes_[g];
    const int own = classes.root(g);
    if (fixed_class[own]) continue;
    const int image = partner[g] < 0 ? own : classes.root(partner[g]);
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

bool DesignSpace::spans_plane(const std::vector<int>& nodes) const {
  if (nodes.size() < 3) return false;
  const auto at = [&](int node) -> const Vec3& { return nodes_[node].initial; };
  const Vec3& a = at(nodes[0]);
  const int far = *std::max_element(nodes.begin(), nodes.end(), [&](int p, int q) {
    return (at(p) - a).squaredNorm() < (at(q) - a).squaredNorm();
  });
  const Vec3 line = at(far) - a;
  if (line.norm() <= weld_tolerance_) return false;
  double widest = 0.0;
  for (int node : nodes) widest = std::max(widest, line.cross(at(node) - a).norm() / line.norm());
  return widest > weld_tolerance_;
}

void DesignSpace::build_plane_groups() {
  const auto at = [&](int node) -> const Vec3& { return nodes_[node].initial; };
  const int node_count = static_cast<int>(nodes_.size());

  // Faces once each (welded blocks share contact faces), as node loops.
  std::vector<FaceRef> faces;
  std::vector<std::vector<int>> loops;
  std::map<std::vector<int>, int> face_of_nodes;
  for (int b = 0; b < static_cast<int>(faces_.size()); ++b) {
    for (int f = 0; f < static_cast<int>(faces_[b].size()); ++f) {
      std::vector<int> loop;
      for (int index : faces_[b][f]) loop.push_back(node_of_position_[block_offset_[b] + index]);
      std::vector<int> key = loop;
      std::sort(key.begin(), key.end());
      if (!face_of_nodes.emplace(key, static_cast<int>(faces.size())).second) continue;
      faces.push_back(FaceRef{b, f});
      loops.push_back(loop);
    }
  }
  const int face_count = static_cast<int>(faces.size());

  // Every node on each face: its loop, positions of other blocks (or free
  // points) inside it, and vertices on its outline of faces in contact with
  // it (opposite normals), found among nodes bucketed about one a cell. A
  // vertex on the outline of a face it only lies flush with is left free:
  // keeping it in that plane is no contact, and would make the constraints
  // singular wherever such faces are coplanar.
  std::vector<std::vector<Vec3>> normals_of_node(node_count);
  for (int b = 0; b < static_cast<int>(faces_.size()); ++b) {
    const std::vector<FacePlane> planes = face_planes(initial_.block_vertices[b], faces_[b]);
    for (size_t f = 0; f < faces_[b].size(); ++f) {
      for (int index : faces_[b][f]) {
        normals_of_node[node_of_position_[block_offset_[b] + index]].push_back(planes[f].normal);
      }
    }
  }
  Box3 bounds;
  for (const Node& node : nodes_) bounds.add(node.initial);
  PointGrid grid(bounds.lo, std::max(model_size_ / std::cbrt(static_cast<double>(node_count)),
                                     2.0 * weld_tolerance_));
  for (int g = 0; g < node_count; ++g) grid.insert(at(g), g);
  std::vector<std::vector<int>> on_face(face_count);
  std::vector<Vec3> face_area(face_count);  // Newell: direction and twice the area
  std::vector<int> own_block_mark(node_count, -1);
  for (int f = 0; f < face_count; ++f) {
    const FaceRef face = faces[f];
    for (int i = block_offset_[face.block]; i < block_offset_[face.block + 1]; ++i) {
      own_block_mark[node_of_position_[i]] = f;
    }
    std::vector<Vec3> corners;
    Box3 extent;
    for (int node : loops[f]) {
      corners.push_back(at(node));
      extent.add(at(node));
    }
    face_area[f] = newell_normal(corners);
    const Vec3 normal = face_area[f].normalized();
    const PlaneFrame frame = PlaneFrame::from_normal(corners[0], normal);
    Loop2 outline;
    for (const Vec3& corner : corners) outline.push_back(frame.project(corner));
    const auto in_contact = [&](int node) {
      return std::any_of(normals_of_node[node].begin(), normals_of_node[node].end(),
                         [&](const Vec3& n) { return n.dot(normal) <= -kParallel; });
    };
    on_face[f] = loops[f];
    const Vec3 margin = Vec3::Constant(weld_tolerance_);
    grid.for_each_in(extent.lo - margin, extent.hi + margin, [&](int node) {
      if (own_block_mark[node] == f) return;
      if (std::abs(frame.distance(at(node))) > weld_tolerance_) return;
      const Placement placement = locate(outline, frame.project(at(node)), weld_tolerance_);
      if (placement == Placement::inside ||
          (placement == Placement::on_outline && in_contact(node))) {
        on_face[f].push_back(node);
      }
    });
    std::sort(on_face[f].begin(), on_face[f].end());
  }

  FaceSet set;
  set.faces = std::move(faces);
  set.nodes = std::move(on_face);
  set.areas = std::move(face_area);
  set.keeps_normal.assign(face_count, 0);
  for (const FaceRef& face : constraints_.keep_normal) {
    std::vector<int> key;
    for (int index : faces_[face.block][face.face]) {
      key.push_back(node_of_position_[block_offset_[face.block] + index]);
    }
    std::sort(key.begin(), key.end());
    set.keeps_normal[face_of_nodes.at(key)] = 1;
  }

  // Faces with three non-collinear nodes in common lie in one plane.
  UnionFind merged(face_count);
  std::vector<std::vector<int>> faces_of_node(node_count);
  for (int f = 0; f < face_count; ++f) {
    for (int node : set.nodes[f]) faces_of_node[node].push_back(f);
  }
  for (int f = 0; f < face_count; ++f) {
    std::map<int, std::vector<int>> common;
    for (int node : set.nodes[f]) {
      for (int g : faces_of_node[node]) {
        if (g > f) common[g].push_back(node);
      }
    }
    for (const auto& [g, nodes] : common) {
      if (spans_plane(nodes)) merged.join(f, g);
    }
  }
  // So do coplanar faces whose equations are dependent at the start: a
  // flat strip of faces sharing edges, held at both ends (the side of an
  // arch between fixed blocks), can stay flat or fold, and its equations
  // are singular where the two meet. Flat is the design's reading.
  for (bool changed = true; changed;) {
    std::vector<int> root(face_count);
    for (int f = 0; f < face_count; ++f) root[f] = merged.root(f);
    form_groups(set, root);
    changed = false;
    for (const auto& [f, g] : dependent_coplanar_faces()) changed |= merged.join(f, g);
  }
}

void DesignSpace::form_groups(const FaceSet& set, const std::vector<int>& root) {
  const auto at = [&](int node) -> const Vec3& { return nodes_[node].initial; };
  groups_.clear();
  rows_.clear();
  variable_count_ = position_variable_count_;
  std::vector<int> group_of_root(root.size(), -1);
  std::vector<char> keeps_normal;
  for (size_t f = 0; f < root.size(); ++f) {
    int& group = group_of_root[root[f]];
    if (group < 0) {
      group = static_cast<int>(groups_.size());
      groups_.push_back(PlaneGroup{});
      groups_.back().source = static_cast<int>(f);
      keeps_normal.push_back(0);
    }
    PlaneGroup& plane = groups_[group];
    plane.nodes.insert(plane.nodes.end(), set.nodes[f].begin(), set.nodes[f].end());
    // The group's normal and name come from its kept-normal face, or else
    // from its widest face.
    if (set.keeps_normal[f] && !keeps_normal[group]) {
      keeps_normal[group] = 1;
      plane.source = static_cast<int>(f);
    } else if (!keeps_normal[group] && set.areas[f].norm() > set.areas[plane.source].norm()) {
      plane.source = static_cast<int>(f);
    }
  }
  for (PlaneGroup& plane : groups_) {
    std::sort(plane.nodes.begin(), plane.nodes.end());
    plane.nodes.erase(std::unique(plane.nodes.begin(), plane.nodes.end()), plane.nodes.end());
    plane.face = set.faces[plane.source];
    // Outward, as the face is oriented: a kept normal keeps its sign.
    const FaceRef face = plane.face;
    plane.normal =
        face_planes(initial_.block_vertices[face.block], {faces_[face.block][face.face]})[0].normal;
    for (int node : plane.nodes) plane.center += at(node);
    plane.center /= static_cast<double>(plane.nodes.size());
    plane.size = 0.0;
    for (int node : plane.nodes) {
      plane.size = std::max(plane.size, (at(node) - plane.center).norm());
    }
  }
  assign_plane_variables(keeps_normal);
}

std::vector<std::pair<int, int>> DesignSpace::dependent_coplanar_faces() const {
  std::vector<std::pair<int, int>> pairs;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian =
      constraint_jacobian(Eigen::VectorXd::Zero(variable_count_));
  NormalFactor factor;
  const std::vector<int> kept = independent_rows(jacobian, factor);
  if (static_cast<int>(kept.size()) == constraint_count()) return pairs;
  const Eigen::SparseMatrix<double> kept_jacobian = selection(kept, constraint_count()) * jacobian;
  factor.compute(kept_jacobian * kept_jacobian.transpose());
  const auto coplanar = [&](const PlaneGroup& a, const PlaneGroup& b) {
    return std::abs(a.normal.dot(b.normal)) >= kParallel &&
           std::abs(a.normal.dot(b.center - a.center)) <= weld_tolerance_;
  };
  for (int row = 0, next = 0; row < constraint_count(); ++row) {
    if (next < static_cast<int>(kept.size()) && kept[next] == row) {
      ++next;
      continue;
    }
    // The row as a combination of the kept rows: their groups are involved.
    const Eigen::VectorXd gradient = jacobian.row(row).transpose();
    const Eigen::VectorXd weights = factor.solve(kept_jacobian * gradient);
    const PlaneGroup& own = groups_[rows_[row].group];
    for (Eigen::Index k = 0; k < weights.size(); ++k) {
      const PlaneGroup& other = groups_[rows_[kept[k]].group];
      if (std::abs(weights[k]) > kInvolved * weights.cwiseAbs().maxCoeff() && &other != &own &&
          coplanar(own, other)) {
        pairs.emplace_back(own.source, other.source);
      }
    }
  }
  return pairs;
}

void DesignSpace::assign_plane_variables(const std::vector<char>& keeps_normal) {
  const auto at = [&](int node) -> const Vec3& { return nodes_[node].initial; };
  std::map<std::vector<int>, int> group_of_nodes;
  for (size_t g = 0; g < groups_.size(); ++g) {
    group_of_nodes.emplace(groups_[g].nodes, static_cast<int>(g));
  }
  const Vec3 mirror_normal =
      constraints_.mirror ? constraints_.mirror->normal.normalized() : Vec3::Zero();
  double magnitude = 0.0;  // of coordinates, for rounding
  for (const Node& node : nodes_) {
    magnitude = std::max(magnitude, node.initial.cwiseAbs().maxCoeff());
  }
  std::vector<double> tolerances;

  for (size_t g = 0; g < groups_.size(); ++g) {
    PlaneGroup& plane = groups_[g];
    // A mirror image of a group whose plane is already a variable keeps its
    // faces planar by symmetry; a self-symmetric plane only turns about the
    // mirror normal.
    int image = -1;
    if (constraints_.mirror) {
      std::vector<int> mirrored;
      for (int node : plane.nodes) mirrored.push_back(partner_[node]);
      std::sort(mirrored.begin(), mirrored.end());
      const auto found = group_of_nodes.find(mirrored);
      if (mirrored.front() >= 0 && found != group_of_nodes.end()) image = found->second;
    }
    if (image >= 0 && image < static_cast<int>(g)) continue;
    const bool self_symmetric = image == static_cast<int>(g);
    if (self_symmetric && mirror_normal.cross(plane.normal).norm() < 0.5) {
      continue;  // the mirror plane
    }

    std::vector<int> fixed;
    for (int node : plane.nodes) {
      if (nodes_[node].variable_count == 0) fixed.push_back(node);
    }
    const bool determined = spans_plane(fixed) || (keeps_normal[g] && !fixed.empty());
    if (!determined) {
      if (self_symmetric) {
        plane.tilts.col(0) = mirror_normal.cross(plane.normal).normalized();
        plane.tilt_count = 1;
      } else if (!keeps_normal[g]) {
        plane.tilts = plane_basis(plane.normal);
        plane.tilt_count = 2;
      }
      plane.moves = true;
      plane.first_variable = variable_count_;
      variable_count_ += plane.tilt_count + 1;
    }

    // One row per node; fixed nodes only while they still pin the plane's
    // variables (their rows depend on nothing else).
    std::vector<Eigen::Vector3d> pinned;  // orthonormalised plane parts of kept fixed rows
    const double tolerance = kRelativeRowTolerance * plane.size +
                             8.0 * std::numeric_limits<double>::epsilon() * magnitude;
    for (int node : plane.nodes) {
      if (nodes_[node].variable_count == 0) {
        if (determined) continue;
        Eigen::Vector3d part = Eigen::Vector3d::Zero();
        for (int k = 0; k < plane.tilt_count; ++k) {
          part[k] = (at(node) - plane.center).dot(plane.tilts.col(k)) / plane.size;
        }
        part[plane.tilt_count] = -1.0;
        const double length = part.norm();
        for (const Eigen::Vector3d& earlier : pinned) part -= part.dot(earlier) * earlier;
        if (part.norm() <= 1e-6 * length) continue;
        pinned.push_back(part.normalized());
      } else if (self_symmetric && partner_[node] < node) {
        continue;  // the same equation as its partner's
      }
      rows_.push_back(ConstraintRow{static_cast<int>(g), node});
      tolerances.push_back(tolerance);
    }
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

Eigen::VectorXd DesignSpace::lower_bounds() const { return -upper_bounds(); }

Eigen::VectorXd DesignSpace::upper_bounds() const {
  Eigen::VectorXd bounds =
      Eigen::VectorXd::Constant(variable_count_, std::numeric_limits<double>::infinity());
  bounds.head(position_variable_count_).setConstant(constraints_.max_displacement);
  return bounds;
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
    for (int k = 0; k < node.variable_count; ++k) {
      p += node.basis.col(k) * z[node.first_variable + k];
    }
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
    for (int k = 0; k < node.variable_count; ++k) {
      reduced[node.first_variable + k] += node.basis.col(k).dot(g);
    }
  };
  for (size_t b = 0; b < faces_.size(); ++b) {
    const auto& vertices = gradient.block_vertices[b];
    const size_t expected = block_offset_[b + 1] - block_offset_[b];
    if (vertices.size() != expected) {
      throw shape_error("block " + std::to_string(b + 1) + " has " +
                        std::to_string(vertices.size()) + " vertices, expected " +
                        std::to_string(expected));
    }
    for (size_t k = 0; k < vertices.size(); ++k) {
      add(block_offset_[b] + static_cast<int>(k), vertices[k]);
    }
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
        return describe(nodes_[g].example) + " moves " + message_number(moved, kGivenValueDigits) +
               " m along an axis, beyond max_displacement (" + message_number(bound, kGivenValueDigits) + " m)";
      }
    }
  }
  const Eigen::VectorXd residuals = constraint_values(z);
  for (int r = 0; r < constraint_count(); ++r) {
    const double off = std::abs(residuals[r]);
    if (off > kRowSlack * tolerances_[r] + start_residuals_[r]) {
      return describe(groups_[rows_[r].group].face) + " is not planar (a vertex " + message_number(off, kGivenValueDigits) +
             " m off its plane)";
    }
  }
  const DesignPoint candidate = design(z);
  for (size_t b = 0; b < faces_.size(); ++b) {
    const double volume = mass_properties(candidate.block_vertices[b], faces_[b]).volume;
    const std::string block = "block " + std::to_string(b + 1);
    if (volume <= 0.0) return block + " is inverted or flat (volume " + message_number(volume, kGivenValueDigits) + " m^3)";
    if (volume < constraints_.min_block_volume) {
      return block + " has volume " + message_number(volume, kGivenValueDigits) + " m^3, below min_block_volume (" +
             message_number(constraints_.min_block_volume, kGivenValueDigits) + " m^3)";
    }
  }
  return {};
}

std::pair<Vec3, double> DesignSpace::plane_at(const PlaneGroup& plane,
                                              const Eigen::VectorXd& z) const {
  if (!plane.moves) return {plane.normal, 0.0};
  Vec3 normal = plane.normal;
  for (int k = 0; k < plane.tilt_count; ++k) {
    normal += z[plane.first_variable + k] / plane.size * plane.tilts.col(k);
  }
  return {normal, z[plane.first_variable + plane.tilt_count]};
}

Eigen::VectorXd DesignSpace::constraint_values(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  Eigen::VectorXd values(constraint_count());
  for (int r = 0; r < constraint_count(); ++r) {
    const PlaneGroup& plane = groups_[rows_[r].group];
    const auto [normal, offset] = plane_at(plane, z);
    values[r] = normal.dot(positions[rows_[r].node] - plane.center) - offset;
  }
  return values;
}

Eigen::SparseMatrix<double> DesignSpace::constraint_jacobian(const Eigen::VectorXd& z) const {
  const std::vector<Vec3> positions = node_positions(z);
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < constraint_count(); ++r) {
    const PlaneGroup& plane = groups_[rows_[r].group];
    const Node& node = nodes_[rows_[r].node];
    const Vec3 normal = plane_at(plane, z).first;
    for (int c = 0; c < node.variable_count; ++c) {
      entries.emplace_back(r, node.first_variable + c, node.basis.col(c).dot(normal));
    }
    if (!plane.moves) continue;
    const Vec3 arm = positions[rows_[r].node] - plane.center;
    for (int k = 0; k < plane.tilt_count; ++k) {
      entries.emplace_back(r, plane.first_variable + k, arm.dot(plane.tilts.col(k)) / plane.size);
    }
    entries.emplace_back(r, plane.first_variable + plane.tilt_count, -1.0);
  }
  Eigen::SparseMatrix<double> jacobian(constraint_count(), variable_count_);
  jacobian.setFromTriplets(entries.begin(), entries.end());
  return jacobian;
}

}  // namespace ashlar
