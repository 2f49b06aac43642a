// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Nearly degenerate faces added to a closed mesh, as real inputs have them: slivers (CAD
// tessellations, cleaned scans) and near-duplicate vertices with their needles (welding
// leftovers). Used by the benchmark's MESH@sliversN and MESH@needlesN and by test_robustness.

#ifndef SPHERICAL_PARAMETERIZATION_BENCHMARK_MESH_DEFECTS_H
#define SPHERICAL_PARAMETERIZATION_BENCHMARK_MESH_DEFECTS_H

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <vector>

namespace mesh_defects {

/// `count` faces of `mesh`, chosen at random, each split in three at the point
/// `place(a, b, c)` of its corners.
template <class Point, class Random, class Place>
void split_faces(CGAL::Surface_mesh<Point>& mesh, int count, Random& random, const Place& place)
{
  std::vector<typename CGAL::Surface_mesh<Point>::Face_index> faces(mesh.faces().begin(), mesh.faces().end());
  std::shuffle(faces.begin(), faces.end(), random);
  for(int i = 0; i < count && i < int(faces.size()); ++i) {
    const auto h = mesh.halfedge(faces[i]);
    const Point a = mesh.point(mesh.source(h)), b = mesh.point(mesh.target(h)), c = mesh.point(mesh.target(mesh.next(h)));
    const auto v = mesh.target(CGAL::Euler::add_center_vertex(h, mesh));
    mesh.point(v) = place(a, b, c);
  }
}

/// Faces split at a point `height` (relative) above the midpoint of one of their edges: two
/// slivers of tiny area each.
template <class Point, class Random>
void add_slivers(CGAL::Surface_mesh<Point>& mesh, int count, double height, Random& random)
{
  split_faces(mesh, count, random, [height](const Point& a, const Point& b, const Point& c) {
    const Point middle = CGAL::midpoint(a, b);
    return middle + height * (c - middle);
  });
}

/// Faces `(a, b, c)` split at the point `a + distance (c - a) + off_edge (b - a)`: a
/// near-duplicate vertex and two needles. With `off_edge` 0 the point is on the edge `ac` but
/// for rounding, which may leave an exactly collinear face; with both 0 it is `a` itself, and
/// two faces have zero area.
template <class Point, class Random>
void add_needles(CGAL::Surface_mesh<Point>& mesh, int count, double distance, double off_edge, Random& random)
{
  split_faces(mesh, count, random, [=](const Point& a, const Point& b, const Point& c) {
    return a + distance * (c - a) + off_edge * (b - a);
  });
}

} // namespace mesh_defects

#endif // SPHERICAL_PARAMETERIZATION_BENCHMARK_MESH_DEFECTS_H
