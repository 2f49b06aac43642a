// The shortest use of the package: one call with every default (Combined energy with
// weights (1, 1), robust pipeline), then the quality figures of the map.
//
//   one_call [INPUT]        (default: data/triceratops.off)
//
// Exit status 0 if and only if the map is a valid embedding onto the unit sphere.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
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

  // The sphere points go to a property map of their own rather than over the vertex
  // positions: measure_distortion() below compares the two.
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere);

  // A bad input (not closed, not genus 0, ...) is reported here, not by an exception.
  std::cout << "input      " << input << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces\n"
            << "status     " << r.message() << (r.detail.empty() ? "" : " (" + r.detail + ")") << "\n"
            << "valid      " << (r.is_valid() ? "yes" : "no") << ": " << r.flipped << " flipped, " << r.degenerate
            << " degenerate, degree " << r.degree << (r.inward_oriented ? ", input oriented inward" : "") << "\n"
            << "solver     " << r.iterations << " iterations (" << r.stage_summary() << "), energy " << r.energy << ", "
            << r.time_seconds << " s\n";
  if(!r.is_valid())
    return 1;

  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  std::cout << "distortion quasi-conformal mean " << d.quasi_conformal.mean << " (95% "
            << d.quasi_conformal.percentile_95 << "), angle error mean " << d.angle_error.mean
            << " deg, |log area ratio| mean " << d.log_area_ratio.mean << ", smallest area ratio "
            << d.min_area_ratio << ", L2 stretch " << d.l2_stretch << "\n";
  return d.is_valid() ? 0 : 1;
}
