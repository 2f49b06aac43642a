// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_AREA_DISTORTION_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_AREA_DISTORTION_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// A symmetric area distortion, `InputArea * (s + 1 / s) / 2`, with
/// `s = det(a, b, c) / (2 InputArea)` the signed area ratio of the chord triangle (its area
/// times its plane's distance to the centre, which is 1 up to the square of the edge lengths)
/// and `InputArea` at least the reference triangle's `area_floor`. Each face's term is
/// smallest at `s = 1` and grows without bound as the face shrinks, and it is `+inf` for a
/// flipped face. Unlike the paper's `Area_energy`, whose gain from squeezing a face away is
/// bounded, it keeps every face's area away from zero, so a protrusion that a conformal
/// energy squeezes into a few pixels of the sphere keeps a share of it; and a Newton step
/// from a fold-free map cannot fold it. Near `s = 1` it is `InputArea * (1 + (s - 1)^2 / 2)`.
/// It ignores triangle shape: use it in a sum with an energy of angles (`balanced_energy()`).
/// \cgalModels `SphericalEnergy`
struct Area_distortion_energy
{
  /// \cond SKIP_IN_MANUAL
  using Face_data = double;  // input area
  bool has_area_barrier() const { return true; }
  Face_data face_data(const Reference_triangle& r) const { return std::max(r.area, r.area_floor); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& input_area) const
  {
    const Number det = t.determinant();
    if(!(value_of(det) > 0))
      return Number(std::numeric_limits<double>::infinity());
    // InputArea (s + 1/s) / 2 = det / 4 + InputArea^2 / det
    return det * 0.25 + (input_area * input_area) * inverse(det);
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_AREA_DISTORTION_ENERGY_H
