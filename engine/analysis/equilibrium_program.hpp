// The equilibrium QP's constraints without its penalised unknowns (tension,
// cable compression, virtual torques), as a linear program: the set of
// compression-only equilibria that respect friction. Load capacity, the
// load factor and the friction demand each add a column or change a bound
// and hand it to an LP solver (COIN-OR Clp, kept out of this header).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/margin_status.hpp"
#include "core/progress.hpp"

class ClpSimplex;

namespace ashlar {

// Triplets and bounds in the layout Clp's loadProblem takes. Rows are the
// problem's balance rows (scaled, as in EquilibriumProblem), equal to its
// right-hand side; columns are non-negative combinations of a contact
// vertex's friction-cone edges (free tangential forces when friction is
// unbounded) and cable tensions.
struct EquilibriumProgram {
  std::vector<int> row_index, column_index;
  std::vector<double> value;
  std::vector<double> column_lower, column_upper, row_lower, row_upper;
  // Per column: the group it belongs to (-1 for added columns) and the
  // group's unknowns (c, s, f_u, f_v) per unit of the column.
  std::vector<int> column_group;
  std::vector<Eigen::Vector4d> column_unknowns;
  int columns = 0, rows = 0;

  int add_column(double lower, double upper, int group = -1,
                 const Eigen::Vector4d& unknowns = Eigen::Vector4d::Zero()) {
    column_lower.push_back(lower);
    column_upper.push_back(upper);
    column_group.push_back(group);
    column_unknowns.push_back(unknowns);
    return columns++;
  }
  void add_entry(int row, int column, double entry) {
    row_index.push_back(row);
    column_index.push_back(column);
    value.push_back(entry);
  }
  // A column for the combination `unknowns` (c, s, f_u, f_v) of group k of
  // `problem`, with its entries in the group's bodies' balance rows.
  int add_group_column(const EquilibriumProblem& problem, int k, const Eigen::Vector4d& unknowns,
                       double lower, double upper);
  // The groups' unknowns (c, s, f_u, f_v), scaled, for column values x.
  std::vector<Eigen::Vector4d> group_unknowns(const EquilibriumProblem& problem, const double* x) const;
};

// The edges of the friction cone's inner approximation as (c, f_u, f_v):
// a contact vertex's force is a non-negative combination of them, so the
// program needs no friction rows. They span exactly the cone that
// friction_rows bounds; none when friction is unbounded.
std::vector<Eigen::Vector3d> friction_edges(const EquilibriumOptions& options);

// The friction coefficient a tangential force (f_u, f_v) needs with normal
// force c > 0 under the options' friction model and sides: the smallest mu
// whose cone approximation holds it (infinite when c <= 0 and f != 0).
double friction_needed(const EquilibriumOptions& options, double c, double f_u, double f_v);

EquilibriumProgram equilibrium_program(const EquilibriumProblem& problem, const EquilibriumOptions& options);

// Every iteration Clp takes on a program: the barrier's, its crossover's
// and the simplex's pivots (which numberIterations() does not all keep:
// after a crossover it tells only the barrier's), each told to `progress`
// as (iterations so far, kTotalUnknown).
struct IterationTally {
  int iterations = 0;
  ProgressCount progress;
};

// Loads the program into `simplex` with no objective and Clp's log off,
// stopping on request (stop_on_request, with `tally`).
void load_program(ClpSimplex& simplex, const EquilibriumProgram& program, IterationTally* tally = nullptr);

// Makes `simplex` stop at the end of an iteration once Ctrl-C or the
// calling thread's sandbox deadline asks (core/interrupt.hpp): its status
// is then kClpInterrupted. With `tally` (which must outlive the solves,
// copies of `simplex` included), each iteration is counted into it too.
void stop_on_request(ClpSimplex& simplex, IterationTally* tally = nullptr);
constexpr int kClpInterrupted = 5;  // Clp's "stopped by event handler"

// The outcome of a Clp status that is no answer: stopped (3, the iteration
// limit), numerical_difficulties (4), interrupted (5), else unexpected.
MarginStatus clp_failure(int status);

}  // namespace ashlar
