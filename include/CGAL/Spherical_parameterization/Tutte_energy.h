// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_TUTTE_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_TUTTE_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// Tutte's uniform spring energy `|a-b|^2 + |b-c|^2 + |c-a|^2`; it ignores the input
/// geometry. The most robust start of the pipeline.
/// \cgalModels `SphericalEnergy`
struct Tutte_energy
{
  /// \cond SKIP_IN_MANUAL
  struct Face_data {};
  Face_data face_data(const Reference_triangle&) const { return {}; }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data&) const
  {
    return t.spring({1.0, 1.0, 1.0});
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_TUTTE_ENERGY_H
