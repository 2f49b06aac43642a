// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_REMESH_ON_ICOSPHERE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_REMESH_ON_ICOSPHERE_H

#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/internal/sphere/add_triangles.h>

#include <CGAL/assertions.h>
#include <CGAL/property_map.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// A geodesic icosphere (`make_icosphere()`): unit vectors and triangles indexing them,
/// oriented counterclockwise seen from outside.
struct Icosphere
{
  std::vector<Eigen::Vector3d> points;       ///< unit vectors
  std::vector<std::array<int, 3>> faces;     ///< triangles, as indices into `points`
};

/// \ingroup PkgSphericalParameterizationRef
/// The geodesic icosphere of subdivision level `level`: the regular icosahedron inscribed in
/// the unit sphere, whose triangles are split `level` times into four at their edge
/// midpoints, each new point pushed out onto the sphere. It has `20 * 4^level` faces and
/// `10 * 4^level + 2` vertices; the first 12 are the icosahedron's, and every level appends
/// the midpoints of its edges, so the points of a level are a prefix of those of the next.
/// \pre `0 <= level <= 12`
inline Icosphere make_icosphere(int level)
{
  CGAL_precondition(level >= 0 && level <= 12);
  const double t = (1 + std::sqrt(5.0)) / 2;  // the golden ratio: vertices (0, +-1, +-t) and their cyclic shifts
  Icosphere s;
  s.points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  s.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for(Eigen::Vector3d& p : s.points)
    p.normalize();
  for(int l = 0; l < level; ++l) {
    std::unordered_map<std::uint64_t, int> midpoint;  // shared by the two faces of an edge
    midpoint.reserve(s.faces.size() * 3 / 2);
    auto middle = [&s, &midpoint](int i, int j) {
      const auto ends = std::minmax(i, j);
      const auto inserted = midpoint.emplace((std::uint64_t(ends.first) << 32) | std::uint32_t(ends.second),
                                             int(s.points.size()));
      if(inserted.second)
        s.points.push_back((s.points[i] + s.points[j]).normalized());
      return inserted.first->second;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(4 * s.faces.size());
    for(const std::array<int, 3>& f : s.faces) {
      const int a = middle(f[0], f[1]), b = middle(f[1], f[2]), c = middle(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    s.faces = std::move(finer);
  }
  return s;
}

/// \ingroup PkgSphericalParameterizationRef
/// Resamples the surface of a sphere map on a geodesic icosphere: appends to `out` a mesh
/// with the connectivity of `make_icosphere(level)` whose vertex `i` is the point of the
/// input surface that the map sends to icosphere point `i` (`location.surface_point()`).
/// The faces keep the input's orientation. Writes each new vertex's icosphere point to
/// `out_sphere_map`, which is then a valid sphere map of `out`.
///
/// The result is close to the input when the map's stretch is moderate: its faces have
/// about equal area on the sphere, so the input is sampled densely where the map expands it
/// (small area ratio) and coarsely where it shrinks it.
///
/// \tparam PolygonMesh a model of `MutableFaceGraph` with an internal point property map
/// \tparam OutputSphereMap a writable property map `vertex_descriptor of PolygonMesh -> Point_3`
/// \return false if `out` refused a face (it then holds a partial mesh)
/// \pre `location.has_valid_map()` and `0 <= level <= 12`
template <class TriangleMesh, class GeomTraits, class PolygonMesh, class OutputSphereMap>
bool remesh_on_icosphere(const Sphere_point_location<TriangleMesh, GeomTraits>& location, int level,
                         PolygonMesh& out, OutputSphereMap out_sphere_map)
{
  using Sphere_point = typename boost::property_traits<OutputSphereMap>::value_type;
  const Icosphere icosphere = make_icosphere(level);
  std::vector<Eigen::Vector3d> surface_points;
  surface_points.reserve(icosphere.points.size());
  for(const Eigen::Vector3d& q : icosphere.points)
    surface_points.push_back(internal::to_eigen(location.surface_point(q)));
  const auto vertices = internal::add_triangles(surface_points, icosphere.faces, location.inward_oriented(), out);
  for(std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d& q = icosphere.points[i];
    put(out_sphere_map, vertices[i], Sphere_point(q.x(), q.y(), q.z()));
  }
  return vertices.size() == icosphere.points.size();
}

/// \ingroup PkgSphericalParameterizationRef
/// As above, without writing the sphere map of `out`.
template <class TriangleMesh, class GeomTraits, class PolygonMesh>
bool remesh_on_icosphere(const Sphere_point_location<TriangleMesh, GeomTraits>& location, int level,
                         PolygonMesh& out)
{
  using Point = typename boost::property_traits<
    typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>::value_type;
  using vertex_descriptor = typename boost::graph_traits<PolygonMesh>::vertex_descriptor;
  return remesh_on_icosphere(location, level, out, CGAL::Constant_property_map<vertex_descriptor, Point>());
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_REMESH_ON_ICOSPHERE_H
