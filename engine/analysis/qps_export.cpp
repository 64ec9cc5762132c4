// The equilibrium QP as a QPS file: free-format MPS with a QUADOBJ section
// (the layout of the Maros-Meszaros QP test set), one entry per line.
//
//   NAME          <file name without folder and extension>
//   ROWS
//    N  obj                    the objective
//    E  B<i>F1 ... B<i>F3      force balance of free block i along x, y, z
//    E  B<i>M1 ... B<i>M3      moment balance of block i about its centroid
//    G  V<k>R<j>               friction side j of contact vertex k, >= 0
//   COLUMNS
//       C<k>  <row>  <value>   compression c at contact vertex k
//       S<k>  ...              tension s
//       U<k>  ...              friction f_u along the interface's u axis
//       V<k>  ...              friction f_v along the interface's v axis
//   RHS
//       RHS  B<i>F3  <value>   weights and point loads (zero entries omitted)
//   BOUNDS
//    FR BND  U<k>              friction is free; C and S keep the MPS
//    FR BND  V<k>              default bounds [0, inf)
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

#include "io/atomic_file.hpp"

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

std::string column_name(int vertex, int unknown) {
  return kColumnPrefix[unknown] + std::to_string(vertex + 1);
}

std::string friction_row_name(int vertex, int side) {
  return "V" + std::to_string(vertex + 1) + "R" + std::to_string(side + 1);
}

std::vector<std::string> balance_row_names(const EquilibriumProblem& problem) {
  std::vector<std::string> names(problem.row_count);
  for (size_t block = 0; block < problem.row_of_block.size(); ++block) {
    const int first = problem.row_of_block[block];
    if (first < 0) continue;
    for (int component = 0; component < problem.block_rows; ++component) {
      names[first + component] = "B" + std::to_string(block + 1) +
                                 (problem.block_rows == 3 ? kPlanarComponentName[component]
                                                          : kComponentName[component]);
    }
  }
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
  const int vertex_count = static_cast<int>(problem.vertices.size());
  // The first two vertex rows are c >= 0 and s >= 0: bounds, not rows.
  const int friction_sides = static_cast<int>(problem.vertex_rows.rows()) - 2;
  const std::vector<std::string> balance_rows = balance_row_names(problem);
  const Eigen::SparseMatrix<double> equality = problem.equality_matrix();

  std::string out;
  // About 40 characters per entry, 30 entries per vertex.
  out.reserve(1024 + static_cast<size_t>(vertex_count) * 1200);
  out += "NAME          " + name + "\nROWS\n N  obj\n";
  for (const std::string& row : balance_rows) out += " E  " + row + "\n";
  for (int k = 0; k < vertex_count; ++k) {
    for (int side = 0; side < friction_sides; ++side) out += " G  " + friction_row_name(k, side) + "\n";
  }

  out += "COLUMNS\n";
  for (int k = 0; k < vertex_count; ++k) {
    for (int unknown = 0; unknown < 4; ++unknown) {
      const std::string column = column_name(k, unknown);
      const size_t length_before = out.size();
      if (problem.linear(unknown) != 0.0) append_entry(out, column, "obj", problem.linear(unknown));
      for (Eigen::SparseMatrix<double>::InnerIterator entry(equality, 4 * k + unknown); entry;
           ++entry) {
        append_entry(out, column, balance_rows[entry.row()], entry.value());
      }
      for (int side = 0; side < friction_sides; ++side) {
        const double coefficient = problem.vertex_rows(2 + side, unknown);
        if (coefficient != 0.0) append_entry(out, column, friction_row_name(k, side), coefficient);
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
  for (int k = 0; k < vertex_count; ++k) {
    out += " FR BND " + column_name(k, 2) + "\n";
    out += " FR BND " + column_name(k, 3) + "\n";
  }

  out += "QUADOBJ\n";
  for (int k = 0; k < vertex_count; ++k) {
    for (int unknown = 0; unknown < 4; ++unknown) {
      const double curvature = problem.hessian_diagonal(unknown);
      if (curvature == 0.0) continue;
      const std::string column = column_name(k, unknown);
      append_entry(out, column, column, curvature);
    }
  }
  out += "ENDATA\n";
  return out;
}

void write_equilibrium_qps(const EquilibriumProblem& problem, const std::string& path) {
  write_file_atomically(path, equilibrium_qps(problem, problem_name_of(path)));
}

}  // namespace ashlar
