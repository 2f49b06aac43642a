// An octahedral geometry image (Praun and Hoppe 2003): the surface sampled on a regular
// N x N grid of the octahedral square, through the spherical map. Written twice: as a float
// image (PFM) whose pixels hold x, y, z, and as the closed mesh of the grid.
//
//   geometry_image [INPUT [N [OUTPUT_STEM]]]
//        (defaults: data/triceratops.off, N = 129, OUTPUT_STEM = triceratops_geometry_image)
//
// Writes OUTPUT_STEM.pfm and OUTPUT_STEM.off. N must be odd (Praun and Hoppe use 2^k + 1), so
// that the grid contains the octahedron's fold lines. The PFM has a three-line text header
// "PF", "N N", "-1" (little-endian), then N x N pixels of three 32-bit floats, bottom row
// first; see write_geometry_image_PFM(). Exit status 0 on success.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/geometry_image.h>

#include <filesystem>
#include <fstream>
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
  const int size = argc > 2 ? std::stoi(argv[2]) : 129;
  const std::string stem =
    argc > 3 ? argv[3] : std::filesystem::path(input).stem().string() + "_geometry_image";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh) || size < 3 || size % 2 == 0) {
    std::cerr << "cannot read " << input << ", or N is not odd and at least 3\n";
    return 1;
  }
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  if(!CGAL::spherical_parameterize(mesh, sphere).is_valid()) {
    std::cerr << "no valid map of " << input << "\n";
    return 1;
  }

  const SP::Sphere_point_location<Mesh> location(mesh, sphere);
  const SP::Geometry_image image = SP::make_geometry_image(location, size);
  // Pixel (column, row) is the surface point at the square point image.square_point(column, row).
  std::cout << "centre pixel (north pole): " << image.at(size / 2, size / 2).transpose()
            << "\ncorner pixels (south pole): " << image.at(0, 0).transpose() << "\n";

  std::ofstream pfm(stem + ".pfm", std::ios::binary);
  Mesh grid_mesh;
  if(!SP::write_geometry_image_PFM(pfm, image) || !SP::geometry_image_to_mesh(image, grid_mesh) ||
     !CGAL::IO::write_polygon_mesh(stem + ".off", grid_mesh, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << stem << ".pfm or " << stem << ".off\n";
    return 1;
  }
  std::cout << "wrote " << stem << ".pfm (" << size << " x " << size << " floats x 3) and " << stem << ".off ("
            << grid_mesh.number_of_vertices() << " vertices, " << grid_mesh.number_of_faces() << " faces)\n";
  return 0;
}
