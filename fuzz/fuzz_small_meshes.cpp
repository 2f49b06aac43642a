// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: the bytes are decoded into a small polygon soup, which becomes a
// Surface_mesh through CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh() when
// is_polygon_soup_a_polygon_mesh() accepts it; spherical_parameterize() then runs with
// number_of_iterations(20), a fuzzed energy and pipeline, and its invariants are checked
// (fuzz_common.h). Build and run: fuzz/run_fuzz.sh.
//
// Layout of the bytes (missing bytes read as 0):
//   0      shape: bit 0-1 = 0 or 1 free triangles, 2 octahedron, 3 subdivided icosahedron
//   1      energy (mod 6: tutte, dirichlet, area, stretch, mips, combined); bit 7: PAPER pipeline
//   2      scale exponent: coordinates times 10^(5 (b mod 64) - 160), from 1e-160 to 1e155
//   3      free triangles: number of vertices, 4 + b mod 29; else unused
//   4      free triangles: number of triangles, 1 + b mod 64; else unused
//   then   3 bytes per vertex, one per coordinate (see coordinate()), then for free
//          triangles 3 bytes per triangle, each an index taken modulo the vertex count.
// For the fixed shapes the coordinates perturb the shape's points, so that the solver sees
// closed genus-0 meshes with folds, slivers and degenerate faces.

#include "fuzz_common.h"

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

using Polygons = std::vector<std::vector<std::size_t>>;

struct Bytes
{
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t next() { return at < size ? data[at++] : 0; }
};

/// One coordinate from one byte: a grid of step 1/8 in [-15.5, 15.5], or for the last eight
/// values a special one (NaN, infinities, huge, tiny, zero).
double coordinate(std::uint8_t b)
{
  static const double special[8] = {std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::infinity(),
                                    -std::numeric_limits<double>::infinity(),
                                    1e300, -1e-300, 1e-320, 0.0, -0.0};
  return b >= 248 ? special[b - 248] : (double(b) - 124) / 8;
}

/// The icosahedron's 12 points and 20 faces, split once into 80 triangles, points on the
/// unit sphere, faces counterclockwise seen from outside.
void icosphere(std::vector<std::array<double, 3>>& points, Polygons& faces)
{
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> p;
  for(double a : {-1.0, 1.0})
    for(double b : {-t, t}) {
      p.push_back({0, a, b});
      p.push_back({a, b, 0});
      p.push_back({b, 0, a});
    }
  auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  auto sub = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
  };
  auto cross = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  Polygons coarse;
  for(std::size_t i = 0; i < 12; ++i)
    for(std::size_t j = i + 1; j < 12; ++j)
      for(std::size_t k = j + 1; k < 12; ++k) {
        auto edge = [&](std::size_t u, std::size_t v) { return std::abs(dot(sub(p[u], p[v]), sub(p[u], p[v])) - 4) < 1e-9; };
        if(!edge(i, j) || !edge(j, k) || !edge(k, i)) continue;
        if(dot(p[i], cross(sub(p[j], p[i]), sub(p[k], p[i]))) > 0) coarse.push_back({i, j, k});
        else coarse.push_back({i, k, j});
      }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> middle;
  auto midpoint = [&](std::size_t a, std::size_t b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto found = middle.find(key);
    if(found != middle.end()) return found->second;
    std::array<double, 3> m = {p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]};
    const double n = std::sqrt(dot(m, m));
    p.push_back({m[0] / n, m[1] / n, m[2] / n});
    middle.emplace(key, p.size() - 1);
    return p.size() - 1;
  };
  faces.clear();
  for(const auto& f : coarse) {
    const std::size_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    faces.push_back({f[0], ab, ca});
    faces.push_back({f[1], bc, ab});
    faces.push_back({f[2], ca, bc});
    faces.push_back({ab, bc, ca});
  }
  for(auto& q : p) {
    const double n = std::sqrt(dot(q, q));
    q = {q[0] / n, q[1] / n, q[2] / n};
  }
  points = p;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Bytes in{data, size};
  const int shape = in.next() & 3;
  const std::uint8_t energy_byte = in.next();
  const double scale = std::pow(10.0, 5.0 * (in.next() % 64) - 160);
  const std::size_t free_vertices = 4 + in.next() % 29;
  const std::size_t free_triangles = 1 + in.next() % 64;

  std::vector<std::array<double, 3>> base;
  Polygons polygons;
  double amplitude = 1;  // of the perturbation, relative to the shape
  if(shape == 2) {
    base = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    polygons = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    amplitude = 1.0 / 32;
  } else if(shape == 3) {
    icosphere(base, polygons);
    amplitude = 1.0 / 128;
  } else {
    base.assign(free_vertices, {0, 0, 0});
  }

  std::vector<fuzz::Point> points;
  for(const auto& b : base) {
    double c[3];
    for(int k = 0; k < 3; ++k) c[k] = (b[k] + amplitude * coordinate(in.next())) * scale;
    points.emplace_back(c[0], c[1], c[2]);
  }
  if(shape < 2)
    for(std::size_t f = 0; f < free_triangles; ++f) {
      const std::size_t a = in.next() % free_vertices, b = in.next() % free_vertices, c = in.next() % free_vertices;
      polygons.push_back({a, b, c});
    }

  if(!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons))
    return 0;
  fuzz::Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);

  static const char* const names[6] = {"tutte", "dirichlet", "area", "stretch", "mips", "combined"};
  const auto energy = fuzz::SP::energy_by_name(names[(energy_byte & 127) % 6]);
  const auto pipeline = (energy_byte & 128) ? fuzz::SP::Pipeline::PAPER : fuzz::SP::Pipeline::ROBUST;
  fuzz::check_parameterization(
    mesh, fuzz::SP::parameters::energy(*energy, fuzz::SP::parameters::pipeline(pipeline)).number_of_iterations(20));
  return 0;
}
