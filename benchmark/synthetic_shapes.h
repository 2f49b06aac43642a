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

#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace synthetic_shapes {

using Vec = std::array<double, 3>;

inline Vec cross(const Vec& a, const Vec& b)
{
  return Vec{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// A centre line `point(s)`, `s` in [0, 1], with two unit normals `first_normal(s)` and
/// `second_normal(s)` such that (first, second, tangent) is right-handed.
struct Centre_line
{
  std::function<Vec(double)> point, first_normal, second_normal;
  double length = 0;
};

/// A tube of `radius` around `line`, `around` vertices per ring, rings about as far apart as
/// the vertices of a ring, closed by a fan at each end; faces oriented outwards.
template <class Point>
CGAL::Surface_mesh<Point> tube(const Centre_line& line, double radius, int around)
{
  const double pi = std::acos(-1.0);
  const int rings = 1 + int(std::ceil(line.length / (2 * pi * radius / around)));
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

/// A straight tube of radius 1 and the given length, 32 vertices around.
template <class Point>
CGAL::Surface_mesh<Point> capsule(double length)
{
  Centre_line line;
  line.point = [length](double s) { return Vec{0, 0, length * s}; };
  line.first_normal = [](double) { return Vec{1, 0, 0}; };
  line.second_normal = [](double) { return Vec{0, 1, 0}; };
  line.length = length;
  return tube<Point>(line, 1, 32);
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

/// The shape named `capsuleL` or `helixT` (L, T positive numbers), or nothing.
template <class Point>
std::optional<CGAL::Surface_mesh<Point>> by_name(const std::string& name)
{
  for(const std::string kind : {"capsule", "helix"}) {
    if(name.compare(0, kind.size(), kind) != 0)
      continue;
    const std::string number = name.substr(kind.size());
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    if(number.empty() || *end != '\0' || !(value > 0) || value > 1e4)
      return std::nullopt;
    return kind == "capsule" ? capsule<Point>(value) : helix<Point>(value);
  }
  return std::nullopt;
}

} // namespace synthetic_shapes

#endif // SPHERICAL_PARAMETERIZATION_BENCHMARK_SYNTHETIC_SHAPES_H
