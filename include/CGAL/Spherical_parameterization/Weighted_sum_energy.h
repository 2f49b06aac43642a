// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_WEIGHTED_SUM_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_WEIGHTED_SUM_ENERGY_H

#include <CGAL/Spherical_parameterization/Area_energy.h>
#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>
#include <CGAL/Spherical_parameterization/internal/energies/area_barrier.h>

#include <array>
#include <tuple>
#include <utility>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// `sum_i w_i E_i` of two or more energies (Friedel et al., Section 2.2). Terms of weight 0
/// are skipped. The weights can be changed between solves.
/// \cgalModels `SphericalEnergy`
template <class... Energies>
class Weighted_sum
{
public:
  /// The number of terms.
  static constexpr std::size_t size = sizeof...(Energies);
  /// The weights `w_i`, in the order of the terms.
  using Weights = std::array<double, size>;

  /// The sum of the terms `energies` with the weights `weights`.
  explicit Weighted_sum(const Weights& weights, Energies... energies)
    : weights_(weights), energies_(energies...) {}

  /// The weights of the terms.
  const Weights& weights() const { return weights_; }
  /// Changes the weights; the terms stay. A term of weight 0 is skipped.
  void set_weights(const Weights& weights) { weights_ = weights; }

  /// \cond SKIP_IN_MANUAL
  using Face_data = std::tuple<typename Energies::Face_data...>;

  Face_data face_data(const Reference_triangle& r) const
  {
    return std::apply([&](const auto&... e) { return Face_data(e.face_data(r)...); }, energies_);
  }

  // A term of non-zero weight has an area barrier.
  bool has_area_barrier() const
  {
    return std::apply(
      [&](const auto&... e) {
        std::size_t i = 0;
        return ((weights_[i++] != 0 && internal::has_area_barrier(e)) || ...);
      },
      energies_);
  }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    Number sum(0.0);
    add_terms(t, d, sum, std::index_sequence_for<Energies...>());
    return sum;
  }
  /// \endcond

private:
  template <class Number, std::size_t... I>
  void add_terms(const Chord_triangle<Number>& t, const Face_data& d, Number& sum,
                 std::index_sequence<I...>) const
  {
    ((weights_[I] != 0 ? (void)(sum += std::get<I>(energies_).flat_energy(t, std::get<I>(d)) * weights_[I])
                       : (void)0), ...);
  }

  Weights weights_;
  std::tuple<Energies...> energies_;
};

/// \ingroup PkgSphericalParameterizationEnergies
/// The paper's Combined energy `a * Dirichlet + b * Area`; (1, 1) is its default for big meshes.
using Combined_energy = Weighted_sum<Dirichlet_energy, Area_energy>;

/// Combined energy with weights `a` (Dirichlet) and `b` (Area).
inline Combined_energy combined_energy(double a = 1, double b = 1)
{
  return Combined_energy({a, b}, Dirichlet_energy(), Area_energy());
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_WEIGHTED_SUM_ENERGY_H
