// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STEP_BOUND_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STEP_BOUND_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The first root in `(0, horizon]` of `p(t) = c[0] + c[1] t + c[2] t^2 + c[3] t^3` with
/// `p(0) > 0`, or +inf. The interval is split at the critical points, so that `p` is
/// monotone on each piece, and the first sign change is bisected.
inline double first_positive_root(const std::array<double, 4>& c, double horizon)
{
  auto p = [&](double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); };
  std::array<double, 4> breaks{horizon, horizon, horizon, horizon};
  int count = 0;
  // Critical points: roots of 3 c3 t^2 + 2 c2 t + c1, by the cancellation-free formula.
  const double qa = 3 * c[3], qb = 2 * c[2], qc = c[1];
  if(qa != 0) {
    const double disc = qb * qb - 4 * qa * qc;
    if(disc >= 0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      if(q != 0) { breaks[count++] = q / qa; breaks[count++] = qc / q; }
    }
  } else if(qb != 0) {
    breaks[count++] = -qc / qb;
  }
  std::sort(breaks.begin(), breaks.end());
  double left = 0;
  for(double right : breaks) {
    if(!(right > left) || right > horizon) continue;
    if(p(right) <= 0) {
      for(int k = 0; k < 100 && right - left > 1e-15 * horizon; ++k) {
        const double mid = 0.5 * (left + right);
        (p(mid) > 0 ? left : right) = mid;
      }
      return left;
    }
    left = right;
  }
  return std::numeric_limits<double>::infinity();
}

/// The largest `t` in `(0, horizon]` for which no face with positive `det(a, b, c)` reaches
/// `det = 0` along `x_v + t * step_v` (+inf if none does). Normalizing the points onto the
/// sphere scales them by positive factors and so does not change the sign of det.
inline double largest_fold_free_step(const Faces& faces, const Points& x, const Points& step,
                                     double horizon = 1.25)
{
  auto det = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return a.dot(b.cross(c));
  };
  double bound = std::numeric_limits<double>::infinity();
  for(const auto& t : faces) {
    const Eigen::Vector3d &a = x[t[0]], &b = x[t[1]], &c = x[t[2]];
    const Eigen::Vector3d &u = step[t[0]], &v = step[t[1]], &w = step[t[2]];
    const std::array<double, 4> coefficients{
      a.dot((b - a).cross(c - a)),
      det(u, b, c) + det(a, v, c) + det(a, b, w),
      det(a, v, w) + det(u, b, w) + det(u, v, c),
      det(u, v, w)};
    if(!(coefficients[0] > 0)) continue;  // already folded: nothing to keep
    bound = std::min(bound, first_positive_root(coefficients, std::min(bound, horizon)));
  }
  return bound;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STEP_BOUND_H
