// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Long closed tubes built in code, for the benchmark's `tube:capsuleL` and `tube:helixT`:
// vessels, colons and worms are genus 0 too, and a tube is the hardest case for a spherical
// map. The conformal map of a tube of length L and circumference C squeezes part of it by
// about exp(-2 pi L / C) in area, below the fold barrier's floor (1e-7) once L / C passes 2.6,
// so the maps of these tubes end with many faces on that floor.

#ifndef SPHERICAL_PARAMETERIZATION_BENCHMARK_SYNTHETIC_SHAPES_H
#define SPHERICAL_PARAMETERIZATION_BENCHMARK_SYNTHETIC_SHAPES_H

#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace synthetic_shapes {

using Vec = std::array<double, 3>;

inline Vec cross(const Vec& a, const Vec& b)
{
  return Vec{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

inline double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

inline Vec normalized(const Vec& a)
{
  const double length = std::sqrt(dot(a, a));
  return Vec{a[0] / length, a[1] / length, a[2] / length};
}

/// A centre line `point(s)`, `s` in [0, 1], with two unit normals `first_normal(s)` and
/// `second_normal(s)` such that (first, second, tangent) is right-handed.
struct Centre_line
{
  std::function<Vec(double)> point, first_normal, second_normal;
  double length = 0;
};

/// A tube of `radius` around `line`, `around` vertices per ring, `rings` rings (by default
/// about as far apart as the vertices of a ring), closed by a fan at each end; faces oriented
/// outwards.
template <class Point>
CGAL::Surface_mesh<Point> tube(const Centre_line& line, double radius, int around, int rings = 0)
{
  const double pi = std::acos(-1.0);
  if(rings < 2)
    rings = 1 + int(std::ceil(line.length / (2 * pi * radius / around)));
  CGAL::Surface_mesh<Point> mesh;
  using Vertex = typename CGAL::Surface_mesh<Point>::Vertex_index;
  std::vector<Vertex> ring_vertex;
  for(int i = 0; i < rings; ++i) {
    const double s = double(i) / (rings - 1);
    const Vec c = line.point(s), n1 = line.first_normal(s), n2 = line.second_normal(s);
    for(int j = 0; j < around; ++j) {
      const double phi = 2 * pi * j / around, u = radius * std::cos(phi), v = radius * std::sin(phi);
      ring_vertex.push_back(
        mesh.add_vertex(Point(c[0] + u * n1[0] + v * n2[0], c[1] + u * n1[1] + v * n2[1], c[2] + u * n1[2] + v * n2[2])));
    }
  }
  auto at = [&](int i, int j) { return ring_vertex[std::size_t(i) * around + (j % around)]; };
  for(int i = 0; i + 1 < rings; ++i)
    for(int j = 0; j < around; ++j) {
      mesh.add_face(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      mesh.add_face(at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  const Vec first = line.point(0), last = line.point(1);
  const Vertex start = mesh.add_vertex(Point(first[0], first[1], first[2]));
  const Vertex end = mesh.add_vertex(Point(last[0], last[1], last[2]));
  for(int j = 0; j < around; ++j) {
    mesh.add_face(start, at(0, j + 1), at(0, j));
    mesh.add_face(end, at(rings - 1, j), at(rings - 1, j + 1));
  }
  return mesh;
}

/// The segment from the origin up the z axis, of the given length.
inline Centre_line straight_line(double length)
{
  Centre_line line;
  line.point = [length](double s) { return Vec{0, 0, length * s}; };
  line.first_normal = [](double) { return Vec{1, 0, 0}; };
  line.second_normal = [](double) { return Vec{0, 1, 0}; };
  line.length = length;
  return line;
}

/// A straight tube of radius 1 and the given length, 32 vertices around.
template <class Point>
CGAL::Surface_mesh<Point> capsule(double length)
{
  return tube<Point>(straight_line(length), 1, 32);
}

/// A cylinder as CAD tessellations make it: radius 1, length 2, `around` vertices on each of
/// only five rings, so that its sides are needles (24:1 for 300 around), and a fan of
/// `around` faces on each cap.
template <class Point>
CGAL::Surface_mesh<Point> cad_cylinder(int around)
{
  return tube<Point>(straight_line(2), 1, around, 5);
}

/// A tube of radius 0.5 coiled `turns` times around the z axis (coil radius 3, rising 3 per
/// turn), 48 vertices around: long like a capsule, and not star-shaped.
template <class Point>
CGAL::Surface_mesh<Point> helix(double turns)
{
  const double pi = std::acos(-1.0), coil = 3, rise = 3;
  const double speed = std::hypot(2 * pi * coil, rise);  // length per turn
  auto angle = [=](double s) { return 2 * pi * turns * s; };
  auto outwards = [=](double s) { return Vec{std::cos(angle(s)), std::sin(angle(s)), 0}; };
  auto tangent = [=](double s) {
    const double a = angle(s);
    return Vec{-2 * pi * coil * std::sin(a) / speed, 2 * pi * coil * std::cos(a) / speed, rise / speed};
  };
  Centre_line line;
  line.point = [=](double s) {
    const double a = angle(s);
    return Vec{coil * std::cos(a), coil * std::sin(a), rise * turns * s};
  };
  line.first_normal = outwards;
  line.second_normal = [=](double s) { return cross(tangent(s), outwards(s)); };
  line.length = speed * turns;
  return tube<Point>(line, 0.5, 48);
}

/// The surface `field = 0` sampled on the grid `origin + spacing * (i, j, k)`, `0 <= i, j, k
/// <= n`, by marching tetrahedra (six per cube, around its main diagonal, so that neighbouring
/// cubes cut their common faces alike), faces oriented away from the region `field > 0`. Every
/// vertex lies on a grid edge: where the surface passes close to a grid point, the vertices on
/// that point's edges nearly coincide, the clusters of tiny faces and needles that isosurfaces
/// of scans and segmentations are made of. Empty if the faces do not make a manifold.
template <class Point>
CGAL::Surface_mesh<Point> marching_tetrahedra(const std::function<double(const Vec&)>& field, int n, const Vec& origin,
                                              double spacing)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  using Vertex = typename Mesh::Vertex_index;
  const std::size_t side = std::size_t(n) + 1;
  auto index = [side](int i, int j, int k) { return (std::size_t(i) * side + std::size_t(j)) * side + std::size_t(k); };
  auto grid_point = [&](std::size_t g) {
    const double i = double(g / (side * side)), j = double(g / side % side), k = double(g % side);
    return Vec{origin[0] + spacing * i, origin[1] + spacing * j, origin[2] + spacing * k};
  };
  std::vector<double> value(side * side * side);
  for(std::size_t g = 0; g < value.size(); ++g)
    value[g] = field(grid_point(g));

  Mesh mesh;
  std::map<std::pair<std::size_t, std::size_t>, Vertex> on_edge;
  auto edge_vertex = [&](std::size_t a, std::size_t b) {
    const auto key = std::minmax(a, b);
    const auto found = on_edge.find(key);
    if(found != on_edge.end())
      return found->second;
    const double t = value[a] / (value[a] - value[b]);
    const Vec p = grid_point(a), q = grid_point(b);
    const Vertex v = mesh.add_vertex(Point(p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])));
    on_edge.emplace(key, v);
    return v;
  };
  bool manifold = true;
  // A face of the vertices on edges (a, b), (c, d), (e, f), turned away from `inside`.
  auto add_face = [&](std::array<std::size_t, 6> e, std::size_t inside) {
    std::array<Vertex, 3> v{edge_vertex(e[0], e[1]), edge_vertex(e[2], e[3]), edge_vertex(e[4], e[5])};
    const auto& p0 = mesh.point(v[0]);
    const auto normal = CGAL::cross_product(mesh.point(v[1]) - p0, mesh.point(v[2]) - p0);
    const Vec g = grid_point(inside);
    if(normal * (Point(g[0], g[1], g[2]) - p0) > 0)
      std::swap(v[1], v[2]);
    manifold = manifold && mesh.add_face(v[0], v[1], v[2]) != Mesh::null_face();
  };
  const std::array<std::array<int, 3>, 8> corner{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                                  {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}};
  const std::array<std::array<int, 4>, 6> tetrahedra{{{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                                                      {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}}};
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j)
      for(int k = 0; k < n; ++k)
        for(const auto& tetrahedron : tetrahedra) {
          std::array<std::size_t, 4> g;
          std::vector<std::size_t> in, out;
          for(int m = 0; m < 4; ++m) {
            const auto& c = corner[std::size_t(tetrahedron[std::size_t(m)])];
            g[std::size_t(m)] = index(i + c[0], j + c[1], k + c[2]);
            (value[g[std::size_t(m)]] > 0 ? in : out).push_back(g[std::size_t(m)]);
          }
          if(in.size() == 1 || in.size() == 3) {
            const std::size_t apex = in.size() == 1 ? in[0] : out[0];
            std::vector<std::size_t> rest;
            for(std::size_t c : g)
              if(c != apex)
                rest.push_back(c);
            add_face({apex, rest[0], apex, rest[1], apex, rest[2]}, in[0]);
          } else if(in.size() == 2) {  // the quad (a c, a d, b d, b c), a and b inside
            add_face({in[0], out[0], in[0], out[1], in[1], out[1]}, in[0]);
            add_face({in[0], out[0], in[1], out[1], in[1], out[0]}, in[0]);
          }
        }
  return manifold && CGAL::is_closed(mesh) ? mesh : Mesh();
}

/// Five overlapping ellipsoidal blobs (an organ-like shape in [-1, 1]^3), the isosurface of
/// their summed Gaussians by `marching_tetrahedra()` on a grid of `resolution` cubes a side.
template <class Point>
CGAL::Surface_mesh<Point> metaballs(int resolution)
{
  const std::array<std::array<double, 6>, 5> blobs{{{0.0, 0.0, 0.0, 0.55, 0.4, 0.35},
                                                    {0.45, 0.15, 0.05, 0.35, 0.3, 0.25},
                                                    {-0.4, -0.2, 0.1, 0.3, 0.35, 0.3},
                                                    {0.1, -0.35, -0.1, 0.25, 0.2, 0.3},
                                                    {-0.1, 0.3, 0.25, 0.2, 0.2, 0.2}}};
  auto field = [blobs](const Vec& p) {
    double sum = 0;
    for(const auto& b : blobs) {
      double d = 0;
      for(int c = 0; c < 3; ++c)
        d += (p[std::size_t(c)] - b[std::size_t(c)]) * (p[std::size_t(c)] - b[std::size_t(c)]) / (b[std::size_t(c) + 3] * b[std::size_t(c) + 3]);
      sum += std::exp(-d);
    }
    return sum - 0.5 - 1e-7 * std::sqrt(2.0);  // the level off the grid's values
  };
  return marching_tetrahedra<Point>(field, resolution, Vec{-1.1, -1.1, -1.1}, 2.2 / resolution);
}

/// A ball with five long thin arms of radius 0.06 to 0.1 (a starfish, or the protrusions of
/// a segmented skeleton), the isosurface of the largest of their signed distances by
/// `marching_tetrahedra()` on a grid of `resolution` cubes a side in [-1.1, 1.1]^3.
template <class Point>
CGAL::Surface_mesh<Point> starfish(int resolution)
{
  struct Arm
  {
    Vec axis;  // unit
    double length, radius;
  };
  const std::array<Arm, 5> arms{{{normalized(Vec{1.0, 0.1, 0.0}), 0.95, 0.1},
                                 {normalized(Vec{-0.3, 1.0, 0.2}), 0.9, 0.08},
                                 {normalized(Vec{-0.8, -0.6, 0.1}), 0.95, 0.07},
                                 {normalized(Vec{0.4, -0.7, 0.6}), 0.85, 0.06},
                                 {normalized(Vec{0.1, 0.2, -1.0}), 0.9, 0.09}}};
  auto field = [arms](const Vec& p) {
    double largest = 0.3 - std::sqrt(dot(p, p));  // the body
    for(const Arm& a : arms) {
      const double along = std::clamp(dot(p, a.axis), 0.0, a.length);
      const Vec off{p[0] - along * a.axis[0], p[1] - along * a.axis[1], p[2] - along * a.axis[2]};
      largest = std::max(largest, a.radius - std::sqrt(dot(off, off)));
    }
    return largest - 1e-7 * std::sqrt(2.0);  // the level off the grid's values
  };
  return marching_tetrahedra<Point>(field, resolution, Vec{-1.1, -1.1, -1.1}, 2.2 / resolution);
}

/// A ball creased by one connected network of valleys, `marching_tetrahedra()` of it on a grid
/// of `resolution` cubes a side in [-1.1, 1.1]^3: at distance r from the centre, the surface
/// point in direction d has radius `radius(s)`, with s = sin 9 e_x + sin 9 e_y + sin 9 e_z for
/// e the direction d turned about the z axis by `turn_rate (r - 0.7)` radians (the valleys
/// are where s is 0). Without a turn the ball is star-shaped; with one, its folds lean.
template <class Point, class Radius>
CGAL::Surface_mesh<Point> creased_ball(int resolution, double turn_rate, const Radius& radius)
{
  auto field = [turn_rate, &radius](const Vec& q) {
    const double r = std::sqrt(dot(q, q));
    if(r < 1e-9)
      return 1.0;
    const double turn = turn_rate * (r - 0.7), c = std::cos(turn), t = std::sin(turn);
    const Vec p{c * q[0] - t * q[1], t * q[0] + c * q[1], q[2]};
    const double s = std::sin(9 * p[0] / r) + std::sin(9 * p[1] / r) + std::sin(9 * p[2] / r);
    return radius(s) - r - 1e-7 * std::sqrt(2.0);  // the level off the grid's values
  };
  return marching_tetrahedra<Point>(field, resolution, Vec{-1.1, -1.1, -1.1}, 2.2 / resolution);
}

/// A ball with deep narrow folds, like a brain's cortex (medical imaging's genus-0 surfaces),
/// `creased_ball()` without a turn: radius 0.7 + 0.1 sqrt(s^2 + 1), so the creases are 0.22
/// deep, their bottoms rounded over about 0.07 (a sharp V left bubbles of air in the marching
/// tetrahedra's creases). Star-shaped, hence one closed genus-0 surface.
template <class Point>
CGAL::Surface_mesh<Point> cortex(int resolution)
{
  return creased_ball<Point>(resolution, 0, [](double s) { return 0.7 + 0.1 * std::sqrt(s * s + 1); });
}

/// A cortex with folds about 0.3 deep, a third of the radius, that lean sideways:
/// `creased_ball()` with radius 0.6 + 0.35 sqrt(s^2 + 0.1) / 3, its directions turned by 1.5
/// (r - 0.7) radians, so a ray from the centre crosses a fold's wall more than once, as in a
/// real brain's overhanging gyri (the surface is not star-shaped).
template <class Point>
CGAL::Surface_mesh<Point> folded_cortex(int resolution)
{
  return creased_ball<Point>(resolution, 1.5, [](double s) { return 0.6 + 0.35 * std::sqrt(s * s + 0.1) / 3; });
}

/// A segment from `a` to `b` thickened by `radius`: the field `radius - distance` is
/// positive inside.
struct Capsule
{
  Vec a, b;
  double radius;

  double inside(const Vec& p) const
  {
    const Vec ab{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double t = std::clamp(dot(ap, ab) / dot(ab, ab), 0.0, 1.0);
    const Vec off{ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
    return radius - std::sqrt(dot(off, off));
  }
};

/// A standing figure 2 high (a person as scans and segmentations give them): head, trunk,
/// arms held out and down, legs, feet, and on each hand four fingers and a thumb of radius
/// 0.014 and length 0.075 to 0.1, 0.012 apart at their bases; the union of capsules,
/// `marching_tetrahedra()` of it on a grid of `resolution` cubes a side in [-1.1, 1.1]^3 (a
/// finger is 4 cubes across at 300). Protrusions on protrusions: the fingertips get the
/// smallest share of the sphere.
template <class Point>
CGAL::Surface_mesh<Point> figure(int resolution)
{
  constexpr double finger = 0.014;
  std::vector<Capsule> parts{{Vec{0, -0.05, 0}, Vec{0, 0.33, 0}, 0.17},    // trunk
                             {Vec{0, 0.45, 0}, Vec{0, 0.64, 0}, 0.06},     // neck
                             {Vec{0, 0.73, 0.01}, Vec{0, 0.76, 0.01}, 0.11}};  // head
  for(double side : {-1.0, 1.0}) {
    parts.push_back({Vec{side * 0.09, -0.1, 0}, Vec{side * 0.11, -0.55, 0}, 0.075});  // thigh
    parts.push_back({Vec{side * 0.11, -0.55, 0}, Vec{side * 0.11, -0.93, 0}, 0.055}); // shin
    parts.push_back({Vec{side * 0.11, -0.96, -0.02}, Vec{side * 0.11, -0.96, 0.14}, 0.035});  // foot
    parts.push_back({Vec{side * 0.2, 0.38, 0}, Vec{side * 0.47, 0.2, 0}, 0.05});      // upper arm
    parts.push_back({Vec{side * 0.47, 0.2, 0}, Vec{side * 0.72, 0.05, 0}, 0.04});     // forearm
    for(double z : {-0.025, 0.025})                                                     // palm
      parts.push_back({Vec{side * 0.72, 0.05, z}, Vec{side * 0.8, 0.0, z}, 0.03});
    for(int i = 0; i < 4; ++i) {
      const double spread = 0.25 * (i - 1.5), length = (i == 1 || i == 2) ? 0.087 : 0.075;
      const Vec base{side * 0.81, -0.005, (i - 1.5) * (2 * finger + 0.012)};
      const Vec along = normalized(Vec{side * 0.86 * std::cos(spread), -0.5, std::sin(spread)});
      const Vec tip{base[0] + length * along[0], base[1] + length * along[1], base[2] + length * along[2]};
      parts.push_back({base, tip, finger});
    }
    parts.push_back({Vec{side * 0.74, 0.04, 0.045}, Vec{side * 0.79, 0.02, 0.11}, 1.15 * finger});  // thumb
  }
  auto field = [parts](const Vec& p) {
    double largest = -1e9;
    for(const Capsule& part : parts)
      largest = std::max(largest, part.inside(p));
    return largest - 1e-7 * std::sqrt(2.0);  // the level off the grid's values
  };
  return marching_tetrahedra<Point>(field, resolution, Vec{-1.1, -1.1, -1.1}, 2.2 / resolution);
}

/// The sphere of squared radius `squared_radius` (plus 1e-5) around a point of the integer
/// grid, by `marching_tetrahedra()` on that grid: it passes 1e-5 away from every grid point
/// on the sphere of that radius, so each of them is a cluster of near-coincident vertices.
template <class Point>
CGAL::Surface_mesh<Point> lattice_sphere(double squared_radius)
{
  const int half = int(std::ceil(std::sqrt(squared_radius))) + 1;
  auto field = [squared_radius](const Vec& p) { return squared_radius + 1e-5 - dot(p, p); };
  return marching_tetrahedra<Point>(field, 2 * half, Vec{-double(half), -double(half), -double(half)}, 1.0);
}

/// `count` unit vectors spread evenly over the sphere (a Fibonacci lattice).
inline std::vector<Vec> fibonacci_directions(int count)
{
  const double golden_angle = std::acos(-1.0) * (3 - std::sqrt(5.0));
  std::vector<Vec> directions;
  for(int i = 0; i < count; ++i) {
    const double z = 1 - (2 * i + 1.0) / count, r = std::sqrt(1 - z * z);
    directions.push_back({r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z});
  }
  return directions;
}

/// The icosphere `sphere` with its point `i` moved to radius `radii[i]`, then stretched
/// `stretch_x` times along x.
template <class Point>
CGAL::Surface_mesh<Point> radial_graph(const CGAL::Spherical_parameterization::Icosphere& sphere,
                                       const std::vector<double>& radii, double stretch_x)
{
  CGAL::Surface_mesh<Point> mesh;
  using Vertex = typename CGAL::Surface_mesh<Point>::Vertex_index;
  std::vector<Vertex> vertex;
  for(std::size_t i = 0; i < sphere.points.size(); ++i) {
    const Eigen::Vector3d& p = sphere.points[i];
    vertex.push_back(mesh.add_vertex(Point(stretch_x * radii[i] * p.x(), radii[i] * p.y(), radii[i] * p.z())));
  }
  for(const std::array<int, 3>& f : sphere.faces)
    mesh.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]);
  return mesh;
}

/// `values`, one per point of `sphere`, after `passes` steps halfway towards the mean of each
/// point's neighbours.
inline std::vector<double> smoothed_over_sphere(const CGAL::Spherical_parameterization::Icosphere& sphere,
                                                std::vector<double> values, int passes)
{
  std::vector<std::vector<int>> neighbours(values.size());
  for(const std::array<int, 3>& f : sphere.faces)
    for(int i = 0; i < 3; ++i)
      neighbours[f[i]].push_back(f[(i + 1) % 3]);  // each neighbour once: it follows in one of the edge's two faces
  for(int pass = 0; pass < passes; ++pass) {
    std::vector<double> next(values.size());
    for(std::size_t v = 0; v < values.size(); ++v) {
      double sum = 0;
      for(int u : neighbours[v])
        sum += values[u];
      next[v] = 0.5 * values[v] + 0.5 * sum / double(neighbours[v].size());
    }
    values.swap(next);
  }
  return values;
}

/// A ball covered with `count` long thin spikes, like a sea urchin: the geodesic icosphere
/// of level 6 (82k faces, `make_icosphere()`) moved out radially by a Gaussian bump two radii
/// high and 0.04 radian wide around each of `count` directions spread evenly (a Fibonacci
/// lattice). Each spike's apex is a sharp cone, which a conformal map opens; the spikes, most
/// of the surface, share a resampling's samples.
template <class Point>
CGAL::Surface_mesh<Point> spikes(int count)
{
  const double height = 2, width = 0.04;
  const std::vector<Vec> directions = fibonacci_directions(count);
  const CGAL::Spherical_parameterization::Icosphere sphere = CGAL::Spherical_parameterization::make_icosphere(6);
  std::vector<double> radii;
  for(const Eigen::Vector3d& point : sphere.points) {
    const Vec p{point.x(), point.y(), point.z()};
    double radius = 1;
    for(const Vec& d : directions) {
      const double angle = std::acos(std::clamp(dot(p, d), -1.0, 1.0)) / width;
      radius += height * std::exp(-angle * angle);
    }
    radii.push_back(radius);
  }
  return radial_graph<Point>(sphere, radii, 1);
}

/// A brain surface as a segmentation of the cortex gives it, at the size of one hemisphere's
/// (`level` 7: 328k faces): an ellipsoidal core (semi-axes 0.69, 0.55, 0.55) with folds 0.3
/// high along a curve network, the zero set of a sum of 24 plane waves on the directions
/// (15 to 20 folds around the core, as many as a hemisphere's gyri). `white`: thin folds 0.05
/// wide, the gyri of a white matter surface (2.4 times the area of the convex hull); else
/// narrow grooves 0.04 wide cut into the full shell, the sulci of a pial surface (2.5). A radial
/// graph over the icosphere of that level, hence star-shaped and genus 0; its radius is
/// smoothed over the sphere (an angular scale of about 0.03), since the fold profile leaves
/// pits and cracks one vertex wide where two folds nearly meet, which no resampling reaches.
template <class Point>
CGAL::Surface_mesh<Point> brain(int level, bool white)
{
  const double pi = std::acos(-1.0), golden_ratio = (1 + std::sqrt(5.0)) / 2;
  const double core = 0.55, height = 0.3, stretch_x = 1.25, frequency = 14;
  const double half_width = (white ? 0.025 : 0.02) / core;  // angular
  const std::vector<Vec> waves = fibonacci_directions(24);
  std::vector<double> phases;
  for(std::size_t k = 0; k < waves.size(); ++k)
    phases.push_back(2 * pi * std::fmod(double(k) * golden_ratio, 1.0));
  // The folds' mid-curves are the zero set of g, the waves' sum; the angular distance to it
  // is about |g| / |g's tangential gradient|.
  auto angular_distance_to_fold = [&](const Vec& d) {
    double g = 0;
    Vec gradient{0, 0, 0};
    for(std::size_t k = 0; k < waves.size(); ++k) {
      const double argument = frequency * dot(waves[k], d) + phases[k];
      g += std::sin(argument);
      for(int i = 0; i < 3; ++i)
        gradient[i] += frequency * std::cos(argument) * waves[k][i];
    }
    const double radial = dot(gradient, d);
    for(int i = 0; i < 3; ++i)
      gradient[i] -= radial * d[i];
    return std::abs(g) / (std::sqrt(dot(gradient, gradient)) + 1e-12);
  };
  auto radius = [&](const Vec& d) {
    const double fold = 1 / (1 + std::exp(-(half_width - angular_distance_to_fold(d)) / (0.25 * half_width)));
    return core + height * (white ? fold : 1 - fold);
  };
  const CGAL::Spherical_parameterization::Icosphere sphere = CGAL::Spherical_parameterization::make_icosphere(level);
  std::vector<double> radii;
  for(const Eigen::Vector3d& p : sphere.points)
    radii.push_back(radius(Vec{p.x(), p.y(), p.z()}));
  // The passes grow as the edges shrink, so that the angular scale smoothed over does not
  // depend on the level.
  const int passes = std::max(1, int(std::lround(10 * std::pow(4.0, level - 7))));
  return radial_graph<Point>(sphere, smoothed_over_sphere(sphere, std::move(radii), passes), stretch_x);
}

/// The shape named `capsuleL`, `helixT`, `cylinderN`, `spikesN`, `metaballsN`, `starfishN`,
/// `cortexN`, `foldedN`, `figureN`, `latticeR`, `whiteL` or `pialL` (positive numbers: length,
/// turns, vertices around, spikes, grid resolution, squared radius, icosphere level), or
/// nothing.
template <class Point>
std::optional<CGAL::Surface_mesh<Point>> by_name(const std::string& name)
{
  for(const std::string kind :
      {"capsule", "helix", "cylinder", "spikes", "metaballs", "starfish", "cortex", "folded", "figure", "lattice",
       "white", "pial"}) {
    if(name.compare(0, kind.size(), kind) != 0)
      continue;
    const std::string number = name.substr(kind.size());
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    if(number.empty() || *end != '\0' || !(value > 0) || value > 1e4)
      return std::nullopt;
    if(kind == "capsule") return capsule<Point>(value);
    if(kind == "helix") return helix<Point>(value);
    if(kind == "cylinder") return value >= 3 ? std::optional(cad_cylinder<Point>(int(value))) : std::nullopt;
    if(kind == "spikes") return value <= 1000 ? std::optional(spikes<Point>(int(value))) : std::nullopt;
    if(kind == "white" || kind == "pial")
      return value <= 8 && value == std::floor(value) ? std::optional(brain<Point>(int(value), kind == "white"))
                                                       : std::nullopt;
    if(value > 400) return std::nullopt;  // a grid of 400^3 points is already 512 MB
    if(kind == "metaballs") return metaballs<Point>(int(value));
    if(kind == "starfish") return starfish<Point>(int(value));
    if(kind == "cortex") return cortex<Point>(int(value));
    if(kind == "folded") return folded_cortex<Point>(int(value));
    if(kind == "figure") return figure<Point>(int(value));
    return lattice_sphere<Point>(value);
  }
  return std::nullopt;
}

} // namespace synthetic_shapes

#endif // SPHERICAL_PARAMETERIZATION_BENCHMARK_SYNTHETIC_SHAPES_H
