// CHOLMOD behind a plain interface, for the sparse factorisations of
// core/sparse_cholesky.hpp and core/split_cholesky.hpp: one sparse
// symmetric pattern with its analysis and supernodal factor, owned and freed
// with the object (CholmodSystem), and the orderings asked of CHOLMOD
// (bisect, order_with_last_rows). cholmod.h is included by
// cholmod_system.cpp alone (engine/CMakeLists.txt gives that file its
// include directory).
//
// Patterns are n x n in compressed columns: rows of column j are
// row_indices[column_starts[j] .. column_starts[j + 1]), ascending; values
// follow the same order.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

namespace ashlar {

// One CHOLMOD matrix (the upper or the lower triangle) with its analysis
// and factor.
class CholmodSystem {
public:
  enum class Triangle { upper, lower };
  enum class Solve {
    whole,     // A x = b
    forward,   // L x = b
    backward,  // L^T x = b
  };

  // The matrix to factorise, a column at a time in factor order:
  // fill(j, slot, column) writes column j's entry at each row i >= j of its
  // pattern to column[slot[i]]. The values stay where the caller keeps
  // them; they are read, never copied as a whole.
  class Columns {
  public:
    virtual ~Columns() = default;
    virtual void fill(int j, const int* slot, double* column) const = 0;
  };

  // The pattern (copied, until the analysis no longer needs it); no
  // values: factorize() takes them from the caller. widest_supernode: the
  // factor's supernodes are cut into panels of at most this many columns
  // (memory: cholmod_system.cpp), 0 for the default, 96 columns from
  // 20,000 rows and none cut below.
  CholmodSystem(int n, const int* column_starts, const int* row_indices, Triangle stored,
                int widest_supernode = 0);
  ~CholmodSystem();
  CholmodSystem(const CholmodSystem&) = delete;
  CholmodSystem& operator=(const CholmodSystem&) = delete;

  // Fill-reducing ordering of CHOLMOD's choice; then permutation()[k] is
  // the row placed k-th (postordered).
  void analyze();
  // The rows' own order (the caller has permuted them), kept as given: no
  // postordering. Only a system analysed so, a lower triangle, can be
  // factorised (factorize()): its columns then go straight into the
  // factor's. The pattern is freed.
  void analyze_as_ordered();
  const int* permutation() const;

  int rows() const;
  double factor_nonzeros() const;
  // Values the factor stores once factorisable (analyze_as_ordered): its
  // nonzeros and, in each supernode's dense diagonal block, the unused
  // ones above the diagonal.
  size_t stored_values() const;

  // Numeric factorisation of the lower triangle in factor order (a system
  // analysed with analyze_as_ordered, `columns` on its pattern) into
  // CHOLMOD's supernodal factor, which solve() then uses; false when the
  // matrix is not positive definite.
  bool factorize(const Columns& columns);
  // Solves `system` for the right-hand side rhs[0 .. rows()); the solution
  // stays valid until the next solve, which reuses its storage.
  const double* solve(Solve system, const double* rhs);
  // The factor's trailing block L(first.., first..) (s = rows() - first
  // square, lower triangular) reversed in both directions: out(a, b) =
  // L(last - a, last - b) with last = rows() - 1, upper triangular.
  void trailing_block_reversed(int first, Eigen::MatrixXd& out) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The rows of the pattern's graph (upper triangle) that separate it into
// two parts (METIS through CHOLMOD): part[i] is 0 or 1, or 2 for the
// separator. Empty when CHOLMOD cannot bisect.
std::vector<int> bisect(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices);

// A fill-reducing order of the pattern's rows (upper triangle; order[k]:
// the row placed k-th) that places the rows from `first_last` on after all
// others. Where the rows come in runs of `block` (a body's unknowns, with
// one pattern) and n and first_last are multiples of it, the runs are
// ordered as one row each and kept together. Empty if CHOLMOD fails.
std::vector<int> order_with_last_rows(int n, const std::vector<int>& column_starts,
                                      const std::vector<int>& row_indices, int first_last, int block);

}  // namespace ashlar
