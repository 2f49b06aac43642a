// Any model of FaceListGraph works, here a Polyhedron_3, and the sphere map can be the mesh's
// own vertex point map: the mesh is then turned into its spherical image in place, with no
// second mesh or property to allocate. Its vertices and faces keep their order, so the file
// written matches the input vertex for vertex.
//
//   polyhedron_in_place [INPUT [OUTPUT]]   (defaults: data/triceratops.off, triceratops_sphere_polyhedron.off)
//
// Exit status 0 if and only if the map is valid (the file is written in any case).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/spherical_parameterize.h>

#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  const std::string output = argc > 2 ? argv[2] : "triceratops_sphere_polyhedron.off";
  Polyhedron polyhedron;
  if(!CGAL::IO::read_polygon_mesh(input, polyhedron) || polyhedron.empty()) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }

  // The input positions are read once, before the solve, so overwriting them is safe. They
  // are gone afterwards: measure_distortion() needs both, so the figures come from Result.
  const SP::Result r = CGAL::spherical_parameterize(polyhedron, get(CGAL::vertex_point, polyhedron));
  std::cout << "status " << r.message() << ", " << r.iterations << " iterations (" << r.stage_summary() << "), valid map: "
            << (r.is_valid() ? "yes" : "no") << ", degree " << r.degree << ", smallest area ratio "
            << r.min_area_ratio << "\n";

  // 17 digits keep the points on the unit sphere to the last bit when the file is read back.
  if(!CGAL::IO::write_polygon_mesh(output, polyhedron, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << output << "\n";
    return 1;
  }
  std::cout << "wrote " << output << "\n";
  return r.is_valid() ? 0 : 1;
}
