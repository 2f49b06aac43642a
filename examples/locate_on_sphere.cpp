// Point location on the sphere, the inverse of the map: for a direction, the face of the
// spherical triangulation that contains it, the barycentric coordinates there, and the point
// of the surface (or of any per-vertex attribute) that the map sends to that direction.
//
//   locate_on_sphere [INPUT]        (default: data/triceratops.off)
//
// Exit status 0 if the map is valid and locating the sphere point of every vertex gives the
// vertex back (to 1e-12 of the bounding box diagonal).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Sphere_point_location.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

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
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  if(!CGAL::spherical_parameterize(mesh, sphere).is_valid()) {
    std::cerr << "no valid map of " << input << "\n";
    return 1;
  }

  // Built once (O(faces)), then each query walks a few faces from a seed grid.
  const SP::Sphere_point_location<Mesh> location(mesh, sphere);

  // One query in detail: the direction of the north pole.
  const SP::Sphere_location<Mesh> north = location.locate(Eigen::Vector3d(0, 0, 1));
  std::cout << "north pole: face " << north.face << ", coordinates " << north.coordinates[0] << ' '
            << north.coordinates[1] << ' ' << north.coordinates[2] << ", surface point "
            << location.surface_point(north) << "\n";
  // Any per-vertex attribute interpolates the same way, here the vertex degree.
  auto degree = mesh.add_property_map<Mesh::Vertex_index, double>("v:degree", 0).first;
  for(auto v : mesh.vertices()) degree[v] = double(mesh.degree(v));
  std::cout << "            interpolated vertex degree " << location.interpolate(north, degree) << "\n";

  // The sphere point of each vertex leads back to the vertex: the map is inverted exactly.
  double worst = 0;
  for(auto v : mesh.vertices()) {
    const Point& s = sphere[v];
    worst = std::max(worst, std::sqrt(CGAL::squared_distance(location.surface_point(Eigen::Vector3d(s.x(), s.y(), s.z())),
                                                             mesh.point(v))));
  }
  std::cout << "vertices from their own sphere points: worst error " << worst << "\n";

  // A million random directions.
  std::mt19937_64 random(1);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> directions(1000000);
  for(Eigen::Vector3d& d : directions) d = Eigen::Vector3d(normal(random), normal(random), normal(random));
  const auto start = std::chrono::steady_clock::now();
  double checksum = 0;
  for(const Eigen::Vector3d& d : directions) checksum += location.surface_point(d).x();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "1,000,000 random directions located and mapped to the surface in " << seconds << " s"
            << " (checksum " << checksum << ")\n";
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(mesh);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  return worst < 1e-12 * diagonal ? 0 : 1;
}
