// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H

#include <CGAL/Spherical_parameterization/Area_energy.h>
#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/MIPS_energy.h>
#include <CGAL/Spherical_parameterization/Stretch_energy.h>
#include <CGAL/Spherical_parameterization/Tutte_energy.h>
#include <CGAL/Spherical_parameterization/Weighted_sum_energy.h>

#include <cmath>
#include <optional>
#include <string>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The energy chosen at run time: a weighted sum of the five built-in energies, in the order
/// Tutte, Dirichlet, Area, Stretch, MIPS: what the command line uses. (The default energy of
/// `spherical_parameterize()` is `combined_energy(1, 1)`, of type `Combined_energy`.)
using Energy_mix = Weighted_sum<Tutte_energy, Dirichlet_energy, Area_energy, Stretch_energy, MIPS_energy>;

/// \ingroup PkgSphericalParameterizationEnergies
/// The energy called `name`: "tutte", "dirichlet", "area", "stretch", "mips" (weight `a`),
/// or "combined" (`a` Dirichlet + `b` Area). Empty for an unknown name or a weight that is
/// not finite and positive.
inline std::optional<Energy_mix> energy_by_name(const std::string& name, double a = 1, double b = 1)
{
  auto positive = [](double w) { return std::isfinite(w) && w > 0; };
  if(!positive(a) || (name == "combined" && !positive(b)))
    return std::nullopt;
  Energy_mix::Weights w{0, 0, 0, 0, 0};
  if(name == "tutte") w[0] = a;
  else if(name == "dirichlet") w[1] = a;
  else if(name == "area") w[2] = a;
  else if(name == "stretch") w[3] = a;
  else if(name == "mips") w[4] = a;
  else if(name == "combined") { w[1] = a; w[2] = b; }
  else return std::nullopt;
  return Energy_mix(w, Tutte_energy(), Dirichlet_energy(), Area_energy(), Stretch_energy(), MIPS_energy());
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H
