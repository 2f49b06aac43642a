// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_TRIANGLE_JET_H
#define CGAL_SPHERICAL_PARAMETERIZATION_TRIANGLE_JET_H

#include <Eigen/Core>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// Value, gradient and Hessian of a scalar function of the nine coordinates
/// `(a.x, a.y, a.z, b.x, ..., c.z)` of a triangle: a second-order forward-mode
/// derivative ("jet"). Energies are written once on a generic number type; with
/// `Triangle_jet` the same code yields exact derivatives, with `double` only the value.
struct Triangle_jet
{
  using Gradient = Eigen::Matrix<double, 9, 1>;  ///< derivatives in `(a.x, a.y, a.z, b.x, ..., c.z)`
  using Hessian = Eigen::Matrix<double, 9, 9>;   ///< second derivatives, in the same order

  double value = 0;                      ///< the value of the function
  Gradient gradient = Gradient::Zero();  ///< its gradient
  Hessian hessian = Hessian::Zero();     ///< its Hessian

  Triangle_jet() = default;
  /// a constant
  Triangle_jet(double v) : value(v) {}

  /// Adds `o`.
  Triangle_jet& operator+=(const Triangle_jet& o) { value += o.value; gradient += o.gradient; hessian += o.hessian; return *this; }
  /// Subtracts `o`.
  Triangle_jet& operator-=(const Triangle_jet& o) { value -= o.value; gradient -= o.gradient; hessian -= o.hessian; return *this; }
  /// Multiplies by the constant `s`.
  Triangle_jet& operator*=(double s) { value *= s; gradient *= s; hessian *= s; return *this; }
};

/// Applies a scalar function with derivatives `d1`, `d2` at `f.value` to the jet `f` (chain rule).
inline Triangle_jet chain(const Triangle_jet& f, double value, double d1, double d2)
{
  Triangle_jet r;
  r.value = value;
  r.gradient = d1 * f.gradient;
  r.hessian = d1 * f.hessian + d2 * (f.gradient * f.gradient.transpose());
  return r;
}

/// The same for a plain number: only the value.
inline double chain(double, double value, double, double) { return value; }

/// `f + g`.
inline Triangle_jet operator+(Triangle_jet f, const Triangle_jet& g) { return f += g; }
/// `f - g`.
inline Triangle_jet operator-(Triangle_jet f, const Triangle_jet& g) { return f -= g; }
/// `-f`.
inline Triangle_jet operator-(Triangle_jet f) { return f *= -1.0; }
/// `f * s` for a constant `s`.
inline Triangle_jet operator*(Triangle_jet f, double s) { return f *= s; }
/// `s * f` for a constant `s`.
inline Triangle_jet operator*(double s, Triangle_jet f) { return f *= s; }
/// `f / s` for a constant `s`.
inline Triangle_jet operator/(Triangle_jet f, double s) { return f *= 1.0 / s; }

/// `f * g` (product rule).
inline Triangle_jet operator*(const Triangle_jet& f, const Triangle_jet& g)
{
  Triangle_jet r;
  r.value = f.value * g.value;
  r.gradient = g.value * f.gradient + f.value * g.gradient;
  const Triangle_jet::Hessian cross = f.gradient * g.gradient.transpose();
  r.hessian = g.value * f.hessian + f.value * g.hessian + cross + cross.transpose();
  return r;
}

/// `1 / f`.
inline Triangle_jet inverse(const Triangle_jet& f)
{
  const double inv = 1.0 / f.value;
  return chain(f, inv, -inv * inv, 2 * inv * inv * inv);
}
/// `1 / x` for a plain number.
inline double inverse(double x) { return 1.0 / x; }

/// `f / g`.
inline Triangle_jet operator/(const Triangle_jet& f, const Triangle_jet& g) { return f * inverse(g); }
/// `s / g` for a constant `s`.
inline Triangle_jet operator/(double s, const Triangle_jet& g) { return s * inverse(g); }

/// The square root of `f`, for `f.value > 0`.
inline Triangle_jet sqrt(const Triangle_jet& f)
{
  const double s = std::sqrt(f.value);
  return chain(f, s, 0.5 / s, -0.25 / (s * f.value));
}

/// The natural logarithm of `f`, for `f.value > 0`.
inline Triangle_jet log(const Triangle_jet& f)
{
  return chain(f, std::log(f.value), 1.0 / f.value, -1.0 / (f.value * f.value));
}

/// The value of a jet or of a plain number.
inline double value_of(const Triangle_jet& f) { return f.value; }
/// The same for a plain number: `x`.
inline double value_of(double x) { return x; }

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_TRIANGLE_JET_H
