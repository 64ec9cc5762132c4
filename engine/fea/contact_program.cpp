#include "fea/contact_program.hpp"

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>
#include <algorithm>
#include <stdexcept>

#include "core/blas.hpp"
#include "core/interrupt.hpp"

namespace ashlar {

namespace {

using Ipopt::Index;
using Ipopt::Number;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// In scaled units: x = u / displacement_scale, the objective divided by
// force_scale x displacement_scale, the rows by displacement_scale. Then
// the row multipliers are forces / force_scale.
class ContactProgram : public Ipopt::TNLP {
public:
  ContactProgram(const SparseMatrix& stiffness, const Eigen::VectorXd& loads, const std::vector<ContactRow>& rows,
                 double bound, double displacement_scale, double force_scale, const Eigen::VectorXd& start)
      : stiffness_(stiffness), loads_(loads), rows_(rows), bound_(bound / displacement_scale),
        stiffness_factor_(displacement_scale / force_scale), force_scale_(force_scale),
        displacement_scale_(displacement_scale), start_(start / displacement_scale) {}

  const ContactProgramResult& result() const { return result_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = static_cast<Index>(loads_.size());
    m = 3 * static_cast<Index>(rows_.size());
    nnz_jac_g = 0;
    for (const ContactRow& row : rows_) nnz_jac_g += 9 * static_cast<Index>(row.nodes.size());
    nnz_h_lag = static_cast<Index>(stiffness_.nonZeros());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    std::fill(x_l, x_l + n, -bound_);
    std::fill(x_u, x_u + n, bound_);
    std::fill(g_l, g_l + m, 0.0);
    std::fill(g_u, g_u + m, 0.0);
    for (Index k = 2; k < m; k += 3) g_u[k] = 2e19;  // the opening: >= 0, no upper bound
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index i = 0; i < n; ++i) x[i] = std::clamp(start_[i], -0.5 * bound_, 0.5 * bound_);
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    const Eigen::Map<const Eigen::VectorXd> u(x, n);
    const Eigen::VectorXd ku = stiffness_.selfadjointView<Eigen::Upper>() * u;
    value = 0.5 * stiffness_factor_ * u.dot(ku) - loads_.dot(u) / force_scale_;
    return true;
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    const Eigen::Map<const Eigen::VectorXd> u(x, n);
    const Eigen::VectorXd ku = stiffness_.selfadjointView<Eigen::Upper>() * u;
    Eigen::Map<Eigen::VectorXd>(gradient, n) = stiffness_factor_ * ku - loads_ / force_scale_;
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    for (size_t k = 0; k < rows_.size(); ++k) {
      const ContactRow& row = rows_[k];
      Vec3 gap = Vec3::Zero();
      for (size_t j = 0; j < row.nodes.size(); ++j)
        gap += row.weights[j] * Vec3(x[3 * row.nodes[j]], x[3 * row.nodes[j] + 1], x[3 * row.nodes[j] + 2]);
      g[3 * k] = row.tangent1.dot(gap);
      g[3 * k + 1] = row.tangent2.dot(gap);
      g[3 * k + 2] = row.side * row.normal.dot(gap);
    }
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* rows, Index* columns, Number* values) override {
    Index entry = 0;
    for (size_t k = 0; k < rows_.size(); ++k) {
      const ContactRow& row = rows_[k];
      const Vec3 axes[3] = {row.tangent1, row.tangent2, row.side * row.normal};
      for (int r = 0; r < 3; ++r)
        for (size_t j = 0; j < row.nodes.size(); ++j)
          for (int d = 0; d < 3; ++d, ++entry) {
            if (values) {
              values[entry] = row.weights[j] * axes[r][d];
            } else {
              rows[entry] = static_cast<Index>(3 * k + r);
              columns[entry] = static_cast<Index>(3 * row.nodes[j] + d);
            }
          }
    }
    return true;
  }

  // The rows are linear: the Lagrangian's Hessian is the objective's, K.
  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index, Index* rows,
              Index* columns, Number* values) override {
    Index entry = 0;
    for (int col = 0; col < stiffness_.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(stiffness_, col); it; ++it, ++entry) {
        if (values) {
          values[entry] = obj_factor * stiffness_factor_ * it.value();
        } else {  // IPOPT reads the lower triangle: K's (row <= col) entries transposed
          rows[entry] = static_cast<Index>(it.col());
          columns[entry] = static_cast<Index>(it.row());
        }
      }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index m,
                         const Number*, const Number* lambda, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    result_.displacements = displacement_scale_ * Eigen::Map<const Eigen::VectorXd>(x, n);
    result_.normal_forces.resize(rows_.size());
    // IPOPT's Lagrangian is f + lambda^T g: a pressed node's opening row
    // has lambda <= 0, and -lambda is its force (scaled).
    for (Index k = 2; k < m; k += 3) result_.normal_forces[k / 3] = std::max(0.0, -lambda[k]) * force_scale_;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index iteration, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    result_.iterations = static_cast<int>(iteration);
    if (stop_requested()) result_.interrupted = true;
    return !result_.interrupted;
  }

private:
  const SparseMatrix& stiffness_;
  const Eigen::VectorXd& loads_;
  const std::vector<ContactRow>& rows_;
  double bound_, stiffness_factor_, force_scale_, displacement_scale_;
  Eigen::VectorXd start_;
  ContactProgramResult result_;
};

}  // namespace

ContactProgramResult solve_contact_program(const SparseMatrix& stiffness, const Eigen::VectorXd& loads,
                                           const std::vector<ContactRow>& rows, double bound,
                                           double displacement_scale, double force_scale,
                                           const Eigen::VectorXd& start) {
  Ipopt::SmartPtr<ContactProgram> program =
      new ContactProgram(stiffness, loads, rows, bound, displacement_scale, force_scale, start);
  // MUMPS runs on OpenBLAS: the engine's process-wide setting first (one
  // thread, the CPU's kernels), as analyze_cra does, in case no sparse
  // factorisation came before.
  set_up_blas_in_whole_process();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");  // no banner
  app->Options()->SetNumericValue("tol", 1e-10);
  app->Options()->SetIntegerValue("max_iter", 1000);
  app->Options()->SetStringValue("mu_strategy", "adaptive");
  app->Options()->SetStringValue("nlp_scaling_method", "none");  // scaled by the program
  app->Options()->SetStringValue("hessian_constant", "yes");
  app->Options()->SetStringValue("jac_c_constant", "yes");
  app->Options()->SetStringValue("jac_d_constant", "yes");
  // PORD, MUMPS's own nested dissection: good on 3D meshes like METIS's,
  // without METIS, whose calls must pass core/cholmod_system's guard (one
  // at a time, SIGTERM kept) and MUMPS's would not.
  app->Options()->SetIntegerValue("mumps_pivot_order", 4);
  app->Options()->SetIntegerValue("mumps_mem_percent", kMumpsWorkspacePercent);  // why: core/blas.hpp
  // No options file: an ipopt.opt in the working directory would change the answer unseen.
  if (app->Initialize("") != Ipopt::Solve_Succeeded) throw std::runtime_error("IPOPT failed to initialise");
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(program);
  ContactProgramResult result = program->result();
  result.solved = status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  return result;
}

}  // namespace ashlar
