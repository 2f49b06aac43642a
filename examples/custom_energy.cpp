// Writing your own energy: a model of the SphericalEnergy concept is a struct with
//   - a Face_data type: the per-face constants, computed once from the input triangle;
//   - face_data(const Reference_triangle&): computes them (the input is already scaled to
//     the sphere's area 4 pi, so lengths and areas of every mesh are comparable);
//   - template <class Number> Number flat_energy(const Chord_triangle<Number>&, const Face_data&):
//     the energy of the flat triangle spanned by the three sphere points.
// flat_energy() is written once on a generic Number: with Number = double the solver gets
// values, with Number = Triangle_jet it gets exact gradients and Hessians, so no derivative
// is written by hand. The package multiplies the result by d_min^-2 itself.
//
// The energy below is the Dirichlet energy plus a logarithmic area term,
//   E = sum_i w_i |e_i|^2 + lambda * InputArea * log(Area / InputArea)^2,
// which, unlike the built-in Area energy (Area^2 / InputArea), punishes a face shrunk by a
// factor k as much as one grown by k, and goes to infinity as a chord triangle degenerates.
//
//   custom_energy [INPUT [LAMBDA]]        (defaults: data/triceratops.off, 0.1)
//
// Exit status 0 if and only if the map is valid.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Chord_triangle.h>
#include <CGAL/Spherical_parameterization/Reference_triangle.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

struct Dirichlet_log_area_energy
{
  double lambda = 1;  // weight of the area term; the Dirichlet term has weight 1

  struct Face_data
  {
    std::array<double, 3> half_cotangents;  // of the input angles, one per opposite edge
    double input_area;
  };

  Face_data face_data(const SP::Reference_triangle& r) const
  {
    // The exact cotangents rather than the paper's clamped ones: with them the spring term
    // is InputArea * |J|_F^2 for the affine map J, never negative even on obtuse inputs.
    return {r.exact_half_cotangents(), r.area};
  }

  template <class Number>
  Number flat_energy(const SP::Chord_triangle<Number>& t, const Face_data& d) const
  {
    using std::log;  // for Number = double; Triangle_jet's log() is found by argument-dependent lookup
    const Number dirichlet = t.spring(d.half_cotangents);
    // squared_double_area() is 4 Area^2, a polynomial: cheaper and smoother than Area itself.
    const Number log_ratio = log(t.squared_double_area() * (0.25 / (d.input_area * d.input_area))) * 0.5;
    return dirichlet + log_ratio * log_ratio * (lambda * d.input_area);
  }
};

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  const double lambda = argc > 2 ? std::atof(argv[2]) : 0.1;
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  // The robust pipeline starts with its own Tutte and untangling stages, then minimizes this
  // energy with fold-free steps: an energy without a barrier of its own is safe to use.
  const SP::Result r = CGAL::spherical_parameterize(
    mesh, sphere, SP::parameters::energy(Dirichlet_log_area_energy{lambda}).number_of_iterations(500));

  std::cout << "Dirichlet + " << lambda << " log-area: " << r.message() << ", " << r.iterations << " iterations ("
            << r.stage_summary() << "), " << r.time_seconds << " s\n";
  if(!r.is_valid()) {
    std::cerr << r.detail << "\n";
    return 1;
  }
  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  std::cout << "mean angle error " << d.angle_error.mean << " deg, mean |log area ratio| " << d.log_area_ratio.mean
            << ", smallest area ratio " << d.min_area_ratio << ", quasi-conformal mean " << d.quasi_conformal.mean
            << "\n";
  return d.is_valid() ? 0 : 1;
}
