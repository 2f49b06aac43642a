// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H

#include <CGAL/Spherical_parameterization/internal/newton/Symmetric_eigen.h>

#include <Eigen/Core>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Makes the symmetric matrix `h` positive semi-definite by replacing its negative
/// eigenvalues with their absolute values (rather than clamping them to 0: a clamped
/// direction has no curvature left and draws huge steps that the fold-free step cap then
/// cuts to 1e-3, which costs iterations), except along `invariant`: a negative eigenvalue
/// whose eigenvector lies mostly (more than half its squared length) in the span of these
/// orthonormal directions becomes 0. They are directions in which the function does not
/// change to first order, such as the rotations of a face's three points: its curvature
/// there comes from the chart's second-order term, not from the energy, and made absolute it
/// would stiffen the model along the map's smooth modes, which are made of them.
/// A matrix without negative eigenvalue is left as it is. No Cholesky test first: the face
/// Hessians sent here have a negative eigenvalue along those rotations or along a compressed
/// shape, nearly all of them. A matrix with a non-finite entry becomes 0.
template <int N, int K>
void project_to_psd(Eigen::Matrix<double, N, N>& h, const Eigen::Matrix<double, N, K>& invariant)
{
  const Symmetric_eigen<N> eigen(h);
  if(!eigen.converged()) {
    h.setZero();
    return;
  }
  if((eigen.values().array() >= 0).all())
    return;
  Eigen::Matrix<double, N, 1> values = eigen.values();
  for(int k = 0; k < N; ++k)
    if(values[k] < 0)
      values[k] = (invariant.transpose() * eigen.vectors().col(k)).squaredNorm() > 0.5 ? 0.0 : -values[k];
  h = eigen.vectors() * values.asDiagonal() * eigen.vectors().transpose();
}

/// `project_to_psd(h, invariant)` with no invariant direction: every negative eigenvalue
/// made absolute.
template <int N>
void project_to_psd(Eigen::Matrix<double, N, N>& h)
{
  project_to_psd(h, Eigen::Matrix<double, N, 0>());
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_PROJECT_PSD_H
