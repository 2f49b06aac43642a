// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_UNTANGLING_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_UNTANGLING_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <array>
#include <cmath>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The regularized shape + area energy of Garanzha et al. 2021 ("Foldover-free maps in 50
/// lines of code"), on the chord triangle with the signed area `det(a, b, c) / 2`:
/// `A_in ((1 - theta) |J|^2 + theta (s^2 + 1)) / (2 chi(s, eps))`, `s = det / (2 A_in)`,
/// `chi(s, eps) = (s + sqrt(s^2 + eps^2)) / 2`. Finite for folded faces, so it can unfold
/// them; as `eps -> 0` it becomes a barrier against folds.
struct Untangling_energy
{
  double epsilon = 1;
  double theta = 0.5;

  using Face_data = Jacobian_face_data;
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    using std::sqrt;
    const Number s = t.determinant() * (0.5 / d.input_area);
    const Number chi = (s + sqrt(s * s + epsilon * epsilon)) * 0.5;
    // A_in |J|^2 = sum_i cot_i |e_i|^2 = 2 * spring(half cotangents)
    const Number shape = t.spring(d.weights) * (2 * (1 - theta));
    const Number area = (s * s + 1.0) * (theta * d.input_area);
    return (shape + area) * inverse(chi * 2.0);
  }
};

/// Sander's stretch with the signed chord area `det(a, b, c) / 2` in place of the flat area:
/// `(A_in / (det / 2))^2 * A_in |J|^2`. Infinite at `det = 0`, so together with a line
/// search that never crosses `det = 0` it keeps a fold-free map fold-free.
struct Signed_stretch_energy
{
  using Face_data = Jacobian_face_data;
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    const Number ratio = (2 * d.input_area) * inverse(t.determinant());
    return t.spring(d.weights) * ratio * ratio;
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_UNTANGLING_ENERGY_H
