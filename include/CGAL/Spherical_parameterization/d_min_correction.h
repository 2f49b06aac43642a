// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_D_MIN_CORRECTION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_D_MIN_CORRECTION_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// `d_min^-2`, the factor (Friedel et al., Section 2.1, Equation 2) that turns a flat energy
/// of the chord triangle into an upper bound of its spherical counterpart. `d_min` is the
/// distance from the sphere centre to the closest point of the flat triangle:
/// - acute triangle: the circumcentre, which is the foot of the centre on the plane, so
///   `d_min^2 = det(a,b,c)^2 / |(b-a) x (c-a)|^2` (more accurate than `1 - R^2` near 0);
/// - obtuse triangle: the midpoint of the longest edge, `d_min^2 = |x_j + x_k|^2 / 4`.
/// Both branches agree with their first derivatives on right triangles. The result is
/// `+inf` (or not finite) when the triangle reaches a hemisphere; callers must reject it.
/// The points must lie on the unit sphere.
template <class Number>
Number inverse_squared_d_min(const Chord_triangle<Number>& t)
{
  const int obtuse = t.obtuse_vertex();
  if(obtuse >= 0)
    return inverse(t.squared_midpoint_norm(obtuse));
  const Number det = t.determinant();
  return t.squared_double_area() * inverse(det * det);
}

/// \ingroup PkgSphericalParameterizationEnergies
/// `d_min^2` itself, for reports and tests (values only).
inline double squared_d_min(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return 1.0 / inverse_squared_d_min(Chord_triangle<double>(a, b, c));
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_D_MIN_CORRECTION_H
