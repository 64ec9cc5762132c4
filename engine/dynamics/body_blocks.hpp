// A symmetric matrix in the free bodies' velocities, 6 unknowns a body
// (velocity, then angular velocity; free bodies numbered in index order),
// whose off-diagonal 6 x 6 blocks are those of bodies a contact links: the
// pattern of its upper triangle in compressed columns (for
// core/sparse_cholesky.hpp) and where a block's entries go in its values.
// The contact solver's global step and the interior-point method
// (contact_interior.hpp) factor such matrices, M + J^T S J.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

namespace ashlar {

class BodyBlocks {
public:
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  // links: pairs of free-body numbers (i < j), sorted, without repeats.
  // Returns the upper triangle's row indices (column_starts() gives the
  // columns), every diagonal block whole.
  std::vector<int> set(int free_bodies, const std::vector<std::pair<int, int>>& links) {
    column_bodies_.assign(free_bodies, {});
    for (const auto& [i, j] : links) column_bodies_[j].push_back(i);
    std::vector<int> rows;
    column_starts_.assign(6 * free_bodies + 1, 0);
    for (int j = 0; j < free_bodies; ++j) {
      std::vector<int>& bodies = column_bodies_[j];
      bodies.push_back(j);  // links are sorted: the others come ascending
      for (int c = 0; c < 6; ++c) {
        for (const int i : bodies) {
          for (int r = 0; r <= (i == j ? c : 5); ++r) rows.push_back(6 * i + r);
        }
        column_starts_[6 * j + c + 1] = static_cast<int>(rows.size());
      }
    }
    return rows;
  }

  const std::vector<int>& column_starts() const { return column_starts_; }

  // Adds `block` to the values at block (i, j), i <= j linked (i == j: its
  // upper triangle).
  void add(double* values, int i, int j, const Mat6& block) const {
    const std::vector<int>& bodies = column_bodies_[j];
    const int k = static_cast<int>(std::lower_bound(bodies.begin(), bodies.end(), i) - bodies.begin());
    for (int c = 0; c < 6; ++c) {
      double* column = values + column_starts_[6 * j + c] + 6 * k;
      for (int r = 0; r < (i == j ? c + 1 : 6); ++r) column[r] += block(r, c);
    }
  }

  // Sets body j's column (its blocks with every linked i <= j) to zero.
  void clear_column(double* values, int j) const {
    std::fill(values + column_starts_[6 * j], values + column_starts_[6 * j + 6], 0.0);
  }

private:
  std::vector<std::vector<int>> column_bodies_;  // per free body j: the linked i <= j, ascending (j last)
  std::vector<int> column_starts_;               // of the 6 m x 6 m upper triangle
};

}  // namespace ashlar
