#include "fea/hex_element.hpp"

#include <Eigen/LU>
#include <cmath>

namespace ashlar {

const std::array<std::array<int, 3>, 8> kHexCorners = {{{-1, -1, -1},
                                                         {1, -1, -1},
                                                         {1, 1, -1},
                                                         {-1, 1, -1},
                                                         {-1, -1, 1},
                                                         {1, -1, 1},
                                                         {1, 1, 1},
                                                         {-1, 1, 1}}};

namespace {

// 2x2x2 Gauss points +-1/sqrt(3), weight 1 each: exact for the trilinear
// element's mass and load integrals and the usual full integration of K.
const double kGauss = 1.0 / std::sqrt(3.0);

template <class Visit>
void for_each_gauss_point(Visit&& visit) {
  for (const auto& corner : kHexCorners)
    visit(Vec3(corner[0] * kGauss, corner[1] * kGauss, corner[2] * kGauss));
}

// dN_a/dxi as the rows of an 8 x 3 matrix.
Eigen::Matrix<double, 8, 3> shape_derivatives(const Vec3& xi) {
  Eigen::Matrix<double, 8, 3> d;
  for (int a = 0; a < 8; ++a) {
    const double sx = kHexCorners[a][0], sy = kHexCorners[a][1], sz = kHexCorners[a][2];
    const double fx = 1 + sx * xi.x(), fy = 1 + sy * xi.y(), fz = 1 + sz * xi.z();
    d(a, 0) = 0.125 * sx * fy * fz;
    d(a, 1) = 0.125 * fx * sy * fz;
    d(a, 2) = 0.125 * fx * fy * sz;
  }
  return d;
}

Eigen::Matrix<double, 6, 6> elasticity_matrix(const Elasticity& m) {
  const double e = m.young, nu = m.poisson;
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = e / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) d(i, i) = lambda + 2 * mu;
  for (int i = 3; i < 6; ++i) d(i, i) = mu;
  return d;
}

// Strain-displacement matrix (engineering shear strains, order xx yy zz yz
// xz xy) and the Jacobian determinant at xi.
Eigen::Matrix<double, 6, 24> strain_matrix(const HexNodes& nodes, const Vec3& xi, double& det) {
  const Eigen::Matrix<double, 8, 3> dxi = shape_derivatives(xi);
  const Mat3 jacobian = hex_jacobian(nodes, xi);
  det = jacobian.determinant();
  // Rows: dN_a/dx. J = dx/dxi, so dN/dx = dN/dxi J^-1.
  const Eigen::Matrix<double, 8, 3> dx = dxi * jacobian.inverse();
  Eigen::Matrix<double, 6, 24> b = Eigen::Matrix<double, 6, 24>::Zero();
  for (int a = 0; a < 8; ++a) {
    const int c = 3 * a;
    b(0, c) = dx(a, 0);
    b(1, c + 1) = dx(a, 1);
    b(2, c + 2) = dx(a, 2);
    b(3, c + 1) = dx(a, 2);
    b(3, c + 2) = dx(a, 1);
    b(4, c) = dx(a, 2);
    b(4, c + 2) = dx(a, 0);
    b(5, c) = dx(a, 1);
    b(5, c + 1) = dx(a, 0);
  }
  return b;
}

}  // namespace

std::array<double, 8> hex_shape(const Vec3& xi) {
  std::array<double, 8> n{};
  for (int a = 0; a < 8; ++a)
    n[a] = 0.125 * (1 + kHexCorners[a][0] * xi.x()) * (1 + kHexCorners[a][1] * xi.y()) *
           (1 + kHexCorners[a][2] * xi.z());
  return n;
}

Vec3 hex_point(const HexNodes& nodes, const Vec3& xi) {
  const std::array<double, 8> n = hex_shape(xi);
  Vec3 p = Vec3::Zero();
  for (int a = 0; a < 8; ++a) p += n[a] * nodes[a];
  return p;
}

Mat3 hex_jacobian(const HexNodes& nodes, const Vec3& xi) {
  const Eigen::Matrix<double, 8, 3> d = shape_derivatives(xi);
  Mat3 j = Mat3::Zero();
  for (int a = 0; a < 8; ++a) j += nodes[a] * d.row(a);
  return j;
}

Vec3 hex_parametric(const HexNodes& nodes, const Vec3& p) {
  Vec3 xi = Vec3::Zero();
  double size = 0;
  for (int a = 1; a < 8; ++a) size = std::max(size, (nodes[a] - nodes[0]).norm());
  // Newton converges quadratically on the (mildly) nonlinear trilinear map;
  // a valid element's map is invertible, so a few steps reach round-off.
  for (int step = 0; step < 50; ++step) {
    const Vec3 residual = hex_point(nodes, xi) - p;
    if (residual.norm() <= 1e-14 * size) break;
    xi -= hex_jacobian(nodes, xi).inverse() * residual;
  }
  return xi;
}

double hex_min_jacobian(const HexNodes& nodes) {
  double least = std::numeric_limits<double>::infinity();
  for (const auto& corner : kHexCorners) {
    least = std::min(least, hex_jacobian(nodes, Vec3(corner[0], corner[1], corner[2])).determinant());
    least = std::min(least, hex_jacobian(nodes, Vec3(corner[0], corner[1], corner[2]) * kGauss).determinant());
  }
  return least;
}

HexStiffness hex_stiffness(const HexNodes& nodes, const Elasticity& material) {
  const Eigen::Matrix<double, 6, 6> d = elasticity_matrix(material);
  HexStiffness k = HexStiffness::Zero();
  for_each_gauss_point([&](const Vec3& xi) {
    double det = 0;
    const Eigen::Matrix<double, 6, 24> b = strain_matrix(nodes, xi, det);
    k.noalias() += b.transpose() * d * b * det;
  });
  return k;
}

HexVector hex_body_load(const HexNodes& nodes, const Vec3& body_force) {
  HexVector f = HexVector::Zero();
  for_each_gauss_point([&](const Vec3& xi) {
    const double det = hex_jacobian(nodes, xi).determinant();
    const std::array<double, 8> n = hex_shape(xi);
    for (int a = 0; a < 8; ++a) f.segment<3>(3 * a) += n[a] * det * body_force;
  });
  return f;
}

Stress hex_stress(const HexNodes& nodes, const HexVector& displacements, const Elasticity& material,
                  const Vec3& xi) {
  double det = 0;
  return elasticity_matrix(material) * (strain_matrix(nodes, xi, det) * displacements);
}

double von_mises(const Stress& s) {
  const double normal = (s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) +
                        (s(2) - s(0)) * (s(2) - s(0));
  const double shear = s(3) * s(3) + s(4) * s(4) + s(5) * s(5);
  return std::sqrt(0.5 * normal + 3 * shear);
}

}  // namespace ashlar
