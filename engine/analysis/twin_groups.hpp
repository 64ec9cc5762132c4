// Twin contact vertices, solved as one force group per class.
//
// Twins: contact vertices with the same rules, bodies, bound and effect on
// the balance rows (a planar problem's vertex pairs on either face of the
// wall, which differ only in y) have one optimum, the same forces at each
// (the objective is strictly convex in them and symmetric). The solver
// (interior_point.hpp) takes m such twins as one group with effect m A,
// objective m (1/2 x^T H x + q^T x) and the same inequalities, whose
// multipliers are m times each twin's, and hands every twin the group's x,
// w and z / m: the same QP, with half the per-group work on a planar wall.
//
// Shapes: a problem of n groups has x of 4 n (scaled forces), y of its
// balance rows, w and z of its inequality rows (group k's from
// first_row[k], EquilibriumProblem::inequality_starts); the merged problem
// the same with its classes in place of groups.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point_iterate.hpp"

namespace ashlar {

class TwinGroups {
public:
  // The twin classes of `problem` (none unless `merge`); false when they
  // are the ones already held (so the caller keeps what it derived from
  // them), true when they changed.
  bool find(const EquilibriumProblem& problem, int block_rows, bool merge);
  // Forgets the classes (the problem's groups changed).
  void clear() { *this = TwinGroups{}; }

  // Whether some twins merged: otherwise the problem is solved as it is.
  bool merged() const { return !merged_of_.empty(); }
  int classes() const { return static_cast<int>(first_member_.size()); }
  // The class of problem group k, and the first problem group of class j.
  int class_of(int group) const { return merged_of_[group]; }
  int first_member(int merged) const { return first_member_[merged]; }
  // The number of twins group k of the groups worked on stands for: its
  // class's m, or 1 when nothing merged.
  double count(int k) const { return count_.empty() ? 1.0 : count_[k]; }

  // `problem` with each class as one group.
  EquilibriumProblem merge(const EquilibriumProblem& problem) const;
  // Where each class's inequality rows start (and the total), from the
  // problem's (EquilibriumProblem::inequality_starts).
  std::vector<int> merged_first_rows(const std::vector<int>& full_first_row) const;
  // One of the problem's solutions in the classes' unknowns, and back.
  void merge_solution(const InteriorPointIterate& full, const std::vector<int>& full_first_row,
                      InteriorPointIterate& merged) const;
  void split_solution(const InteriorPointIterate& merged, const std::vector<int>& full_first_row,
                      InteriorPointIterate& full) const;

private:
  std::vector<int> merged_of_;     // problem group -> merged group; empty: no twins
  std::vector<int> first_member_;  // merged group -> its first problem group
  std::vector<double> count_;      // merged group -> its number of twins (m)
};

}  // namespace ashlar
