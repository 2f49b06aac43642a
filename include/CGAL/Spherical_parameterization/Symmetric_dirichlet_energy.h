// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SYMMETRIC_DIRICHLET_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SYMMETRIC_DIRICHLET_ENERGY_H

#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Inverse_dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Weighted_sum_energy.h>

#include <CGAL/assertions.h>

#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// `(1 - w) Dirichlet + w Inverse_dirichlet`, both with the exact cotangents:
/// `InputArea ((1 - w) |J|_F^2 + w |J^-1|_F^2)`. `w = 0` is the conformal energy, `w = 1/2`
/// half the symmetric Dirichlet energy (Schreiner et al. 2004, Smith and Schaefer 2015). The
/// inverse term is a barrier at zero area that also keeps a face from being squeezed in one
/// direction, so this family keeps long tubes sampled around and along them (the user
/// manual compares it with the default).
/// \cgalModels `SphericalEnergy`
using Symmetric_dirichlet_energy = Weighted_sum<Dirichlet_energy, Inverse_dirichlet_energy>;

/// \ingroup PkgSphericalParameterizationEnergies
/// The energy `(1 - w) Dirichlet + w Inverse_dirichlet` with `w = inverse_weight`.
/// \pre `0 <= inverse_weight <= 1`
inline Symmetric_dirichlet_energy symmetric_dirichlet_energy(double inverse_weight = 0.5)
{
  CGAL_precondition(inverse_weight >= 0 && inverse_weight <= 1);
  return Symmetric_dirichlet_energy({1 - inverse_weight, inverse_weight}, Dirichlet_energy{0, M_PI},
                                    Inverse_dirichlet_energy());
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SYMMETRIC_DIRICHLET_ENERGY_H
