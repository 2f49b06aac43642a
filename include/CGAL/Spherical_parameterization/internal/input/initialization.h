// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INITIALIZATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INITIALIZATION_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>

#include <cmath>
#include <optional>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Central projection of the soup's points about `center` onto the unit sphere
/// (the paper's initial guess, Section 3). Empty if a point coincides with the centre.
inline std::optional<Points> central_projection(const Points& points, const Eigen::Vector3d& center)
{
  Points x(points.size());
  for(std::size_t v = 0; v < points.size(); ++v) {
    const Eigen::Vector3d d = points[v] - center;
    const double norm = d.norm();
    if(!(norm > 0) || !std::isfinite(norm))
      return std::nullopt;
    x[v] = d / norm;
  }
  return x;
}

/// The winding number of the soup's surface around `center`: the degree of its central
/// projection about that point. It is 1 exactly when the point lies inside the volume.
inline double winding_number(const Triangle_soup& soup, const Eigen::Vector3d& center)
{
  const auto x = central_projection(soup.points, center);
  if(!x)
    return 0;
  return degree(soup.faces, *x);
}

/// A centre inside the volume for the central projection: the area centroid (the paper's
/// choice, the origin of the soup) when it lies inside, else the inside point among the
/// vertex centroid and the midpoints of the inward normal segments of sample vertices
/// that is farthest from the surface's vertices. Empty if no candidate is inside.
inline std::optional<Eigen::Vector3d> interior_center(const Triangle_soup& soup)
{
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  if(std::abs(winding_number(soup, origin) - 1) < 0.5)
    return origin;

  std::vector<Eigen::Vector3d> candidates;
  Eigen::Vector3d vertex_centroid = Eigen::Vector3d::Zero();
  for(const auto& p : soup.points) vertex_centroid += p;
  candidates.push_back(vertex_centroid / double(soup.points.size()));

  // Inward vertex normals, and points at several depths along them.
  Points normal(soup.points.size(), Eigen::Vector3d::Zero());
  for(const auto& t : soup.faces) {
    const Eigen::Vector3d n = (soup.points[t[1]] - soup.points[t[0]]).cross(soup.points[t[2]] - soup.points[t[0]]);
    for(int i : t) normal[i] += n;
  }
  const std::size_t samples = 64, stride = std::max<std::size_t>(1, soup.points.size() / samples);
  for(std::size_t v = 0; v < soup.points.size(); v += stride) {
    if(!(normal[v].norm() > 0)) continue;
    for(double depth : {0.05, 0.1, 0.2, 0.4})
      candidates.push_back(soup.points[v] - depth * normal[v].normalized());
  }

  std::optional<Eigen::Vector3d> best;
  double best_clearance = 0;
  for(const auto& c : candidates) {
    if(std::abs(winding_number(soup, c) - 1) >= 0.5) continue;
    double clearance = std::numeric_limits<double>::infinity();
    for(const auto& p : soup.points) clearance = std::min(clearance, (p - c).squaredNorm());
    if(clearance > best_clearance) { best_clearance = clearance; best = c; }
  }
  return best;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INITIALIZATION_H
