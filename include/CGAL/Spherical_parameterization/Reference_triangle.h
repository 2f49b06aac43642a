// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_REFERENCE_TRIANGLE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_REFERENCE_TRIANGLE_H

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// An input triangle, after the whole mesh has been scaled to the sphere's area `4 pi`; for a
/// nearly degenerate one, a slightly fatter triangle of the plane (the user manual's
/// intrinsic mollification). Energies read their weights and areas from it (never from the
/// sphere points).
struct Reference_triangle
{
  std::array<Eigen::Vector3d, 3> points;  ///< the vertices, in the order of the face
  double area = 0;                        ///< the area, after scaling
  std::array<double, 3> angles{0, 0, 0};  ///< interior angle at each vertex, in radians
  /// The smallest input area that energies of area take for this triangle (0: none). The
  /// parameterizer sets 0.003 times the square of the local edge length, which exceeds `area`
  /// only on faces much smaller than the edges around them, such as the clusters of
  /// near-coincident vertices of isosurfaces (see the user manual): far tinier area targets
  /// make the area energy stiff enough to leave no valid map.
  double area_floor = 0;

  Reference_triangle() = default;
  /// The triangle `(p, q, r)`, with its area and angles.
  Reference_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r)
    : points{p, q, r}
  {
    area = 0.5 * (q - p).cross(r - p).norm();
    for(int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = points[(i + 1) % 3] - points[i], v = points[(i + 2) % 3] - points[i];
      angles[i] = std::atan2(u.cross(v).norm(), u.dot(v));
    }
  }

  /// `cot(angle_i) / 2` for edge `i` (opposite vertex `i`), the angle first clamped to
  /// `[min_angle, max_angle]`: the paper clamps to [5, 85] degrees so no weight is negative.
  std::array<double, 3> half_cotangents(double min_angle, double max_angle) const
  {
    std::array<double, 3> w;
    for(int i = 0; i < 3; ++i)
      w[i] = 0.5 / std::tan(std::clamp(angles[i], min_angle, max_angle));
    return w;
  }

  /// Exact `cot(angle_i) / 2`: `sum_i w_i |e_i|^2 = area * |J|_F^2` for the affine map `J`
  /// from this triangle to any other, non-negative whatever the angles.
  std::array<double, 3> exact_half_cotangents() const
  {
    std::array<double, 3> w;
    for(int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = points[(i + 1) % 3] - points[i], v = points[(i + 2) % 3] - points[i];
      w[i] = 0.5 * u.dot(v) / u.cross(v).norm();
    }
    return w;
  }
};

/// \ingroup PkgSphericalParameterizationEnergies
/// The per-face data of energies of the Jacobian (stretch, MIPS, untangling): the exact half
/// cotangents, with which `sum_i w_i |e_i|^2 = InputArea * |J|_F^2`, and the input area.
struct Jacobian_face_data
{
  std::array<double, 3> weights;  ///< `exact_half_cotangents()` of the input triangle
  double input_area;              ///< the area of the input triangle

  Jacobian_face_data() = default;
  /// The data of the input triangle `r`.
  explicit Jacobian_face_data(const Reference_triangle& r) : weights(r.exact_half_cotangents()), input_area(r.area) {}
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_REFERENCE_TRIANGLE_H
