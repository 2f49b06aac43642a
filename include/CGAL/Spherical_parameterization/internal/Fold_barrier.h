// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_FOLD_BARRIER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_FOLD_BARRIER_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <cmath>
#include <limits>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A barrier that is zero on faces whose area ratio `s r0 = (det(a, b, c) / 2) / InputArea`
/// is above `activation` (r0) and grows to `+inf` as the face degenerates:
/// `InputArea * b(s)`, `b(s) = -(1 - s)^2 log(s)` for `0 < s < 1` (C2 at `s = 1`, the
/// clamped barrier of incremental potential contact, Li et al. 2020). Added to the user's
/// energy once the map is fold-free, it keeps it fold-free and puts a floor under the area
/// ratios (protrusions are otherwise squeezed below double precision), while every face
/// above the activation ratio sees the user's energy alone.
struct Fold_barrier
{
  double activation = 1e-4;

  using Face_data = double;  // input area
  Face_data face_data(const Reference_triangle& r) const { return r.area; }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& input_area) const
  {
    const Number s = t.determinant() * (0.5 / (input_area * activation));
    const double v = value_of(s);
    if(v >= 1)
      return Number(0.0);
    if(!(v > 0))
      return Number(std::numeric_limits<double>::infinity());
    const double l = std::log(v), u = 1 - v;
    const double b = -u * u * l;
    const double d1 = 2 * u * l - u * u / v;
    const double d2 = -2 * l + 4 * u / v + u * u / (v * v);
    return chain(s, b, d1, d2) * input_area;
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_FOLD_BARRIER_H
