// The equilibrium QP as a QPS file: free-format MPS with a QUADOBJ section
// (the layout of the Maros-Meszaros QP test set), one entry per line.
//
//   NAME          <file name without folder and extension>
//   ROWS
//    N  obj                    the objective
//    E  B<i>F1 ... B<i>F3      force balance of free block i along x, y, z
//    E  B<i>M1 ... B<i>M3      moment balance of block i about its centroid
//    E  J<j>F1 ... J<j>M3      balance of cable junction j (moments: virtual only)
//    G  V<k>R<j>               friction side j of contact vertex k, >= 0
//   COLUMNS
//       C<k>  <row>  <value>   compression c at contact vertex k
//       S<k>  ...              tension s
//       U<k>  ...              friction f_u along the interface's u axis
//       V<k>  ...              friction f_v along the interface's v axis
//       T<c>, K<c>             tension and (penalised) compression of cable c
//       P<j>, N<j>             the j-th virtual torque (or junction force), p - n
//   RHS
//       RHS  B<i>F3  <value>   weights and point loads (zero entries omitted)
//   BOUNDS
//    FR BND  U<k>              friction is free; C and S keep the MPS
//    FR BND  V<k>              default bounds [0, inf)
//    UP BND  T<c>  <value>     a cable's max_tension
//   QUADOBJ
//       C<k>  C<k>  <value>    the diagonal Hessian, so the lower triangle
//   ENDATA
//
// Block indices i and vertex indices k are 1-based, as in Lua: i is the
// block's index in the structure, k the vertex's index in r.vertices. Rows
// and columns are separate name spaces (V<k> is a column, V<k>R<j> a row).
// Names fit the 8 characters of fixed-format readers up to 99,999 blocks
// and 99,999 contact vertices with at most 9 friction sides; larger problems
// need a free-format reader.
//
// Every value is scaled as in EquilibriumProblem (forces in mean block
// weights, lengths in mean block sizes) and printed with 17 significant
// digits, so the file's QP is the solver's to the last bit and its optimum,
// 1/2 x^T Q x + c^T x, is EquilibriumResult::objective.
#include "analysis/qps_export.hpp"

#include <cctype>
#include <charconv>

#include "core/error.hpp"
#include "core/atomic_file.hpp"

namespace ashlar {

namespace {

constexpr char kColumnPrefix[4] = {'C', 'S', 'U', 'V'};  // c, s, f_u, f_v
constexpr char kComponentName[6][3] = {"F1", "F2", "F3", "M1", "M2", "M3"};
// A planar problem's rows: Fx, Fz, My.
constexpr char kPlanarComponentName[3][3] = {"F1", "F3", "M2"};

void append_number(std::string& out, double value) {
  char buffer[32];
  const std::to_chars_result written =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  out.append(buffer, written.ptr);
}

// Each group's column names: C, S, U, V of contact vertex k; T and K of
// cable c (its other two unknowns stay zero and are left out); P and N of
// the j-th virtual torque or force.
std::vector<std::vector<std::string>> column_names(const EquilibriumProblem& problem) {
  std::vector<std::vector<std::string>> names(problem.groups.size());
  int slack = 0;
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& group = problem.groups[k];
    switch (group.kind) {
      case GroupKind::contact_vertex:
        for (char prefix : kColumnPrefix) names[k].push_back(prefix + std::to_string(k + 1));
        break;
      case GroupKind::cable:
      case GroupKind::bounded_cable:
        names[k] = {"T" + std::to_string(group.source + 1), "K" + std::to_string(group.source + 1)};
        break;
      case GroupKind::slack:
        ++slack;
        names[k] = {"P" + std::to_string(slack), "N" + std::to_string(slack)};
        break;
      case GroupKind::weight:
        names[k] = {"W" + std::to_string(group.source + 1)};
        break;
    }
  }
  return names;
}

std::string friction_row_name(int vertex, int side) {
  return "V" + std::to_string(vertex + 1) + "R" + std::to_string(side + 1);
}

std::vector<std::string> balance_row_names(const EquilibriumProblem& problem) {
  std::vector<std::string> names(problem.row_count);
  auto name_rows = [&](const std::vector<int>& first_rows, char prefix) {
    for (size_t body = 0; body < first_rows.size(); ++body) {
      const int first = first_rows[body];
      if (first < 0) continue;
      for (int component = 0; component < problem.block_rows; ++component) {
        names[first + component] = prefix + std::to_string(body + 1) +
                                   (problem.block_rows == 3 ? kPlanarComponentName[component]
                                                            : kComponentName[component]);
      }
    }
  };
  name_rows(problem.row_of_block, 'B');
  name_rows(problem.row_of_junction, 'J');
  return names;
}

void append_entry(std::string& out, const std::string& column, const std::string& row,
                  double value) {
  out += "    ";
  out += column;
  out += ' ';
  out += row;
  out += ' ';
  append_number(out, value);
  out += '\n';
}

// MPS names end at whitespace, so the file name's blanks become underscores.
std::string problem_name_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  for (char& ch : name) {
    if (std::isspace(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name.empty() ? "ashlar" : name;
}

}  // namespace

std::string equilibrium_qps(const EquilibriumProblem& problem, const std::string& name) {
  const int group_count = static_cast<int>(problem.groups.size());
  const GroupRules& contact = problem.rules[static_cast<int>(GroupKind::contact_vertex)];
  if (contact.bound_coefficients.size()) {
    throw InvalidArgument("QPS export: friction with given strengths (the kinematic method's rounds) is not exported");
  }
  // The first two rows of every kind are its two non-negativities: bounds,
  // not rows; a cable's tension bound is an upper bound.
  const int friction_sides = static_cast<int>(contact.rows.rows()) - 2;
  const std::vector<std::string> balance_rows = balance_row_names(problem);
  const Eigen::SparseMatrix<double> equality = problem.equality_matrix();
  const std::vector<std::vector<std::string>> columns = column_names(problem);

  std::string out;
  // About 40 characters per entry, 30 entries per vertex.
  out.reserve(1024 + static_cast<size_t>(group_count) * 1200);
  out += "NAME          " + name + "\nROWS\n N  obj\n";
  for (const std::string& row : balance_rows) out += " E  " + row + "\n";
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    for (int side = 0; side < friction_sides; ++side) out += " G  " + friction_row_name(k, side) + "\n";
  }

  out += "COLUMNS\n";
  for (int k = 0; k < group_count; ++k) {
    const GroupRules& rules = problem.rules_of(problem.groups[k]);
    for (size_t unknown = 0; unknown < columns[k].size(); ++unknown) {
      const std::string& column = columns[k][unknown];
      const size_t length_before = out.size();
      if (rules.linear(unknown) != 0.0) append_entry(out, column, "obj", rules.linear(unknown));
      for (Eigen::SparseMatrix<double>::InnerIterator entry(equality, 4 * k + unknown); entry;
           ++entry) {
        append_entry(out, column, balance_rows[entry.row()], entry.value());
      }
      if (k < problem.contact_vertex_count) {
        for (int side = 0; side < friction_sides; ++side) {
          const double coefficient = contact.rows(2 + side, unknown);
          if (coefficient != 0.0) append_entry(out, column, friction_row_name(k, side), coefficient);
        }
      }
      // A column exists only through its entries: declare an unused one.
      if (out.size() == length_before) append_entry(out, column, "obj", 0.0);
    }
  }

  out += "RHS\n";
  for (int row = 0; row < problem.row_count; ++row) {
    if (problem.rhs(row) != 0.0) append_entry(out, "RHS", balance_rows[row], problem.rhs(row));
  }

  out += "BOUNDS\n";
  for (int k = 0; k < group_count; ++k) {
    const ForceGroup& group = problem.groups[k];
    if (group.kind == GroupKind::contact_vertex) {
      out += " FR BND " + columns[k][2] + "\n";
      out += " FR BND " + columns[k][3] + "\n";
    } else if (group.kind == GroupKind::bounded_cable) {
      out += " UP BND " + columns[k][0] + " ";
      append_number(out, group.bound);
      out += "\n";
    }
  }

  out += "QUADOBJ\n";
  for (int k = 0; k < group_count; ++k) {
    const GroupRules& rules = problem.rules_of(problem.groups[k]);
    for (size_t unknown = 0; unknown < columns[k].size(); ++unknown) {
      const double curvature = rules.hessian(unknown);
      if (curvature != 0.0) append_entry(out, columns[k][unknown], columns[k][unknown], curvature);
    }
  }
  out += "ENDATA\n";
  return out;
}

void write_equilibrium_qps(const EquilibriumProblem& problem, const std::string& path) {
  write_file_atomically(path, equilibrium_qps(problem, problem_name_of(path)));
}

}  // namespace ashlar
