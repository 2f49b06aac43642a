// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ADD_TRIANGLES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ADD_TRIANGLES_H

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <Eigen/Core>

#include <array>
#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Appends the triangles `faces` over `points` to `out` (a `MutableFaceGraph`), reversed if
/// `reverse`, and returns the new vertices in the order of `points`. Returns an empty vector
/// if `out` refuses a face (the triangles do not form an oriented 2-manifold).
template <class PolygonMesh>
std::vector<typename boost::graph_traits<PolygonMesh>::vertex_descriptor>
add_triangles(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& faces, bool reverse,
              PolygonMesh& out)
{
  using vertex_descriptor = typename boost::graph_traits<PolygonMesh>::vertex_descriptor;
  using Point = typename boost::property_traits<
    typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>::value_type;
  auto vpm = get(CGAL::vertex_point, out);
  std::vector<vertex_descriptor> vertices;
  vertices.reserve(points.size());
  for(const Eigen::Vector3d& p : points) {
    const vertex_descriptor v = add_vertex(out);
    put(vpm, v, Point(p.x(), p.y(), p.z()));
    vertices.push_back(v);
  }
  for(const std::array<int, 3>& t : faces) {
    const std::array<vertex_descriptor, 3> corners{
      {vertices[t[0]], reverse ? vertices[t[2]] : vertices[t[1]], reverse ? vertices[t[1]] : vertices[t[2]]}};
    if(CGAL::Euler::add_face(corners, out) == boost::graph_traits<PolygonMesh>::null_face())
      return {};
  }
  return vertices;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ADD_TRIANGLES_H
