// The 8-node trilinear hexahedron: shape functions, stiffness by 2x2x2 Gauss
// quadrature, consistent body loads and stresses, for isotropic linear
// elasticity. Node order: 0-3 counter-clockwise on the face zeta = -1 seen
// from zeta = +1, then 4-7 above them; node a sits at parametric corner
// (xi, eta, zeta) = kHexCorners[a], each coordinate -1 or +1.
#pragma once

#include <array>

#include <Eigen/Core>

#include "core/types.hpp"

namespace ashlar {

using HexNodes = std::array<Vec3, 8>;              // corner positions (m)
using HexStiffness = Eigen::Matrix<double, 24, 24>;  // N/m, dofs (node a, axis d) at 3a + d
using HexVector = Eigen::Matrix<double, 24, 1>;
using Stress = Eigen::Matrix<double, 6, 1>;  // Pa: xx, yy, zz, yz, xz, xy

extern const std::array<std::array<int, 3>, 8> kHexCorners;

// Isotropic elasticity: Young's modulus (Pa) and Poisson's ratio.
struct Elasticity {
  double young = 20e9;
  double poisson = 0.2;
};

// Shape function values N_a at parametric point xi (each coordinate in [-1, 1]).
std::array<double, 8> hex_shape(const Vec3& xi);
// Position of parametric point xi.
Vec3 hex_point(const HexNodes& nodes, const Vec3& xi);
// Jacobian dx/dxi at xi (columns: d/dxi, d/deta, d/dzeta).
Mat3 hex_jacobian(const HexNodes& nodes, const Vec3& xi);
// The parametric point whose image is p (Newton on the trilinear map);
// the result may lie outside [-1, 1]^3 when p is outside the element.
Vec3 hex_parametric(const HexNodes& nodes, const Vec3& p);
// Smallest Jacobian determinant over the corners and Gauss points (m^3 per
// unit parametric volume); <= 0 means the map folds.
double hex_min_jacobian(const HexNodes& nodes);

HexStiffness hex_stiffness(const HexNodes& nodes, const Elasticity& material);
// Consistent nodal forces of a uniform body force density (N/m^3), summed
// over Gauss points: their total is body_force * volume.
HexVector hex_body_load(const HexNodes& nodes, const Vec3& body_force);
// Stress at parametric point xi from the element's nodal displacements.
Stress hex_stress(const HexNodes& nodes, const HexVector& displacements, const Elasticity& material,
                  const Vec3& xi = Vec3::Zero());
double von_mises(const Stress& stress);

}  // namespace ashlar
