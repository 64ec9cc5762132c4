#include "analysis/equilibrium_problem.hpp"

#include <array>
#include <cmath>
#include <numeric>

#include "core/error.hpp"

namespace ashlar {

namespace {

void check_options(const EquilibriumOptions& options) {
  if (std::isnan(options.friction) || options.friction < 0.0) {
    throw InvalidArgument("friction must be a number >= 0 (math.huge for no sliding)");
  }
  if (options.friction_sides < 3 || options.friction_sides > 1024) {
    throw InvalidArgument("friction_sides must be an integer from 3 to 1024, got " +
                          std::to_string(options.friction_sides));
  }
  if (!std::isfinite(options.tension_weight) || options.tension_weight < 0.0) {
    throw InvalidArgument("tension_weight must be a finite number >= 0");
  }
  if (!std::isfinite(options.force_weight) || options.force_weight < 0.0) {
    throw InvalidArgument("force_weight must be a finite number >= 0");
  }
}

// Union-find over blocks, to find free blocks with no contact path to a support.
class Components {
public:
  explicit Components(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(int a, int b) { parent_[root(a)] = root(b); }

private:
  std::vector<int> parent_;
};

std::vector<bool> grounded_blocks(const Structure& structure,
                                  const std::vector<Interface>& interfaces) {
  const int n = structure.size();
  Components components(n);
  for (const Interface& contact : interfaces) components.join(contact.a, contact.b);
  std::vector<bool> root_grounded(n, false);
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) root_grounded[components.root(i)] = true;
  }
  std::vector<bool> grounded(n);
  for (int i = 0; i < n; ++i) grounded[i] = root_grounded[components.root(i)];
  return grounded;
}

void check_planar_loads(const Structure& structure) {
  for (size_t k = 0; k < structure.loads().size(); ++k) {
    const PointLoad& load = structure.loads()[k];
    const Block& block = structure.block(load.block);
    const double size = block.bounds().diagonal();
    if (std::abs(load.force.y()) > 1e-12 * load.force.norm() ||
        std::abs(load.at.y() - block.centroid().y()) > 1e-9 * size) {
      throw InvalidArgument("planar structure: load " + std::to_string(k + 1) + " on block " +
                            std::to_string(load.block + 1) +
                            " is out of the x-z plane (a y force, or applied off the block's "
                            "mid-plane y = " + std::to_string(block.centroid().y()) + ")");
    }
  }
}

}  // namespace

// The balance rows a problem keeps, in order: all six, or for a planar
// structure (x-z plane) the in-plane force and moment Fx, Fz, My.
const std::array<int, 6>& balance_rows(bool planar) {
  static const std::array<int, 6> all = {0, 1, 2, 3, 4, 5};
  static const std::array<int, 6> planar_first = {0, 2, 4, 1, 3, 5};
  return planar ? planar_first : all;
}

Eigen::Matrix<double, 6, 4> contact_vertex_effect(const Interface& contact, const Vec3& position,
                                          const Vec3& centroid, double length_unit,
                                          double sign, const std::array<int, 6>& rows) {
  const Vec3 arm = (position - centroid) / length_unit;
  Eigen::Matrix<double, 6, 4> effect;
  const Vec3 directions[3] = {contact.normal, contact.u, contact.v};
  const int columns[3] = {0, 2, 3};
  for (int k = 0; k < 3; ++k) {
    effect.block<3, 1>(0, columns[k]) = sign * directions[k];
    effect.block<3, 1>(3, columns[k]) = sign * arm.cross(directions[k]);
  }
  effect.col(1) = -effect.col(0);  // tension pulls where compression pushes
  Eigen::Matrix<double, 6, 4> ordered;
  for (int r = 0; r < 6; ++r) ordered.row(r) = effect.row(rows[r]);
  return ordered;
}

Eigen::Matrix<double, Eigen::Dynamic, 3> friction_rows(const EquilibriumOptions& options) {
  const double mu = options.friction;
  Eigen::Matrix<double, Eigen::Dynamic, 3> rows;
  if (std::isinf(mu)) return rows;
  if (options.friction_model == FrictionModel::box) {
    rows.resize(4, 3);
    rows << mu, -1, 0, mu, 1, 0, mu, 0, -1, mu, 0, 1;
    return rows;
  }
  // Inscribed pyramid: edges on the cone at angles 2 pi j / m (one along u);
  // side j faces the direction (2j + 1) pi / m at distance mu c cos(pi / m).
  const int m = options.friction_sides;
  rows.resize(m, 3);
  for (int j = 0; j < m; ++j) {
    const double facing = (2 * j + 1) * M_PI / m;
    rows.row(j) << mu * std::cos(M_PI / m), -std::cos(facing), -std::sin(facing);
  }
  return rows;
}

EquilibriumProblem build_equilibrium_problem(const Structure& structure,
                                             const EquilibriumOptions& options) {
  check_options(options);
  const std::vector<Interface>& interfaces = structure.interfaces(options.contact);
  const std::vector<bool> grounded = grounded_blocks(structure, interfaces);

  EquilibriumProblem problem;
  const bool planar = structure.planar();
  if (planar) check_planar_loads(structure);
  const std::array<int, 6>& rows = balance_rows(planar);
  problem.block_rows = planar ? 3 : 6;
  const int d = problem.block_rows;
  const int n = structure.size();
  problem.row_of_block.assign(n, -1);
  double size_sum = 0.0;
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) continue;
    if (!grounded[i]) {
      problem.floating_blocks.push_back(i);
      continue;
    }
    problem.row_of_block[i] = problem.row_count;
    problem.row_count += d;
    problem.total_weight += structure.block(i).mass() * kGravity;
    size_sum += structure.block(i).bounds().diagonal();
  }
  const int analysed = problem.row_count / d;
  if (analysed > 0) {
    problem.weight_unit = problem.total_weight / analysed;
    problem.length_unit = size_sum / analysed;
  }
  const double wu = problem.weight_unit, lu = problem.length_unit;

  // Each block's external force and moment, then the rows the problem keeps.
  std::vector<Eigen::Matrix<double, 6, 1>> external(n, Eigen::Matrix<double, 6, 1>::Zero());
  for (int i = 0; i < n; ++i) external[i](2) = structure.block(i).mass() * kGravity / wu;
  for (const PointLoad& load : structure.loads()) {
    const Vec3 arm = (load.at - structure.block(load.block).centroid()) / lu;
    external[load.block].head<3>() -= load.force / wu;
    external[load.block].tail<3>() -= arm.cross(load.force / wu);
  }
  problem.rhs = Eigen::VectorXd::Zero(problem.row_count);
  for (int i = 0; i < n; ++i) {
    const int row = problem.row_of_block[i];
    if (row < 0) continue;
    for (int r = 0; r < d; ++r) problem.rhs(row + r) = external[i](rows[r]);
  }

  for (size_t k = 0; k < interfaces.size(); ++k) {
    const Interface& contact = interfaces[k];
    const int row_a = problem.row_of_block[contact.a], row_b = problem.row_of_block[contact.b];
    if (row_a < 0 && row_b < 0) continue;  // between supports, or floating
    for (const Vec3& p : contact.vertices) {
      ContactVertex vertex;
      vertex.interface_index = static_cast<int>(k);
      vertex.block_a = contact.a;
      vertex.block_b = contact.b;
      vertex.row_a = row_a;
      vertex.row_b = row_b;
      vertex.position = p;
      vertex.on_b =
          contact_vertex_effect(contact, p, structure.block(contact.b).centroid(), lu, 1.0, rows);
      vertex.on_a =
          contact_vertex_effect(contact, p, structure.block(contact.a).centroid(), lu, -1.0, rows);
      problem.vertices.push_back(vertex);
    }
  }

  const Eigen::Matrix<double, Eigen::Dynamic, 3> friction = friction_rows(options);
  problem.vertex_rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(2 + friction.rows(), 4);
  problem.vertex_rows(0, 0) = 1.0;
  problem.vertex_rows(1, 1) = 1.0;
  for (int j = 0; j < friction.rows(); ++j) {
    problem.vertex_rows(2 + j, 0) = friction(j, 0);
    problem.vertex_rows(2 + j, 2) = friction(j, 1);
    problem.vertex_rows(2 + j, 3) = friction(j, 2);
  }
  // The regularisation's pull on the multipliers grows with the forces,
  // which grow with the number of blocks sharing the load (an arch's thrust
  // is a fraction of its whole weight). Dividing it by the block count keeps
  // the tension penalty exact on large structures, while staying far above
  // the scale at which near-free friction unknowns spoil the factorisation.
  const double regularisation = options.force_weight / std::max(analysed, 1);
  problem.hessian_diagonal << regularisation, options.tension_weight, regularisation,
      regularisation;
  problem.linear << 0.0, 1.0, 0.0, 0.0;
  return problem;
}

Eigen::SparseMatrix<double> EquilibriumProblem::equality_matrix() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(vertices.size() * 48);
  for (size_t k = 0; k < vertices.size(); ++k) {
    const ContactVertex& v = vertices[k];
    for (int col = 0; col < 4; ++col) {
      const int variable = 4 * static_cast<int>(k) + col;
      for (int r = 0; r < block_rows; ++r) {
        if (v.row_b >= 0 && v.on_b(r, col) != 0.0) {
          entries.emplace_back(v.row_b + r, variable, v.on_b(r, col));
        }
        if (v.row_a >= 0 && v.on_a(r, col) != 0.0) {
          entries.emplace_back(v.row_a + r, variable, v.on_a(r, col));
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(row_count, variable_count());
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace ashlar
