// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VALIDITY_MAP_VALIDITY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VALIDITY_MAP_VALIDITY_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// `|det(a, b, c)|` below this makes a face degenerate (the validity contract of the package).
constexpr double degenerate_determinant = 1e-14;

/// Signed area of the spherical triangle (a, b, c) (Van Oosterom and Strackee 1983):
/// `tan(E / 2) = det(a, b, c) / (1 + a.b + b.c + c.a)`.
inline double signed_spherical_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  const double det = a.dot((b - a).cross(c - a));
  return 2 * std::atan2(det, 1 + a.dot(b) + b.dot(c) + c.dot(a));
}

/// The degree of the map `x` of the faces: the sum of their signed spherical areas over 4 pi.
/// 1 for a map onto the sphere that keeps the faces' orientation, 0 for one that folds back
/// onto itself, -1 for one that reverses it.
inline double degree(const Faces& faces, const Points& x)
{
  double area = 0;
  for(const auto& t : faces)
    area += signed_spherical_area(x[t[0]], x[t[1]], x[t[2]]);
  return area / (4 * M_PI);
}

/// The validity contract of the package (`Result`, `Distortion_report`): no flipped or
/// degenerate face, degree 1, every point on the unit sphere.
inline bool is_valid_map(std::size_t flipped, std::size_t degenerate, double degree, double max_norm_error)
{
  return flipped == 0 && degenerate == 0 && std::abs(degree - 1) < 1e-6 && max_norm_error <= 1e-12;
}

/// What makes a sphere map valid: every face positively oriented and the degree 1.
struct Map_validity
{
  std::size_t flipped = 0;     ///< faces with det < -1e-14
  std::size_t degenerate = 0;  ///< faces with |det| <= 1e-14
  double degree = 0;           ///< sum of signed spherical areas / 4 pi
  double max_norm_error = 0;   ///< max | |x| - 1 |
  bool finite = true;

  bool is_valid() const { return finite && is_valid_map(flipped, degenerate, degree, max_norm_error); }
};

/// Checks the map `x` of the soup (faces oriented outward).
inline Map_validity check_map(const Faces& faces, const Points& x)
{
  Map_validity v;
  for(const auto& p : x) {
    if(!p.allFinite()) { v.finite = false; continue; }
    v.max_norm_error = std::max(v.max_norm_error, std::abs(p.norm() - 1));
  }
  for(const auto& t : faces) {
    const Eigen::Vector3d &a = x[t[0]], &b = x[t[1]], &c = x[t[2]];
    const double det = a.dot((b - a).cross(c - a));
    if(!std::isfinite(det)) { v.finite = false; continue; }
    if(std::abs(det) <= degenerate_determinant) ++v.degenerate;
    else if(det < 0) ++v.flipped;
  }
  v.degree = degree(faces, x);
  return v;
}

/// The smallest area ratio of the map `x` of the soup: min over faces of the spherical
/// area's share of the sphere over the input area's share of the surface (both totals are
/// 4 pi in the soup). 1 for an equal-area map; near 0 where a map squeezes a region.
inline double min_area_ratio(const Triangle_soup& soup, const Points& x)
{
  double smallest = std::numeric_limits<double>::infinity();
  for(std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& t = soup.faces[f];
    smallest = std::min(smallest, signed_spherical_area(x[t[0]], x[t[1]], x[t[2]]) / soup.face_area(f));
  }
  return smallest;
}

/// True if the face `t` is flipped or degenerate.
inline bool is_bad_face(const std::array<int, 3>& t, const Points& x)
{
  const double det = x[t[0]].dot((x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]));
  return !(det > degenerate_determinant);
}

/// The number of faces that are flipped or degenerate: 0 for a fold-free map.
inline std::size_t count_bad_faces(const Faces& faces, const Points& x)
{
  std::size_t bad = 0;
  for(const auto& t : faces)
    bad += is_bad_face(t, x);
  return bad;
}

/// The faces that are flipped or degenerate.
inline std::vector<int> bad_faces(const Faces& faces, const Points& x)
{
  std::vector<int> bad;
  for(std::size_t f = 0; f < faces.size(); ++f)
    if(is_bad_face(faces[f], x))
      bad.push_back(int(f));
  return bad;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VALIDITY_MAP_VALIDITY_H
