// Maps a mesh onto the unit sphere with the installed package: by default an icosahedron
// stretched into an ellipsoid, else the mesh file given as argument.
// Exit status 0 if and only if the map is valid.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <iostream>

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(argc > 1) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh)) {
      std::cerr << "cannot read " << argv[1] << "\n";
      return 1;
    }
  } else {
    CGAL::make_icosahedron(mesh, Point(0, 0, 0), 1.0);
    for(auto v : vertices(mesh)) {
      const Point& p = mesh.point(v);
      mesh.point(v) = Point(3 * p.x(), p.y(), 0.5 * p.z());
    }
  }

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere);
  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  std::cout << num_vertices(mesh) << " vertices: " << r.message() << ", " << r.iterations << " iterations ("
            << r.stage_summary() << "), valid " << (r.is_valid() ? "yes" : "no") << ", mean |log area ratio| "
            << d.log_area_ratio.mean << "\n";
  return r.is_valid() && d.is_valid() ? 0 : 1;
}
