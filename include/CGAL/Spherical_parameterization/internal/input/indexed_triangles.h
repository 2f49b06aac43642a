// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INDEXED_TRIANGLES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INDEXED_TRIANGLES_H

#include <CGAL/assertions.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <array>
#include <boost/graph/graph_traits.hpp>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A point or vector of any CGAL kernel as an Eigen vector.
template <class Point>
Eigen::Vector3d to_eigen(const Point& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

/// A triangle mesh as arrays: its vertices in the order of `vertices(tm)`, and its faces in
/// the order of `faces(tm)` as indices into them, each corner in the order of
/// `vertices_around_face(halfedge(f, tm), tm)`. Per-vertex values are read by walking
/// `vertices`, so that every array the package builds from a mesh shares this numbering.
template <class TriangleMesh>
struct Indexed_triangles
{
  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// \pre every face of `tm` is a triangle
template <class TriangleMesh>
Indexed_triangles<TriangleMesh> indexed_triangles(const TriangleMesh& tm)
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  Indexed_triangles<TriangleMesh> mesh;
  std::unordered_map<vertex_descriptor, int> index;
  for(vertex_descriptor v : vertices(tm)) {
    index.emplace(v, int(mesh.vertices.size()));
    mesh.vertices.push_back(v);
  }
  mesh.triangles.reserve(num_faces(tm));
  for(auto f : faces(tm)) {
    std::array<int, 3> t{{0, 0, 0}};
    int k = 0;
    for(vertex_descriptor v : vertices_around_face(halfedge(f, tm), tm)) {
      if(k < 3)  // never write past the triangle, even with preconditions disabled
        t[k] = index.at(v);
      ++k;
    }
    CGAL_precondition(k == 3);
    mesh.triangles.push_back(t);
  }
  return mesh;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_INDEXED_TRIANGLES_H
