#include "analysis/interior_point.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/sparse_cholesky.hpp"
#include "core/clock.hpp"
#include "core/interrupt.hpp"

namespace ashlar {

namespace {

using Matrix4 = Eigen::Matrix4d;
using Vector4 = Eigen::Vector4d;
// A block's balance rows: 6, or 3 for planar problems (no heap either way).
using BlockByVertex = Eigen::Matrix<double, Eigen::Dynamic, 4, 0, 6, 4>;
using BlockByBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using RowsMatrix = Eigen::Matrix<double, Eigen::Dynamic, 4>;

// Iterations without a more accurate iterate, once one is within the
// inaccurate tolerance, after which the solve stops; and at any accuracy,
// after which more iterations are not going to help.
constexpr int kStallIterations = 8;
constexpr int kHopelessIterations = 20;


// Largest step in (0, 1] keeping v + step * dv >= 0.
double step_to_boundary(const Eigen::VectorXd& v, const Eigen::VectorXd& dv) {
  double step = 1.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (dv(i) < 0.0) step = std::min(step, -v(i) / dv(i));
  }
  return step;
}

}  // namespace

const char* status_name(SolverStatus status) {
  switch (status) {
    case SolverStatus::converged:
      return "converged";
    case SolverStatus::inaccurate:
      return "inaccurate";
    case SolverStatus::max_iterations:
      return "max_iterations";
    case SolverStatus::numerical_error:
      return "numerical_error";
    case SolverStatus::interrupted:
      return "interrupted";
  }
  return "numerical_error";
}

EquilibriumSolver::EquilibriumSolver(const EquilibriumProblem& problem)
    : size_(problem.row_count), block_rows_(problem.block_rows) {
  const int d = block_rows_;
  const int blocks = problem.row_count / d;
  // Upper-triangle block pattern: for block column J, the block rows I <= J.
  std::vector<std::vector<int>> upper(blocks);
  for (int j = 0; j < blocks; ++j) upper[j].push_back(j);
  for (const ForceGroup& v : problem.groups) {
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      upper[std::max(a, b)].push_back(std::min(a, b));
    }
  }
  for (std::vector<int>& rows : upper) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  column_starts_.assign(problem.row_count + 1, 0);
  std::vector<int> row_indices;
  for (int j = 0; j < blocks; ++j) {
    for (int cj = 0; cj < d; ++cj) {
      for (int i : upper[j]) {
        const int last = i == j ? cj : d - 1;  // diagonal block: upper part only
        for (int ri = 0; ri <= last; ++ri) row_indices.push_back(d * i + ri);
      }
      column_starts_[d * j + cj + 1] = static_cast<int>(row_indices.size());
    }
  }
  auto rank = [&](int i, int j) {
    return static_cast<int>(std::lower_bound(upper[j].begin(), upper[j].end(), i) -
                            upper[j].begin());
  };
  slots_.resize(problem.groups.size());
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    VertexSlots& slot = slots_[k];
    if (v.row_a >= 0) slot.aa = rank(v.row_a / d, v.row_a / d);
    if (v.row_b >= 0) slot.bb = rank(v.row_b / d, v.row_b / d);
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      slot.ab_transposed = a > b;
      slot.ab = rank(std::min(a, b), std::max(a, b));
    }
  }
  if (problem.row_count > 0) {
    cholesky_ = std::make_unique<SparseCholesky>(problem.row_count, column_starts_, row_indices);
  }
}

EquilibriumSolver::~EquilibriumSolver() = default;

void EquilibriumSolver::assemble_normal_matrix(const EquilibriumProblem& problem,
                                               const std::vector<int>& first_row,
                                               const Eigen::VectorXd& scaling,
                                               std::vector<Eigen::Matrix4d>& inverse_phi) {
  const int d = block_rows_;
  const int nv = static_cast<int>(problem.groups.size());
  double* values = cholesky_->values();
  std::fill_n(values, cholesky_->nonzeros(), 0.0);
  inverse_phi.resize(nv);
  for (int k = 0; k < nv; ++k) {
    const ForceGroup& v = problem.groups[k];
    const GroupRules& rules = problem.rules_of(v);
    Matrix4 phi = rules.hessian.asDiagonal();
    for (int i = 0; i < rules.rows.rows(); ++i) {
      phi.noalias() += scaling(first_row[k] + i) * rules.rows.row(i).transpose() * rules.rows.row(i);
    }
    inverse_phi[k] = phi.llt().solve(Matrix4::Identity());
    const VertexSlots& slot = slots_[k];
    // Adds a d x d block to block column col_block at its rank-th block row.
    auto add_block = [&](int col_block, int rank, const BlockByBlock& block, bool diagonal) {
      for (int cj = 0; cj < d; ++cj) {
        double* column = values + column_starts_[d * col_block + cj] + d * rank;
        const int last = diagonal ? cj : d - 1;
        for (int ri = 0; ri <= last; ++ri) column[ri] += block(ri, cj);
      }
    };
    BlockByVertex a_phi, b_phi;
    if (v.row_a >= 0) {
      a_phi = v.on_a.topRows(d) * inverse_phi[k];
      add_block(v.row_a / d, slot.aa, a_phi * v.on_a.topRows(d).transpose(), true);
    }
    if (v.row_b >= 0) {
      b_phi = v.on_b.topRows(d) * inverse_phi[k];
      add_block(v.row_b / d, slot.bb, b_phi * v.on_b.topRows(d).transpose(), true);
    }
    if (slot.ab >= 0) {
      const BlockByBlock ab = a_phi * v.on_b.topRows(d).transpose();  // rows of a, columns of b
      if (slot.ab_transposed) add_block(v.row_a / d, slot.ab, ab.transpose(), false);
      else add_block(v.row_b / d, slot.ab, ab, false);
    }
  }
}

bool EquilibriumSolver::factorize_shifted() {
  // Near the optimum the scales of z/w spread over many orders and the
  // matrix can lose positive definiteness in rounding; a small diagonal
  // shift, raised until the factorisation succeeds, restores it, and the
  // next iterations correct the slightly perturbed step.
  if (cholesky_->factorize()) return true;
  double* values = cholesky_->values();
  std::vector<double> unshifted(values, values + cholesky_->nonzeros());
  double largest = 0.0;
  for (int col = 0; col < size_; ++col) {
    largest = std::max(largest, std::abs(values[column_starts_[col + 1] - 1]));
  }
  for (double shift = 1e-14; shift <= 1e-8; shift *= 100.0) {
    std::copy(unshifted.begin(), unshifted.end(), values);
    for (int col = 0; col < size_; ++col) values[column_starts_[col + 1] - 1] += shift * largest;
    if (cholesky_->factorize()) return true;
  }
  return false;
}

bool EquilibriumSolver::prepare_response(const EquilibriumProblem& problem,
                                         const InteriorPointSolution& solution) {
  response_ready_ = false;
  if (!cholesky_) return false;
  const std::vector<int> first_row = problem.inequality_starts();
  const int m_total = first_row.back();
  if (solution.w.size() != m_total || solution.z.size() != m_total) return false;
  // Slacks of active rows are near zero; keep the ratio finite.
  const Eigen::VectorXd scaling =
      solution.z.cwiseQuotient(solution.w.cwiseMax(std::numeric_limits<double>::min()));
  assemble_normal_matrix(problem, first_row, scaling, response_phi_);
  response_ready_ = factorize_shifted();
  return response_ready_;
}

Eigen::VectorXd EquilibriumSolver::multiplier_response(const Eigen::VectorXd& delta_rhs) const {
  if (!response_ready_) throw std::logic_error("multiplier_response before prepare_response");
  return cholesky_->solve(delta_rhs);
}

Eigen::Vector4d EquilibriumSolver::group_response(const EquilibriumProblem& problem, int group,
                                                  const Eigen::VectorXd& multipliers) const {
  return response_phi_[group] * problem.reaction(problem.groups[group], multipliers);
}

InteriorPointInfo EquilibriumSolver::solve(const EquilibriumProblem& problem,
                                           const InteriorPointSettings& settings,
                                           InteriorPointSolution& solution, bool warm_start) {
  InteriorPointInfo info;
  const int nv = static_cast<int>(problem.groups.size());
  const Eigen::VectorXd& b = problem.rhs;
  // Each group's inequality rows start at first_row[k] in w and z; `lower`
  // holds their constant sides (G x_k >= lower).
  const std::vector<int> first_row = problem.inequality_starts();
  const int m_total = first_row[nv];
  Eigen::VectorXd lower(m_total);
  for (int k = 0; k < nv; ++k) {
    lower.segment(first_row[k], first_row[k + 1] - first_row[k]) =
        problem.lower_bounds(problem.groups[k]);
  }
  auto rows_of = [&](int k) -> const RowsMatrix& { return problem.rules_of(problem.groups[k]).rows; };
  auto ineq = [&](Eigen::VectorXd& v, int k) {
    return v.segment(first_row[k], first_row[k + 1] - first_row[k]);
  };

  Eigen::VectorXd& x = solution.x;
  Eigen::VectorXd& y = solution.y;
  Eigen::VectorXd& w = solution.w;
  Eigen::VectorXd& z = solution.z;
  const bool sizes_match = x.size() == 4 * nv && y.size() == size_ && w.size() == m_total &&
                           z.size() == m_total;
  if (warm_start && sizes_match) {
    // Interior-point iterates must start strictly inside the cone.
    constexpr double kMargin = 1e-2;
    for (int k = 0; k < nv; ++k) {
      ineq(w, k) = (rows_of(k) * x.segment<4>(4 * k) - ineq(lower, k)).cwiseMax(kMargin);
    }
    z = z.cwiseMax(kMargin);
  } else {
    x = Eigen::VectorXd::Zero(4 * nv);
    y = Eigen::VectorXd::Zero(size_);
    w = Eigen::VectorXd::Ones(m_total);
    z = Eigen::VectorXd::Ones(m_total);
  }
  if (nv == 0 && size_ == 0) {
    info.status = SolverStatus::converged;
    return info;
  }
  if (!cholesky_) {
    info.status = SolverStatus::numerical_error;
    return info;
  }

  const double rhs_scale = 1.0 + (b.size() ? b.lpNorm<Eigen::Infinity>() : 0.0);
  double largest_linear = 0.0;
  for (const GroupRules& rules : problem.rules) {
    largest_linear = std::max(largest_linear, rules.linear.lpNorm<Eigen::Infinity>());
  }
  const double dual_scale = 1.0 + largest_linear;

  Eigen::VectorXd r_p(size_), r_d(4 * nv), r_g(m_total), r_c(m_total);
  std::vector<Matrix4> inverse_phi(nv);
  Eigen::VectorXd dx(4 * nv), dy(size_), dw(m_total), dz(m_total);
  Eigen::VectorXd dx_aff, dw_aff, dz_aff, rhs(size_);
  const int factorizations_before = cholesky_->factorizations();


  // Solves the Newton system for complementarity residual r_c (uses the
  // current factorisation and inverse_phi); fills dx, dy, dw, dz.
  auto newton_direction = [&](const Eigen::VectorXd& complementarity) {
    const auto start = Clock::now();
    // Per inequality row: (r_c + D r_g) / w, combined below as G^T (...).
    Eigen::VectorXd row_terms = (complementarity + z.cwiseProduct(r_g)).cwiseQuotient(w);
    rhs = -r_p;
    for (int k = 0; k < nv; ++k) {
      const ForceGroup& v = problem.groups[k];
      const Vector4 reduced = -r_d.segment<4>(4 * k) - rows_of(k).transpose() * ineq(row_terms, k);
      const Vector4 t = inverse_phi[k] * reduced;
      dx.segment<4>(4 * k) = t;  // completed below with the A^T dy part
      problem.add_effect(v, -t, rhs);
    }
    dy = cholesky_->solve(rhs);
    for (int k = 0; k < nv; ++k) {
      dx.segment<4>(4 * k) += inverse_phi[k] * problem.reaction(problem.groups[k], dy);
      ineq(dw, k) = rows_of(k) * dx.segment<4>(4 * k) + ineq(r_g, k);
    }
    dz = -(complementarity + z.cwiseProduct(dw)).cwiseQuotient(w);
    info.solve_seconds += seconds_since(start);
  };

  auto objective_value = [&] {
    double sum = 0.0;
    for (int k = 0; k < nv; ++k) {
      const GroupRules& rules = problem.rules_of(problem.groups[k]);
      const Vector4 xk = x.segment<4>(4 * k);
      sum += 0.5 * xk.dot(rules.hessian.cwiseProduct(xk)) + rules.linear.dot(xk);
    }
    return sum;
  };

  // The most accurate iterate so far: when rounding stops the iterations
  // short of the tolerance (active constraints whose slacks fall to 1e-12),
  // it is the answer, reported as inaccurate.
  struct Iterate {
    double error = std::numeric_limits<double>::infinity();
    int iteration = 0;
    Eigen::VectorXd x, y, w, z;
    InteriorPointInfo info;
  } best;

  for (int iteration = 0;; ++iteration) {
    auto start = Clock::now();
    // Residuals.
    r_p = -b;
    for (int k = 0; k < nv; ++k) {
      const ForceGroup& v = problem.groups[k];
      const GroupRules& rules = problem.rules_of(v);
      const Vector4 xk = x.segment<4>(4 * k);
      problem.add_effect(v, xk, r_p);
      r_d.segment<4>(4 * k) = rules.hessian.cwiseProduct(xk) + rules.linear -
                              problem.reaction(v, y) - rules.rows.transpose() * ineq(z, k);
      ineq(r_g, k) = rules.rows * xk - ineq(lower, k) - ineq(w, k);
    }
    // The total gap, not its mean, bounds the objective's error.
    const double duality_gap = w.dot(z);
    const double mu = m_total > 0 ? duality_gap / m_total : 0.0;
    info.iterations = iteration;
    info.primal_residual = std::max(r_p.size() ? r_p.lpNorm<Eigen::Infinity>() : 0.0,
                                    r_g.size() ? r_g.lpNorm<Eigen::Infinity>() : 0.0);
    info.dual_residual = r_d.size() ? r_d.lpNorm<Eigen::Infinity>() : 0.0;
    info.complementarity = mu;
    if (!std::isfinite(mu) || !std::isfinite(info.primal_residual) ||
        !std::isfinite(info.dual_residual)) {
      info.status = SolverStatus::numerical_error;
      break;
    }
    const double error = std::max({info.primal_residual / rhs_scale,
                                   info.dual_residual / dual_scale,
                                   duality_gap / (1.0 + std::abs(objective_value()))});
    if (error <= settings.tolerance) {
      info.status = SolverStatus::converged;
      break;
    }
    if (error < best.error) best = {error, iteration, x, y, w, z, info};
    const int stalled = iteration - best.iteration;
    if ((best.error <= settings.inaccurate_tolerance && stalled > kStallIterations) ||
        stalled > kHopelessIterations) {
      info.status = SolverStatus::max_iterations;
      break;
    }
    if (iteration >= settings.max_iterations) {
      info.status = SolverStatus::max_iterations;
      break;
    }
    if (stop_requested()) {
      info.status = SolverStatus::interrupted;
      break;
    }

    // Eliminate each vertex's unknowns and assemble the normal matrix.
    assemble_normal_matrix(problem, first_row, z.cwiseQuotient(w), inverse_phi);
    info.assembly_seconds += seconds_since(start);
    start = Clock::now();
    const bool factored = factorize_shifted();
    info.factorization_seconds += seconds_since(start);
    if (!factored) {
      info.status = SolverStatus::numerical_error;
      break;
    }

    // Predictor: the affine-scaling direction.
    r_c = w.cwiseProduct(z);
    newton_direction(r_c);
    const double affine_step = std::min(step_to_boundary(w, dw), step_to_boundary(z, dz));
    const double mu_affine =
        (w + affine_step * dw).dot(z + affine_step * dz) / static_cast<double>(m_total);
    const double centering = std::pow(mu_affine / mu, 3);
    dw_aff = dw;
    dz_aff = dz;
    // Corrector: second-order term and centring, same factorisation.
    r_c = w.cwiseProduct(z) + dw_aff.cwiseProduct(dz_aff) -
          Eigen::VectorXd::Constant(m_total, centering * mu);
    newton_direction(r_c);
    const double step =
        std::min(1.0, settings.step_fraction *
                          std::min(step_to_boundary(w, dw), step_to_boundary(z, dz)));
    if (!(step > 1e-12)) {
      info.status = SolverStatus::numerical_error;
      break;
    }
    x += step * dx;
    y += step * dy;
    w += step * dw;
    z += step * dz;
  }
  // Short of convergence the most accurate iterate is the answer: within
  // the inaccurate tolerance it says so, else the status stays.
  if (info.status != SolverStatus::converged && std::isfinite(best.error)) {
    const int iterations = info.iterations;
    const SolverStatus status = info.status;
    info = best.info;
    info.iterations = iterations;
    info.status = best.error <= settings.inaccurate_tolerance ? SolverStatus::inaccurate : status;
    x = std::move(best.x);
    y = std::move(best.y);
    w = std::move(best.w);
    z = std::move(best.z);
  }
  info.factorizations = cholesky_->factorizations() - factorizations_before;
  info.objective = objective_value();
  return info;
}

}  // namespace ashlar
