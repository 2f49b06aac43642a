// Shows the spherical image of a mesh in CGAL's basic viewer (Qt5), to judge a map by eye:
// crowded regions are the parts of the model the energy had to shrink.
//
//   draw_sphere [INPUT]        (default: data/triceratops.off)
//
// Built only when CGAL_Qt5 is found; needs a display, so it is not a test.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/draw_surface_mesh.h>
#include <CGAL/spherical_parameterize.h>

#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }
  // In place: the viewer draws the mesh's own points, which become the sphere points.
  const SP::Result r = CGAL::spherical_parameterize(mesh, mesh.points());
  std::cout << r.message() << (r.is_valid() ? "" : ": " + r.detail) << "\n";
  if(!r.is_valid())
    return 1;
  CGAL::draw(mesh);
  return 0;
}
