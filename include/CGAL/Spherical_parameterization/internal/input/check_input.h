// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_CHECK_INPUT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_CHECK_INPUT_H

#include <CGAL/Spherical_parameterization/Error_code.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Outcome of `check_input()`: the first failing check and a human-readable "where/what".
struct Input_report
{
  Error_code code = Error_code::OK;
  std::string detail;  ///< empty when `code == OK`
};

/// Coordinates beyond this are rejected: squaring them in the solver would overflow.
constexpr double max_input_coordinate = 1e150;

/// "1 border edge" / "12 border edges": details are read by users, so get plurals right.
inline std::string count_of(std::size_t n, const std::string& noun, const std::string& plural = std::string())
{
  return std::to_string(n) + " " + (n == 1 ? noun : plural.empty() ? noun + "s" : plural);
}

/// Numbers gathered by the structural pass. Indices are positions in `vertices(tm)` and
/// `faces(tm)` order, the only numbering every BGL graph has.
struct Mesh_census
{
  std::size_t vertices = 0, edges = 0, halfedges = 0, faces = 0;
  std::size_t border_halfedges = 0;

  std::size_t non_triangles = 0, non_triangle_example = 0, non_triangle_degree = 0;
  std::size_t isolated = 0, isolated_example = 0;
  std::size_t non_manifold = 0, non_manifold_example = 0;
  std::size_t non_manifold_fan = 0, non_manifold_degree = 0;  ///< halfedges in one fan / in all
};

template <class TriangleMesh>
void count_elements(const TriangleMesh& tm, Mesh_census& census)
{
  // std::distance and not num_*(): a Surface_mesh counts its removed elements in num_*().
  census.vertices = static_cast<std::size_t>(std::distance(vertices(tm).begin(), vertices(tm).end()));
  census.edges = static_cast<std::size_t>(std::distance(edges(tm).begin(), edges(tm).end()));
  census.halfedges = static_cast<std::size_t>(std::distance(halfedges(tm).begin(), halfedges(tm).end()));
  census.faces = static_cast<std::size_t>(std::distance(faces(tm).begin(), faces(tm).end()));
}

/// The halfedge rules of `is_valid_polygon_mesh()`, checked one halfedge at a time so that
/// later passes may circulate without looping forever. Returns an empty string when all hold.
template <class TriangleMesh>
std::string broken_halfedge_rule(const TriangleMesh& tm,
                                 typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  const auto null_h = GT::null_halfedge();
  if(next(h, tm) == null_h || prev(h, tm) == null_h || opposite(h, tm) == null_h)
    return "a null next, prev or opposite halfedge";
  if(halfedge(edge(h, tm), tm) != h)
    return "halfedge(edge(h)) != h";
  if(opposite(h, tm) == h || opposite(opposite(h, tm), tm) != h)
    return "an inconsistent opposite halfedge";
  if(prev(next(h, tm), tm) != h || next(prev(h, tm), tm) != h)
    return "inconsistent next and prev halfedges";
  if(target(h, tm) == GT::null_vertex())
    return "a null target vertex";
  if(target(h, tm) != target(opposite(next(h, tm), tm), tm))
    return "target(h) != source(next(h))";
  if(face(h, tm) != face(next(h, tm), tm))
    return "face(h) != face(next(h))";
  // Both sides null is a dangling edge, which no polygon mesh has.
  if(face(h, tm) == face(opposite(h, tm), tm))
    return "the same face (or no face) on both sides";
  if(next(h, tm) == h || next(next(h, tm), tm) == h || target(h, tm) == target(opposite(h, tm), tm) ||
     target(h, tm) == target(next(h, tm), tm) || target(h, tm) == target(next(next(h, tm), tm), tm))
    return "a cycle with fewer than 3 distinct vertices";
  return std::string();
}

/// Per-halfedge pass: the rules above, border halfedges, and how many halfedges point to
/// each vertex (compared with the fan sizes later to find non-manifold vertices).
template <class TriangleMesh, class CountMap>
bool check_halfedges(const TriangleMesh& tm, CountMap incoming, Mesh_census& census, std::string& detail)
{
  std::size_t index = 0;
  for(auto h : halfedges(tm)) {
    const std::string broken = broken_halfedge_rule(tm, h);
    if(!broken.empty()) {
      detail = "halfedge " + std::to_string(index) + " has " + broken;
      return false;
    }
    if(is_border(h, tm))
      ++census.border_halfedges;
    put(incoming, target(h, tm), get(incoming, target(h, tm)) + 1);
    ++index;
  }
  return true;
}

/// Walks every face cycle, recording its degree. The walks share one step budget, the number
/// of halfedges, so that a corrupted `next()` that never returns cannot make this hang or
/// go quadratic.
template <class TriangleMesh>
bool check_face_cycles(const TriangleMesh& tm, Mesh_census& census, std::string& detail)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  std::size_t budget = census.halfedges;
  std::size_t index = 0;
  for(auto f : faces(tm)) {
    const auto start = halfedge(f, tm);
    if(start == GT::null_halfedge() || face(start, tm) != f) {
      detail = "face " + std::to_string(index) + " has no halfedge on its boundary";
      return false;
    }
    std::size_t degree = 0;
    auto h = start;
    do {
      if(degree == budget || face(h, tm) != f) {
        detail = "the halfedge cycle of face " + std::to_string(index) + " is broken";
        return false;
      }
      ++degree;
      h = next(h, tm);
    } while(h != start);
    budget -= degree;
    if(degree != 3 && census.non_triangles++ == 0) {
      census.non_triangle_example = index;
      census.non_triangle_degree = degree;
    }
    ++index;
  }
  const std::size_t walked = census.halfedges - budget;
  if(walked + census.border_halfedges != census.halfedges) {
    detail = "some face has several halfedge cycles";
    return false;
  }
  return true;
}

/// Number of halfedges met circulating around the target of `start`, or 0 when the walk
/// leaves the vertex or has not closed after `limit` steps (only corrupted links do that).
template <class TriangleMesh>
std::size_t fan_size(const TriangleMesh& tm,
                     typename boost::graph_traits<TriangleMesh>::halfedge_descriptor start,
                     std::size_t limit)
{
  const auto v = target(start, tm);
  std::size_t size = 0;
  auto h = start;
  do {
    if(size == limit || target(h, tm) != v)
      return 0;
    ++size;
    h = opposite(next(h, tm), tm);
  } while(h != start);
  return size;
}

/// Compares, at each vertex, the halfedges pointing to it with those of the fan around
/// `halfedge(v)`. Fewer in the fan means several fans, i.e. a non-manifold vertex; this is
/// told apart from broken links, which `is_valid_polygon_mesh()` lumps together with it.
/// Each walk is bounded by the vertex's own halfedge count, so the pass is linear.
template <class TriangleMesh, class CountMap>
bool check_vertex_fans(const TriangleMesh& tm, CountMap incoming, Mesh_census& census, std::string& detail)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  std::size_t pointed = 0;  // halfedges whose target is a listed vertex
  std::size_t index = 0;
  for(auto v : vertices(tm)) {
    const std::size_t in = get(incoming, v);
    pointed += in;
    const auto h = halfedge(v, tm);
    if(h == GT::null_halfedge()) {
      if(in != 0) {
        detail = "vertex " + std::to_string(index) + " has no halfedge but is the target of " +
                 count_of(in, "halfedge");
        return false;
      }
      if(census.isolated++ == 0)
        census.isolated_example = index;
      ++index;
      continue;
    }
    const std::size_t fan = fan_size(tm, h, in);
    if(fan == 0) {
      detail = "the halfedges around vertex " + std::to_string(index) + " are broken";
      return false;
    }
    if(fan < in && census.non_manifold++ == 0) {
      census.non_manifold_example = index;
      census.non_manifold_fan = fan;
      census.non_manifold_degree = in;
    }
    ++index;
  }
  if(pointed != census.halfedges) {
    detail = "some halfedges point to a vertex not in vertices(tm)";
    return false;
  }
  return true;
}

/// Validity in the sense of `is_valid_polygon_mesh()`, except that isolated and
/// non-manifold vertices are only counted: they get their own, more helpful, error codes.
template <class TriangleMesh>
bool check_structure(const TriangleMesh& tm, Mesh_census& census, std::string& detail)
{
  auto incoming = get(CGAL::dynamic_vertex_property_t<std::size_t>(), tm);
  for(auto v : vertices(tm))
    put(incoming, v, std::size_t(0));
  if(!check_halfedges(tm, incoming, census, detail) || !check_face_cycles(tm, census, detail) ||
     !check_vertex_fans(tm, incoming, census, detail))
    return false;
  // When nothing was deferred CGAL's own check must agree; it is safe to run now that
  // every cycle is known to close.
  if(census.isolated == 0 && census.non_manifold == 0 && !CGAL::is_valid_polygon_mesh(tm)) {
    detail = "CGAL::is_valid_polygon_mesh() failed";
    return false;
  }
  return true;
}

inline bool is_finite_point(const Eigen::Vector3d& p)
{
  for(double x : {p.x(), p.y(), p.z()})
    if(!std::isfinite(x) || std::abs(x) > max_input_coordinate)
      return false;
  return true;
}

/// `coordinates(v)`: the point of vertex `v` as an `Eigen::Vector3d`.
template <class TriangleMesh, class Coordinates>
Input_report check_finite(const TriangleMesh& tm, const Coordinates& coordinates)
{
  std::size_t bad = 0, example = 0, index = 0;
  for(auto v : vertices(tm)) {
    if(!is_finite_point(coordinates(v)) && bad++ == 0)
      example = index;
    ++index;
  }
  if(bad == 0)
    return Input_report();
  return {Error_code::NON_FINITE_INPUT,
          "vertex " + std::to_string(example) + " has a non-finite coordinate or one larger than 1e150 (" +
              count_of(bad, "such vertex", "such vertices") + ")"};
}

template <class TriangleMesh>
std::size_t count_border_edges(const TriangleMesh& tm)
{
  std::size_t border = 0;
  for(auto e : edges(tm))
    if(CGAL::is_border(e, tm))
      ++border;
  return border;
}

/// Number of face components, by a depth-first search across edges. Only called on closed
/// manifold meshes, where edge-connected and vertex-connected components are the same.
template <class TriangleMesh>
std::size_t count_components(const TriangleMesh& tm)
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  auto seen = get(CGAL::dynamic_face_property_t<bool>(), tm);
  for(auto f : faces(tm))
    put(seen, f, false);
  std::size_t components = 0;
  std::vector<face_descriptor> stack;
  for(auto seed : faces(tm)) {
    if(get(seen, seed))
      continue;
    ++components;
    put(seen, seed, true);
    stack.push_back(seed);
    while(!stack.empty()) {
      const face_descriptor f = stack.back();
      stack.pop_back();
      for(auto h : halfedges_around_face(halfedge(f, tm), tm)) {
        const face_descriptor g = face(opposite(h, tm), tm);
        if(!get(seen, g)) {
          put(seen, g, true);
          stack.push_back(g);
        }
      }
    }
  }
  return components;
}

/// A surface without area: every triangle has zero area, decided exactly (filtered predicate)
/// on the double coordinates (a repeated point is the collinear case with two equal points).
/// Single zero-area faces are fine: their reference triangles are mollified
/// (`Triangle_soup::reference_triangle()`), but a mesh without area has no scale to map.
template <class TriangleMesh, class Coordinates>
Input_report check_has_area(const TriangleMesh& tm, const Coordinates& coordinates)
{
  const auto point = [&](auto v) {
    const Eigen::Vector3d p = coordinates(v);
    return Epick::Point_3(p.x(), p.y(), p.z());
  };
  for(auto f : faces(tm)) {
    const auto h = halfedge(f, tm);
    if(!CGAL::collinear(point(target(h, tm)), point(target(next(h, tm), tm)), point(target(prev(h, tm), tm))))
      return Input_report();
  }
  return {Error_code::DEGENERATE_INPUT, "every face has zero area (collinear or repeated points)"};
}

/// Checks, in this order, that `tm` is a non-empty valid triangle mesh with finite
/// coordinates, no isolated vertex, no border, only manifold vertices, one component,
/// genus 0 and some area: the input a spherical parameterization needs.
/// Linear time plus hashing (for graphs without index-based descriptors); never loops on
/// corrupted halfedge structures. `detail` says where the first failing check failed.
/// `coordinates(v)`: the point of vertex `v` as an `Eigen::Vector3d` (`point_coordinates()`).
template <class TriangleMesh, class Coordinates>
Input_report check_input(const TriangleMesh& tm, const Coordinates& coordinates)
{
  Mesh_census census;
  count_elements(tm, census);
  if(census.faces == 0)
    return {Error_code::EMPTY_MESH, "the mesh has no face (" + count_of(census.vertices, "vertex", "vertices") + ")"};
  if(census.vertices == 0)
    return {Error_code::EMPTY_MESH, "the mesh has no vertex"};

  std::string detail;
  if(!check_structure(tm, census, detail))
    return {Error_code::INVALID_MESH, detail};

  if(census.non_triangles != 0)
    return {Error_code::NOT_TRIANGLE_MESH,
            "face " + std::to_string(census.non_triangle_example) + " has " +
                count_of(census.non_triangle_degree, "vertex", "vertices") + " (" +
                count_of(census.non_triangles, "non-triangular face") +
                " in total); the CLI option --triangulate can fix it"};

  Input_report report = check_finite(tm, coordinates);
  if(report.code != Error_code::OK)
    return report;

  if(census.isolated != 0)
    return {Error_code::ISOLATED_VERTICES,
            count_of(census.isolated, "isolated vertex", "isolated vertices") + ", e.g. vertex " +
                std::to_string(census.isolated_example)};

  const std::size_t border = count_border_edges(tm);
  if(border != 0)
    return {Error_code::NOT_CLOSED, count_of(border, "border edge")};

  if(census.non_manifold != 0)
    return {Error_code::NON_MANIFOLD,
            "vertex " + std::to_string(census.non_manifold_example) +
                " is non-manifold (its faces form several fans: one has " +
                std::to_string(census.non_manifold_fan) + " of its " +
                count_of(census.non_manifold_degree, "halfedge") + "; " +
                count_of(census.non_manifold, "non-manifold vertex", "non-manifold vertices") + " in total)"};

  const std::size_t components = count_components(tm);
  if(components != 1)
    return {Error_code::NOT_CONNECTED, count_of(components, "connected component")};

  const long long chi = static_cast<long long>(census.vertices) - static_cast<long long>(census.edges) +
                        static_cast<long long>(census.faces);
  if(chi != 2)
    return {Error_code::NOT_GENUS_ZERO,
            "genus " + std::to_string((2 - chi) / 2) + " (Euler characteristic " + std::to_string(chi) + ")"};

  return check_has_area(tm, coordinates);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_CHECK_INPUT_H
