// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Shared by the libFuzzer targets: runs spherical_parameterize() on a mesh and aborts when
// an invariant of its contract does not hold. libFuzzer reports the abort as a crash and
// saves the input.

#ifndef SPHERICAL_PARAMETERIZATION_FUZZ_COMMON_H
#define SPHERICAL_PARAMETERIZATION_FUZZ_COMMON_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

// After the mesh headers (see test/test_parameterizer.cpp).
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Energy_mix.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace fuzz {

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Vertex = Mesh::Vertex_index;

/// Meshes with more faces are skipped: the solver's cost would slow the fuzzer down.
constexpr std::size_t max_faces = 200;

[[noreturn]] inline void violation(const char* what, const SP::Result& r)
{
  std::fprintf(stderr, "INVARIANT VIOLATED: %s\n  status %d (%s), detail '%s', valid %d, iterations %zu, stages '%s'\n",
               what, int(r.status), r.message(), r.detail.c_str(), int(r.valid), r.iterations, r.stage_summary().c_str());
  std::abort();
}

inline bool same_bits(const Point& a, const Point& b)
{
  const double u[3] = {a.x(), a.y(), a.z()}, v[3] = {b.x(), b.y(), b.z()};
  return std::memcmp(u, v, sizeof u) == 0;
}

/// The codes that `Error_code.h` says are found before any solve: nothing is written.
inline bool is_input_error(SP::Error_code c)
{
  return c != SP::Error_code::OK && c <= SP::Error_code::INVALID_INITIALIZATION;
}

/// Runs the solver with `np` and checks: never a crash (the sanitizers and CGAL's assertions
/// watch); an input error leaves the output map untouched and says why; a written map has
/// finite points; OK and NOT_CONVERGED come with a valid map, every point of norm 1 within
/// 1e-9; `Result::valid` agrees with `measure_distortion()`.
template <class NamedParameters>
void check_parameterization(Mesh mesh, const NamedParameters& np)
{
  if(mesh.number_of_faces() > max_faces)
    return;
  const Point sentinel(-7.25, 3.5, 11.0);
  auto out = mesh.add_property_map<Vertex, Point>("v:fuzz_sphere", sentinel).first;
  const SP::Result r = CGAL::spherical_parameterize(mesh, out, np);

  if(is_input_error(r.status)) {
    for(Vertex v : mesh.vertices())
      if(!same_bits(out[v], sentinel))
        violation("an input error wrote to the output map", r);
    if(r.detail.empty())
      violation("an input error without a detail", r);
    return;
  }
  double worst = 0;
  for(Vertex v : mesh.vertices()) {
    const Point& p = out[v];
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      violation("a non-finite point in the output map", r);
    worst = std::max(worst, std::abs(std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z()) - 1));
  }
  const bool claims_valid = r.status == SP::Error_code::OK || r.status == SP::Error_code::NOT_CONVERGED;
  if(claims_valid && worst > 1e-9)
    violation("OK or NOT_CONVERGED with a point off the unit sphere by more than 1e-9", r);
  if(claims_valid && !r.valid)
    violation("OK or NOT_CONVERGED with Result::valid false", r);
  if(r.valid != SP::measure_distortion(mesh, out).is_valid())
    violation("Result::valid disagrees with measure_distortion()", r);
}

} // namespace fuzz

#endif // SPHERICAL_PARAMETERIZATION_FUZZ_COMMON_H
