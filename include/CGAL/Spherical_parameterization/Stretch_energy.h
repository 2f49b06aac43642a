// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_STRETCH_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_STRETCH_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <array>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The stretch energy of Sander et al., as written by Friedel et al., Section 2.2:
/// `(InputArea / Area(a,b,c))^2 * Dirichlet`, with the flat chord area and the exact
/// cotangents of the input (`InputArea * |J|_F^2`, non-negative). It grows without bound as
/// a chord triangle shrinks, so it needs a start without degenerate faces.
/// \cgalModels `SphericalEnergy`
struct Stretch_energy
{
  /// \cond SKIP_IN_MANUAL
  using Face_data = Jacobian_face_data;
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    // (A_in / A)^2 = 4 A_in^2 / |(b-a) x (c-a)|^2
    return t.spring(d.weights) * (4 * d.input_area * d.input_area) * inverse(t.squared_double_area());
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_STRETCH_ENERGY_H
