// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TRIANGLE_SOUP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TRIANGLE_SOUP_H

#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

using Points = std::vector<Eigen::Vector3d>;
using Faces = std::vector<std::array<int, 3>>;

/// The input mesh as arrays, the form the solver works on. Faces are oriented outward
/// (the input's inward-oriented faces are reversed and `inward` remembers it) and the
/// points are centred at the area centroid and scaled to total area `4 pi`, so that energies
/// mixing lengths and areas do not depend on the model's size.
struct Triangle_soup
{
  Points points;
  Faces faces;
  bool inward = false;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< of the input, before scaling
  double scale = 1;                                    ///< input length * scale = soup length
  /// For a coarse level of the input: the input area each face stands for, which replaces
  /// its own area in the energies; empty for the input itself.
  std::vector<double> represented_areas;

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_faces() const { return faces.size(); }

  double face_area(std::size_t f) const
  {
    const auto& t = faces[f];
    return 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
  }

  /// The triangle the energies compare face `f` with: its own shape, with the area it
  /// stands for.
  Reference_triangle reference_triangle(std::size_t f) const
  {
    const auto& t = faces[f];
    Reference_triangle r(points[t[0]], points[t[1]], points[t[2]]);
    if(!represented_areas.empty())
      r.area = represented_areas[f];
    return r;
  }
};

/// Builds the soup from input points and faces as the user oriented them.
inline Triangle_soup make_triangle_soup(Points points, Faces faces)
{
  Triangle_soup soup;
  // First into the unit box, so that areas neither underflow nor overflow (inputs from
  // 1e-150 to 1e150 in size): input = box_center + box_size * p.
  Eigen::Vector3d low = points.front(), high = points.front();
  for(const auto& p : points) { low = low.cwiseMin(p); high = high.cwiseMax(p); }
  const Eigen::Vector3d box_center = 0.5 * low + 0.5 * high;
  const double box_size = std::max((0.5 * high - 0.5 * low).maxCoeff(), std::numeric_limits<double>::min());
  for(auto& p : points)
    p = (p - box_center) / box_size;

  double area = 0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for(const auto& t : faces) {
    const double a = 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
    area += a;
    weighted += a * (points[t[0]] + points[t[1]] + points[t[2]]) / 3;
  }
  const Eigen::Vector3d centroid = weighted / area;
  const double scale = std::sqrt(4 * M_PI / area);
  for(auto& p : points)
    p = (p - centroid) * scale;
  soup.centroid = box_center + box_size * centroid;
  soup.scale = scale / box_size;

  double volume = 0;  // six times the signed volume enclosed by the faces
  for(const auto& t : faces)
    volume += points[t[0]].dot(points[t[1]].cross(points[t[2]]));
  soup.inward = volume < 0;
  if(soup.inward)
    for(auto& t : faces)
      std::swap(t[1], t[2]);
  soup.points = std::move(points);
  soup.faces = std::move(faces);
  return soup;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TRIANGLE_SOUP_H
