// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_LOCALITY_ORDER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_LOCALITY_ORDER_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// The bits of `x` (21 of them) spread to every third bit, for a 3D Morton code.
inline std::uint64_t spread_bits(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffff;
  x = (x | x << 16) & 0x1f0000ff0000ff;
  x = (x | x << 8) & 0x100f00f00f00f00f;
  x = (x | x << 4) & 0x10c30c30c30c30c3;
  x = (x | x << 2) & 0x1249249249249249;
  return x;
}

/// The vertices in the order of a Z-order (Morton) curve through their bounding box, 2^21
/// cells per axis: `order[k]` is the vertex that comes k-th. Points that share a cell keep
/// their relative order.
inline std::vector<int> z_order(const Points& points)
{
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  if(points.empty())
    return order;
  Eigen::Vector3d low = points.front(), high = points.front();
  for(const auto& p : points) { low = low.cwiseMin(p); high = high.cwiseMax(p); }
  const double extent = (high - low).maxCoeff();
  const double cells = extent > 0 ? double(0x1fffff) / extent : 0;
  std::vector<std::uint64_t> key(points.size());
  for(std::size_t v = 0; v < points.size(); ++v) {
    const Eigen::Vector3d cell = (points[v] - low) * cells;
    key[v] = spread_bits(std::uint64_t(cell.x())) | spread_bits(std::uint64_t(cell.y())) << 1 |
             spread_bits(std::uint64_t(cell.z())) << 2;
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

/// Renumbers a mesh so that neighbours are near each other in memory: the vertices along
/// `z_order()`, each triangle turned (its orientation kept) to start at its smallest new
/// index, and the triangles sorted. Input meshes come in any order (a subdivided mesh appends
/// its new vertices at the end), and the hierarchy of a renumbered mesh builds in about half
/// the time. The numbering depends on the points and the faces only, not on the order they
/// came in (but for coincident points), so neither does the map. `vertices` (the caller's
/// per-vertex data) is permuted with `points`.
template <class Vertex>
void order_by_locality(std::vector<Vertex>& vertices, Points& points, Faces& triangles)
{
  const std::vector<int> order = z_order(points);
  std::vector<int> new_index(points.size());
  for(std::size_t k = 0; k < order.size(); ++k)
    new_index[order[k]] = int(k);
  Points ordered_points(points.size());
  std::vector<Vertex> ordered_vertices(vertices.size());
  for(std::size_t k = 0; k < order.size(); ++k) {
    ordered_points[k] = points[order[k]];
    ordered_vertices[k] = std::move(vertices[order[k]]);
  }
  points = std::move(ordered_points);
  vertices = std::move(ordered_vertices);
  for(auto& t : triangles) {
    for(int& v : t)
      v = new_index[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(triangles.begin(), triangles.end());
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_LOCALITY_ORDER_H
