// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_SPHERICAL_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_SPHERICAL_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>
#include <CGAL/Spherical_parameterization/d_min_correction.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/backends/parallel_for.h>

#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The sum of `values` in their order (so that it does not depend on how they were
/// computed), or `+inf` if one is not finite.
inline double finite_sum(const std::vector<double>& values)
{
  double sum = 0;
  for(double e : values) {
    if(!std::isfinite(e))
      return std::numeric_limits<double>::infinity();
    sum += e;
  }
  return sum;
}

/// The energy of a sphere map: `sum_f d_min(f)^-2 * E_flat(f)` (Friedel et al., Section 1),
/// or the plain flat sum when the correction is off. The per-face constants of the energy
/// policy are computed once from the reference triangles.
template <class Energy>
class Spherical_energy
{
public:
  /// With `CGAL::Parallel_tag`, the per-face constants are computed in parallel where the
  /// policy's `Face_data` is default constructible: on a large mesh they take a noticeable time
  /// on one core.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  Spherical_energy(const Triangle_soup& soup, const Energy& energy, bool d_min_correction = true,
                   ConcurrencyTag = ConcurrencyTag())
    : faces_(&soup.faces), energy_(energy), correction_(d_min_correction)
  {
    const std::size_t n = soup.faces.size();
    if constexpr(std::is_default_constructible<typename Energy::Face_data>::value) {
      data_.resize(n);
      parallel_for<ConcurrencyTag>(n, [&](std::size_t f) { data_[f] = energy_.face_data(soup.reference_triangle(f)); });
    } else {
      data_.reserve(n);
      for(std::size_t f = 0; f < n; ++f)
        data_.push_back(energy_.face_data(soup.reference_triangle(f)));
    }
  }

  std::size_t number_of_faces() const { return faces_->size(); }
  const Faces& faces() const { return *faces_; }

  /// The energy of face `f`, as a `double` or as a `Triangle_jet` with derivatives.
  /// Its value is not finite, or infinite, once the chord triangle reaches a hemisphere.
  template <class Number>
  Number face(std::size_t f, const Points& x) const
  {
    const auto& t = (*faces_)[f];
    const Chord_triangle<Number> chord(x[t[0]], x[t[1]], x[t[2]]);
    Number e = energy_.flat_energy(chord, data_[f]);
    if(!correction_)
      return e;
    return e * inverse_squared_d_min(chord);
  }

  /// The total energy, `+inf` if any face is past the barrier or not finite; the faces
  /// evaluated in parallel with `CGAL::Parallel_tag`, summed in their order either way.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  double value(const Points& x) const
  {
    std::vector<double> values(data_.size());
    parallel_for<ConcurrencyTag>(data_.size(), [&](std::size_t f) { values[f] = face<double>(f, x); });
    return finite_sum(values);
  }

private:
  const Faces* faces_;
  Energy energy_;
  bool correction_;
  std::vector<typename Energy::Face_data> data_;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_SPHERICAL_ENERGY_H
