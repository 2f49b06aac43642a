// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of the per-face building blocks, without any mesh: the energies and their exact
// derivatives (Triangle_jet), the d_min correction of Friedel et al., the Triangle_jet chain
// rules, the fold-free step bound, the tangent bases, the positive semi-definite
// projection (with its small eigen solver) and the stopping rules of the Newton solver.
// Usage: test_energies            (prints PASS/FAIL per check, then "N passed, M failed")

#include <CGAL/Spherical_parameterization/Area_distortion_energy.h>
#include <CGAL/Spherical_parameterization/Area_energy.h>
#include <CGAL/Spherical_parameterization/Balanced_energy.h>
#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Energy_mix.h>
#include <CGAL/Spherical_parameterization/Symmetric_dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/MIPS_energy.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>
#include <CGAL/Spherical_parameterization/Stretch_energy.h>
#include <CGAL/Spherical_parameterization/Triangle_jet.h>
#include <CGAL/Spherical_parameterization/Tutte_energy.h>
#include <CGAL/Spherical_parameterization/Weighted_sum_energy.h>
#include <CGAL/Spherical_parameterization/d_min_correction.h>
#include <CGAL/Spherical_parameterization/internal/energies/Fold_barrier.h>
#include <CGAL/Spherical_parameterization/internal/newton/Symmetric_eigen.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/energies/Untangling_energy.h>
#include <CGAL/Spherical_parameterization/internal/newton/project_psd.h>
#include <CGAL/Spherical_parameterization/internal/newton/step_bound.h>
#include <CGAL/Spherical_parameterization/internal/newton/stopping_rules.h>
#include <CGAL/Spherical_parameterization/internal/newton/tangent_basis.h>

#include "test_support.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;

using Vector = Eigen::Vector3d;
using Jet = SP::Triangle_jet;
using Coordinates = Eigen::Matrix<double, 9, 1>;

// ---------------------------------------------------------------------------------------
// Harness

using namespace test_support;

// ---------------------------------------------------------------------------------------
// Random triangles

struct Sphere_triangle
{
  std::array<Vector, 3> p;
};

double corner_angle(const Vector& p, const Vector& q, const Vector& r)
{
  const Vector u = q - p, v = r - p;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

double determinant(const Vector& a, const Vector& b, const Vector& c) { return a.dot(b.cross(c)); }

/// A random triangle on the unit sphere, counterclockwise seen from outside (det > 0), with
/// every angle above 15 degrees; acute ones have every angle below 80 degrees, obtuse ones
/// one angle above 100 degrees, so that no finite-difference step crosses a right angle.
Sphere_triangle random_sphere_triangle(bool obtuse)
{
  for(;;) {
    const Vector center = random_unit_vector();
    const Vector u = center.unitOrthogonal(), v = center.cross(u);
    const double radius = uniform(0.2, 0.9);
    Sphere_triangle t;
    for(Vector& p : t.p) {
      const double phi = uniform(0, 2 * M_PI), r = radius * std::sqrt(uniform(0.2, 1.0));
      p = (center + r * (std::cos(phi) * u + std::sin(phi) * v)).normalized();
    }
    if(determinant(t.p[0], t.p[1], t.p[2]) < 0)
      std::swap(t.p[1], t.p[2]);
    double smallest = M_PI, largest = 0;
    for(int i = 0; i < 3; ++i) {
      const double a = corner_angle(t.p[i], t.p[(i + 1) % 3], t.p[(i + 2) % 3]);
      smallest = std::min(smallest, a);
      largest = std::max(largest, a);
    }
    const double deg = M_PI / 180;
    if(smallest < 15 * deg) continue;
    if(obtuse ? largest > 100 * deg : largest < 80 * deg)
      return t;
  }
}

/// A random input triangle scaled to `area`.
SP::Reference_triangle random_reference(double area)
{
  for(;;) {
    std::array<Vector, 3> q;
    for(Vector& p : q) p = Vector(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    const double a = 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm();
    double smallest = M_PI;
    for(int i = 0; i < 3; ++i) smallest = std::min(smallest, corner_angle(q[i], q[(i + 1) % 3], q[(i + 2) % 3]));
    if(smallest < 10 * M_PI / 180) continue;
    const double s = std::sqrt(area / a);
    return SP::Reference_triangle(s * q[0], s * q[1], s * q[2]);
  }
}

// ---------------------------------------------------------------------------------------
// Finite differences of a function of the nine coordinates

Coordinates pack(const std::array<Vector, 3>& p)
{
  Coordinates x;
  x << p[0], p[1], p[2];
  return x;
}

/// Central differences of `value` (for the gradient) and of `gradient` (for the Hessian).
struct Finite_differences
{
  Jet::Gradient gradient;
  Jet::Hessian hessian;
};

Finite_differences central_differences(const std::function<double(const Coordinates&)>& value,
                                       const std::function<Jet::Gradient(const Coordinates&)>& gradient,
                                       const Coordinates& x, double h)
{
  Finite_differences fd;
  for(int k = 0; k < 9; ++k) {
    Coordinates plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    fd.gradient[k] = (value(plus) - value(minus)) / (2 * h);
    fd.hessian.col(k) = (gradient(plus) - gradient(minus)) / (2 * h);
  }
  return fd;
}

double relative_error(const Eigen::MatrixXd& approx, const Eigen::MatrixXd& exact)
{
  return (approx - exact).cwiseAbs().maxCoeff() / std::max(exact.cwiseAbs().maxCoeff(), 1e-300);
}

// ---------------------------------------------------------------------------------------
// Energies: value, gradient and Hessian of flat_energy (times d_min^-2 or not)

/// The face energy as the solver evaluates it (Spherical_energy::face): the flat energy,
/// times `inverse_squared_d_min` when `corrected`.
template <class Number, class Energy>
Number face_energy(const Energy& energy, const typename Energy::Face_data& data, const Coordinates& x, bool corrected)
{
  const SP::Chord_triangle<Number> chord(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6));
  const Number e = energy.flat_energy(chord, data);
  if(!corrected)
    return e;
  return e * SP::inverse_squared_d_min(chord);
}

struct Energy_errors
{
  double value = 0, gradient = 0, hessian = 0, asymmetry = 0, rotation = 0;
  double smallest = std::numeric_limits<double>::infinity();  // smallest face value met
  bool finite = true;
};

/// Worst errors of the energy over `count` random triangles of the given shape, each against
/// its own random reference triangle, whose area is 1.2 to 3 times det(a, b, c) so that the
/// fold barrier with activation 0.5 is active.
template <class Energy>
Energy_errors energy_errors(const Energy& energy, bool corrected, bool obtuse, int count)
{
  Energy_errors worst;
  for(int n = 0; n < count; ++n) {
    const Sphere_triangle t = random_sphere_triangle(obtuse);
    const double det = determinant(t.p[0], t.p[1], t.p[2]);
    const SP::Reference_triangle reference = random_reference(uniform(1.2, 3.0) * det);
    const typename Energy::Face_data data = energy.face_data(reference);
    const Coordinates x = pack(t.p);

    auto value = [&](const Coordinates& y) { return face_energy<double>(energy, data, y, corrected); };
    auto gradient = [&](const Coordinates& y) { return face_energy<Jet>(energy, data, y, corrected).gradient; };
    const Jet jet = face_energy<Jet>(energy, data, x, corrected);
    const double plain = value(x);
    const Finite_differences fd = central_differences(value, gradient, x, 1e-5);

    if(!std::isfinite(jet.value) || !jet.gradient.allFinite() || !jet.hessian.allFinite())
      worst.finite = false;
    worst.smallest = std::min(worst.smallest, jet.value);
    worst.value = std::max(worst.value, std::abs(jet.value - plain) / std::abs(plain));
    worst.gradient = std::max(worst.gradient, relative_error(fd.gradient, jet.gradient));
    worst.hessian = std::max(worst.hessian, relative_error(fd.hessian, jet.hessian));
    worst.asymmetry = std::max(worst.asymmetry, relative_error(jet.hessian.transpose(), jet.hessian));

    const Eigen::Matrix3d r = random_rotation();
    const std::array<Vector, 3> rotated{r * t.p[0], r * t.p[1], r * t.p[2]};
    worst.rotation = std::max(worst.rotation, std::abs(value(pack(rotated)) - plain) / std::abs(plain));
  }
  return worst;
}

template <class Energy>
void check_energy(const std::string& name, const Energy& energy)
{
  const int count = 12;
  for(bool corrected : {false, true}) {
    double rotation = 0;
    for(bool obtuse : {false, true}) {
      const std::string tag = " [" + name + (corrected ? ", x d_min^-2, " : ", flat, ") + (obtuse ? "obtuse]" : "acute]");
      const Energy_errors e = energy_errors(energy, corrected, obtuse, count);
      report("jet value, gradient and Hessian are finite" + tag, e.finite);
      report("jet value equals the double evaluation" + tag, e.value <= 1e-14, "rel. diff. " + str(e.value));
      report("gradient matches central differences (rel 1e-5)" + tag, e.gradient <= 1e-5, "rel. err. " + str(e.gradient));
      report("Hessian matches central differences of the gradient (rel 1e-5)" + tag, e.hessian <= 1e-5,
             "rel. err. " + str(e.hessian));
      report("Hessian is symmetric" + tag, e.asymmetry <= 1e-14, "rel. asym. " + str(e.asymmetry));
      rotation = std::max(rotation, e.rotation);
    }
    report(std::string("value is invariant under rotations of the sphere (rel 1e-12) [") + name +
             (corrected ? ", x d_min^-2]" : ", flat]"),
           rotation <= 1e-12, "rel. diff. " + str(rotation));
  }
}

// The area distortion of one face: smallest, equal to the input area, where the chord
// triangle's signed area ratio is 1; larger on either side; infinite once the face flips.
void test_area_distortion_minimum()
{
  const double input_area = 0.005;
  const Eigen::Vector3d p(0, 0, 1), u(0.1, 0, 0), v(0, 0.1, 0);
  const SP::Area_distortion_energy energy;
  auto chord = [&](double scale, bool flipped) {
    const Eigen::Vector3d a = p, b = (p + scale * u).normalized(), c = (p + scale * v).normalized();
    return flipped ? SP::Chord_triangle<double>(a, c, b) : SP::Chord_triangle<double>(a, b, c);
  };
  auto value = [&](double scale, bool flipped) { return energy.flat_energy(chord(scale, flipped), input_area); };
  // The scale at which det(a, b, c) = 2 InputArea, by bisection (det grows with the scale here).
  double lo = 0.01, hi = 3;
  for(int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (chord(mid, false).determinant() < 2 * input_area ? lo : hi) = mid;
  }
  const double at_one = value(lo, false);
  report("area distortion of a face at area ratio 1 is its input area (rel 1e-9)",
         std::abs(at_one / input_area - 1) <= 1e-9, str(at_one / input_area, 12));
  report("area distortion grows on both sides of area ratio 1",
         value(0.9 * lo, false) > at_one && value(1.1 * lo, false) > at_one);
  report("area distortion grows without bound as the face shrinks", value(1e-3 * lo, false) > 1e5 * at_one);
  report("area distortion of a flipped face is infinite", std::isinf(value(lo, true)));
}

// The inverse Dirichlet term of one face mapped by a known linear stretch: the chord triangle
// of (p, p + sx u, p + sy v) pulled back to the plane is the input right triangle scaled by
// (sx, sy) up to the chord's curvature, so the term is near InputArea (1/sx^2 + 1/sy^2);
// it is infinite once the face flips and grows as one direction alone is squeezed.
void test_inverse_dirichlet_stretch()
{
  const double h = 1e-3;  // small, so the chord triangle is nearly the tangent one
  const SP::Reference_triangle input(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(h, 0, 0), Eigen::Vector3d(0, h, 0));
  const SP::Inverse_dirichlet_energy energy;
  const auto data = energy.face_data(input);
  const Eigen::Vector3d p(0, 0, 1), u(1, 0, 0), v(0, 1, 0);
  auto value = [&](double sx, double sy, bool flipped) {
    const Eigen::Vector3d a = p, b = (p + sx * h * u).normalized(), c = (p + sy * h * v).normalized();
    return flipped ? energy.flat_energy(SP::Chord_triangle<double>(a, c, b), data)
                   : energy.flat_energy(SP::Chord_triangle<double>(a, b, c), data);
  };
  double worst = 0;
  for(double sx : {0.5, 1.0, 3.0})
    for(double sy : {0.2, 1.0, 2.0}) {
      const double expected = input.area * (1 / (sx * sx) + 1 / (sy * sy));
      worst = std::max(worst, std::abs(value(sx, sy, false) / expected - 1));
    }
  report("inverse Dirichlet of a face stretched by (sx, sy) is InputArea (1/sx^2 + 1/sy^2) (rel 1e-5)",
         worst <= 1e-5, "rel. err. " + str(worst));
  report("inverse Dirichlet grows as one direction alone is squeezed, the area kept",
         value(4, 0.25, false) > 4 * value(1, 1, false));
  report("inverse Dirichlet of a flipped face is infinite", std::isinf(value(1, 1, true)));
}

// "balanced" with a third weight is the sum of its three terms, face by face; the third
// weight belongs to "balanced" alone, and a negative or non-finite one is refused.
void test_balanced_with_sample_spacing()
{
  const SP::Reference_triangle input(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.1, 0), Eigen::Vector3d(0.3, 0.8, 0));
  const Eigen::Vector3d a(0.1, 0.2, 1), b(0.6, 0.1, 0.9), c(0.2, 0.7, 0.8);
  const SP::Chord_triangle<double> chord(a.normalized(), b.normalized(), c.normalized());
  auto value = [&](const auto& energy) { return energy.flat_energy(chord, energy.face_data(input)); };
  const std::optional<SP::Energy_mix> mix = SP::energy_by_name("balanced", 0.7, 0.3, 0.2);
  report("energy_by_name(\"balanced\", a, b, c) exists", bool(mix));
  if(!mix)
    return;
  const double expected = 0.7 * value(SP::Dirichlet_energy{0, M_PI}) + 0.3 * value(SP::Area_distortion_energy()) +
                          0.2 * value(SP::Inverse_dirichlet_energy());
  const double error = std::abs(value(*mix) / expected - 1);
  report("balanced with weight c adds c Inverse_dirichlet to its two terms (rel 1e-12)", error <= 1e-12,
         "rel. err. " + str(error));
  check_energy("Energy_mix balanced with sample spacing", *mix);
  report("energy_by_name refuses a third weight for another energy than balanced",
         !SP::energy_by_name("combined", 1, 1, 0.2) && !SP::energy_by_name("symmetric_dirichlet", 1, 1, 0.2));
  report("energy_by_name refuses a negative or non-finite third weight",
         !SP::energy_by_name("balanced", 0.5, 0.5, -0.1) && !SP::energy_by_name("balanced", 0.5, 0.5, NAN));
}

void test_energies()
{
  test_area_distortion_minimum();
  test_inverse_dirichlet_stretch();
  test_balanced_with_sample_spacing();
  check_energy("Tutte", SP::Tutte_energy());
  check_energy("Dirichlet", SP::Dirichlet_energy());
  check_energy("Area", SP::Area_energy());
  check_energy("Stretch", SP::Stretch_energy());
  check_energy("MIPS", SP::MIPS_energy());
  check_energy("combined(1,1)", SP::combined_energy(1, 1));
  check_energy("Area_distortion", SP::Area_distortion_energy());
  check_energy("balanced()", SP::balanced_energy());
  check_energy("Inverse_dirichlet", SP::Inverse_dirichlet_energy());
  check_energy("symmetric_dirichlet()", SP::symmetric_dirichlet_energy());
  for(const char* name : {"tutte", "dirichlet", "area", "stretch", "mips", "combined", "area_distortion", "balanced",
                          "inverse_dirichlet", "symmetric_dirichlet"}) {
    const std::optional<SP::Energy_mix> mix = SP::energy_by_name(name, 1.5, 0.5);
    report(std::string("energy_by_name knows \"") + name + "\"", bool(mix));
    if(mix)
      check_energy(std::string("Energy_mix ") + name, *mix);
  }
  check_energy("Untangling", SP::internal::Untangling_energy());
  SP::internal::Untangling_energy sharp;
  sharp.epsilon = 1e-2;
  check_energy("Untangling eps=1e-2", sharp);
  check_energy("Signed_stretch", SP::internal::Signed_stretch_energy());

  SP::internal::Fold_barrier barrier;
  barrier.activation = 0.5;
  check_energy("Fold_barrier activation=0.5", barrier);
  // The barrier is checked above only if it is active on the triangles used.
  double smallest = std::numeric_limits<double>::infinity();
  for(bool obtuse : {false, true})
    smallest = std::min(smallest, energy_errors(barrier, false, obtuse, 12).smallest);
  report("Fold_barrier with activation 0.5 is active (positive) on the test triangles", smallest > 0,
         "smallest value " + str(smallest));

  // With the outer layer, reaching out to 3 x 0.2 = 0.6: active on all the test triangles
  // (t < 0.5), the barrier itself on some of them, so that both parts are checked.
  SP::internal::Fold_barrier layered;
  layered.activation = 0.2;
  layered.outer_weight = 0.5;
  check_energy("Fold_barrier activation=0.2 with an outer layer", layered);
  smallest = std::numeric_limits<double>::infinity();
  for(bool obtuse : {false, true})
    smallest = std::min(smallest, energy_errors(layered, false, obtuse, 12).smallest);
  report("Fold_barrier's outer layer is active (positive) on the test triangles", smallest > 0,
         "smallest value " + str(smallest));
}

/// With `floored_activation` (the continuation's barrier), a face whose input area is under its
/// area floor is measured as a face of the floor's area and held from that activation on; a
/// face above its floor is measured as without it.
void test_barrier_on_area_floors()
{
  using Barrier = SP::internal::Fold_barrier;
  int held = 0, as_floor_sized = 0, unchanged = 0;
  const int count = 12;
  for(int n = 0; n < count; ++n) {
    const Sphere_triangle t = random_sphere_triangle(n % 2 == 1);
    const SP::Chord_triangle<double> chord(t.p[0], t.p[1], t.p[2]);
    const double det = determinant(t.p[0], t.p[1], t.p[2]);
    // t of about 1e8 on its own area, about 0.1 on its floor.
    SP::Reference_triangle tiny = random_reference(1e-8 * det);
    tiny.area_floor = 2 * det;
    const Barrier::Face_data d(tiny);
    Barrier::Face_data floor_sized = d;
    floor_sized.input_area = tiny.area_floor;
    const double floored = Barrier::energy(chord, d, 1e-4, 0, 0.5);
    held += Barrier::energy(chord, d, 1e-4) == 0 && floored > 0;
    as_floor_sized += floored == Barrier::energy(chord, floor_sized, 0.5);
    SP::Reference_triangle fair = random_reference(2 * det);
    fair.area_floor = 0.5 * fair.area;
    const Barrier::Face_data f(fair);
    unchanged += Barrier::energy(chord, f, 0.2, 0.5, 0.9) == Barrier::energy(chord, f, 0.2, 0.5);
  }
  report("Fold_barrier with floored_activation holds a tiny face that its own area does not", held == count,
         std::to_string(held) + " of " + std::to_string(count));
  report("Fold_barrier with floored_activation measures it as a face of its floor's area", as_floor_sized == count,
         std::to_string(as_floor_sized) + " of " + std::to_string(count));
  report("Fold_barrier with floored_activation leaves a face above its floor as it was", unchanged == count,
         std::to_string(unchanged) + " of " + std::to_string(count));
}

/// The untangling energy must be finite, with exact derivatives, on folded (det < 0) faces.
void test_untangling_on_folded_faces()
{
  SP::internal::Untangling_energy energy;
  double gradient = 0, hessian = 0;
  bool finite = true;
  for(int n = 0; n < 12; ++n) {
    Sphere_triangle t = random_sphere_triangle(n % 2 == 1);
    std::swap(t.p[1], t.p[2]);  // folded: det < 0
    const auto data = energy.face_data(random_reference(uniform(0.5, 2.0)));
    const Coordinates x = pack(t.p);
    auto value = [&](const Coordinates& y) { return face_energy<double>(energy, data, y, false); };
    auto grad = [&](const Coordinates& y) { return face_energy<Jet>(energy, data, y, false).gradient; };
    const Jet jet = face_energy<Jet>(energy, data, x, false);
    finite = finite && std::isfinite(jet.value) && jet.value > 0;
    const Finite_differences fd = central_differences(value, grad, x, 1e-5);
    gradient = std::max(gradient, relative_error(fd.gradient, jet.gradient));
    hessian = std::max(hessian, relative_error(fd.hessian, jet.hessian));
  }
  report("Untangling energy is finite and positive on folded faces", finite);
  report("Untangling energy gradient matches central differences on folded faces", gradient <= 1e-5,
         "rel. err. " + str(gradient));
  report("Untangling energy Hessian matches central differences on folded faces", hessian <= 1e-5,
         "rel. err. " + str(hessian));
}

// ---------------------------------------------------------------------------------------
// d_min

/// The closest point of the triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vector closest_point_on_triangle(const Vector& p, const Vector& a, const Vector& b, const Vector& c)
{
  const Vector ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if(d1 <= 0 && d2 <= 0) return a;
  const Vector bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if(d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if(vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if(d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if(vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if(va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

/// Brute force: the smallest |p|^2 over a dense barycentric grid, as an independent check
/// of the closed-form closest point above.
double sampled_squared_distance(const Vector& a, const Vector& b, const Vector& c, int n)
{
  double best = std::numeric_limits<double>::infinity();
  for(int i = 0; i <= n; ++i)
    for(int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, ((1 - u - v) * a + u * b + v * c).squaredNorm());
    }
  return best;
}

void test_squared_d_min()
{
  const Vector origin = Vector::Zero();
  for(bool obtuse : {false, true}) {
    const std::string tag = obtuse ? " [obtuse]" : " [acute]";
    double worst = 0, sampled_gap = 0;
    for(int n = 0; n < 200; ++n) {
      const Sphere_triangle t = random_sphere_triangle(obtuse);
      const double exact = closest_point_on_triangle(origin, t.p[0], t.p[1], t.p[2]).squaredNorm();
      const double d2 = SP::squared_d_min(t.p[0], t.p[1], t.p[2]);
      worst = std::max(worst, std::abs(d2 - exact) / exact);
      if(n < 20) {  // the grid is slow; it only confirms the exact routine
        const double sampled = sampled_squared_distance(t.p[0], t.p[1], t.p[2], 400);
        sampled_gap = std::max(sampled_gap, (sampled - exact) / exact);
        if(sampled < exact * (1 - 1e-12)) sampled_gap = std::numeric_limits<double>::infinity();
      }
    }
    report("test's exact closest point agrees with a dense barycentric sampling" + tag, sampled_gap <= 1e-3,
           "gap " + str(sampled_gap));
    report("squared_d_min equals the exact squared distance of the flat triangle to the centre (rel 1e-6)" + tag,
           worst <= 1e-6, "rel. err. " + str(worst));
  }

  // Three points of the equator 120 degrees apart: the flat triangle contains the centre.
  const Vector a(1, 0, 0), b(std::cos(2 * M_PI / 3), std::sin(2 * M_PI / 3), 0),
               c(std::cos(4 * M_PI / 3), std::sin(4 * M_PI / 3), 0);
  const double d2 = SP::squared_d_min(a, b, c);
  report("squared_d_min is 0 for three equator points 120 degrees apart", d2 <= 1e-30, "got " + str(d2));
  const double inverse = SP::inverse_squared_d_min(SP::Chord_triangle<double>(a, b, c));
  report("inverse_squared_d_min is infinite or huge for that triangle", !(inverse < 1e30), "got " + str(inverse));

  // The same triangle raised to latitude theta: d_min = sin(theta), tending to 0.
  double worst = 0, previous = 1;
  bool decreasing = true;
  for(double theta : {0.5, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    const double z = std::sin(theta), r = std::cos(theta);
    const Vector p(r * a.x(), r * a.y(), z), q(r * b.x(), r * b.y(), z), s(r * c.x(), r * c.y(), z);
    const double value = SP::squared_d_min(p, q, s);
    worst = std::max(worst, std::abs(value - z * z) / (z * z));
    decreasing = decreasing && value < previous;
    previous = value;
  }
  report("squared_d_min = sin^2(latitude) as a triangle approaches a hemisphere (rel 1e-6)", worst <= 1e-6,
         "rel. err. " + str(worst));
  report("squared_d_min decreases to 0 as the triangle approaches a hemisphere", decreasing && previous < 1e-11,
         "last " + str(previous));

  // Obtuse triangle whose longest edge approaches a diameter: d_min -> 0 at its midpoint.
  previous = 1;
  decreasing = true;
  for(double eps : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5}) {
    const Vector p = Vector(1, eps, 0).normalized(), q = Vector(-1, eps, 0).normalized(), s = Vector(0, 0.3, 0.2).normalized();
    const double value = SP::squared_d_min(p, q, s);
    const double expected = ((p + q) / 2).squaredNorm();
    decreasing = decreasing && value < previous && std::abs(value - expected) <= 1e-9 * expected;
    previous = value;
  }
  report("squared_d_min -> 0 as the longest edge of an obtuse triangle approaches a diameter", decreasing,
         "last " + str(previous));
}

/// The component of each vertex gradient tangent to the sphere at that vertex.
Jet::Gradient tangential(const Jet::Gradient& g, const std::array<Vector, 3>& p)
{
  Jet::Gradient t;
  for(int i = 0; i < 3; ++i) {
    const Vector gi = g.segment<3>(3 * i);
    t.segment<3>(3 * i) = gi - gi.dot(p[i]) * p[i];
  }
  return t;
}

/// A right triangle on the sphere: b and c at opposite ends of a diameter of a small circle,
/// a on that circle (Thales), so the right angle is at a; then a pushed by `shift` towards
/// the cap centre (shift > 0 makes it obtuse, shift < 0 acute).
std::array<Vector, 3> right_triangle(const Vector& n, double height, double phi_a, double phi_b, double shift)
{
  const Vector u = n.unitOrthogonal(), v = n.cross(u);
  const double r = std::sqrt(1 - height * height);
  auto on_circle = [&](double phi) { return Vector(height * n + r * (std::cos(phi) * u + std::sin(phi) * v)); };
  std::array<Vector, 3> p{on_circle(phi_a), on_circle(phi_b), on_circle(phi_b + M_PI)};
  p[0] = (p[0] + shift * n).normalized();
  if(determinant(p[0], p[1], p[2]) < 0) std::swap(p[1], p[2]);
  return p;
}

void test_d_min_branches()
{
  double value_gap = 0, gradient_gap = 0, jump_value = 0, jump_gradient = 0;
  for(int n = 0; n < 50; ++n) {
    const Vector axis = random_unit_vector();
    const double height = uniform(0.1, 0.9), phi_a = uniform(0, 2 * M_PI), phi_b = phi_a + uniform(0.3, M_PI - 0.3);
    const std::array<Vector, 3> p = right_triangle(axis, height, phi_a, phi_b, 0);
    const SP::Chord_triangle<Jet> chord(p[0], p[1], p[2]);
    // The two branches of d_min^2 evaluated explicitly, at the right angle (vertex 0).
    const Jet det = chord.determinant();
    const Jet acute = det * det * SP::inverse(chord.squared_double_area());
    const Jet obtuse = chord.squared_midpoint_norm(0);
    value_gap = std::max(value_gap, std::abs(acute.value - obtuse.value) / obtuse.value);
    const Jet::Gradient ga = tangential(acute.gradient, p), go = tangential(obtuse.gradient, p);
    gradient_gap = std::max(gradient_gap, relative_error(ga, go));

    // The library's selection just inside each branch: no jump in value or tangential gradient.
    const double delta = 1e-7;
    const std::array<Vector, 3> q_acute = right_triangle(axis, height, phi_a, phi_b, -delta);
    const std::array<Vector, 3> q_obtuse = right_triangle(axis, height, phi_a, phi_b, delta);
    const SP::Chord_triangle<Jet> chord_acute(q_acute[0], q_acute[1], q_acute[2]);
    const SP::Chord_triangle<Jet> chord_obtuse(q_obtuse[0], q_obtuse[1], q_obtuse[2]);
    if(chord_acute.obtuse_vertex() != -1 || chord_obtuse.obtuse_vertex() != 0) {
      value_gap = std::numeric_limits<double>::infinity();  // the construction itself is wrong
      continue;
    }
    const Jet left = SP::inverse_squared_d_min(chord_acute), right = SP::inverse_squared_d_min(chord_obtuse);
    jump_value = std::max(jump_value, std::abs(left.value - right.value) / right.value);
    jump_gradient = std::max(jump_gradient,
                             relative_error(tangential(left.gradient, q_acute), tangential(right.gradient, q_obtuse)));
  }
  report("d_min^2: acute (plane) and obtuse (edge midpoint) formulas agree in value on right triangles (rel 1e-12)",
         value_gap <= 1e-12, "rel. diff. " + str(value_gap));
  report("d_min^2: both formulas have the same gradient tangent to the sphere on right triangles (C1, rel 1e-9)",
         gradient_gap <= 1e-9, "rel. diff. " + str(gradient_gap));
  report("inverse_squared_d_min does not jump in value across the right angle (rel 1e-5 for a 1e-7 shift)",
         jump_value <= 1e-5, "rel. jump " + str(jump_value));
  report("inverse_squared_d_min does not jump in tangential gradient across the right angle (rel 1e-5)",
         jump_gradient <= 1e-5, "rel. jump " + str(jump_gradient));
}

// ---------------------------------------------------------------------------------------
// Triangle_jet chain rules

using Jet_inputs = std::array<Jet, 9>;

Jet_inputs variables(const Coordinates& x)
{
  Jet_inputs v;
  for(int k = 0; k < 9; ++k) {
    v[k] = Jet(x[k]);
    v[k].gradient[k] = 1;
  }
  return v;
}

template <class Function>
void check_jet_rule(const std::string& name, Function f)
{
  double value = 0, gradient = 0, hessian = 0;
  for(int n = 0; n < 20; ++n) {
    Coordinates x;
    for(int k = 0; k < 9; ++k) x[k] = uniform(0.5, 2.0);
    auto plain = [&](const Coordinates& y) {
      std::array<double, 9> d;
      for(int k = 0; k < 9; ++k) d[k] = y[k];
      return f(d);
    };
    auto jet_gradient = [&](const Coordinates& y) { return f(variables(y)).gradient; };
    const Jet jet = f(variables(x));
    const Finite_differences fd = central_differences(plain, jet_gradient, x, 1e-5);
    value = std::max(value, std::abs(jet.value - plain(x)) / std::abs(plain(x)));
    gradient = std::max(gradient, relative_error(fd.gradient, jet.gradient));
    hessian = std::max(hessian, relative_error(fd.hessian, jet.hessian));
  }
  report("Triangle_jet " + name + ": value", value <= 1e-14, "rel. diff. " + str(value));
  report("Triangle_jet " + name + ": gradient matches central differences", gradient <= 1e-7, "rel. err. " + str(gradient));
  report("Triangle_jet " + name + ": Hessian matches central differences", hessian <= 1e-7, "rel. err. " + str(hessian));
}

void test_jet_arithmetic()
{
  using std::log;
  using std::sqrt;
  check_jet_rule("product", [](const auto& x) { return (x[0] + 2.0 * x[1]) * (x[2] * x[3] - x[4]); });
  check_jet_rule("quotient", [](const auto& x) { return (x[0] * x[5] + 1.0) / (x[6] * x[6] + x[7]); });
  check_jet_rule("quotient of a constant", [](const auto& x) { return 3.0 / (x[1] * x[8] + x[2]); });
  check_jet_rule("sqrt", [](const auto& x) { return sqrt(x[0] * x[1] + x[8] * x[8]); });
  check_jet_rule("log", [](const auto& x) { return log(x[2] * x[3] + x[4] * x[5]); });
  check_jet_rule("composition", [](const auto& x) {
    // No factor that can cancel to near 0: the value is compared relative to itself.
    return log(sqrt(x[0] * x[4] + x[8]) / (x[1] * x[2]) + 1.0) * (x[3] + x[6] * x[7]);
  });
}

// ---------------------------------------------------------------------------------------
// Step bound

double cubic(const std::array<double, 4>& c, double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }

/// Coefficients of k (t - r[0]) (t - r[1]) ... for the given roots (1 to 3 of them).
std::array<double, 4> polynomial(double k, const std::vector<double>& roots)
{
  std::array<double, 4> c{k, 0, 0, 0};
  for(double r : roots) {  // multiply by (t - r)
    std::array<double, 4> next{0, 0, 0, 0};
    for(int i = 0; i < 3; ++i) {
      next[i + 1] += c[i];
      next[i] -= r * c[i];
    }
    c = next;
  }
  return c;
}

void test_first_positive_root()
{
  const double horizon = 2;
  for(int degree : {1, 2, 3}) {
    double error = 0;
    int found = 0, none = 0, wrong_inf = 0, not_before = 0;
    for(int n = 0; n < 2000; ++n) {
      std::vector<double> roots;
      while(int(roots.size()) < degree) {
        const double r = uniform(-3, 3);
        bool apart = std::abs(r) > 0.05;
        for(double s : roots) apart = apart && std::abs(r - s) > 0.05;
        if(apart) roots.push_back(r);
      }
      double product = 1;
      for(double r : roots) product *= -r;
      const double k = uniform(0.1, 10) * (product > 0 ? 1 : -1);  // p(0) = k prod(-r) > 0
      const std::array<double, 4> c = polynomial(k, roots);
      double expected = std::numeric_limits<double>::infinity();
      for(double r : roots)
        if(r > 0 && r <= horizon) expected = std::min(expected, r);
      const double t = SP::internal::first_positive_root(c, horizon);
      if(std::isinf(expected)) {
        ++none;
        if(!std::isinf(t)) wrong_inf += 1, error = std::max(error, std::abs(t));
        continue;
      }
      ++found;
      if(!std::isfinite(t)) { ++wrong_inf; continue; }
      error = std::max(error, std::abs(t - expected) / expected);
      // p(expected) is 0 only up to the rounding of the coefficients: judge by the sign of p.
      if(!(cubic(c, t) > 0) || !(cubic(c, t + 1e-12) <= 0)) ++not_before;
    }
    const std::string tag = " [degree " + std::to_string(degree) + ", " + std::to_string(found) + " with a root, " +
                            std::to_string(none) + " without]";
    report("first_positive_root finds the smallest root in (0, horizon] (rel 1e-9) or +inf" + tag,
           wrong_inf == 0 && error <= 1e-9 && found > 0 && none > 0,
           std::to_string(wrong_inf) + " wrong finiteness, rel. err. " + str(error));
    report("first_positive_root returns t just before the sign change: p(t) > 0 >= p(t + 1e-12)" + tag,
           not_before == 0, std::to_string(not_before) + " not just before the sign change");
  }
  // (t + 0.5)(t - 1)(t - 1.5) + shift: a local maximum and minimum in (0, 2]; with a shift of
  // 0.05 the minimum dips below 0 (two close roots), with 0.2 it stays above (no root).
  for(double shift : {0.05, 0.2}) {
    std::array<double, 4> c = polynomial(1, {-0.5, 1.0, 1.5});
    c[0] += shift;
    double expected = std::numeric_limits<double>::infinity();
    for(double t = 1e-5; t <= 2; t += 1e-5)
      if(cubic(c, t) <= 0) { expected = t; break; }
    const double t = SP::internal::first_positive_root(c, 2);
    report("first_positive_root agrees with a fine scan on a cubic with a dip [shift " + str(shift) + "]",
           std::isinf(expected) ? std::isinf(t) : std::abs(t - expected) < 2e-5,
           "got " + str(t) + ", scan " + str(expected));
  }
}

/// A closed octahedron on the unit sphere, faces counterclockwise from outside.
void octahedron(std::vector<Vector>& x, SP::internal::Faces& faces)
{
  x = {Vector(1, 0, 0), Vector(-1, 0, 0), Vector(0, 1, 0), Vector(0, -1, 0), Vector(0, 0, 1), Vector(0, 0, -1)};
  faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
}

double face_det(const std::vector<Vector>& x, const std::vector<Vector>& step, const std::array<int, 3>& f, double t)
{
  return determinant(x[f[0]] + t * step[f[0]], x[f[1]] + t * step[f[1]], x[f[2]] + t * step[f[2]]);
}

void test_largest_fold_free_step()
{
  const double horizon = 1.25;
  int capped = 0, free_steps = 0, early = 0, not_reached = 0, missed = 0;
  for(int n = 0; n < 500; ++n) {
    std::vector<Vector> x;
    SP::internal::Faces faces;
    octahedron(x, faces);
    const Eigen::Matrix3d r = random_rotation();
    for(Vector& p : x) p = (r * p + 0.2 * random_unit_vector()).normalized();
    bool positive = true;
    for(const auto& f : faces) positive = positive && determinant(x[f[0]], x[f[1]], x[f[2]]) > 0;
    if(!positive) continue;
    std::vector<Vector> step(x.size());
    const double size = uniform(0.1, 2.5);
    for(Vector& s : step) s = size * uniform(0, 1) * random_unit_vector();

    const double bound = SP::internal::largest_fold_free_step(faces, x, step, horizon);
    const double end = std::isfinite(bound) ? bound : horizon;
    // No face reaches det = 0 before the bound (scan, plus 0.99 * bound).
    for(const auto& f : faces) {
      bool ok = face_det(x, step, f, 0.99 * end) > 0;
      for(int k = 1; k < 400; ++k) ok = ok && face_det(x, step, f, end * k / 400.0 * (1 - 1e-9)) > 0;
      if(!ok) ++early;
    }
    if(std::isfinite(bound)) {
      ++capped;
      if(bound > horizon) ++not_reached;
      // Some face is at det <= 0 just after the bound.
      double lowest = std::numeric_limits<double>::infinity();
      for(const auto& f : faces) lowest = std::min(lowest, face_det(x, step, f, bound * (1 + 1e-9) + 1e-12));
      if(lowest > 0) ++missed;
    } else {
      ++free_steps;
    }
  }
  const std::string tag = " [" + std::to_string(capped) + " capped, " + std::to_string(free_steps) + " free steps]";
  report("largest_fold_free_step: no face flips before the bound (det > 0 up to 0.99 * bound)" + tag,
         early == 0 && capped > 0 && free_steps > 0, std::to_string(early) + " faces flip earlier");
  report("largest_fold_free_step: some face has det <= 0 just past a finite bound" + tag, missed == 0,
         std::to_string(missed) + " bounds with every face still positive");
  report("largest_fold_free_step: a finite bound is within the horizon" + tag, not_reached == 0,
         std::to_string(not_reached) + " beyond the horizon");

  // A face already folded does not limit the step.
  std::vector<Vector> x;
  SP::internal::Faces faces;
  octahedron(x, faces);
  std::vector<Vector> step(x.size(), Vector::Zero());
  step[4] = Vector(0.5, 0.5, -1.0);  // the north pole moves through the faces around it
  const double with_all = SP::internal::largest_fold_free_step(faces, x, step, horizon);
  SP::internal::Faces folded = faces;
  std::swap(folded[0][1], folded[0][2]);
  SP::internal::Faces without_first(faces.begin() + 1, faces.end());
  const double ignoring = SP::internal::largest_fold_free_step(folded, x, step, horizon);
  const double reference = SP::internal::largest_fold_free_step(without_first, x, step, horizon);
  report("largest_fold_free_step ignores faces that are already folded",
         std::isfinite(with_all) && ignoring == reference, "with folded face " + str(ignoring) + ", without it " + str(reference));
}

// ---------------------------------------------------------------------------------------
// Tangent bases

void test_tangent_basis()
{
  std::vector<Vector> points{Vector(0, 0, 1), Vector(0, 0, -1), Vector(1, 0, 0), Vector(0, -1, 0),
                             Vector(1e-9, -1e-9, -1).normalized(), Vector(-1e-12, 1e-12, 1).normalized()};
  for(int n = 0; n < 1000; ++n) points.push_back(random_unit_vector());
  double orthonormal = 0, orthogonal = 0, poles = 0;
  for(std::size_t i = 0; i < points.size(); ++i) {
    const Vector& p = points[i];
    const Eigen::Matrix<double, 3, 2> b = SP::internal::tangent_basis(p);
    const double e1 = (b.transpose() * b - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff();
    const double e2 = (b.transpose() * p).cwiseAbs().maxCoeff();
    if(!b.allFinite()) orthonormal = orthogonal = std::numeric_limits<double>::infinity();
    orthonormal = std::max(orthonormal, e1);
    orthogonal = std::max(orthogonal, e2);
    if(i < 2) poles = std::max({poles, e1, e2, b.allFinite() ? 0.0 : 1.0});
  }
  report("tangent_basis is orthonormal (1e-12)", orthonormal <= 1e-12, "err. " + str(orthonormal));
  report("tangent_basis is orthogonal to p (1e-12)", orthogonal <= 1e-12, "err. " + str(orthogonal));
  report("tangent_basis is an orthonormal tangent basis at both poles (0,0,1) and (0,0,-1)", poles <= 1e-15,
         "err. " + str(poles));
}

// ---------------------------------------------------------------------------------------
// Reference triangles of nearly degenerate faces

std::array<double, 3> edge_lengths(const SP::Reference_triangle& r)
{
  std::array<double, 3> l;
  for(int i = 0; i < 3; ++i) l[i] = (r.points[(i + 1) % 3] - r.points[(i + 2) % 3]).norm();
  return l;
}

void test_mollified_triangles()
{
  namespace I = SP::internal;
  // Fair triangles keep their exact points; a triangle of the plane from their edge lengths
  // has those lengths and the same area.
  bool fair_kept = true;
  double planar_error = 0;
  for(int n = 0; n < 1000; ++n) {
    const SP::Reference_triangle fair = random_reference(uniform(1e-6, 10.0));
    const SP::Reference_triangle same = I::mollified_triangle(fair.points[0], fair.points[1], fair.points[2]);
    fair_kept = fair_kept && same.points == fair.points && same.area == fair.area;
    const std::array<double, 3> l = edge_lengths(fair);
    const SP::Reference_triangle planar = I::planar_triangle(l);
    const std::array<double, 3> lp = edge_lengths(planar);
    for(int i = 0; i < 3; ++i) planar_error = std::max(planar_error, std::abs(lp[i] - l[i]) / l[i]);
    planar_error = std::max(planar_error, std::abs(planar.area - fair.area) / fair.area);
  }
  report("mollified_triangle keeps fair triangles (smallest angle over 10 degrees) bit for bit", fair_kept);
  report("planar_triangle has the given edge lengths and Heron's area (rel 1e-12)", planar_error <= 1e-12,
         "rel. err. " + str(planar_error));

  // Needles (a near-duplicate vertex, collinear up to rounding) and slivers: one length added
  // to the three edges, the smallest that gives the minimum relative height.
  const Vector a(0.3, -0.2, 0.1), b(1.7, 0.4, -0.5), c(0.2, 1.1, 0.9);
  const std::vector<std::array<Vector, 3>> thin{
    {a, a + 1e-9 * (b - a), b},                            // collinear but for rounding
    {a, a + 1e-6 * (b - a) + 1e-7 * (c - a), c},           // a needle
    {a, b, 0.5 * (a + b) + 1e-8 * (c - 0.5 * (a + b))},    // a sliver
    {a, b, 0.5 * (a + b)},                                 // collinear
    {a, b, 0.5 * (a + b) + 0.01 * (c - 0.5 * (a + b))}};   // thin, not degenerate
  double added_spread = 0, height_error = 0;
  bool fat_enough = true;
  for(const auto& t : thin) {
    const SP::Reference_triangle r = I::mollified_triangle(t[0], t[1], t[2]);
    const std::array<double, 3> l{(t[1] - t[2]).norm(), (t[2] - t[0]).norm(), (t[0] - t[1]).norm()};
    const std::array<double, 3> lm = edge_lengths(r);
    const double added = lm[0] - l[0], longest = *std::max_element(lm.begin(), lm.end());
    added_spread = std::max({added_spread, std::abs(lm[1] - l[1] - added) / longest, std::abs(lm[2] - l[2] - added) / longest});
    const double height = 2 * r.area / (longest * longest);
    height_error = std::max(height_error, std::abs(height - I::minimum_relative_height) / I::minimum_relative_height);
    const double angles = r.angles[0] + r.angles[1] + r.angles[2];
    fat_enough = fat_enough && added > 0 && std::abs(angles - M_PI) < 1e-12;
  }
  report("mollified_triangle adds one length to the three edges of thin triangles (rel 1e-12)", added_spread <= 1e-12,
         "rel. spread " + str(added_spread));
  report("mollified_triangle gives thin triangles exactly the minimum relative height (rel 1e-9)", height_error <= 1e-9,
         "rel. err. " + str(height_error));
  report("mollified_triangle of thin triangles: a positive added length, angles summing to pi", fat_enough);
}

// ---------------------------------------------------------------------------------------
// The small symmetric eigen solver and the positive semi-definite projection

// Symmetric N x N test matrices of the kinds the solver meets or could: random, of low rank
// (as the face Hessians with their near-null rotations), with repeated eigenvalues, already
// diagonal or nearly, zero, and spanning twelve orders of magnitude.
template <int N>
std::vector<Eigen::Matrix<double, N, N>> symmetric_test_matrices()
{
  using Matrix = Eigen::Matrix<double, N, N>;
  std::normal_distribution<double> normal;
  auto gaussian = [&] { Matrix m; for(int i = 0; i < N * N; ++i) m(i) = normal(rng); return m; };
  auto rotation = [&] { return Matrix(Eigen::HouseholderQR<Matrix>(gaussian()).householderQ()); };
  std::vector<Matrix> matrices{Matrix::Zero(), Matrix::Identity(), Matrix(Matrix::Identity() * -2)};
  for(int n = 0; n < 2000; ++n) {
    const Matrix g = gaussian();
    matrices.push_back(g + g.transpose());
    const Eigen::Matrix<double, N, N / 2> low = gaussian().leftCols(N / 2);
    matrices.push_back(low * low.transpose() * (n % 2 ? 1 : -1));
    Eigen::Matrix<double, N, 1> values;
    for(int i = 0; i < N; ++i)
      values(i) = i % 2 ? values(i - 1) : normal(rng) * std::pow(10.0, uniform(-6, 6));
    const Matrix q = rotation();
    matrices.push_back(q * values.asDiagonal() * q.transpose());
    Matrix nearly_diagonal = Matrix(values.asDiagonal());
    nearly_diagonal(N - 1, 0) = nearly_diagonal(0, N - 1) = 1e-300 * normal(rng);
    matrices.push_back(nearly_diagonal);
  }
  return matrices;
}

template <int N>
void check_symmetric_eigen()
{
  using Matrix = Eigen::Matrix<double, N, N>;
  double reconstruction = 0, orthogonality = 0, against_eigen = 0;
  bool converged = true;
  for(const Matrix& a : symmetric_test_matrices<N>()) {
    const SP::internal::Symmetric_eigen<N> eigen(a);
    converged = converged && eigen.converged();
    const Matrix& v = eigen.vectors();
    const double size = std::max(a.norm(), std::numeric_limits<double>::min());
    reconstruction = std::max(reconstruction, (v * eigen.values().asDiagonal() * v.transpose() - a).norm() / size);
    orthogonality = std::max(orthogonality, (v.transpose() * v - Matrix::Identity()).norm());
    Eigen::Matrix<double, N, 1> sorted = eigen.values();
    std::sort(sorted.data(), sorted.data() + N);
    const Eigen::SelfAdjointEigenSolver<Matrix> reference(a, Eigen::EigenvaluesOnly);
    against_eigen = std::max(against_eigen, (sorted - reference.eigenvalues()).norm() / size);
  }
  const std::string n = std::to_string(N) + "x" + std::to_string(N);
  report("Symmetric_eigen " + n + " converges on 8003 test matrices", converged);
  report("Symmetric_eigen " + n + ": V diag(values) V^T = A (rel 1e-13)", reconstruction <= 1e-13, "rel. err. " + str(reconstruction));
  report("Symmetric_eigen " + n + ": V is orthogonal (1e-13)", orthogonality <= 1e-13, "err. " + str(orthogonality));
  report("Symmetric_eigen " + n + ": the eigenvalues of Eigen's SelfAdjointEigenSolver (rel 1e-13)", against_eigen <= 1e-13,
         "rel. err. " + str(against_eigen));
}

void test_symmetric_eigen()
{
  check_symmetric_eigen<2>();
  check_symmetric_eigen<3>();
  check_symmetric_eigen<6>();
  Eigen::Matrix<double, 6, 6> not_finite = Eigen::Matrix<double, 6, 6>::Identity();
  not_finite(3, 2) = std::numeric_limits<double>::quiet_NaN();
  const SP::internal::Symmetric_eigen<6> nan(not_finite);
  not_finite(3, 2) = std::numeric_limits<double>::infinity();
  const SP::internal::Symmetric_eigen<6> inf(not_finite);
  report("Symmetric_eigen does not converge on a matrix with NaN or inf", !nan.converged() && !inf.converged());
}

// |A|: positive semi-definite, the absolute values of A's eigenvalues on the same
// eigenvectors (so it commutes with A, and |A|^2 = A^2), A itself if A has no negative one.
void test_project_to_psd()
{
  using Matrix = Eigen::Matrix<double, 6, 6>;
  double negative = 0, commutator = 0, square = 0;
  bool psd_kept = true;
  for(const Matrix& a : symmetric_test_matrices<6>()) {
    Matrix p = a;
    SP::internal::project_to_psd(p);
    const double size = std::max(a.norm(), std::numeric_limits<double>::min());
    const Eigen::SelfAdjointEigenSolver<Matrix> eigen(p, Eigen::EigenvaluesOnly);
    negative = std::max(negative, -eigen.eigenvalues().minCoeff() / size);
    commutator = std::max(commutator, (a * p - p * a).norm() / (size * size));
    square = std::max(square, (p * p - a * a).norm() / (size * size));
    const Eigen::SelfAdjointEigenSolver<Matrix> of_a(a, Eigen::EigenvaluesOnly);
    if(of_a.eigenvalues().minCoeff() > 1e-12 * size)
      psd_kept = psd_kept && p == a;
  }
  report("project_to_psd gives a positive semi-definite matrix (rel 1e-13)", negative <= 1e-13, "rel. " + str(negative));
  report("project_to_psd keeps the eigenvectors: |A| A = A |A| (rel 1e-13)", commutator <= 1e-13, "rel. err. " + str(commutator));
  report("project_to_psd keeps the absolute eigenvalues: |A|^2 = A^2 (rel 1e-13)", square <= 1e-13, "rel. err. " + str(square));
  report("project_to_psd leaves positive definite matrices bit for bit", psd_kept);
  Matrix not_finite = Matrix::Identity();
  not_finite(0, 5) = not_finite(5, 0) = std::numeric_limits<double>::quiet_NaN();
  SP::internal::project_to_psd(not_finite);
  report("project_to_psd makes a matrix with NaN zero", not_finite.isZero(0));
}

// With invariant directions: a negative eigenvalue along them becomes 0, one across them
// its absolute value, a positive one stays; built from known eigenvectors, so that each
// case is checked on its own direction.
void test_project_to_psd_with_invariant_directions()
{
  using Matrix = Eigen::Matrix<double, 6, 6>;
  double worst = 0;
  for(int trial = 0; trial < 100; ++trial) {
    const Eigen::HouseholderQR<Matrix> qr(Matrix::Random());
    const Matrix q = qr.householderQ();  // orthonormal eigenvectors
    Eigen::Matrix<double, 6, 1> values;
    values << -3, -2e-3, -1, 0.5, 2, 4;
    const Matrix a = q * values.asDiagonal() * q.transpose();
    // The first two eigenvectors span the invariant directions, mixed by a rotation.
    const double angle = 0.3 + trial * 0.01;
    Eigen::Matrix<double, 6, 2> invariant;
    invariant.col(0) = std::cos(angle) * q.col(0) + std::sin(angle) * q.col(1);
    invariant.col(1) = -std::sin(angle) * q.col(0) + std::cos(angle) * q.col(1);
    Matrix p = a;
    SP::internal::project_to_psd(p, invariant);
    Eigen::Matrix<double, 6, 1> expected;
    expected << 0, 0, 1, 0.5, 2, 4;
    worst = std::max(worst, (p - q * expected.asDiagonal() * q.transpose()).norm() / a.norm());
  }
  report("project_to_psd with invariant directions drops their negative curvature and makes the rest absolute (rel 1e-12)",
         worst <= 1e-12, "rel. err. " + str(worst));
}

// The stopping rules' extrapolations of Newton's decrement: exact on the sequences they
// model (quadratic d_next = C d^2, linear d_next = r d), and no prediction (the decrement
// itself, which never stops earlier than the decrement would) when the decrement grew.
void test_decrement_predictions()
{
  double quadratic = 0, linear = 0;
  for(double c : {0.5, 3.0, 40.0}) {
    const double d0 = 1e-2 / c, d1 = c * d0 * d0, d2 = c * d1 * d1;
    quadratic = std::max(quadratic, std::abs(SP::internal::predicted_decrement(d0, d1) - d2) / d2);
  }
  for(double r : {0.05, 0.3, 0.9}) {
    const double d0 = 1e-3, d1 = r * d0, d2 = r * d1;
    linear = std::max(linear, std::abs(SP::internal::linearly_predicted_decrement(d0, d1) - d2) / d2);
  }
  report("predicted_decrement is exact on a quadratic sequence (rel 1e-14)", quadratic <= 1e-14, "rel. err. " + str(quadratic));
  report("linearly_predicted_decrement is exact on a geometric sequence (rel 1e-14)", linear <= 1e-14, "rel. err. " + str(linear));
  report("no prediction below a decrement that grew or had no predecessor",
         SP::internal::predicted_decrement(1e-4, 2e-4) == 2e-4 && SP::internal::linearly_predicted_decrement(1e-4, 2e-4) == 2e-4 &&
           SP::internal::linearly_predicted_decrement(0, 2e-4) == 2e-4);
}

int main()
{
  rng.seed(20260501);
  test_mollified_triangles();
  test_energies();
  test_untangling_on_folded_faces();
  test_barrier_on_area_floors();
  test_squared_d_min();
  test_d_min_branches();
  test_jet_arithmetic();
  test_first_positive_root();
  test_largest_fold_free_step();
  test_tangent_basis();
  test_symmetric_eigen();
  test_project_to_psd();
  test_project_to_psd_with_invariant_directions();
  test_decrement_predictions();
  std::cout << passed << " passed, " << failed << " failed" << std::endl;
  return failed == 0 ? 0 : 1;
}
