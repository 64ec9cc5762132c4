// The interior-point normal matrix A Phi^-1 A^T (rows x rows, rows = D x
// analysed bodies, D = 6 or 3 balance rows per body) of the equilibrium QP:
// what is left of the Newton system once every force group's unknowns are
// eliminated (interior_point.hpp). Its pattern (normal_pattern.hpp) is
// analysed once, at construction; then every interior-point iteration
// fills its values for the iterate's barrier scaling z / w (one per
// inequality row), factorises them and solves with them.
//
// Precompute / solve: the constructor (pattern, group slots, the
// fill-reducing analysis of SparseCholesky) is the expensive part done
// once; assemble, factorize_shifted and solve run per iteration.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/normal_pattern.hpp"
#include "analysis/phi_factor.hpp"
#include "core/parallel_loop.hpp"
#include "core/sparse_cholesky.hpp"

namespace ashlar {

class TwinGroups;

class NormalMatrix {
public:
  // Analyses the pattern of `problem`'s groups; `loop` (which must outlive
  // this) runs the assembly's passes, `factorisation` says how to factor.
  NormalMatrix(const EquilibriumProblem& problem, ParallelLoop& loop, const SparseCholeskyOptions& factorisation);

  int rows() const { return pattern_.rows(); }
  int block_rows() const { return pattern_.block_rows(); }
  // False for a problem with no balance rows: nothing to factor.
  bool analysed() const { return cholesky_ != nullptr; }

  // Whether `problem` has the groups' bodies this matrix was built for.
  bool fits(const EquilibriumProblem& problem) const;
  // Takes `problem`'s groups when they add only to blocks of the analysed
  // pattern: true then (the twins worked on are reset to none), false and
  // unchanged otherwise. Same rows as fits() checks, or false.
  bool refit(const EquilibriumProblem& problem);
  // Works on the twin classes of `twins` (twin_groups.hpp) from now on, or
  // on the problem's groups when none merged.
  void work_on(const TwinGroups& twins);

  // Fills the values for barrier scaling z / w (slacks w and multipliers
  // z, one per inequality row, rows of group k from first_row[k]) and each
  // group's factor R of Phi = R^T R into phi_factors; `problem` is the one
  // worked on (merged when twins merged). D = block_rows() at compile time.
  template <int D>
  void assemble(const EquilibriumProblem& problem, const std::vector<int>& first_row, const Eigen::VectorXd& w,
                const Eigen::VectorXd& z, const TwinGroups& twins, std::vector<PhiFactor>& phi_factors);
  // The same with D picked at run time.
  void assemble_any(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                    const Eigen::VectorXd& w, const Eigen::VectorXd& z, const TwinGroups& twins,
                    std::vector<PhiFactor>& phi_factors);
  // Factorises the assembled values, with the least diagonal shift that
  // keeps them positive definite; false when even the largest fails.
  bool factorize_shifted();
  // Solves with the last factorisation (rhs and out: rows()).
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) const { cholesky_->solve(rhs, out); }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return cholesky_->solve(rhs); }
  int factorizations() const { return cholesky_->factorizations(); }

private:
  const std::vector<GroupSlots>& worked_slots() const {
    return merged_slots_.empty() ? pattern_slots_ : merged_slots_;
  }
  void partition();

  ParallelLoop& loop_;
  NormalPattern pattern_;
  std::vector<GroupSlots> pattern_slots_;  // per group of the problem analysed (fits())
  std::vector<GroupSlots> merged_slots_;   // per twin class, when twins merged
  AssemblyParts parts_;
  std::unique_ptr<SparseCholesky> cholesky_;
};

}  // namespace ashlar
