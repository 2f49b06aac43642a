// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_FOLD_BARRIER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_FOLD_BARRIER_H

#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A barrier under the scale of a face in all directions, zero while the face's
/// `t = (det J)^2 / |J|_F^2` stays above its activation and `+inf` once the face flips.
/// `J` is the map from the input triangle to the chord triangle (both surfaces of area
/// `4 pi`), `det J = det(a, b, c) / (2 InputArea)` its signed area ratio. `t` lies between
/// `sigma_min^2 / 2` and `sigma_min^2`: for a conformal face it is half the area ratio, and
/// a needle reaches a small `t` long before its area is small. A barrier on the area alone
/// lets squeezed protrusions collapse into needles, with a very large quasi-conformal ratio.
/// The barrier is `InputArea * b(t / activation)`, `b(u) = -(1 - u)^2 log(u)` for
/// `0 < u < 1` (C2 at `u = 1`, the clamped barrier of incremental potential contact, Li et
/// al. 2020). A model of `SphericalEnergy` with its `activation`; the solver calls the
/// static functions with the floor of its options.
struct Fold_barrier
{
  double activation = 1e-7;
  /// The weight of the weak outer layer (see `energy()`), 0 for none.
  double outer_weight = 0;

  /// How far the outer layer reaches, in multiples of the activation.
  static constexpr double outer_reach = 3;

  /// The chord determinant the barrier defends on faces of tiny input area, 100 times the
  /// degeneracy threshold of the validity contract (`degenerate_determinant`). The relative
  /// floor alone bounds the area ratio, not the determinant: a face of tiny input area can
  /// then reach a determinant under that threshold.
  static constexpr double determinant_floor = 1e-12;

  /// The activation of a face: `floor`, raised where the face's input area is so small that
  /// `t = floor` would put its chord determinant below `determinant_floor` (for a conformal
  /// face, `t = det J / 2 = det(a, b, c) / (4 InputArea)`).
  static double face_activation(const Jacobian_face_data& d, double floor)
  {
    return std::max(floor, determinant_floor * 0.25 / d.input_area);
  }

  /// The weight of a face's barrier: its input area, but not less than the area below which
  /// `face_activation()` is raised. Weighted by its own tiny area, the barrier of such a face
  /// is too weak to hold it: the face sinks far under its activation.
  static double face_weight(const Jacobian_face_data& d, double floor)
  {
    return std::max(d.input_area, determinant_floor * 0.25 / floor);
  }

  /// The input triangle's data, and its `Reference_triangle::area_floor`.
  struct Face_data : Jacobian_face_data
  {
    double area_floor = 0;

    Face_data() = default;
    explicit Face_data(const Reference_triangle& r) : Jacobian_face_data(r), area_floor(r.area_floor) {}
  };
  Face_data face_data(const Reference_triangle& r) const { return Face_data(r); }

  template <class Number>
  Number flat_energy(const Chord_triangle<Number>& t, const Face_data& d) const
  {
    return energy(t, d, activation, outer_weight);
  }

  /// `t` of the face, for a positively oriented chord triangle.
  /// `t` of a face whose determinant is `det`.
  template <class Number>
  static Number scale(const Chord_triangle<Number>& t, const Number& det, const Face_data& d)
  {
    return det * det * inverse(t.spring(d.weights)) * (0.25 / d.input_area);
  }

  /// The barrier, plus with `outer_weight` a second one of that weight relative to the
  /// input area, activated at `outer_reach` times `activation`. The clamped barrier has no
  /// curvature at its activation, so the Newton model does not see a face coming down to it
  /// until it is there; steps that would fold faces above it are capped instead, to a few
  /// percent of Newton's in the squeezed protrusions. The weak layer lets the model see them
  /// one step earlier without changing the minimum much (see
  /// `Robust_pipeline::continuation_stage()`).
  /// With `floored_activation`, a face whose input area is under its area floor is measured
  /// as a face of the floor's area, and held from `floored_activation` on: see
  /// `Newton_options::floored_activation`.
  template <class Number>
  static Number energy(const Chord_triangle<Number>& t, const Face_data& d, double activation, double outer_weight = 0,
                       double floored_activation = 0)
  {
    if(floored_activation > 0 && d.area_floor > d.input_area) {
      Face_data floored = d;
      floored.input_area = d.area_floor;
      return energy(t, floored, std::max(activation, floored_activation), outer_weight);
    }
    const Number det = t.determinant();
    if(!(value_of(det) > 0))
      return Number(std::numeric_limits<double>::infinity());
    const Number s = scale(t, det, d);
    Number e = clamped_log(s * (1 / face_activation(d, activation))) * face_weight(d, activation);
    if(outer_weight > 0)
      e += clamped_log(s * (1 / (outer_reach * activation))) * (outer_weight * d.input_area);
    return e;
  }

private:
  // b(u) = -(1 - u)^2 log(u) for 0 < u < 1, 0 from 1 on, +inf at 0 and under.
  template <class Number>
  static Number clamped_log(const Number& u)
  {
    const double v = value_of(u);
    if(v >= 1)
      return Number(0.0);
    if(!(v > 0))
      return Number(std::numeric_limits<double>::infinity());
    const double l = std::log(v), w = 1 - v;
    const double b = -w * w * l;
    const double d1 = 2 * w * l - w * w / v;
    const double d2 = -2 * l + 4 * w / v + w * w / (v * v);
    return chain(u, b, d1, d2);
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ENERGIES_FOLD_BARRIER_H
