// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H

#include <CGAL/Spherical_parameterization/internal/newton/Symmetric_eigen.h>

#include <Eigen/Core>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Makes the symmetric matrix `h` positive semi-definite by replacing its eigenvalues with
/// their absolute values (rather than clamping negative ones to 0: a clamped direction has
/// no curvature left and draws huge steps that the fold-free step cap then cuts to 1e-3,
/// which costs iterations). A matrix without negative eigenvalue is left as it is. No
/// Cholesky test first: the face Hessians sent here have the near-null directions of the
/// rotations of their three points, so the test fails on nearly all of them. A matrix with a
/// non-finite entry becomes 0.
template <int N>
void project_to_psd(Eigen::Matrix<double, N, N>& h)
{
  const Symmetric_eigen<N> eigen(h);
  if(!eigen.converged()) {
    h.setZero();
    return;
  }
  if((eigen.values().array() >= 0).all())
    return;
  h = eigen.vectors() * eigen.values().cwiseAbs().asDiagonal() * eigen.vectors().transpose();
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H
