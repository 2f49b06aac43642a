// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_AREA_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_AREA_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <algorithm>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The area energy of Friedel et al., `Area(a,b,c)^2 / InputArea`, with the flat chord area,
/// `InputArea` at least the reference triangle's `area_floor`.
/// Alone it ignores triangle shape (needles, folds): use it in a `Weighted_sum`.
/// \cgalModels `SphericalEnergy`
struct Area_energy
{
  /// \cond SKIP_IN_MANUAL
  using Face_data = double;  // input area
  Face_data face_data(const Reference_triangle& r) const { return std::max(r.area, r.area_floor); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& input_area) const
  {
    return t.squared_double_area() * (0.25 / input_area);
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_AREA_ENERGY_H
