// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_CHORD_TRIANGLE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_CHORD_TRIANGLE_H

#include <CGAL/Spherical_parameterization/Triangle_jet.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <type_traits>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationEnergies
/// The flat triangle `(a, b, c)` spanned by three points of the sphere, with the few
/// polynomial quantities every energy is built from. `Number` is `double` (values only)
/// or `Triangle_jet` (values with exact gradients and Hessians in the nine coordinates).
/// Edge `i` is the edge opposite vertex `i`.
template <class Number>
class Chord_triangle
{
public:
  using Vector = Eigen::Vector3d;  ///< a point of the sphere
  /// True if `Number` is `Triangle_jet`: the primitives return derivatives too.
  static constexpr bool with_derivatives = std::is_same<Number, Triangle_jet>::value;

  /// The triangle `(a, b, c)` of three points of the unit sphere.
  Chord_triangle(const Vector& a, const Vector& b, const Vector& c) : x_{a, b, c} {}

  /// Vertex `i` (0, 1 or 2), as a plain point: no derivatives.
  const Vector& point(int i) const { return x_[i]; }

  /// `|x_j - x_k|^2` for the edge `(j, k)` opposite vertex `i`.
  Number squared_edge_length(int i) const
  {
    std::array<double, 3> w{0, 0, 0};
    w[i] = 1;
    return spring(w);
  }

  /// `sum_i w[i] |x_j - x_k|^2`: Tutte and cotangent (Dirichlet) energies.
  Number spring(const std::array<double, 3>& w) const
  {
    Number r(0.0);
    for(int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const Vector e = x_[j] - x_[k];
      if constexpr(with_derivatives) {
        r.value += w[i] * e.squaredNorm();
        r.gradient.template segment<3>(3 * j) += 2 * w[i] * e;
        r.gradient.template segment<3>(3 * k) -= 2 * w[i] * e;
        const Eigen::Matrix3d block = 2 * w[i] * Eigen::Matrix3d::Identity();
        r.hessian.template block<3, 3>(3 * j, 3 * j) += block;
        r.hessian.template block<3, 3>(3 * k, 3 * k) += block;
        r.hessian.template block<3, 3>(3 * j, 3 * k) -= block;
        r.hessian.template block<3, 3>(3 * k, 3 * j) -= block;
      } else {
        r += w[i] * e.squaredNorm();
      }
    }
    return r;
  }

  /// `|(b - a) x (c - a)|^2`, that is 4 Area^2 of the flat triangle.
  Number squared_double_area() const
  {
    const Vector e1 = x_[1] - x_[0], e2 = x_[2] - x_[0];
    const double n1 = e1.squaredNorm(), n2 = e2.squaredNorm(), s = e1.dot(e2);
    // Lagrange's identity avoids the cancellation-prone cross product derivatives.
    const double q = n1 * n2 - s * s;
    if constexpr(!with_derivatives) {
      return q;
    } else {
      Number r(q);
      const Vector g1 = 2 * n2 * e1 - 2 * s * e2, g2 = 2 * n1 * e2 - 2 * s * e1;
      r.gradient << -g1 - g2, g1, g2;
      const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d h11 = 2 * n2 * I - 2 * e2 * e2.transpose();
      const Eigen::Matrix3d h22 = 2 * n1 * I - 2 * e1 * e1.transpose();
      const Eigen::Matrix3d h12 = 4 * e1 * e2.transpose() - 2 * e2 * e1.transpose() - 2 * s * I;
      // (e1, e2) = (b - a, c - a): pull the 6x6 Hessian back to (a, b, c).
      set_block(r, 1, 1, h11);
      set_block(r, 2, 2, h22);
      set_block(r, 1, 2, h12);
      set_block(r, 0, 1, -(h11 + h12.transpose()));
      set_block(r, 0, 2, -(h12 + h22));
      r.hessian.template block<3, 3>(0, 0) = h11 + h12 + h12.transpose() + h22;
      return r;
    }
  }

  /// `det(a, b, c)`: six times the signed volume of the tetrahedron (origin, a, b, c).
  /// Positive when the triangle is seen counterclockwise from outside the sphere.
  Number determinant() const
  {
    const Vector& a = x_[0]; const Vector& b = x_[1]; const Vector& c = x_[2];
    // a . ((b-a) x (c-a)) equals a . (b x c) but keeps its accuracy on tiny triangles.
    const double d = a.dot((b - a).cross(c - a));
    if constexpr(!with_derivatives) {
      return d;
    } else {
      Number r(d);
      r.gradient << b.cross(c), c.cross(a), a.cross(b);
      set_block(r, 0, 1, -skew(c));
      set_block(r, 0, 2, skew(b));
      set_block(r, 1, 2, -skew(a));
      return r;
    }
  }

  /// `|x_j + x_k|^2 / 4`: the squared distance from the centre to the midpoint of edge `i`.
  Number squared_midpoint_norm(int i) const
  {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const Vector m = 0.5 * (x_[j] + x_[k]);
    if constexpr(!with_derivatives) {
      return m.squaredNorm();
    } else {
      Number r(m.squaredNorm());
      r.gradient.template segment<3>(3 * j) = m;
      r.gradient.template segment<3>(3 * k) = m;
      const Eigen::Matrix3d half = 0.5 * Eigen::Matrix3d::Identity();
      for(int p : {j, k})
        for(int q : {j, k})
          r.hessian.template block<3, 3>(3 * p, 3 * q) = half;
      return r;
    }
  }

  /// The vertex with an angle above 90 degrees, or -1 for an acute (or right) triangle.
  int obtuse_vertex() const
  {
    for(int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      if((x_[j] - x_[i]).dot(x_[k] - x_[i]) < 0)
        return i;
    }
    return -1;
  }

private:
  static Eigen::Matrix3d skew(const Vector& v)
  {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
  }

  // Sets the symmetric pair of Hessian blocks (i, j) and (j, i).
  static void set_block(Triangle_jet& r, int i, int j, const Eigen::Matrix3d& m)
  {
    r.hessian.template block<3, 3>(3 * i, 3 * j) = m;
    r.hessian.template block<3, 3>(3 * j, 3 * i) = m.transpose();
  }

  std::array<Vector, 3> x_;
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_CHORD_TRIANGLE_H
