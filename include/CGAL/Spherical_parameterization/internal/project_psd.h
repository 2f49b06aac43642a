// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PROJECT_PSD_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PROJECT_PSD_H

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Replaces the symmetric matrix `h` by its closest positive semi-definite matrix
/// (negative eigenvalues clamped to 0), so that the assembled Newton matrix is
/// positive semi-definite. Matrices that are already positive definite, the common
/// case near a minimum, are recognized by a cheap Cholesky attempt and left as they are.
template <int N>
void project_to_psd(Eigen::Matrix<double, N, N>& h)
{
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(h);
  if(llt.info() == Eigen::Success)
    return;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(h);
  if(eigen.info() != Eigen::Success) {
    h.setZero();
    return;
  }
  const auto clamped = eigen.eigenvalues().cwiseMax(0.0);
  h = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PROJECT_PSD_H
