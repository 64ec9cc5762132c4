// The sparsity pattern of the interior-point normal matrix A Phi^-1 A^T
// (interior_point.hpp), and where each force group adds into it.
//
// The matrix is (rows x rows), rows = D x (analysed bodies) with D the
// balance rows per body (6, or 3 for planar problems). It is made of D x D
// blocks: one on the diagonal per body, and one per pair of bodies that a
// group acts on together (two blocks in contact, a cable's two ends). Only
// the upper triangle is stored, in compressed columns: block column J holds
// its block rows I <= J in ascending order, D x D values each (on the
// diagonal block only its upper part). A group of bodies a and b adds
// C_a C_a^T to block (a, a), C_b C_b^T to (b, b) and C_a C_b^T to the
// off-diagonal block of the pair (C = A R^-1, phi_factor.hpp); its
// GroupSlots say where those blocks are, so that the assembly, run for
// every group at every iteration, never searches the pattern.
#pragma once

#include <vector>

#include "analysis/equilibrium_problem.hpp"

namespace ashlar {

// Where one group adds into the pattern.
struct GroupSlots {
  int row_a = -1, row_b = -1;     // the group's bodies' first balance rows
  int aa = -1, bb = -1, ab = -1;  // rank of each block among its block column's, -1 if absent
  bool ab_transposed = false;     // block (a, b) stored as (b, a) in the upper triangle
};

// The upper triangle in compressed columns: rows of column j are
// row_indices[column_starts[j] .. column_starts[j + 1]), ascending.
struct UpperPattern {
  std::vector<int> column_starts, row_indices;
};

class NormalPattern {
public:
  // The pattern of `problem`'s groups (their bodies' pairs).
  explicit NormalPattern(const EquilibriumProblem& problem);

  int rows() const { return rows_; }
  int block_rows() const { return block_rows_; }
  int blocks() const { return rows_ / block_rows_; }
  UpperPattern upper_triangle() const;
  // The slots of `problem`'s groups; false if some group adds to a block
  // the pattern lacks.
  bool find_slots(const EquilibriumProblem& problem, std::vector<GroupSlots>& slots) const;

private:
  std::vector<std::vector<int>> block_pattern_;  // per block column J, its block rows I <= J, sorted
  int rows_ = 0;
  int block_rows_ = 6;
};

// The assembly split among threads: part p adds into block columns
// [first_column[p], first_column[p + 1]) only, so that no value has two
// writers, taking the groups that add there (groups[p]; empty lists for a
// single part: every group, in order).
struct AssemblyParts {
  std::vector<int> first_column;
  std::vector<std::vector<int>> groups;
};

// At most `parts` parts over `blocks` block columns, each adding about as
// many blocks, for groups with these slots.
AssemblyParts partition_assembly(const std::vector<GroupSlots>& slots, int blocks, int block_rows, int parts);

}  // namespace ashlar
