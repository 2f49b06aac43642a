// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_AREA_BARRIER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_AREA_BARRIER_H

#include <type_traits>
#include <utility>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

template <class Energy, class = void>
struct declares_area_barrier : std::false_type
{
};
template <class Energy>
struct declares_area_barrier<Energy, std::void_t<decltype(std::declval<const Energy&>().has_area_barrier())>>
  : std::true_type
{
};

/// True if `energy` has a term that grows without bound as a face's area goes to zero
/// (`Area_distortion_energy`): it says so with a member `bool has_area_barrier() const`.
/// Such an energy never squeezes a face to the fold floor, and its Hessian stays indefinite in
/// the compressed faces up to its minimum (see `Newton_options::extend_projected_steps`).
template <class Energy>
bool has_area_barrier(const Energy& energy)
{
  if constexpr(declares_area_barrier<Energy>::value)
    return energy.has_area_barrier();
  else
    return false;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_AREA_BARRIER_H
