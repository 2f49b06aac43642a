// Remeshing through the sphere: the surface resampled on a geodesic icosphere, a mesh with
// the regular connectivity of an icosphere and the shape of the input.
//
//   remesh_on_icosphere [INPUT [LEVEL [OUTPUT]]]
//        (defaults: data/triceratops.off, level 5, triceratops_icosphere.off)
//
// Prints how far the remesh is from the input (Hausdorff distance relative to the diagonal
// of the bounding box) for every level up to LEVEL. Exit status 0 on success.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  const int level = argc > 2 ? std::stoi(argv[2]) : 5;
  const std::string output =
    argc > 3 ? argv[3] : std::filesystem::path(input).stem().string() + "_icosphere.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh) || level < 0 || level > 9) {
    std::cerr << "cannot read " << input << ", or LEVEL not in 0..9\n";
    return 1;
  }
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  if(!CGAL::spherical_parameterize(mesh, sphere).is_valid()) {
    std::cerr << "no valid map of " << input << "\n";
    return 1;
  }
  const SP::Sphere_point_location<Mesh> location(mesh, sphere);
  const CGAL::Bbox_3 box = PMP::bbox(mesh);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));

  for(int l = 0; l <= level; ++l) {
    Mesh remeshed;
    if(!SP::remesh_on_icosphere(location, l, remeshed))
      return 1;
    // Both ways: the remesh may miss a thin part of the input that the map squeezed.
    const double to_input = PMP::approximate_Hausdorff_distance<CGAL::Sequential_tag>(remeshed, mesh);
    const double to_remesh = PMP::approximate_Hausdorff_distance<CGAL::Sequential_tag>(mesh, remeshed);
    std::cout << "level " << l << ": " << remeshed.number_of_faces() << " faces, Hausdorff / diagonal "
              << std::max(to_input, to_remesh) / diagonal << " (remesh to input " << to_input / diagonal << ")\n";
    if(l == level && !CGAL::IO::write_polygon_mesh(output, remeshed, CGAL::parameters::stream_precision(17))) {
      std::cerr << "cannot write " << output << "\n";
      return 1;
    }
  }
  std::cout << "wrote " << output << "\n";
  return 0;
}
