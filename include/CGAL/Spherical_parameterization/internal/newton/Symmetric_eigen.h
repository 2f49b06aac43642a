// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SYMMETRIC_EIGEN_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SYMMETRIC_EIGEN_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The eigen decomposition `A = vectors * diag(values) * vectors^T` of a symmetric matrix
/// of small fixed size `N`: Householder reduction to a tridiagonal matrix, then implicit
/// symmetric QR steps with Wilkinson's shift (Golub and Van Loan, Matrix Computations,
/// 8.3.1 and 8.3.3). Written for the 6 x 6 face Hessians that `project_to_psd()` treats,
/// where it takes about half the time of Eigen's `SelfAdjointEigenSolver`: the loops have
/// constant bounds, and a rotation costs one square root where Eigen's takes a `hypot`. An
/// off-diagonal entry is dropped once under the unit round-off times the matrix's size, so
/// small eigenvalues are accurate relative to the largest one, as the projection needs, and
/// not relative to themselves.
/// Only the lower triangle of `A` is read.
template <int N>
class Symmetric_eigen
{
public:
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;

  explicit Symmetric_eigen(const Matrix& a)
  {
    if(!a.allFinite())
      return;
    Vector off_diagonal;
    tridiagonalize(a, off_diagonal);
    converged_ = diagonalize(off_diagonal);
  }

  /// False if `A` has a non-finite entry or the QR steps did not converge: `values()` and
  /// `vectors()` are then meaningless.
  bool converged() const { return converged_; }
  const Vector& values() const { return values_; }
  /// The eigenvectors, in columns, in the order of `values()`.
  const Matrix& vectors() const { return vectors_; }

private:
  // A = Q T Q^T, T tridiagonal: its diagonal in values_, its subdiagonal in `off_diagonal`
  // (the last entry 0), Q in vectors_. Q = P_0 ... P_{N-3}, P_k = I - beta_k v_k v_k^T
  // zeroing column k of A under its subdiagonal.
  void tridiagonalize(const Matrix& a, Vector& off_diagonal)
  {
    Matrix t = a.template selfadjointView<Eigen::Lower>();
    Matrix reflectors = Matrix::Zero();  // v_k in column k, rows k + 1 on
    Vector betas = Vector::Zero();
    for(int k = 0; k + 2 < N; ++k) {
      double tail = 0;  // squared norm of the entries to zero
      for(int i = k + 2; i < N; ++i)
        tail += t(i, k) * t(i, k);
      if(tail == 0)
        continue;
      const double head = t(k + 1, k);
      const double norm = std::sqrt(head * head + tail);
      const double alpha = head > 0 ? -norm : norm;  // the new subdiagonal entry, no cancellation
      auto v = reflectors.col(k);
      v(k + 1) = head - alpha;
      for(int i = k + 2; i < N; ++i)
        v(i) = t(i, k);
      const double beta = 2 / (v(k + 1) * v(k + 1) + tail);
      betas(k) = beta;
      // Trailing block B <- P B P = B - v w^T - w v^T, with p = beta B v, w = p - (beta p.v / 2) v.
      Vector p = Vector::Zero();
      double pv = 0;
      for(int i = k + 1; i < N; ++i) {
        for(int j = k + 1; j < N; ++j)
          p(i) += t(i, j) * v(j);
        p(i) *= beta;
        pv += p(i) * v(i);
      }
      for(int i = k + 1; i < N; ++i)
        p(i) -= 0.5 * beta * pv * v(i);
      for(int i = k + 1; i < N; ++i)
        for(int j = k + 1; j < N; ++j)
          t(i, j) -= v(i) * p(j) + p(i) * v(j);
      t(k + 1, k) = alpha;
    }
    // Q, the reflections applied to the identity from the last.
    vectors_.setIdentity();
    for(int k = N - 3; k >= 0; --k) {
      if(betas(k) == 0)
        continue;
      const auto v = reflectors.col(k);
      for(int j = k + 1; j < N; ++j) {
        double s = 0;
        for(int i = k + 1; i < N; ++i)
          s += v(i) * vectors_(i, j);
        s *= betas(k);
        for(int i = k + 1; i < N; ++i)
          vectors_(i, j) -= s * v(i);
      }
    }
    for(int i = 0; i < N; ++i) {
      values_(i) = t(i, i);
      off_diagonal(i) = i + 1 < N ? t(i + 1, i) : 0.0;
    }
  }

  // Implicit QR steps on the unreduced block at the bottom of the tridiagonal matrix, until
  // every off-diagonal entry is negligible; the rotations accumulate into vectors_.
  bool diagonalize(Vector& e)
  {
    Vector& d = values_;
    double size = 0;
    for(int i = 0; i < N; ++i)
      size = std::max(size, std::abs(d(i)) + std::abs(e(i)) + (i > 0 ? std::abs(e(i - 1)) : 0.0));
    const double negligible = std::numeric_limits<double>::epsilon() * size;
    int steps = 0;
    for(int end = N - 1; end > 0;) {
      if(!(std::abs(e(end - 1)) > negligible)) {
        e(end - 1) = 0;
        --end;
        continue;
      }
      if(++steps > 30 * N)
        return false;
      int start = end - 1;
      while(start > 0 && std::abs(e(start - 1)) > negligible)
        --start;
      qr_step(start, end, e);
    }
    return true;
  }

  // One QR step with Wilkinson's shift on rows and columns start to end: the first rotation
  // from the shifted first column, the next ones chasing the bulge it makes down the band.
  void qr_step(int start, int end, Vector& e)
  {
    Vector& d = values_;
    const double half_gap = 0.5 * (d(end - 1) - d(end));
    const double e2 = e(end - 1) * e(end - 1);
    const double shift = d(end) - e2 / (half_gap + std::copysign(std::sqrt(half_gap * half_gap + e2), half_gap));
    double x = d(start) - shift, bulge = e(start);
    for(int k = start; k < end; ++k) {
      // G = [c s; -s c] on rows k, k + 1 zeroes (x, bulge); T <- G T G^T.
      const double r = std::sqrt(x * x + bulge * bulge);
      const double c = r > 0 ? x / r : 1.0, s = r > 0 ? bulge / r : 0.0;
      if(k > start)
        e(k - 1) = r;
      const double dk = d(k), dk1 = d(k + 1), ek = e(k);
      d(k) = c * c * dk + 2 * c * s * ek + s * s * dk1;
      d(k + 1) = s * s * dk - 2 * c * s * ek + c * c * dk1;
      e(k) = c * s * (dk1 - dk) + (c * c - s * s) * ek;
      if(k + 1 < end) {
        x = e(k);
        bulge = s * e(k + 1);
        e(k + 1) *= c;
      }
      // A = Z T Z^T stays true with Z <- Z G^T.
      for(int i = 0; i < N; ++i) {
        const double zk = vectors_(i, k), zk1 = vectors_(i, k + 1);
        vectors_(i, k) = c * zk + s * zk1;
        vectors_(i, k + 1) = c * zk1 - s * zk;
      }
    }
  }

  Vector values_;
  Matrix vectors_;
  bool converged_ = false;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SYMMETRIC_EIGEN_H
