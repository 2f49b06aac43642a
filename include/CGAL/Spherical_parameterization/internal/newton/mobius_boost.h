// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_MOBIUS_BOOST_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_MOBIUS_BOOST_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The Moebius transformation of the unit sphere that pushes it towards `b` (`|b| < 1`): the
/// boundary action of the hyperbolic translation of the ball taking 0 to `b`. It maps the
/// sphere onto itself conformally, preserves orientation, and its derivative at `b = 0` is
/// the tangent field `2 (b - (b . x) x)`.
inline Eigen::Vector3d mobius_boost(const Eigen::Vector3d& b, const Eigen::Vector3d& x)
{
  const double bx = b.dot(x), bb = b.squaredNorm();
  return (((2 + 2 * bx) * b + (1 - bb) * x) / (1 + 2 * bx + bb)).normalized();
}

/// After a full boost `step` of energy `e` was accepted (the map in `y`, written by
/// `boosted`): the step doubled while that lowers the energy, at most 4 times and up to a
/// boost of norm 0.9. Returns the energy of the map left in `y`. The energies slide along the
/// boosts much farther than the Newton step of their finite differences goes, so doubling
/// saves iterations and reaches the same minimum.
template <class Boosted>
double extend_boost(Eigen::Vector3d step, double e, const Boosted& boosted, Points& y)
{
  Points accepted(y.size());
  for(int k = 0; k < 4 && 2 * step.norm() <= 0.9; ++k) {
    accepted.swap(y);  // y is overwritten by the next try
    step *= 2;
    const double longer = boosted(step);
    if(!(longer < e)) {
      y.swap(accepted);
      break;
    }
    e = longer;
  }
  return e;
}

/// One Newton step on the three parameters of a boost applied to the whole map `x`, with a
/// backtracking line search on `energy(points)` (a callable; `+inf` where the map is not
/// admissible). The conformal energies (Dirichlet, and Tutte and MIPS nearly so) are almost
/// invariant under these transformations: only the `d_min` factor and the discretization pin
/// the map down, so the energy is very flat along them, and Newton's method in the vertex
/// variables, damped by its shift, slides along them over a hundred iterations and more,
/// all else still. Derivatives by finite differences: 9 energy evaluations.
/// Returns true if the map moved; `current`, the energy of `x`, then follows it.
template <class EnergyFunction>
bool boost_step(Points& x, const EnergyFunction& energy, double& current)
{
  constexpr double h = 1e-3;
  Points y(x.size());
  auto boosted = [&](const Eigen::Vector3d& b) {
    for(std::size_t v = 0; v < x.size(); ++v)
      y[v] = mobius_boost(b, x[v]);
    return energy(y);
  };
  Eigen::Vector3d gradient, plus;
  Eigen::Matrix3d hessian;
  for(int i = 0; i < 3; ++i) {
    plus[i] = boosted(h * Eigen::Vector3d::Unit(i));
    const double minus = boosted(-h * Eigen::Vector3d::Unit(i));
    gradient[i] = (plus[i] - minus) / (2 * h);
    hessian(i, i) = (plus[i] - 2 * current + minus) / (h * h);
  }
  // Mixed terms by one-sided differences, accurate to O(h): enough for this step (the line
  // search follows), and 9 energy evaluations in all instead of 19.
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < i; ++j)
      hessian(i, j) = hessian(j, i) =
        (boosted(h * (Eigen::Vector3d::Unit(i) + Eigen::Vector3d::Unit(j))) - plus[i] - plus[j] + current) / (h * h);
  if(!gradient.allFinite() || !hessian.allFinite())
    return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(hessian);
  Eigen::Vector3d step = llt.info() == Eigen::Success ? Eigen::Vector3d(-llt.solve(gradient)) : Eigen::Vector3d(-gradient);
  if(step.norm() > 0.5)  // stay well inside the ball
    step *= 0.5 / step.norm();
  for(int k = 0; k < 20; ++k, step *= 0.5) {
    if(double e = boosted(step); e < current + 1e-4 * gradient.dot(step)) {
      if(k == 0)
        e = extend_boost(step, e, boosted, y);
      x.swap(y);
      current = e;
      return true;
    }
  }
  return false;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_MOBIUS_BOOST_H
