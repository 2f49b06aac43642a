// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETERS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// How the solve starts and proceeds.
enum class Pipeline
{
  /// The default. Starts from a fold-free map where the central projection folds, untangles
  /// what is left, and minimizes the chosen energy without ever letting a face flip.
  ROBUST,
  /// The recipe of Friedel et al., exactly: central projection about the centroid, then
  /// plain minimization of the chosen energy. Fold-free on many meshes, not on all.
  PAPER
};

namespace internal_np {
// Tags of the package's own named parameters (CGAL 5.5 has no hook to register new ones).
struct energy_t {};
struct d_min_correction_t {};
struct pipeline_t {};
struct initial_sphere_map_t {};
struct tolerance_t {};
} // namespace internal_np

/// \ingroup PkgSphericalParameterizationRef
/// The package's named parameters. Each function starts a chain, or appends to one given as
/// its last argument; CGAL's own parameters then follow with dots, for example
/// `parameters::energy(combined_energy(1, 2)).number_of_iterations(50).verbose(true)`.
namespace parameters {

#define CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(NAME)                                     \
  template <class T>                                                                              \
  CGAL::Named_function_parameters<T, internal_np::NAME##_t> NAME(const T& value)                  \
  {                                                                                               \
    return CGAL::Named_function_parameters<T, internal_np::NAME##_t>(value);                      \
  }                                                                                               \
  template <class T, class NP_T, class NP_Tag, class NP_Base>                                     \
  CGAL::Named_function_parameters<T, internal_np::NAME##_t,                                       \
                                  CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>         \
  NAME(const T& value, const CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>& np)          \
  {                                                                                               \
    return {value, np};                                                                           \
  }

/// The energy policy (a model of `SphericalEnergy`); default `combined_energy(1, 1)`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(energy)
/// `false` drops the `d_min^-2` factor, to show the collapse of flat energies; default `true`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(d_min_correction)
/// `Pipeline::ROBUST` (default) or `Pipeline::PAPER`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(pipeline)
/// A readable property map `vertex -> Point_3` with the starting map on the unit sphere; it
/// replaces the built-in initialization (points are normalized; with `Pipeline::ROBUST` its degree
/// must be 1 relative to the input's orientation, else `INVALID_INITIALIZATION`).
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(initial_sphere_map)
/// Relative decrease of the energy below which the solver stops; default `1e-6`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(tolerance)

#undef CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER

using CGAL::parameters::Default_named_parameters;
using CGAL::parameters::default_values;

} // namespace parameters
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETERS_H
