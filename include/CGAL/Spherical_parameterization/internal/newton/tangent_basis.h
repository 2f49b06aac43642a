// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_BASIS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_BASIS_H

#include <Eigen/Core>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// An orthonormal basis (columns) of the tangent plane of the unit sphere at `p`.
/// Branch-free construction of Duff et al. 2017 ("Building an orthonormal basis, revisited").
inline Eigen::Matrix<double, 3, 2> tangent_basis(const Eigen::Vector3d& p)
{
  const double sign = std::copysign(1.0, p.z());
  const double a = -1.0 / (sign + p.z());
  const double b = p.x() * p.y() * a;
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) << 1.0 + sign * p.x() * p.x() * a, sign * b, -sign * p.x();
  basis.col(1) << b, sign + p.y() * p.y() * a, -p.y();
  return basis;
}

/// The retraction of the tangent step `B u` at `p` onto the sphere: central projection.
inline Eigen::Vector3d retract(const Eigen::Vector3d& p, const Eigen::Matrix<double, 3, 2>& basis,
                               const Eigen::Vector2d& u)
{
  return (p + basis * u).normalized();
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_BASIS_H
