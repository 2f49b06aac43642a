// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_KERNEL_PLACEMENT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_KERNEL_PLACEMENT_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/newton/tangent_basis.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The faces `(u, p, q)` around a vertex `u`, as the pairs `(p, q)`.
using Fan = std::vector<std::array<int, 2>>;

/// How well `x` sees the fan's far edges: the smallest `det(x, p, q) / |p - q|^2` over the
/// fan, the height of each face over its far edge relative to that edge (negative if some
/// face `(x, p, q)` is flipped).
inline double fan_clearance(const Eigen::Vector3d& x, const Points& points, const Fan& fan)
{
  double smallest = std::numeric_limits<double>::infinity();
  for(const auto& [p, q] : fan) {
    const Eigen::Vector3d &a = points[p], &b = points[q];
    const double det = x.dot((a - x).cross(b - x));
    smallest = std::min(smallest, det / (a - b).squaredNorm());
  }
  return smallest;
}

/// The area centroid of the convex polygon `{y : normal_i . y + offset_i > 0}` of the plane,
/// clipped to the square `|y|_inf <= bound`; false if the polygon is empty or flat.
inline bool convex_polygon_centroid(const std::vector<Eigen::Vector2d>& normals, const std::vector<double>& offsets,
                                    double bound, Eigen::Vector2d& centroid)
{
  std::vector<Eigen::Vector2d> polygon{{-bound, -bound}, {bound, -bound}, {bound, bound}, {-bound, bound}}, clipped;
  for(std::size_t i = 0; i < normals.size() && !polygon.empty(); ++i) {  // Sutherland-Hodgman
    clipped.clear();
    for(std::size_t k = 0; k < polygon.size(); ++k) {
      const Eigen::Vector2d &from = polygon[k], &to = polygon[(k + 1) % polygon.size()];
      const double s = normals[i].dot(from) + offsets[i], t = normals[i].dot(to) + offsets[i];
      if(s > 0) clipped.push_back(from);
      if((s > 0) != (t > 0)) clipped.push_back(from + (s / (s - t)) * (to - from));
    }
    polygon.swap(clipped);
  }
  if(polygon.size() < 3)
    return false;
  double area = 0;
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  for(std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d &a = polygon[0], &b = polygon[k], &c = polygon[(k + 1) % polygon.size()];
    const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    area += twice;
    weighted += twice * (a + b + c) / 3;
  }
  if(!(area > 0))
    return false;
  centroid = weighted / area;
  return centroid.allFinite();
}

/// Where the vertex `u` goes when a vertex split is undone: its ring's sphere points averaged
/// with Floater's mean value coordinates (2003) of `u` on the input surface, the corner angles
/// of the fan at `u` scaled to sum to `2 pi` (the geodesic polar map) and the input edge
/// lengths. They reproduce the input's local shape, which the ring's plain centre does not,
/// so that a fine level needs fewer Newton iterations. The weights, `tan(angle / 2)`, are
/// positive only while every angle is under `pi`: a fan with one corner of half its total
/// angle or more (a nearly flat pair of faces at a cone point, as marching cubes leave them)
/// would get a weight of either sign and any size, and the point could land anywhere, even
/// opposite its ring. Such a fan keeps its own angles, each a triangle's corner, under `pi`.
inline Eigen::Vector3d mean_value_point(int u, const Points& input, const Points& sphere, const Fan& fan)
{
  auto corner_angle = [&](int p, int q) {
    const Eigen::Vector3d a = input[p] - input[u], b = input[q] - input[u];
    return std::atan2(a.cross(b).norm(), a.dot(b));
  };
  double total_angle = 0, largest = 0;
  for(const auto& [p, q] : fan) {
    const double angle = corner_angle(p, q);
    total_angle += angle;
    largest = std::max(largest, angle);
  }
  const double polar_scale = 2 * M_PI / total_angle;
  const double scale = polar_scale * largest < M_PI ? polar_scale : 1.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for(const auto& [p, q] : fan) {  // each ring vertex is p of one face and q of another
    const double half_tangent = std::tan(0.5 * scale * corner_angle(p, q));
    sum += half_tangent * (sphere[p] / (input[p] - input[u]).norm() + sphere[q] / (input[q] - input[u]).norm());
  }
  return sum.normalized();
}

/// A point of the unit sphere inside the kernel of the fan: every face `(x, p, q)` positively
/// oriented. First `guess`: kept if it lies well inside. Otherwise the area centroid of the
/// kernel, computed in the gnomonic chart at `guess`, where the great circles through `p`
/// and `q` are lines and the kernel a convex polygon. Returns the better of the two by
/// `fan_clearance`; the caller checks that it is positive (the kernel can be empty).
/// Nearly degenerate input faces need no care here: their reference triangles are made fat
/// enough (`mollified_triangle()`) for a fat image to cost little.
inline Eigen::Vector3d place_in_kernel(const Points& points, const Fan& fan, const Eigen::Vector3d& guess)
{
  Eigen::Vector3d center = guess;
  if(!center.allFinite() || !(center.norm() > 0.5)) {
    center = Eigen::Vector3d::Zero();
    for(const auto& [p, q] : fan) center += points[p].cross(points[q]);
    center.normalize();
  }
  const double center_clearance = fan_clearance(center, points, fan);
  if(center_clearance > 0.05)  // well inside: a fair start for the solver
    return center;

  const Eigen::Matrix<double, 3, 2> basis = tangent_basis(center);
  std::vector<Eigen::Vector2d> normals;
  std::vector<double> offsets;
  for(const auto& [p, q] : fan) {
    Eigen::Vector3d n = points[p].cross(points[q]);
    n /= n.norm();  // a ring edge is never a pair of equal or antipodal points on a valid map
    normals.push_back(basis.transpose() * n);
    offsets.push_back(n.dot(center));
  }
  Eigen::Vector2d y;
  if(!convex_polygon_centroid(normals, offsets, 1e3, y))
    return center;
  const Eigen::Vector3d kernel_point = (center + basis * y).normalized();
  return fan_clearance(kernel_point, points, fan) > center_clearance ? kernel_point : center;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_KERNEL_PLACEMENT_H
