// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INVERSE_DIRICHLET_ENERGY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INVERSE_DIRICHLET_ENERGY_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <limits>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The Dirichlet energy of the inverse map, `InputArea |J^-1|_F^2` for the affine map `J` from
/// the input triangle to its chord triangle (the scale of `Dirichlet_energy`, `InputArea
/// |J|_F^2`): `InputArea (1 / s1^2 + 1 / s2^2)` with `s1, s2` the singular values of `J`. It is
/// the exact Dirichlet energy times `(2 InputArea / det(a, b, c))^2`, `+inf` for a flipped face.
///
/// Where the Area_distortion term sees only a face's area, this one sees its smallest
/// stretch: it grows as the sphere's samples along any direction of the surface thin out, so a
/// tube keeps samples around and along it, which a resampling of the surface needs. With
/// `Dirichlet_energy` it forms the symmetric Dirichlet energy (`symmetric_dirichlet_energy()`).
/// It uses the input's own area, not its floor: a tiny face costs little whatever its size on
/// the sphere, so the clusters of near-coincident vertices of isosurfaces do not stiffen it.
/// \cgalModels `SphericalEnergy`
struct Inverse_dirichlet_energy
{
  /// \cond SKIP_IN_MANUAL
  using Face_data = Jacobian_face_data;
  bool has_area_barrier() const { return true; }
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    const Number det = t.determinant();
    if(!(value_of(det) > 0))
      return Number(std::numeric_limits<double>::infinity());
    // |J^-1|_F = |J|_F / det J for a 2x2 map, and det J = det(a, b, c) / (2 InputArea).
    const Number inverse_det_j = (2 * d.input_area) * inverse(det);
    return t.spring(d.weights) * (inverse_det_j * inverse_det_j);
  }
  /// \endcond
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INVERSE_DIRICHLET_ENERGY_H
