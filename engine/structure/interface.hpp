// A contact interface between two blocks: found by contact detection, or
// given explicitly (Structure::add_interface).
#pragma once

#include <algorithm>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

// The contact polygon where a face of block a meets a face of block b
// (coplanar within the tolerance, opposite normals). One interface per
// connected piece of contact. Vertices lie in the plane of block a's face,
// except on a mid-plane joint (see on_mid_plane).
struct Interface {
  int a = -1, b = -1;            // 0-based block indices, a < b
  Vec3 normal = Vec3::Zero();    // unit, pointing from block a into block b
  Vec3 u = Vec3::Zero();         // unit tangent along the polygon's longest edge
  Vec3 v = Vec3::Zero();         // normal x u
  Vec3 center = Vec3::Zero();    // area centroid (m)
  double area = 0.0;             // m^2, holes excluded
  std::vector<Vec3> vertices;    // outer boundary, counter-clockwise about normal
  std::vector<std::vector<Vec3>> holes;  // clockwise about normal
  // Given by the user (Structure::add_interface, or a file's stored
  // interfaces), not found from the geometry: it does not move with the
  // blocks, so nothing differentiates it.
  bool is_explicit = false;
  // Cut from two faces that describe one joint twice, each vertex of one
  // within the tolerance of a vertex of the other but not on it (warped,
  // perturbed, scanned models; see mid_plane_pairing): the polygon of the
  // paired vertices' midpoints on its best-fit plane, so the joint keeps
  // its whole area instead of the overlap of two imprecise copies.
  bool on_mid_plane = false;
  // The faces (of blocks a and b) it was cut from, face_a the one whose
  // plane it lies in (the first of each when several lie on one plane), or
  // the two copies of a mid-plane joint; -1 for explicit interfaces. The
  // interfaces' derivatives start from them.
  int face_a = -1, face_b = -1;
};

// Sets u along the polygon's longest edge and v = normal x u: the frame
// every interface gets, detected or explicit. Edges within 1e-9 of the
// longest tie; of tied edges the lowest (by its midpoint's height), then
// the first, is taken. The friction pyramid has an edge along u, so the
// choice is part of the problem: taken by order alone, a dome's head
// joints (whose top and bottom edges are equally long) got their pyramids
// turned by rounding, a ring's identical blocks load capacities 0.2-1.5 %
// apart. By height, a motion that keeps gravity (a rotation about a
// vertical axis, a reflection in a vertical plane) carries each frame to
// its image's, up to the pyramid's own symmetries
// (analysis/problem_symmetry.hpp). Needs the normal and at least two
// vertices.
inline void set_frame_along_longest_edge(Interface& contact) {
  constexpr double kTiedLength = 1e-9;
  const std::vector<Vec3>& p = contact.vertices;
  const auto edge = [&](size_t i) { return Vec3(p[(i + 1) % p.size()] - p[i]); };
  const auto height = [&](size_t i) { return p[i].z() + p[(i + 1) % p.size()].z(); };
  double longest = 0.0;
  for (size_t i = 0; i < p.size(); ++i) longest = std::max(longest, edge(i).norm());
  size_t chosen = p.size();
  for (size_t i = 0; i < p.size(); ++i) {
    if (edge(i).norm() < (1.0 - kTiedLength) * longest) continue;
    if (chosen == p.size() || height(i) < height(chosen) - kTiedLength * longest) chosen = i;
  }
  contact.u = edge(chosen).normalized();
  contact.v = contact.normal.cross(contact.u);
}

}  // namespace ashlar
