// Reverse-mode derivatives of the contact interfaces with respect to the block
// vertices: the link between the equilibrium sensitivity, which is per contact
// vertex and per interface frame, and the structural gradient, which is per
// block vertex.
#pragma once

#include <vector>

#include "core/types.hpp"
#include "structure/contact_detection.hpp"
#include "structure/structure.hpp"

namespace ashlar {

// dP/d(quantities of one interface), as the equilibrium sensitivity gives them.
struct InterfaceAdjoint {
  std::vector<Vec3> vertices;  // dP/d(interface.vertices[k]), same size and order; empty: zero
  Vec3 normal = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();  // dP/d(each frame vector)
};

// ACCUMULATE_INTERFACE_GRADIENT  Chains the derivatives of a scalar P with
// respect to the contact interfaces (vertices and frames) back to the vertices
// of the blocks, in closed form.
//
//   accumulate_interface_gradient(structure, options, adjoints, gradient);
//
// Inputs:
//   structure  #B blocks; its interfaces are structure.interfaces(options), #I of them
//   options    the contact options of those interfaces (their tolerance picks the faces)
//   adjoints   #I adjoints; adjoints[k] belongs to interfaces[k], its `vertices` holds one
//              entry per interfaces[k].vertices (or none). Units: P per metre for vertices,
//              P per unit vector for normal, u and v, each taken as an independent 3-vector.
//              Interfaces whose adjoint is all zero are skipped.
// Input/Output:
//   gradient   #B lists, gradient[i] sized as structure.block(i).vertices(). Adds to
//              gradient[i][k] the sum over the quantities q of every interface of
//              adjoint_q . dq / d(vertex k of block i), in P per metre.
//
// Each interface lies in the plane of "face A": the face of block a whose plane
// contact detection projected into, with unit Newell normal n and centre c, the
// mean of its vertices (the same plane as Block::face_planes). With
// proj(y) = y - n n.(y - c), every contact vertex x is, by provenance:
//   1. a vertex p of a face of block a on the contact plane:   x = proj(p)
//   2. a vertex q of a face of block b on the contact plane:   x = proj(q)
//   3. the crossing of an edge p0 p1 of such a face of a with the projection of an
//      edge q0 q1 of such a face of b:
//        x = proj(p0 + s (p1 - p0)),  s = w.(q0 - p0) / w.(p1 - p0),  w = (q1 - q0) x n
// and normal = n, u = (x[j+1] - x[j]) / |x[j+1] - x[j]| on the longest edge j (the
// first of equal ones, as detection picks it), v = n x u. The derivative is that
// of these formulas, including how n and c move with face A's vertices.
//
// A contact vertex within 1e-9 of the contact polygon's size (plus rounding) of a
// projected vertex of block a is type 1, even when it is also a vertex of block b
// or lies on an edge of b; failing that, one at a vertex of b is type 2. So where
// two blocks share a joint face exactly (voussoirs), its vertices are type 1 and
// the derivative is exact for moves that keep coincident vertices together, as an
// optimiser that welds them does; a move that separates them changes the
// provenance, and the derivative is then one-sided (the same for a vertex of one
// face lying on an edge of the other, and for a tie between longest edges).
// A mid-plane interface (Interface::on_mid_plane, two copies of one joint)
// has instead x_k = proj(m_k) with m_k = (p_k + q_k) / 2, the midpoint of
// vertex k of face A and the vertex of face B paired with it, on the plane
// through the midpoints' mean with their unit Newell normal: the derivative
// then reaches both faces, half each, and is smooth while the pairing holds.
// Holes, center and area are not differentiated (nothing downstream uses them).
//
// Cost per interface: one scan of the face planes of blocks a and b, the
// pairing test of contact detection between their faces on the contact plane,
// then (expected) O(size of the faces in contact), since vertices and edges are
// looked up in a grid over the plane; the polygon intersection is not rerun.
//
// Throws InvalidArgument when the sizes of adjoints or gradient do not match, or
// when a contact vertex is none of the three kinds (its provenance is unknown).
void accumulate_interface_gradient(const Structure& structure, const ContactOptions& options,
                                   const std::vector<InterfaceAdjoint>& adjoints,
                                   std::vector<std::vector<Vec3>>& gradient);

}  // namespace ashlar
