// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_DIRICHLET_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_DIRICHLET_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <array>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The cotangent (Dirichlet) energy of Pinkall and Polthier,
/// `(cot A |b-c|^2 + cot B |c-a|^2 + cot C |a-b|^2) / 2`, with the input angles clamped to
/// `[min_angle, max_angle]`. By default only obtuse angles are clamped, to 90 degrees, so
/// that no weight is negative. Friedel et al. (Section 3) clamp to `[5, 85]` degrees:
/// `Dirichlet_energy{5 * M_PI / 180, 85 * M_PI / 180}`. That clamp weighs the short edge of
/// a needle too little (cot 5 degrees) against its long ones (cot 85 degrees instead of about
/// 0), which badly distorts the maps of meshes made of long thin triangles.
/// `Dirichlet_energy{0, M_PI}` takes the exact cotangents, negative ones included.
/// \cgalModels `SphericalEnergy`
struct Dirichlet_energy
{
  double min_angle = 0;                ///< lower clamp of the input angles, radians
  double max_angle = 90 * M_PI / 180;  ///< upper clamp of the input angles, radians

  /// \cond SKIP_IN_MANUAL
  using Face_data = std::array<double, 3>;  // half cotangent weight of each edge
  Face_data face_data(const Reference_triangle& r) const { return r.half_cotangents(min_angle, max_angle); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& w) const
  {
    return t.spring(w);
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_DIRICHLET_ENERGY_H
