// Symmetries of an equilibrium problem: the rotations about a vertical axis
// and the reflections in vertical planes through it (the rigid motions that
// keep gravity) that map the problem onto itself. A parametric dome, vault
// or arch has them; a scanned or perturbed one has none.
//
// A motion g counts only when it maps the problem itself, not just the
// blocks' shapes: every free block to a free block whose balance rows'
// right-hand side (its weight and loads) is the image of its own, and every
// contact vertex to one with the same rules at the image of its position
// whose effect on the image blocks' rows is the image of its own, its
// unknowns taken through a signed permutation of the friction pair
// (f_u, f_v) that leaves the friction rows, the Hessian and the linear
// term as they are. To 1e-9 in scaled units: rounding passes, a model
// whose vertices moved by a millionth of a block does not.
//
// Then an optimum x of the problem maps to an optimum of the problem with
// every block's role carried by its image, with the same objective. The
// per-block analyses use that: a linear program's optimal value for block
// g(i) is block i's (load capacity), and a strictly convex program's
// unique optimum for block g(i) is the image of block i's (important
// weights), so one program per orbit of blocks answers for the orbit.
#pragma once

#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct ProblemSymmetry {
  // Each symmetry found as the block each free block maps to (indexed by
  // block; -1 for supports, which have no rows to map), motions that
  // permute the blocks alike counted once. The identity is first; one
  // entry when the problem has no other symmetry.
  std::vector<std::vector<int>> block_maps;
  // Per block, the block of its orbit whose program answers for it (the
  // orbit's first in block order; itself for supports and for blocks of
  // a problem without symmetry) ...
  std::vector<int> representative;
  // ... and the symmetry (index into block_maps) that takes the
  // representative to it.
  std::vector<int> symmetry_of;
};

// The symmetries of `problem` (its groups contact vertices, or weights as
// eq. 8 adds them), built from `structure`: the identity alone unless
// `search`, and for planar problems, cables and floating bodies.
// Linear in the problem's size per candidate motion; the candidates are
// the blocks at the height and distance from the axis of one chosen block.
ProblemSymmetry find_problem_symmetry(const Structure& structure, const EquilibriumProblem& problem,
                                      bool search = true);

}  // namespace ashlar
