// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_PROGRESSIVE_MESH_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_PROGRESSIVE_MESH_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A closed manifold triangle mesh as a corner table (Rossignac): corner `c = 3 f + k` is
/// vertex `k` of face `f`, and `opposite[c]` is the corner facing `c` across the edge opposite
/// to it. Compact, and a half-edge collapse only rewrites a few entries.
struct Corner_table
{
  std::vector<int> vertex;
  std::vector<int> opposite;
  std::vector<int> vertex_corner;  ///< one corner of each vertex

  static int next(int c) { return c % 3 == 2 ? c - 2 : c + 1; }
  static int previous(int c) { return c % 3 == 0 ? c + 2 : c - 1; }
  /// The corner of the same vertex in the neighbouring face (clockwise around the vertex).
  int swing(int c) const { return previous(opposite[previous(c)]); }

  Corner_table(const Faces& faces, std::size_t number_of_vertices)
  {
    const int corners = int(3 * faces.size());
    vertex.resize(corners);
    for(std::size_t f = 0; f < faces.size(); ++f)
      for(int k = 0; k < 3; ++k)
        vertex[3 * f + k] = faces[f][k];
    vertex_corner.assign(number_of_vertices, -1);
    for(int c = 0; c < corners; ++c)
      vertex_corner[vertex[c]] = c;

    // Corner c faces the directed edge next(c) -> previous(c); its opposite faces the reverse
    // edge. Bucket the corners by the source of their edge, then look the reverse up there.
    std::vector<int> start(number_of_vertices + 1, 0);
    for(int c = 0; c < corners; ++c)
      ++start[vertex[next(c)] + 1];
    for(std::size_t v = 0; v < number_of_vertices; ++v)
      start[v + 1] += start[v];
    std::vector<int> bucket(corners), fill(start.begin(), start.end() - 1);
    for(int c = 0; c < corners; ++c)
      bucket[fill[vertex[next(c)]]++] = c;
    opposite.assign(corners, -1);
    for(int c = 0; c < corners; ++c) {
      const int from = vertex[previous(c)], to = vertex[next(c)];
      for(int i = start[from]; i < start[from + 1]; ++i)
        if(vertex[previous(bucket[i])] == to) { opposite[c] = bucket[i]; break; }
    }
  }
};

/// One half-edge collapse `removed -> kept`, recorded so that it can be undone (a vertex
/// split): the two faces of the edge disappear, and the other faces of `removed` take `kept`
/// in its place at the corners listed in `Progressive_mesh::moved_corners()`.
struct Vertex_split
{
  int removed = -1;
  int kept = -1;
  std::array<int, 2> removed_faces{-1, -1};
  int first_moved_corner = 0, end_moved_corner = 0;  ///< range in `moved_corners()`
};

/// A progressive mesh (Hoppe 1996) built by half-edge collapses, so that every coarse vertex
/// is an input vertex at its input position, and a coarse-to-fine solve can insert the
/// vertices back one by one. Collapses are made in passes: each pass visits the vertices by
/// increasing cost and collapses those whose neighbourhood the pass has not touched yet, so
/// the vertices removed in one pass are independent (the ring of each is made of vertices that
/// survive the pass). The cost is the quadric error (Garland and Heckbert 1997) of moving the
/// removed vertex onto the kept one, plus a small edge length term so that flat regions are
/// decimated evenly. A collapse is refused when it would break the manifold (link condition),
/// turn a face's normal by more than about 80 degrees, make a needle, or raise a valence
/// above 12: the coarse levels are solved as meshes of their own and need fair triangles.
/// The geometric tests are skipped for a vertex nearly on top of its target
/// (`is_near_duplicate()`).
/// Passes over arrays rather than one global queue: on large meshes a heap of stale entries
/// no longer fits in the caches, and the passes are several times faster.
class Progressive_mesh
{
public:
  /// Collapses `soup` down to `target_vertices` vertices (at least 4), or as far as legal collapses go.
  Progressive_mesh(const Triangle_soup& soup, std::size_t target_vertices)
    : points_(&soup.points), faces_(soup.faces), mesh_(soup.faces, soup.points.size()),
      alive_(soup.points.size(), 1), face_alive_(soup.faces.size(), 1)
  {
    represented_area_.resize(soup.faces.size());
    for(std::size_t f = 0; f < soup.faces.size(); ++f)
      represented_area_[f] = soup.face_area(f);
    initialize_quadrics();
    stamp_.assign(points_->size(), 0);
    std::vector<char> touched(points_->size(), 0);
    std::vector<std::pair<double, int>> order;
    target_vertices = std::max<std::size_t>(target_vertices, 4);
    std::size_t vertices = points_->size();
    while(vertices > target_vertices) {
      order.clear();
      for(std::size_t v = 0; v < points_->size(); ++v)
        if(alive_[v]) order.emplace_back(cheapest_cost(int(v)), int(v));
      std::sort(order.begin(), order.end());
      std::fill(touched.begin(), touched.end(), 0);
      const std::size_t before = vertices;
      for(const auto& [cost, u] : order) {
        if(vertices <= target_vertices) break;
        if(touched[u]) continue;
        const int kept = collapse_cheapest_legal(u);
        if(kept < 0) continue;
        --vertices;
        touched[kept] = 1;
        for_each_corner(kept, [&](int k) { touched[mesh_.vertex[Corner_table::next(k)]] = 1; });
      }
      if(vertices == before) break;  // no legal collapse left
      pass_ends_.push_back(splits_.size());
    }
  }

  std::size_t number_of_input_vertices() const { return points_->size(); }
  std::size_t number_of_coarse_vertices() const { return points_->size() - splits_.size(); }
  /// The collapses in the order they were made; undo them in reverse order.
  const std::vector<Vertex_split>& splits() const { return splits_; }
  const std::vector<int>& moved_corners() const { return moved_corners_; }
  /// The number of collapses made at the end of each pass: the vertices of one pass are
  /// independent, their splits can be made in any order.
  const std::vector<std::size_t>& pass_ends() const { return pass_ends_; }
  /// The faces after all collapses (dead faces keep the vertices they had when removed).
  const Faces& coarse_faces() const { return faces_; }
  const std::vector<char>& coarse_face_alive() const { return face_alive_; }
  /// The input area each face stands for, after all collapses.
  const std::vector<double>& coarse_represented_areas() const { return represented_area_; }
  /// The represented area of each moved corner's face before its collapse, in the order of
  /// `moved_corners()`.
  const std::vector<double>& previous_represented_areas() const { return previous_area_; }
  const std::vector<char>& coarse_vertex_alive() const { return alive_; }

private:
  using Quadric = Eigen::Matrix4d;

  const Eigen::Vector3d& point(int v) const { return (*points_)[v]; }

  void initialize_quadrics()
  {
    quadric_.assign(points_->size(), Quadric::Zero());
    for(const auto& t : faces_) {
      const Eigen::Vector3d n2 = (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0]));
      const double norm = n2.norm();
      if(!(norm > 0)) continue;
      Eigen::Vector4d plane;
      plane << n2 / norm, -n2.dot(point(t[0])) / norm;
      const Quadric q = (0.5 * norm) * plane * plane.transpose();  // area-weighted
      for(int v : t) quadric_[v] += q;
    }
  }

  double collapse_cost(int u, int v) const
  {
    // Not `p << point(v), 1.0`: that comma initializer compiles to a loop over a dynamic
    // block, a noticeable share of the set-up time on large meshes.
    const Eigen::Vector4d p(point(v).x(), point(v).y(), point(v).z(), 1.0);
    const double squared_length = (point(u) - point(v)).squaredNorm();
    return std::max(0.0, p.dot((quadric_[u] + quadric_[v]) * p)) + 0.01 * squared_length * squared_length;
  }

  // The neighbours of v in the order of its corners.
  template <class Fn>
  void for_each_corner(int v, Fn fn) const
  {
    const int first = mesh_.vertex_corner[v];
    int c = first;
    do { fn(c); c = mesh_.swing(c); } while(c != first);
  }

  int valence(int v) const
  {
    int n = 0;
    for_each_corner(v, [&](int) { ++n; });
    return n;
  }

  double cheapest_cost(int u) const
  {
    double best = std::numeric_limits<double>::infinity();
    for_each_corner(u, [&](int c) { best = std::min(best, collapse_cost(u, mesh_.vertex[Corner_table::next(c)])); });
    return best;
  }

  // Makes u's cheapest legal collapse; returns the kept vertex, or -1 if none is legal.
  int collapse_cheapest_legal(int u)
  {
    std::vector<std::pair<double, int>> targets;  // (cost, corner of u whose next is the target)
    for_each_corner(u, [&](int c) { targets.emplace_back(collapse_cost(u, mesh_.vertex[Corner_table::next(c)]), c); });
    std::sort(targets.begin(), targets.end());
    for(const auto& [cost, c] : targets)
      if(is_legal(c)) {
        const int kept = mesh_.vertex[Corner_table::next(c)];
        collapse(c);
        return kept;
      }
    return -1;
  }

  // The collapse of the edge from corner c (vertex u) to next(c) (vertex v) in face (u, v, a).
  bool is_legal(int c) const
  {
    const int u = mesh_.vertex[c], v = mesh_.vertex[Corner_table::next(c)];
    const int a = mesh_.vertex[Corner_table::previous(c)];
    const int b = mesh_.vertex[mesh_.opposite[Corner_table::previous(c)]];
    if(valence(u) + valence(v) - 4 > 12 || valence(a) <= 3 || valence(b) <= 3)
      return false;
    // Link condition: u and v share exactly the neighbours a and b.
    ++current_stamp_;
    for_each_corner(u, [&](int k) { stamp_[mesh_.vertex[Corner_table::next(k)]] = current_stamp_; });
    int shared = 0;
    for_each_corner(v, [&](int k) { shared += stamp_[mesh_.vertex[Corner_table::next(k)]] == current_stamp_; });
    if(shared != 2)
      return false;
    if(is_near_duplicate(u, v))
      return true;
    // Geometry of the faces of u that v takes over.
    bool ok = true;
    for_each_corner(u, [&](int k) {
      const int p = mesh_.vertex[Corner_table::next(k)], q = mesh_.vertex[Corner_table::previous(k)];
      if(p == v || q == v || !ok) return;
      const Eigen::Vector3d before = (point(p) - point(u)).cross(point(q) - point(u));
      const Eigen::Vector3d after = (point(p) - point(v)).cross(point(q) - point(v));
      const double lengths = (point(p) - point(v)).squaredNorm() + (point(q) - point(v)).squaredNorm() +
                             (point(p) - point(q)).squaredNorm();
      // 2 sqrt(3) |after| / lengths is 1 for an equilateral triangle, 0 for a needle.
      ok = after.dot(before) > 0.2 * after.norm() * before.norm() && 3.4641 * after.norm() > 0.05 * lengths;
    });
    return ok;
  }

  // v is closer to u than a twentieth of u's mean edge: the near-coincident vertices of an
  // isosurface's cluster (see `Triangle_soup::area_floor()`). Moving u onto v changes the
  // surface by less than the noise of the cluster's own faces, whose normals are arbitrary:
  // the geometric tests would refuse those collapses, and the clusters would last into the
  // coarse levels, far above their target size.
  bool is_near_duplicate(int u, int v) const
  {
    double sum = 0;
    int count = 0;
    for_each_corner(u, [&](int k) {
      sum += (point(mesh_.vertex[Corner_table::next(k)]) - point(u)).norm();
      ++count;
    });
    return (point(v) - point(u)).norm() < near_duplicate_share * sum / count;
  }

  static constexpr double near_duplicate_share = 0.05;

  void collapse(int c)
  {
    using T = Corner_table;
    const int u = mesh_.vertex[c], v = mesh_.vertex[T::next(c)];
    const int cb = mesh_.opposite[T::previous(c)];  // corner of b in face (v, u, b)
    const int f1 = c / 3, f2 = cb / 3;
    Vertex_split split;
    split.removed = u;
    split.kept = v;
    split.removed_faces = {f1, f2};
    split.first_moved_corner = int(moved_corners_.size());
    for_each_corner(u, [&](int k) {
      if(k / 3 != f1 && k / 3 != f2) moved_corners_.push_back(k);
    });
    split.end_moved_corner = int(moved_corners_.size());

    // Glue the faces across the two removed ones.
    const int o1 = mesh_.opposite[c], o2 = mesh_.opposite[T::next(c)];             // across v-a, a-u
    const int o3 = mesh_.opposite[T::next(cb)], o4 = mesh_.opposite[T::previous(cb)];  // across u-b, b-v
    mesh_.opposite[o1] = o2; mesh_.opposite[o2] = o1;
    mesh_.opposite[o3] = o4; mesh_.opposite[o4] = o3;
    for(int k = split.first_moved_corner; k < split.end_moved_corner; ++k) {
      const int corner = moved_corners_[k];
      mesh_.vertex[corner] = v;
      faces_[corner / 3][corner % 3] = v;
    }
    share_represented_area(split);
    const int a = mesh_.vertex[T::previous(c)], b = mesh_.vertex[cb];
    mesh_.vertex_corner[v] = T::previous(o1);
    mesh_.vertex_corner[a] = T::next(o1);
    mesh_.vertex_corner[b] = T::previous(o4);
    alive_[u] = 0;
    face_alive_[f1] = face_alive_[f2] = 0;
    quadric_[v] += quadric_[u];
    splits_.push_back(split);
  }

  // The input area of the faces of u, the two removed ones included, goes to the faces
  // that replace them in proportion to their own areas: a coarse face stands for the input
  // area around it, and a coarse level keeps the area shares of the input's regions (a
  // decimated protrusion loses area to the chords that cut its curvature).
  void share_represented_area(const Vertex_split& split)
  {
    double total = represented_area_[split.removed_faces[0]] + represented_area_[split.removed_faces[1]];
    double geometric = 0;
    for(int k = split.first_moved_corner; k < split.end_moved_corner; ++k) {
      const int f = moved_corners_[k] / 3;
      previous_area_.push_back(represented_area_[f]);
      total += represented_area_[f];
      geometric += face_area(f);
    }
    for(int k = split.first_moved_corner; k < split.end_moved_corner; ++k) {
      const int f = moved_corners_[k] / 3;
      represented_area_[f] = geometric > 0 ? total * face_area(f) / geometric : total / (split.end_moved_corner - split.first_moved_corner);
    }
  }

  double face_area(int f) const
  {
    const auto& t = faces_[f];
    return 0.5 * (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0])).norm();
  }

  const Points* points_;
  Faces faces_;
  std::vector<double> represented_area_;  // of each face, see share_represented_area()
  std::vector<double> previous_area_;     // of each moved corner's face, to undo the sharing
  Corner_table mesh_;
  std::vector<char> alive_, face_alive_;
  std::vector<Quadric> quadric_;
  std::vector<Vertex_split> splits_;
  std::vector<int> moved_corners_;
  std::vector<std::size_t> pass_ends_;
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t current_stamp_ = 0;
};

/// The mesh on its way from the coarsest state of a progressive mesh back to the input, one
/// vertex split at a time (the collapses undone in reverse order).
class Refinement
{
public:
  explicit Refinement(const Progressive_mesh& pm)
    : pm_(&pm), faces_(pm.coarse_faces()), represented_area_(pm.coarse_represented_areas()),
      face_alive_(pm.coarse_face_alive()),
      vertex_alive_(pm.coarse_vertex_alive()), splits_left_(pm.splits().size())
  {}

  /// How many collapses are still to undo: 0 once the mesh is the input again.
  std::size_t splits_left() const { return splits_left_; }
  /// How many of the next splits undo collapses of the same pass as the next one: their
  /// vertices are independent (see `Progressive_mesh`), each one's ring made of vertices
  /// present before all of them.
  std::size_t independent_splits() const
  {
    if(splits_left_ == 0)
      return 0;
    const std::vector<std::size_t>& ends = pm_->pass_ends();
    // The first pass end past the next split's collapse; the pass starts at the one before.
    const auto end = std::upper_bound(ends.begin(), ends.end(), splits_left_ - 1);
    return splits_left_ - (end == ends.begin() ? 0 : *(end - 1));
  }
  std::size_t number_of_vertices() const { return pm_->number_of_input_vertices() - splits_left_; }

  /// Undoes the last collapse left and returns it.
  const Vertex_split& split_next()
  {
    const Vertex_split& s = pm_->splits()[--splits_left_];
    for(int k = s.first_moved_corner; k < s.end_moved_corner; ++k) {
      const int corner = pm_->moved_corners()[k];
      faces_[corner / 3][corner % 3] = s.removed;
      represented_area_[corner / 3] = pm_->previous_represented_areas()[k];
    }
    face_alive_[s.removed_faces[0]] = face_alive_[s.removed_faces[1]] = 1;
    vertex_alive_[s.removed] = 1;
    return s;
  }

  /// The faces `(u, p, q)` of the vertex `u` just split back in, as the pairs `(p, q)`.
  void fan(const Vertex_split& s, std::vector<std::array<int, 2>>& pairs) const
  {
    pairs.clear();
    auto add = [&](int f) {
      const auto& t = faces_[f];
      for(int k = 0; k < 3; ++k)
        if(t[k] == s.removed) pairs.push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    };
    add(s.removed_faces[0]);
    add(s.removed_faces[1]);
    for(int k = s.first_moved_corner; k < s.end_moved_corner; ++k)
      add(pm_->moved_corners()[k] / 3);
  }

  const Faces& faces() const { return faces_; }
  const std::vector<char>& face_alive() const { return face_alive_; }
  const std::vector<char>& vertex_alive() const { return vertex_alive_; }
  const std::vector<double>& represented_areas() const { return represented_area_; }

private:
  const Progressive_mesh* pm_;
  Faces faces_;
  std::vector<double> represented_area_;
  std::vector<char> face_alive_, vertex_alive_;
  std::size_t splits_left_;
};

/// The mesh of `refinement` as a soup of its own: its vertices (`to_input` gives the input
/// vertex of each) at their input positions, scaled about the origin to total area `4 pi`
/// like the input, and its faces with the input's (outward) orientation.
inline Triangle_soup level_soup(const Triangle_soup& input, const Refinement& refinement, std::vector<int>& to_input)
{
  std::vector<int> to_level(input.points.size(), -1);
  to_input.clear();
  Triangle_soup soup;
  for(std::size_t v = 0; v < input.points.size(); ++v)
    if(refinement.vertex_alive()[v]) {
      to_level[v] = int(to_input.size());
      to_input.push_back(int(v));
      soup.points.push_back(input.points[v]);
    }
  for(std::size_t f = 0; f < refinement.faces().size(); ++f)
    if(refinement.face_alive()[f]) {
      const auto& t = refinement.faces()[f];
      soup.faces.push_back({to_level[t[0]], to_level[t[1]], to_level[t[2]]});
      soup.represented_areas.push_back(refinement.represented_areas()[f]);
    }
  double area = 0;
  for(std::size_t f = 0; f < soup.faces.size(); ++f)
    area += soup.face_area(f);
  const double scale = std::sqrt(4 * M_PI / area);
  for(auto& p : soup.points)
    p *= scale;
  if(!input.vertex_scales.empty())
    for(int v : to_input)
      soup.vertex_scales.push_back(scale * input.vertex_scales[std::size_t(v)]);
  soup.scale = input.scale * scale;
  soup.centroid = input.centroid;
  return soup;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_PROGRESSIVE_MESH_H
