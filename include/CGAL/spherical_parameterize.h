// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZE_H
#define CGAL_SPHERICAL_PARAMETERIZE_H

#include <CGAL/Spherical_parameterization/Spherical_parameterizer_3.h>
#include <CGAL/Spherical_parameterization/Balanced_energy.h>
#include <CGAL/Spherical_parameterization/named_parameters.h>

#include <CGAL/Named_function_parameters.h>

namespace CGAL {

/// \ingroup PkgSphericalParameterizationRef
/// Maps the closed, connected, genus-0 triangle mesh `tm` one-to-one onto the unit sphere
/// and writes the sphere point of every vertex to `sphere_map`, which may be the mesh's own
/// vertex point map (the mesh is then mapped in place). One call of
/// `Spherical_parameterization::Spherical_parameterizer_3`: see it for the method.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or
///         `CGAL::Parallel_if_available_tag` (the default): whether the per-face work runs on
///         TBB's threads; the map does not depend on it
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam SphereMap a writable property map `vertex_descriptor -> Point_3`
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{energy} a model of `SphericalEnergy`; default `balanced_energy()` \cgalParamNEnd
///   \cgalParamNBegin{pipeline} `Pipeline::ROBUST` (default) or `Pipeline::PAPER` \cgalParamNEnd
///   \cgalParamNBegin{initial_sphere_map} a readable map `vertex -> Point_3` to start from \cgalParamNEnd
///   \cgalParamNBegin{d_min_correction} default `true` \cgalParamNEnd
///   \cgalParamNBegin{tolerance} default `1e-6` \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map} the input positions; default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
///   \cgalParamNBegin{number_of_iterations} cap per stage; default 200 \cgalParamNEnd
///   \cgalParamNBegin{maximum_running_time} seconds; default unlimited \cgalParamNEnd
///   \cgalParamNBegin{visitor} `bool(const Progress&)`, `false` cancels \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver} a model of `SphericalSparseSolverTraits` \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \return the status, the validity figures of the map and the solver's figures.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class SphereMap,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Spherical_parameterization::Result
spherical_parameterize(const TriangleMesh& tm, SphereMap sphere_map,
                       const NamedParameters& np = CGAL::parameters::default_values())
{
  namespace SP = Spherical_parameterization;
  using parameters::choose_parameter;
  using parameters::get_parameter;

  const auto energy = choose_parameter(get_parameter(np, SP::internal_np::energy_t()), SP::balanced_energy());
  using Solver = std::decay_t<decltype(choose_parameter(get_parameter(np, internal_np::sparse_linear_solver),
                                                        SP::Default_sparse_solver_traits()))>;
  // The kernel of the points unless the user gives traits (a point type with no kernel needs them).
  using Given_traits =
    typename internal_np::Lookup_named_param_def<internal_np::geom_traits_t, NamedParameters, CGAL::Default>::type;
  using Geom_traits = typename SP::internal::Geom_traits_of<TriangleMesh, Given_traits, NamedParameters>::type;
  const Geom_traits traits = choose_parameter<Geom_traits>(get_parameter(np, internal_np::geom_traits));
  SP::Spherical_parameterizer_3<TriangleMesh, std::decay_t<decltype(energy)>, Geom_traits, Solver, ConcurrencyTag>
    parameterizer(energy, traits);

  SP::Result result;
  result.status = parameterizer.precompute(tm, np);
  if(result.status != SP::Error_code::OK) {
    result.detail = parameterizer.input_detail();
    return result;
  }
  return parameterizer.solve(sphere_map, np);
}

} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZE_H
