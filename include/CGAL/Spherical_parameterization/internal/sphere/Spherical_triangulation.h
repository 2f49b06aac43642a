// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SPHERICAL_TRIANGULATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SPHERICAL_TRIANGULATION_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>
#include <CGAL/Spherical_parameterization/octahedral_map.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A face found by point location, with the unnormalized coordinates of the query in it.
struct Face_hit
{
  int face = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  ///< `det` with the query in place of each corner

  /// Barycentric coordinates of the central projection of the query onto the chord triangle.
  /// Weights within the tolerance below zero (a query on an edge or a vertex) count as 0.
  Eigen::Vector3d barycentric() const
  {
    const Eigen::Vector3d w = weights.cwiseMax(0.0);
    const double sum = w.sum();
    return sum > 0 ? Eigen::Vector3d(w / sum) : Eigen::Vector3d::Constant(1.0 / 3);
  }
};

/// The spherical triangulation that a valid sphere map induces: the great-circle triangles
/// over the chord triangles of the sphere points, which tile the sphere once. It answers
/// "which face contains this direction" by a walk from a seed taken from a coarse grid.
///
/// Why this works: the chord triangle `(a, b, c)` of a valid map has `det(a, b, c) > 0`, so a
/// direction `q` is in the cone from the centre over it exactly when the three weights
/// `det(q, b, c)`, `det(a, q, c)`, `det(a, b, q)` are `>= 0`. By Cramer's rule the weights divided
/// by their sum are also the barycentric coordinates of the point where the ray along `q`
/// meets the chord triangle, which makes them exact for the piecewise linear map.
///
/// The weights factor as `|n_k| (u_k . q)`, with `n_k` the normal of the plane through the centre
/// and the edge opposite corner `k` (`b x c` for corner `a`) and `u_k` its unit vector:
/// `u_k . q` is the sine of the angle between `q` and that plane, positive on the face's side.
/// The tests use these angles, the coordinates use the weights.
///
/// Robustness: each edge's unit normal is computed once, in a fixed vertex order, and the two
/// faces of the edge use it with opposite signs. Both faces thus see the same side of the
/// edge for every query, whatever the rounding, and a walk never bounces back and forth
/// across one edge. The planes of the edges around a vertex do not quite meet in one line
/// after rounding, so a query within rounding of a vertex could lie outside every face; the
/// angle `tolerance` below closes such gaps and keeps the walk from circling the vertex.
class Spherical_triangulation
{
public:
  static constexpr double tolerance = 1e-14;

  /// `sphere` holds unit vectors; `faces` index into it. An inward-oriented map (the sum of
  /// the signed spherical areas is negative) has its faces reversed here and `reversed()` says so.
  Spherical_triangulation(Points sphere, Faces faces) : sphere_(std::move(sphere)), faces_(std::move(faces))
  {
    orient_faces();
    compute_edge_normals();
    compute_neighbors();
    build_seed_grid();
  }

  const Points& sphere_points() const { return sphere_; }
  const Faces& faces() const { return faces_; }
  std::size_t number_of_faces() const { return faces_.size(); }
  bool reversed() const { return reversed_; }
  /// Faces flipped or degenerate after the orientation fix, and the degree: a valid map has
  /// none and degree 1.
  const Map_validity& validity() const { return validity_; }

  /// The sines of the angles between the unit vector `q` and the planes of the edges of
  /// `face`, positive on the face's side (see the class comment).
  Eigen::Vector3d edge_sines(int face, const Eigen::Vector3d& q) const { return unit_edge_normals_[face] * q; }

  /// The weights of `q` in `face` from its `edge_sines()`: `det` with `q` in place of each corner.
  Eigen::Vector3d weights(int face, const Eigen::Vector3d& sines) const
  {
    return sines.cwiseProduct(edge_normal_lengths_[face]);
  }

  /// True if a direction with these `edge_sines()` is in the cone over the face, to the tolerance.
  static bool contains(const Eigen::Vector3d& sines) { return sines.minCoeff() >= -tolerance; }

  /// The face containing the unit vector `q`. The walk starts at `start`, or at the seed grid's
  /// face when `start < 0`; if it has not arrived after many steps (only on a map that is not a
  /// valid embedding), every face is tried.
  Face_hit locate(const Eigen::Vector3d& q, int start = -1) const
  {
    Face_hit hit;
    hit.face = walk(start >= 0 ? start : seed(q), q, hit.weights);
    if(hit.face < 0)
      hit = locate_by_trying_every_face(q);
    return hit;
  }

  /// The face whose smallest edge sine for `q` is the largest: the containing face on a
  /// valid map, the nearest thing to it otherwise. O(F); the reference the walk is tested against.
  Face_hit locate_by_trying_every_face(const Eigen::Vector3d& q) const
  {
    Face_hit best;
    double best_min = -std::numeric_limits<double>::infinity();
    for(int f = 0; f < int(faces_.size()); ++f) {
      const Eigen::Vector3d sines = edge_sines(f, q);
      if(sines.minCoeff() > best_min) {
        best_min = sines.minCoeff();
        best.face = f;
        best.weights = weights(f, sines);
      }
    }
    return best;
  }

  /// The face that the seed grid proposes for the unit vector `q`.
  int seed(const Eigen::Vector3d& q) const { return seed_faces_[seed_cell(q)]; }

  /// Walks from `face` towards the unit vector `q`, leaving each face through an edge whose
  /// plane separates it from `q`. Returns the face containing `q` with its weights, or -1
  /// after `step_limit()` steps.
  int walk(int face, const Eigen::Vector3d& q, Eigen::Vector3d& w) const
  {
    // Which separating edge to cross is drawn at random: always taking the first one can
    // cycle forever on triangulations that are not Delaunay (Devillers, Pion and Teillaud,
    // "Walking in a triangulation", 2002). A small linear congruential generator suffices.
    std::uint32_t random = 0x9e3779b9u;
    for(int step = 0, limit = step_limit(); step < limit; ++step) {
      const Eigen::Vector3d sines = edge_sines(face, q);
      if(contains(sines)) {
        w = weights(face, sines);
        return face;
      }
      random = random * 1664525u + 1013904223u;
      const int first = int(random >> 30) % 3;
      int exit = -1;
      for(int k = 0; k < 3 && exit < 0; ++k)
        if(sines[(first + k) % 3] < -tolerance)
          exit = (first + k) % 3;
      if(exit < 0)  // a weight is NaN: the query is not a finite direction
        return -1;
      face = neighbors_[face][exit];
    }
    return -1;
  }

  /// The number of steps after which a walk gives up. Walks from the seed grid take a few
  /// steps; the limit only matters on a map that is not a valid embedding.
  int step_limit() const { return 64 + 4 * int(faces_.size()); }

private:
  Points sphere_;
  Faces faces_;
  bool reversed_ = false;
  Map_validity validity_;
  std::vector<Eigen::Matrix3d> unit_edge_normals_;    // row k: u_k, for the edge opposite corner k
  std::vector<Eigen::Vector3d> edge_normal_lengths_;  // |n_k|
  Faces neighbors_;                             // neighbors_[f][k]: the face across that edge
  int grid_size_ = 0;
  std::vector<int> seed_faces_;                 // per cell of the octahedral square

  void orient_faces()
  {
    reversed_ = degree(faces_, sphere_) < 0;
    if(reversed_)
      for(auto& t : faces_)
        std::swap(t[1], t[2]);
    validity_ = check_map(faces_, sphere_);
  }

  void compute_edge_normals()
  {
    unit_edge_normals_.resize(faces_.size());
    edge_normal_lengths_.resize(faces_.size());
    for(std::size_t f = 0; f < faces_.size(); ++f)
      for(int k = 0; k < 3; ++k) {
        const int i = faces_[f][(k + 1) % 3], j = faces_[f][(k + 2) % 3];
        const Eigen::Vector3d n = i < j ? edge_normal(i, j) : Eigen::Vector3d(-edge_normal(j, i));
        const double length = n.norm();  // 0 only for an edge whose ends coincide (no valid map)
        edge_normal_lengths_[f][k] = length;
        unit_edge_normals_[f].row(k) = (length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero()).transpose();
      }
  }

  /// Pairs the two sides of every edge by sorting them on the edge's vertices (faster than
  /// hashing). A side without a twin (the mesh is not closed) leads back into its own face.
  /// `x_i x x_j`, computed as `x_i x (x_j - x_i)`: the difference of two nearby unit vectors
  /// is exact or nearly, so the normal is accurate relative to the edge's length rather than
  /// to 1, and so are the weights of a query next to a vertex of a tiny face. Each edge's
  /// normal is computed once, from its lower index, for the same rounding in both faces.
  Eigen::Vector3d edge_normal(int i, int j) const { return sphere_[i].cross(sphere_[j] - sphere_[i]); }

  void compute_neighbors()
  {
    std::vector<std::pair<std::uint64_t, int>> sides;  // (undirected edge, 3 * face + corner)
    sides.reserve(3 * faces_.size());
    for(std::size_t f = 0; f < faces_.size(); ++f)
      for(int k = 0; k < 3; ++k) {
        const auto ends = std::minmax(faces_[f][(k + 1) % 3], faces_[f][(k + 2) % 3]);
        sides.emplace_back((std::uint64_t(std::uint32_t(ends.first)) << 32) | std::uint32_t(ends.second),
                           int(3 * f) + k);
      }
    std::sort(sides.begin(), sides.end());
    neighbors_.resize(faces_.size());
    for(std::size_t f = 0; f < faces_.size(); ++f)
      neighbors_[f] = {{int(f), int(f), int(f)}};
    for(std::size_t i = 0; i + 1 < sides.size(); ++i)
      if(sides[i].first == sides[i + 1].first) {
        const int a = sides[i].second, b = sides[i + 1].second;
        neighbors_[a / 3][a % 3] = b / 3;
        neighbors_[b / 3][b % 3] = a / 3;
        ++i;
      }
  }

  int seed_cell(const Eigen::Vector3d& q) const
  {
    const Eigen::Vector2d s = sphere_to_octahedral_square(q);
    auto index = [this](double x) { return std::clamp(int((x + 1) / 2 * grid_size_), 0, grid_size_ - 1); };
    return index(s.y()) * grid_size_ + index(s.x());
  }

  /// About two faces per cell on a map of uniform density. Each cell centre is located by a
  /// walk from its predecessor's face, in rows, so that the walks are short. A map that is not
  /// a valid embedding gets a single cell: its walks may fail, and each failure costs O(F).
  void build_seed_grid()
  {
    grid_size_ = validity_.is_valid() ? std::clamp(int(std::ceil(std::sqrt(faces_.size() / 2.0))), 1, 2048) : 1;
    seed_faces_.assign(std::size_t(grid_size_) * grid_size_, 0);
    if(faces_.empty())
      return;
    int face = 0;
    Eigen::Vector3d w;
    for(int row = 0; row < grid_size_; ++row)
      for(int column = 0; column < grid_size_; ++column) {
        const Eigen::Vector2d centre(-1 + (column + 0.5) * 2 / grid_size_, -1 + (row + 0.5) * 2 / grid_size_);
        const Eigen::Vector3d q = octahedral_square_to_sphere(centre);
        const int found = walk(face, q, w);
        face = found >= 0 ? found : locate_by_trying_every_face(q).face;
        seed_faces_[std::size_t(row) * grid_size_ + column] = face;
      }
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SPHERICAL_TRIANGULATION_H
