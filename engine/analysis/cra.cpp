#include "analysis/cra.hpp"

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "analysis/equilibrium_analysis.hpp"
#include "core/blas.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/text.hpp"

namespace ashlar {

namespace {

using Ipopt::Index;
using Ipopt::Number;

// Where a contact vertex's unknowns sit among its stride of IPOPT's
// variables: f_n (cra_penalty: f+, then f-), f_u, f_v, d_n, d_u, d_v, alpha.
struct VertexLayout {
  explicit VertexLayout(bool penalty) : penalty(penalty) {
    const int p = penalty ? 1 : 0;
    tension = penalty ? 1 : -1;
    fu = 1 + p;
    fv = 2 + p;
    dn = 3 + p;
    du = 4 + p;
    dv = 5 + p;
    alpha = 6 + p;
    stride = 7 + p;
  }
  bool penalty;
  int normal = 0, tension, fu, fv, dn, du, dv, alpha, stride;
  // The variable of the group column c of (c, s, f_u, f_v), -1 for none.
  int of_column(int c) const { return c == 0 ? normal : c == 1 ? tension : c == 2 ? fu : fv; }
};

// One Jacobian entry: value = constant + x[variable] (no variable: -1).
// Linear rows have constants only; the bilinear rows' entries are the
// other factor of their product.
struct JacobianEntry {
  Index row, column;
  int variable;
  double constant;
};

// The CRA program (cra.hpp) as IPOPT's TNLP, over the equilibrium QP's
// contact vertices and balance rows. Built once; IPOPT calls back.
class CraProgram : public Ipopt::TNLP {
public:
  // start: the equilibrium method's forces (4 per group, scaled: c, s,
  // f_u, f_v) to start from, or empty.
  CraProgram(const EquilibriumProblem& problem, const EquilibriumOptions& options, const CraSettings& settings,
             bool penalty, Eigen::VectorXd start)
      : problem_(problem), settings_(settings), layout_(penalty), friction_(friction_rows(options)),
        start_(std::move(start)) {
    vertices_ = problem.contact_vertex_count;
    rows_ = problem.block_rows;
    q_start_ = layout_.stride * vertices_;
    variables_ = q_start_ + problem.row_count;
    per_vertex_rows_ = 3 + static_cast<int>(friction_.rows()) + 1 + 2 + (penalty ? 1 : 0);
    constraints_ = problem.row_count + per_vertex_rows_ * vertices_;
    build_jacobian();
  }

  int variable_count() const { return variables_; }
  const std::vector<double>& x() const { return x_; }
  int iterations() const { return iterations_; }
  bool interrupted() const { return interrupted_; }
  double objective() const { return objective_; }
  int q_start() const { return q_start_; }
  const VertexLayout& layout() const { return layout_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = variables_;
    m = constraints_;
    nnz_jac_g = static_cast<Index>(jacobian_.size());
    nnz_h_lag = hessian_per_vertex() * vertices_;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    const double inf = 2e19;  // beyond IPOPT's nlp_upper_bound_inf: no bound
    std::fill(x_l, x_l + n, -inf);
    std::fill(x_u, x_u + n, inf);
    const double bound = settings_.displacement_bound, eps = settings_.overlap;
    for (int k = 0; k < vertices_; ++k) {
      Number* lo = x_l + layout_.stride * k;
      Number* hi = x_u + layout_.stride * k;
      lo[layout_.normal] = 0.0;
      if (layout_.penalty) lo[layout_.tension] = 0.0;
      lo[layout_.dn] = -eps;  // no penetration beyond the overlap
      hi[layout_.dn] = bound;
      lo[layout_.du] = lo[layout_.dv] = -bound;
      hi[layout_.du] = hi[layout_.dv] = bound;
      lo[layout_.alpha] = 0.0;
    }
    std::fill(g_l, g_l + m, 0.0);
    std::fill(g_u, g_u + m, 0.0);
    for (int r = 0; r < problem_.row_count; ++r) g_l[r] = g_u[r] = problem_.rhs(r);
    for (int k = 0; k < vertices_; ++k) {
      const int first = problem_.row_count + per_vertex_rows_ * k + 3;
      for (Eigen::Index i = 0; i < friction_.rows(); ++i) g_u[first + i] = inf;
      // The complementarity products of factors bounded below by 0 as
      // "<= 0", which is the same set: one-sided, IPOPT gives them a slack
      // instead of an equality that is degenerate wherever a factor sits
      // at its bound (with "= 0" the penalty form failed on a column of
      // three blocks at tolerance 1e-8).
      const int products = first + static_cast<int>(friction_.rows());
      g_l[products] = -inf;
      // cra only: the penalty form diverged with it (H.json, A.json).
      if (!layout_.penalty) g_u[products] = settings_.complementarity * settings_.overlap;
      if (layout_.penalty) g_l[products + 3] = -inf;
    }
    return true;
  }

  // Variables and rows in their own units: displacements (d, q) and the
  // rows they fill (compatibility, f_n (d_n + eps)) in d_bnd, alpha (a
  // force per displacement) in 1 / d_bnd, so that every scaled unknown and
  // residual is O(1) and the fraction-to-the-boundary rule does not cut
  // steps in d, whose range is 2 d_bnd, to a thousandth.
  bool get_scaling_parameters(Number& objective_scaling, bool& use_x_scaling, Index n, Number* x_scaling,
                              bool& use_g_scaling, Index m, Number* g_scaling) override {
    const double bound = settings_.displacement_bound;
    // alpha is a force per displacement, O(1 / d_bnd) wherever friction
    // acts, so alpha^2 (and with the penalty w f-^2) outweigh f_n^2 by
    // 1 / d_bnd^2 (w): unscaled, the objective's gradient is O(1e3-1e6)
    // and IPOPT's dual infeasibility (an absolute test) could not reach its
    // tolerance (a dome of 288 voussoirs stalled at 1e0, 1e6 times tol;
    // cra_penalty on compas_cra's A.json diverged to "infeasible").
    objective_scaling = bound * bound;
    if (layout_.penalty) objective_scaling = std::min(objective_scaling, 1.0 / settings_.tension_weight);
    use_x_scaling = use_g_scaling = true;
    std::fill(x_scaling, x_scaling + n, 1.0);
    std::fill(g_scaling, g_scaling + m, 1.0);
    for (int k = 0; k < vertices_; ++k) {
      Number* v = x_scaling + layout_.stride * k;
      v[layout_.dn] = v[layout_.du] = v[layout_.dv] = 1.0 / bound;
      v[layout_.alpha] = bound;
      Number* r = g_scaling + problem_.row_count + per_vertex_rows_ * k;
      r[0] = r[1] = r[2] = 1.0 / bound;
      r[3 + friction_.rows()] = 1.0 / bound;
    }
    std::fill(x_scaling + q_start_, x_scaling + n, 1.0 / bound);
    return true;
  }

  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    // cra: the equilibrium method's forces (balanced, within the friction
    // rows) when it gave an answer, else (as compas_cra's cra) one mean
    // weight each; blocks at rest. cra_penalty: one mean weight each
    // (analyze_cra says why it takes no warm start). compas_cra starts its
    // penalty form at zero forces, where both products f+ f- and
    // f+ (d_n + eps) have zero gradients; from there IPOPT's restoration
    // failed on a block past its support's edge.
    std::fill(x, x + n, 0.0);
    const bool warm = start_.size() == 4 * static_cast<Eigen::Index>(vertices_);
    for (int k = 0; k < vertices_; ++k) {
      Number* v = x + layout_.stride * k;
      if (!warm) {
        v[layout_.normal] = v[layout_.fu] = v[layout_.fv] = 1.0;
        continue;
      }
      const double normal = start_(4 * k) - start_(4 * k + 1);
      v[layout_.normal] = std::max(normal, 0.0);
      v[layout_.fu] = start_(4 * k + 2);
      v[layout_.fv] = start_(4 * k + 3);
      // alpha = 0 with d = 0 zeroes the alignment rows' derivatives in
      // both: their only Newton step would cancel all friction at once.
      v[layout_.alpha] = 1.0 / settings_.displacement_bound;
    }
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& value) override {
    value = 0.0;
    for (int k = 0; k < vertices_; ++k) {
      const Number* v = x + layout_.stride * k;
      value += v[layout_.normal] * v[layout_.normal] + v[layout_.alpha] * v[layout_.alpha];
      if (layout_.penalty) value += settings_.tension_weight * v[layout_.tension] * v[layout_.tension];
    }
    return true;
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad) override {
    std::fill(grad, grad + n, 0.0);
    for (int k = 0; k < vertices_; ++k) {
      const int at = layout_.stride * k;
      grad[at + layout_.normal] = 2.0 * x[at + layout_.normal];
      grad[at + layout_.alpha] = 2.0 * x[at + layout_.alpha];
      if (layout_.penalty) grad[at + layout_.tension] = 2.0 * settings_.tension_weight * x[at + layout_.tension];
    }
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    std::fill(g, g + m, 0.0);
    // The linear rows (balance, compatibility, friction) from the Jacobian's
    // constant entries; the bilinear ones directly.
    for (const JacobianEntry& e : jacobian_) {
      if (e.variable == -1) g[e.row] += e.constant * x[e.column];
    }
    const double eps = settings_.overlap;
    for (int k = 0; k < vertices_; ++k) {
      const Number* v = x + layout_.stride * k;
      Number* r = g + problem_.row_count + per_vertex_rows_ * k + 3 + friction_.rows();
      r[0] = v[layout_.normal] * (v[layout_.dn] + eps);
      r[1] = v[layout_.fu] + v[layout_.alpha] * v[layout_.du];
      r[2] = v[layout_.fv] + v[layout_.alpha] * v[layout_.dv];
      if (layout_.penalty) r[3] = v[layout_.normal] * v[layout_.tension];
    }
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* rows, Index* columns, Number* values) override {
    if (!values) {
      for (size_t i = 0; i < jacobian_.size(); ++i) {
        rows[i] = jacobian_[i].row;
        columns[i] = jacobian_[i].column;
      }
      return true;
    }
    for (size_t i = 0; i < jacobian_.size(); ++i) {
      const JacobianEntry& e = jacobian_[i];
      values[i] = e.constant + (e.variable >= 0 ? x[e.variable] : 0.0);
    }
    return true;
  }

  // Per vertex, lower triangle (row >= column, as the layout orders them):
  // (f_n, f_n), (alpha, alpha) from the objective; (d_n, f_n) from the
  // complementarity; (alpha, d_u), (alpha, d_v) from the alignment; with
  // the penalty (f-, f-) and (f-, f+).
  int hessian_per_vertex() const { return layout_.penalty ? 7 : 5; }

  bool eval_h(Index, const Number*, bool, Number sigma, Index, const Number* lambda, bool, Index, Index* rows,
              Index* columns, Number* values) override {
    const int h = hessian_per_vertex();
    for (int k = 0; k < vertices_; ++k) {
      const int at = layout_.stride * k;
      if (!values) {
        Index* r = rows + h * k;
        Index* c = columns + h * k;
        r[0] = c[0] = at + layout_.normal;
        r[1] = c[1] = at + layout_.alpha;
        r[2] = at + layout_.dn, c[2] = at + layout_.normal;
        r[3] = at + layout_.alpha, c[3] = at + layout_.du;
        r[4] = at + layout_.alpha, c[4] = at + layout_.dv;
        if (layout_.penalty) {
          r[5] = c[5] = at + layout_.tension;
          r[6] = at + layout_.tension, c[6] = at + layout_.normal;
        }
        continue;
      }
      const Number* l = lambda + problem_.row_count + per_vertex_rows_ * k + 3 + friction_.rows();
      Number* v = values + h * k;
      v[0] = 2.0 * sigma;
      v[1] = 2.0 * sigma;
      v[2] = l[0];
      v[3] = l[1];
      v[4] = l[2];
      if (layout_.penalty) {
        v[5] = 2.0 * sigma * settings_.tension_weight;
        v[6] = l[3];
      }
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number objective, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    x_.assign(x, x + n);
    objective_ = objective;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index iteration, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = iteration;
    // Ctrl-C or a sandbox deadline: IPOPT stops with User_Requested_Stop.
    if (stop_requested()) interrupted_ = true;
    return !interrupted_;
  }

private:
  // The Jacobian's pattern and constant values, row by row: balance rows
  // (the QP's group effects), then per vertex its compatibility rows
  // (d - A_k^T q = 0: the transpose of the same effects, so that the
  // virtual work of the forces is the forces times d), friction rows,
  // complementarity, alignment and (cra_penalty) f+ f- = 0.
  void build_jacobian() {
    const int stride = layout_.stride;
    const int columns = layout_.penalty ? 4 : 3;
    const int force_columns[4] = {0, 2, 3, 1};  // group columns used: c, f_u, f_v, then s
    // Balance: every group's effect on its blocks' rows, nonzeros only.
    for (int k = 0; k < vertices_; ++k) {
      const ForceGroup& g = problem_.groups[k];
      const Eigen::Matrix<double, 6, 4> on_a = g.on_a(rows_);
      for (const auto& [first, effect] : {std::pair{g.row_a, &on_a}, std::pair{g.row_b, &g.on_b}}) {
        if (first < 0) continue;
        for (int r = 0; r < rows_; ++r) {
          for (int j = 0; j < columns; ++j) {
            const int c = force_columns[j];
            const double value = (*effect)(r, c);
            if (value != 0.0) jacobian_.push_back({first + r, stride * k + layout_.of_column(c), -1, value});
          }
        }
      }
    }
    const double eps = settings_.overlap;
    for (int k = 0; k < vertices_; ++k) {
      const ForceGroup& g = problem_.groups[k];
      const Eigen::Matrix<double, 6, 4> on_a = g.on_a(rows_);
      const int at = stride * k;
      const Index row = problem_.row_count + per_vertex_rows_ * k;
      // d_n, d_u, d_v pair with the group columns c, f_u, f_v.
      const int displacement[3] = {layout_.dn, layout_.du, layout_.dv};
      const int pairs_with[3] = {0, 2, 3};
      for (int j = 0; j < 3; ++j) {
        jacobian_.push_back({row + j, at + displacement[j], -1, 1.0});
        for (const auto& [first, effect] : {std::pair{g.row_a, &on_a}, std::pair{g.row_b, &g.on_b}}) {
          if (first < 0) continue;
          for (int r = 0; r < rows_; ++r) {
            const double value = (*effect)(r, pairs_with[j]);
            if (value != 0.0) jacobian_.push_back({row + j, q_start_ + first + r, -1, -value});
          }
        }
      }
      // Friction rows over (f_n or f+, f_u, f_v).
      const int friction_variables[3] = {layout_.normal, layout_.fu, layout_.fv};
      for (Eigen::Index i = 0; i < friction_.rows(); ++i) {
        for (int j = 0; j < 3; ++j) {
          if (friction_(i, j) != 0.0) {
            jacobian_.push_back({row + 3 + static_cast<Index>(i), at + friction_variables[j], -1, friction_(i, j)});
          }
        }
      }
      const Index bilinear = row + 3 + static_cast<Index>(friction_.rows());
      // f_n (d_n + eps): d/df_n = d_n + eps, d/dd_n = f_n.
      jacobian_.push_back({bilinear, at + layout_.normal, at + layout_.dn, eps});
      jacobian_.push_back({bilinear, at + layout_.dn, at + layout_.normal, 0.0});
      // f_u + alpha d_u and f_v + alpha d_v.
      jacobian_.push_back({bilinear + 1, at + layout_.fu, -2, 1.0});
      jacobian_.push_back({bilinear + 1, at + layout_.alpha, at + layout_.du, 0.0});
      jacobian_.push_back({bilinear + 1, at + layout_.du, at + layout_.alpha, 0.0});
      jacobian_.push_back({bilinear + 2, at + layout_.fv, -2, 1.0});
      jacobian_.push_back({bilinear + 2, at + layout_.alpha, at + layout_.dv, 0.0});
      jacobian_.push_back({bilinear + 2, at + layout_.dv, at + layout_.alpha, 0.0});
      if (layout_.penalty) {
        jacobian_.push_back({bilinear + 3, at + layout_.normal, at + layout_.tension, 0.0});
        jacobian_.push_back({bilinear + 3, at + layout_.tension, at + layout_.normal, 0.0});
      }
    }
  }

  const EquilibriumProblem& problem_;
  CraSettings settings_;
  VertexLayout layout_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> friction_;
  Eigen::VectorXd start_;
  int vertices_ = 0, rows_ = 6, q_start_ = 0, variables_ = 0, per_vertex_rows_ = 0, constraints_ = 0;
  // variable -2: a constant entry of a nonlinear row (eval_g computes those
  // rows whole, so it must not add it as a linear term).
  std::vector<JacobianEntry> jacobian_;
  std::vector<double> x_;
  double objective_ = 0.0;
  int iterations_ = 0;
  bool interrupted_ = false;
};

SolverStatus status_of(Ipopt::ApplicationReturnStatus status, bool interrupted) {
  if (interrupted) return SolverStatus::interrupted;
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return SolverStatus::converged;
    case Ipopt::Solved_To_Acceptable_Level:
    case Ipopt::Feasible_Point_Found:
      return SolverStatus::inaccurate;
    case Ipopt::Infeasible_Problem_Detected:
      return SolverStatus::infeasible;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded:
      return SolverStatus::max_iterations;
    case Ipopt::User_Requested_Stop:
      return SolverStatus::interrupted;
    default:  // too small a step, diverging, restoration failed, ...: no answer to use
      return SolverStatus::numerical_error;
  }
}

}  // namespace

void check_cra_settings(const CraSettings& settings) {
  if (!(settings.overlap >= 0.0) || !std::isfinite(settings.overlap)) {
    throw InvalidArgument("overlap must be a finite number >= 0, got " + shortest_number(settings.overlap));
  }
  if (!(settings.displacement_bound > settings.overlap) || !std::isfinite(settings.displacement_bound)) {
    throw InvalidArgument("displacement_bound must be a finite number > overlap (" +
                          shortest_number(settings.overlap) + "), got " +
                          shortest_number(settings.displacement_bound));
  }
  if (!(settings.complementarity >= 0.0) || !std::isfinite(settings.complementarity)) {
    throw InvalidArgument("complementarity must be a finite number >= 0, got " +
                          shortest_number(settings.complementarity));
  }
  if (!(settings.tension_weight > 0.0) || !std::isfinite(settings.tension_weight)) {
    throw InvalidArgument("tension_weight must be a finite number > 0, got " +
                          shortest_number(settings.tension_weight));
  }
  if (!(settings.tolerance > 0.0) || !std::isfinite(settings.tolerance)) {
    throw InvalidArgument("tolerance must be a finite number > 0, got " + shortest_number(settings.tolerance));
  }
  if (settings.max_iterations < 1) {
    throw InvalidArgument("max_iterations must be at least 1, got " + std::to_string(settings.max_iterations));
  }
}

EquilibriumResult analyze_cra(const Structure& structure, const AnalysisSettings& settings) {
  const auto start = Clock::now();
  if (!is_cra(settings.method)) {
    throw InvalidArgument(std::string("analyze_cra: method must be cra or cra_penalty, got ") +
                          kAnalysisMethodNames.name(settings.method));
  }
  check_cra_settings(settings.cra);
  if (!(settings.stable_tolerance > 0.0) || !std::isfinite(settings.stable_tolerance)) {
    throw InvalidArgument("stable_tolerance must be a finite number > 0, got " +
                          shortest_number(settings.stable_tolerance));
  }
  if (!structure.cables().empty()) {
    throw InvalidArgument(std::string("method ") + kAnalysisMethodNames.name(settings.method) +
                          " analyses contacts only; this structure has " + std::to_string(structure.cables().size()) +
                          " cables (use method = \"equilibrium\")");
  }
  const bool penalty = settings.method == AnalysisMethod::cra_penalty;
  EquilibriumOptions options = settings.problem;
  options.friction_law = FrictionLaw::coulomb;
  const EquilibriumProblem problem = build_equilibrium_problem(structure, options);
  const double setup_seconds = seconds_since(start);

  EquilibriumResult result;
  result.method = settings.method;
  result.timings.setup = setup_seconds;
  result.floating_blocks = problem.floating_blocks;
  const int vertices = problem.contact_vertex_count;
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(4 * static_cast<Eigen::Index>(problem.groups.size()));
  Eigen::VectorXd q = Eigen::VectorXd::Zero(problem.row_count);
  if (problem.row_count == 0) {
    result.status = SolverStatus::converged;  // nothing to balance
  } else {
    // The penalty form starts cold. From the equilibrium method's forces
    // (an unstable structure's: friction at its limit, tension spread over
    // every vertex) IPOPT's restoration stalled, under some BLAS kernels
    // and not others, at a point where every vertex carried both f+ and f-
    // (f+ f- = 0.023 left on all four vertices of a block sliding off an
    // incline): a local minimum of the infeasibility, reported as
    // infeasible, that only turning some vertices to pure tension leaves.
    // From one mean weight each it took 35 iterations there under
    // OpenBLAS's Prescott, Haswell and SkylakeX kernels alike.
    Eigen::VectorXd start;
    if (!penalty) {
      AnalysisSettings equilibrium = settings;
      equilibrium.method = AnalysisMethod::equilibrium;
      equilibrium.problem = options;
      EquilibriumAnalysis analysis(structure, equilibrium);
      const EquilibriumResult first = analysis.solve();
      if (!has_no_answer(first.status) && analysis.solution().x.size() >= 4 * vertices) {
        start = analysis.solution().x.head(4 * vertices);
      }
    }
    // MUMPS's dense kernels are OpenBLAS's: the engine's process-wide
    // setting (one thread, the CPU's kernels) before IPOPT's first
    // factorisation, as before the engine's own; the penalty form, with no
    // equilibrium solve first, would otherwise run on OpenBLAS's defaults.
    set_up_blas_in_whole_process();
    Ipopt::SmartPtr<CraProgram> program = new CraProgram(problem, options, settings.cra, penalty, std::move(start));
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetIntegerValue("print_level", settings.cra.verbose ? 5 : 0);
    app->Options()->SetStringValue("sb", "yes");  // no banner
    app->Options()->SetNumericValue("tol", settings.cra.tolerance);
    app->Options()->SetNumericValue("constr_viol_tol", settings.cra.tolerance);
    app->Options()->SetNumericValue("compl_inf_tol", settings.cra.tolerance);
    app->Options()->SetNumericValue("acceptable_tol", 100.0 * settings.cra.tolerance);
    app->Options()->SetNumericValue("acceptable_constr_viol_tol", 100.0 * settings.cra.tolerance);
    app->Options()->SetNumericValue("acceptable_compl_inf_tol", 100.0 * settings.cra.tolerance);
    app->Options()->SetIntegerValue("max_iter", settings.cra.max_iterations);
    // The adaptive barrier update: with the monotone one the penalty form
    // failed (restoration) on a block past its support's edge.
    app->Options()->SetStringValue("mu_strategy", "adaptive");
    app->Options()->SetStringValue("nlp_scaling_method", "user-scaling");
    // The ordering of MUMPS's indefinite factorisations. "cra": approximate
    // minimum degree, with which the Armadillo vault's iterates are the
    // same run after run (231 iterations every run): with
    // METIS (5) or AMF (2) its iterates parted in the eighth digit after
    // about 20 iterations, and runs took 226-393 iterations and 98-530 s;
    // MUMPS's default (QAMD) gave fronts whose dense factorisation took
    // 2-20 s per iteration. "cra_penalty", whose f+ f- = 0 rows make every
    // step degenerate: PORD, MUMPS's own nested dissection, with which
    // compas_cra's A converges (292 iterations, the same every run) where
    // AMD and QAMD end in a numerical error after 224. METIS, with which it
    // also converges, would bypass core/cholmod_system's guard (one call at
    // a time, SIGTERM kept).
    app->Options()->SetIntegerValue("mumps_pivot_order", penalty ? 4 : 0);
    app->Options()->SetIntegerValue("mumps_mem_percent", kMumpsWorkspacePercent);  // why: core/blas.hpp
    // No options file: an ipopt.opt in the working directory would change the answer unseen.
    if (app->Initialize("") != Ipopt::Solve_Succeeded) {
      throw std::runtime_error("IPOPT failed to initialise");
    }
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(program);
    result.status = status_of(status, program->interrupted());
    result.iterations = program->iterations();
    result.objective = program->objective();
    const std::vector<double>& x = program->x();
    if (static_cast<int>(x.size()) == program->variable_count()) {
      const VertexLayout& layout = program->layout();
      for (int k = 0; k < vertices; ++k) {
        const double* v = x.data() + layout.stride * k;
        forces.segment<4>(4 * k) << v[layout.normal], layout.penalty ? v[layout.tension] : 0.0, v[layout.fu],
            v[layout.fv];
      }
      q = Eigen::Map<const Eigen::VectorXd>(x.data() + program->q_start(), problem.row_count);
    } else if (!has_no_answer(result.status)) {
      result.status = SolverStatus::numerical_error;  // IPOPT gave no point at all
    }
  }

  const std::vector<Interface>& interfaces = *problem.interfaces;
  const bool answer = !has_no_answer(result.status) && result.status != SolverStatus::infeasible &&
                      result.status != SolverStatus::max_iterations;
  if (answer) {
    fill_result_forces(structure, problem, forces, result);
    // The displacements: q's translations are in L, rotations in radians,
    // in the balance rows' order.
    const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
    result.displacements.assign(structure.size(), BlockDisplacement{});
    for (int b = 0; b < structure.size(); ++b) {
      const int first = problem.row_of_block[b];
      if (first < 0) continue;
      for (int j = 0; j < problem.block_rows; ++j) {
        if (rows[j] < 3) result.displacements[b].translation(rows[j]) = q(first + j) * problem.length_unit;
        else result.displacements[b].rotation(rows[j] - 3) = q(first + j);
      }
    }
  } else {
    // The interfaces still, so that results line up with the structure.
    result.interfaces.resize(interfaces.size());
    for (size_t i = 0; i < interfaces.size(); ++i) {
      result.interfaces[i].a = interfaces[i].a;
      result.interfaces[i].b = interfaces[i].b;
      result.interfaces[i].center_of_pressure = interfaces[i].center;
    }
    result.block_tension.assign(structure.size(), 0.0);
    result.virtual_torques.assign(structure.size(), Vec3::Zero());
  }
  const bool floating = problem.has_floating_bodies();
  const bool solved = result.status == SolverStatus::converged || result.status == SolverStatus::inaccurate;
  result.imbalance_without_tension =
      answer ? compression_only_imbalance(problem, forces) : std::numeric_limits<double>::infinity();
  result.stable = solved && !floating && result.imbalance_without_tension <= settings.stable_tolerance;
  result.borderline = solved && !floating &&
                      result.imbalance_without_tension > settings.stable_tolerance * kBorderlineBelow &&
                      result.imbalance_without_tension <= settings.stable_tolerance * kBorderlineAbove;
  const int bodies = std::max(problem.body_count, 1);
  if (result.stable) {
    result.infeasibility = 0.0;
  } else if (!solved || floating) {
    result.infeasibility = std::numeric_limits<double>::infinity();
  } else if (penalty) {
    double tension = 0.0;
    for (int k = 0; k < vertices; ++k) tension += std::max(forces(4 * k + 1), 0.0);
    result.infeasibility = tension / bodies;  // scaled: over the total weight
  } else {
    result.infeasibility = result.imbalance_without_tension;
  }
  result.penalty = solved ? result.objective / bodies : std::numeric_limits<double>::infinity();
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace ashlar
