// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H

#include <CGAL/Spherical_parameterization/Area_distortion_energy.h>
#include <CGAL/Spherical_parameterization/Area_energy.h>
#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Inverse_dirichlet_energy.h>
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
/// The energy chosen at run time: a weighted sum of the seven built-in energies, in the order
/// Tutte, Dirichlet, Area, Stretch, MIPS, Area_distortion, Inverse_dirichlet: what the command
/// line uses. (The default energy of `spherical_parameterize()` is `balanced_energy()`, of type
/// `Balanced_energy`.)
using Energy_mix = Weighted_sum<Tutte_energy, Dirichlet_energy, Area_energy, Stretch_energy, MIPS_energy,
                                Area_distortion_energy, Inverse_dirichlet_energy>;

/// \ingroup PkgSphericalParameterizationEnergies
/// The energy called `name`: "tutte", "dirichlet", "area", "stretch", "mips" (weight `a`),
/// "area_distortion", "inverse_dirichlet" (weight `a`), "combined" (`a` Dirichlet + `b` Area),
/// "balanced" (`a` Dirichlet with exact cotangents + `b` Area_distortion:
/// `balanced_energy(b / (a + b))` times `a + b`) or "symmetric_dirichlet" (`a` Dirichlet with
/// exact cotangents + `b` Inverse_dirichlet: `symmetric_dirichlet_energy(b / (a + b))` times
/// `a + b`); the two weights of "balanced" and "symmetric_dirichlet" may be 0, not both.
/// "balanced" also takes `c`, the weight of an added Inverse_dirichlet term, which keeps the
/// samples of a resampling close on the surface in every direction (the sharp tips of low-poly
/// models need it; the user manual gives the measurements); every other name takes `c = 0`.
/// Empty for an unknown name or a weight that is not finite and positive.
inline std::optional<Energy_mix> energy_by_name(const std::string& name, double a = 1, double b = 1,
                                                double c = 0)
{
  auto positive = [](double w) { return std::isfinite(w) && w > 0; };
  auto non_negative = [](double w) { return std::isfinite(w) && w >= 0; };
  // The ends of the two knobs, weights (1, 0) and (0, 1), are energies of their own.
  const bool knob = name == "balanced" || name == "symmetric_dirichlet";
  const bool valid = knob ? non_negative(a) && non_negative(b) && a + b > 0
                          : positive(a) && (name != "combined" || positive(b));
  if(!valid || !non_negative(c) || (c != 0 && name != "balanced"))
    return std::nullopt;
  Energy_mix::Weights w{0, 0, 0, 0, 0, 0, 0};
  if(name == "tutte") w[0] = a;
  else if(name == "dirichlet") w[1] = a;
  else if(name == "area") w[2] = a;
  else if(name == "stretch") w[3] = a;
  else if(name == "mips") w[4] = a;
  else if(name == "area_distortion") w[5] = a;
  else if(name == "inverse_dirichlet") w[6] = a;
  else if(name == "combined") { w[1] = a; w[2] = b; }
  else if(name == "balanced") { w[1] = a; w[5] = b; w[6] = c; }
  else if(name == "symmetric_dirichlet") { w[1] = a; w[6] = b; }
  else return std::nullopt;
  // The knobs' conformal ends take the exact cotangents, as `balanced_energy()` does.
  const Dirichlet_energy dirichlet = knob ? Dirichlet_energy{0, M_PI} : Dirichlet_energy();
  return Energy_mix(w, Tutte_energy(), dirichlet, Area_energy(), Stretch_energy(), MIPS_energy(),
                    Area_distortion_energy(), Inverse_dirichlet_energy());
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ENERGY_MIX_H
