// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_TRIANGLE_SOUP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_TRIANGLE_SOUP_H

#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

using Points = std::vector<Eigen::Vector3d>;
using Faces = std::vector<std::array<int, 3>>;

/// The area of a triangle with edge lengths `l`, by Kahan's form of Heron's formula,
/// accurate for needles; 0 if the lengths break the triangle inequalities.
inline double triangle_area(const std::array<double, 3>& l)
{
  std::array<double, 3> s = l;
  std::sort(s.begin(), s.end(), std::greater<double>());
  const double product = (s[0] + (s[1] + s[2])) * (s[2] - (s[0] - s[1])) * (s[2] + (s[0] - s[1])) * (s[0] + (s[1] - s[2]));
  return 0.25 * std::sqrt(std::max(product, 0.0));
}

/// The height of a triangle with edge lengths `l` over its longest edge, relative to that edge.
inline double relative_height(const std::array<double, 3>& l)
{
  const double longest = std::max({l[0], l[1], l[2]});
  return 2 * triangle_area(l) / (longest * longest);
}

/// The triangle of the plane with edge lengths `l` (edge `i` opposite vertex `i`), which
/// satisfy the triangle inequalities.
inline Reference_triangle planar_triangle(const std::array<double, 3>& l)
{
  const double along = (l[2] * l[2] + l[1] * l[1] - l[0] * l[0]) / (2 * l[2]);  // vertex 2 over edge 0-1
  return Reference_triangle(Eigen::Vector3d::Zero(), Eigen::Vector3d(l[2], 0, 0),
                            Eigen::Vector3d(along, 2 * triangle_area(l) / l[2], 0));
}

/// The smallest `relative_height()` of a reference triangle (`mollified_triangle()`).
constexpr double minimum_relative_height = 0.02;

/// The triangle `(p, q, r)`, or, if its height over its longest edge is under
/// `minimum_relative_height` of that edge, the planar triangle whose edge lengths are its own
/// plus the smallest length that gives it that height: Sharp and Crane's intrinsic
/// mollification (2020), per face. Nearly degenerate input faces (needles by near-duplicate
/// vertices, slivers) otherwise give the area and MIPS terms weights of 1e10 and more, against
/// which the solver finds no valid map; with the minimum height, the map is valid at about the
/// energy of the mesh without them.
/// - Per face, not one length added to every edge of the mesh as they do: the energies sum
///   terms of each face with its own reference triangle, so lengths need not agree between
///   faces, and small fair faces of a graded mesh stay as they are.
/// - A minimum height, not their minimum margin in the triangle inequalities: a margin leaves
///   needles far lower than slivers, and their tiny area still raises their barrier's
///   activation (`Fold_barrier::face_activation()`) and pushes protrusions open, so that the
///   solve is slow to converge or does not.
/// Faces with that height keep their exact shape.
inline Reference_triangle mollified_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r)
{
  // The test on the face's own area and squared lengths, no more square roots for the fair
  // faces, nearly all, built at every stage: they cost about what the plain triangle costs,
  // less than Heron's formula first.
  Reference_triangle own(p, q, r);
  const double longest_squared = std::max({(q - r).squaredNorm(), (r - p).squaredNorm(), (p - q).squaredNorm()});
  if(2 * own.area >= minimum_relative_height * longest_squared)
    return own;
  const std::array<double, 3> l{(q - r).norm(), (r - p).norm(), (p - q).norm()};
  auto added = [&l](double length) { return std::array<double, 3>{l[0] + length, l[1] + length, l[2] + length}; };
  // The height grows with the added length; adding the longest edge makes every edge at
  // least half the longest, a fat triangle (relative height over 0.4).
  double thin = 0, fat = std::max({l[0], l[1], l[2]});
  for(int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (thin + fat);
    (relative_height(added(middle)) < minimum_relative_height ? thin : fat) = middle;
  }
  return planar_triangle(added(fat));
}

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
  /// The local scale of each input vertex (`local_scales()`) for `area_floor()`; empty: no
  /// floor.
  std::vector<double> vertex_scales;

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_faces() const { return faces.size(); }

  double face_area(std::size_t f) const
  {
    const auto& t = faces[f];
    return 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
  }

  /// The triangle the energies compare face `f` with: its own shape, made a little fatter if
  /// it is nearly degenerate (`mollified_triangle()`), with the area it stands for. A face
  /// whose three points coincide has no length to mollify: it stands for an equilateral
  /// triangle of the largest local scale at its vertices, as its neighbours see it.
  Reference_triangle reference_triangle(std::size_t f) const
  {
    const auto& t = faces[f];
    Reference_triangle r = mollified_triangle(points[t[0]], points[t[1]], points[t[2]]);
    if(!(r.area > 0) && !vertex_scales.empty()) {
      const double side = std::max({vertex_scales[t[0]], vertex_scales[t[1]], vertex_scales[t[2]]});
      r = planar_triangle({side, side, side});
    }
    if(!represented_areas.empty())
      r.area = represented_areas[f];
    r.area_floor = area_floor(f);
    return r;
  }

  /// The `Reference_triangle::area_floor` of face `f`: `area_floor_share` of the square of the
  /// largest local scale at its vertices. Isosurfaces (marching cubes or tetrahedra) have a
  /// cluster of near-coincident vertices wherever the surface passes close to a grid point:
  /// faces of 1e-6 to 1e-13 of the mean area among needles, which the mollification makes fat.
  /// Those needles want the cluster's image opened, the area energy without a floor wants the
  /// tiny faces' images tiny, and Combined then finds no valid map on most such meshes (see
  /// doc/DESIGN.md). The local scale is the mean edge at a vertex, not the longest: a small fair
  /// face next to a long edge keeps its area, and ordinary meshes have few faces floored.
  double area_floor(std::size_t f) const
  {
    if(vertex_scales.empty())
      return 0;
    const auto& t = faces[f];
    const double scale = std::max({vertex_scales[t[0]], vertex_scales[t[1]], vertex_scales[t[2]]});
    return area_floor_share * scale * scale;
  }

  static constexpr double area_floor_share = 3e-3;
};

/// The local scale of each vertex: the mean length of its edges (each edge counted once per
/// face), raised to at least half of each neighbour's scale. The vertices inside a cluster of
/// near-coincident vertices have only tiny edges; from the cluster's rim inwards their scale
/// then halves at each edge instead of falling to the tiny edges' length, which would leave
/// the faces inside clusters their tiny area targets and no valid map.
inline std::vector<double> local_scales(const Points& points, const Faces& faces)
{
  std::vector<double> scale(points.size(), 0.0);
  std::vector<int> count(points.size(), 0);
  for(const auto& t : faces)
    for(int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      const double length = (points[a] - points[b]).norm();
      scale[a] += length;
      scale[b] += length;
      ++count[a];
      ++count[b];
    }
  for(std::size_t v = 0; v < points.size(); ++v)
    scale[v] /= std::max(count[v], 1);
  // Largest first, as in Dijkstra's algorithm: a vertex's scale is final when it is popped.
  // Only the vertices that raise a neighbour start it (none on most meshes: nothing more to
  // do); a path through a vertex they do not raise is never the largest.
  std::priority_queue<std::pair<double, int>> queue;
  for(const auto& t : faces)
    for(int i = 0; i < 3; ++i)
      for(const auto& [a, b] : {std::pair(t[i], t[(i + 1) % 3]), std::pair(t[(i + 1) % 3], t[i])})
        if(0.5 * scale[std::size_t(a)] > scale[std::size_t(b)])
          queue.emplace(scale[std::size_t(a)], a);
  if(queue.empty())
    return scale;
  // The neighbours of each vertex (each twice on a closed mesh), in `count`'s slots.
  std::vector<std::size_t> first(points.size() + 1, 0);
  for(std::size_t v = 0; v < points.size(); ++v)
    first[v + 1] = first[v] + std::size_t(count[v]);
  std::vector<int> neighbour(first.back());
  std::vector<std::size_t> filled(first.begin(), first.end() - 1);
  for(const auto& t : faces)
    for(int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      neighbour[filled[std::size_t(a)]++] = b;
      neighbour[filled[std::size_t(b)]++] = a;
    }
  while(!queue.empty()) {
    const auto [s, v] = queue.top();
    queue.pop();
    if(s < scale[std::size_t(v)])
      continue;  // a stale entry
    for(std::size_t k = first[std::size_t(v)]; k < first[std::size_t(v) + 1]; ++k) {
      const int w = neighbour[k];
      if(0.5 * s > scale[std::size_t(w)]) {
        scale[std::size_t(w)] = 0.5 * s;
        queue.emplace(0.5 * s, w);
      }
    }
  }
  return scale;
}

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
  soup.vertex_scales = local_scales(soup.points, soup.faces);
  return soup;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_TRIANGLE_SOUP_H
