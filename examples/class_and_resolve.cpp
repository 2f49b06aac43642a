// The stateful class: check the mesh and factor the sparsity pattern once, then solve twice,
// the second time with more weight on the area term, starting from the first map.
// This is the way to explore the angle/area trade-off on one mesh without paying for the
// input checks, the symbolic factorization and the Tutte start again.
//
//   class_and_resolve [INPUT]        (default: data/triceratops.off)
//
// Exit status 0 if and only if both maps are valid.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Spherical_parameterization/Spherical_parameterizer_3.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }

  // Combined_energy is a_dirichlet * Dirichlet + a_area * Area; its weights can change
  // between solves, its type cannot.
  SP::Spherical_parameterizer_3<Mesh, SP::Combined_energy> parameterizer(SP::combined_energy(1, 1));
  if(parameterizer.precompute(mesh) != SP::Error_code::OK) {
    std::cerr << input << ": " << parameterizer.input_detail() << "\n";
    return 1;
  }

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  double log_area_mean = 0;
  auto report = [&](const SP::Result& r) {
    const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
    log_area_mean = d.log_area_ratio.mean;
    const auto& w = parameterizer.energy().weights();
    std::cout << "weights (" << w[0] << ", " << w[1] << "): " << r.message() << ", " << r.iterations
              << " iterations (" << r.stage_summary() << "), " << r.time_seconds << " s; mean |log area ratio| "
              << d.log_area_ratio.mean << ", mean angle error " << d.angle_error.mean << " deg\n";
    return r.is_valid() && d.is_valid();
  };

  // More iterations than the default 200: with a heavy area term the second solve is slow
  // to converge, and NOT_CONVERGED would still be a valid map, just not the minimum.
  const auto np = CGAL::parameters::number_of_iterations(1000);
  const bool first_valid = report(parameterizer.solve(sphere, np));
  const double first_mean = log_area_mean;

  // No initial_sphere_map is given, so the second solve starts from the first map: the
  // Tutte and untangling stages are skipped because that map is already fold-free.
  parameterizer.energy().set_weights({1, 4});
  const bool second_valid = report(parameterizer.solve(sphere, np));
  std::cout << "mean |log area ratio| " << first_mean << " -> " << log_area_mean << "\n";

  return first_valid && second_valid ? 0 : 1;
}
