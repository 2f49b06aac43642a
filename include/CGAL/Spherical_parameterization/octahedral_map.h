// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_OCTAHEDRAL_MAP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_OCTAHEDRAL_MAP_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

// The octahedral parameterization of the sphere of Praun and Hoppe (2003), "Spherical
// parametrization and remeshing": the sphere is mapped onto the octahedron
// `|x| + |y| + |z| = 1`, and the octahedron is cut along its four lower edges and unfolded
// onto the square `[-1, 1]^2`:
// - the upper half (`z >= 0`) fills the inner diamond `|u| + |v| <= 1`, with `(u, v) = (x, y)`;
// - each lower face (`z < 0`) fills the corner triangle of its quadrant, folded outward over
//   the diamond's edge: `(u, v) = (sign(x) (1 - |y|), sign(y) (1 - |x|))`;
// - the north pole is the centre, the four equatorial vertices of the octahedron are the
//   midpoints of the square's sides, and the south pole is all four corners.
//
// The sphere goes to the octahedron by central projection (`x / (|x| + |y| + |z|)`), as in
// octahedral normal encoding: simple, exactly invertible and cheap, though not area
// preserving: a cell at the centre of an octahedron face covers 3 sqrt(3) ~ 5.2 times the
// solid angle of a cell at a vertex (the density of the central projection is cos / r^2). The
// map is continuous inside the square and creased along the fold lines: the diamond's edges
// and the two axes. Each side of the square is glued to itself mirrored about its midpoint:
// `(1, v)` and `(1, -v)` are the same point of the sphere, and so on.
//
// Both functions work on `double` and never divide by zero for a nonzero direction.

/// \ingroup PkgSphericalParameterizationRef
/// The point of `[-1, 1]^2` onto which the octahedral map sends the direction `d` (any
/// nonzero length). Points on the cut (the lower half of the planes `x = 0` and `y = 0`)
/// go to the side with a positive sign.
inline Eigen::Vector2d sphere_to_octahedral_square(const Eigen::Vector3d& d)
{
  const Eigen::Vector3d q = d / d.lpNorm<1>();
  if(q.z() >= 0)
    return Eigen::Vector2d(q.x(), q.y());
  const double sign_x = q.x() >= 0 ? 1 : -1, sign_y = q.y() >= 0 ? 1 : -1;
  return Eigen::Vector2d(sign_x * (1 - std::abs(q.y())), sign_y * (1 - std::abs(q.x())));
}

/// \ingroup PkgSphericalParameterizationRef
/// The unit vector of the sphere at the point `s` of `[-1, 1]^2` of the octahedral map; the
/// inverse of `sphere_to_octahedral_square()`. Points outside the square are clamped onto it.
inline Eigen::Vector3d octahedral_square_to_sphere(const Eigen::Vector2d& s)
{
  const double u = std::clamp(s.x(), -1.0, 1.0), v = std::clamp(s.y(), -1.0, 1.0);
  const double z = 1 - std::abs(u) - std::abs(v);
  Eigen::Vector3d q(u, v, z);
  if(z < 0) {
    q.x() = (u >= 0 ? 1 : -1) * (1 - std::abs(v));
    q.y() = (v >= 0 ? 1 : -1) * (1 - std::abs(u));
  }
  return q.normalized();
}

/// \ingroup PkgSphericalParameterizationRef
/// The point of `[-1, 1]^2` that the point `s` of the plane stands for when the octahedral
/// square is continued beyond its sides by its own symmetries: the point reflections about
/// the midpoints of the sides, which glue each side to itself mirrored (`(1 + a, v)` stands for
/// `(1 - a, -v)`), and from them the translations by `(+-2, +-2)` around the corners. Texture
/// coordinates of faces across the cut of the octahedron lie on such continuations
/// (`texture_coordinates.h`); a texture with a margin can be filled through this function.
inline Eigen::Vector2d fold_into_octahedral_square(Eigen::Vector2d s)
{
  for(int reflections = 0; reflections < 64 && (std::abs(s.x()) > 1 || std::abs(s.y()) > 1); ++reflections) {
    if(s.x() > 1) s = Eigen::Vector2d(2 - s.x(), -s.y());
    else if(s.x() < -1) s = Eigen::Vector2d(-2 - s.x(), -s.y());
    else if(s.y() > 1) s = Eigen::Vector2d(-s.x(), 2 - s.y());
    else s = Eigen::Vector2d(-s.x(), -2 - s.y());
  }
  return s;
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_OCTAHEDRAL_MAP_H
