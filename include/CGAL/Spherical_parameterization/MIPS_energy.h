// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_MIPS_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_MIPS_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <array>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The MIPS energy of Hormann and Greiner, `Dirichlet / (Area(a,b,c) / InputArea)`, with the
/// exact input cotangents: `InputArea * |J|_F^2 / det J`, scale-free and conformal.
/// \cgalModels `SphericalEnergy`
struct MIPS_energy
{
  /// \cond SKIP_IN_MANUAL
  using Face_data = Jacobian_face_data;
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    using std::sqrt;
    // A_in / A = 2 A_in / |(b-a) x (c-a)|
    return t.spring(d.weights) * (2 * d.input_area) * inverse(sqrt(t.squared_double_area()));
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_MIPS_ENERGY_H
