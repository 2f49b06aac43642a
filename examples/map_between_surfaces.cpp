// A map between two surfaces through their spherical maps: every vertex of A goes to the
// point of B at the same place on the sphere, after a rotation of the sphere that matches
// landmarks, pairs (vertex of A, vertex of B) that the user declares to correspond.
//
//   map_between_surfaces A B [LANDMARKS [OUTPUT]]
//   map_between_surfaces                  (demonstration: A = data/triceratops.off and B
//                                          its icosphere remesh, turned by 90 degrees)
//
// LANDMARKS holds lines "I J" (vertex I of A, vertex J of B, from 0). OUTPUT (default
// A_on_B.off) is A with every vertex moved onto B. Sphere maps are unique only up to a
// rotation, so without landmarks the map between two surfaces is arbitrary up to one.
// Exit status 0 on success (in the demonstration: if the map follows the known correspondence).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>
#include <CGAL/Spherical_parameterization/surface_map.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Vertex = Mesh::Vertex_index;
using Landmarks = std::vector<std::pair<Vertex, Vertex>>;

// Adds the property "v:sphere" with the sphere map of `mesh`.
bool map_onto_sphere(Mesh& mesh, const std::string& name)
{
  auto sphere = mesh.add_property_map<Vertex, Point>("v:sphere", CGAL::ORIGIN).first;
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere);
  if(!r.is_valid())
    std::cerr << "no valid map of " << name << ": " << r.message() << " " << r.detail << "\n";
  return r.is_valid();
}

bool read_and_map(const std::string& path, Mesh& mesh)
{
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << path << "\n";
    return false;
  }
  return map_onto_sphere(mesh, path);
}

// The demonstration's B: A remeshed on an icosphere (level 4), turned by 90 degrees about z,
// with a sphere map of its own. Its landmarks pair a few B vertices with the nearest A vertex.
bool make_demonstration(Mesh& a, Mesh& b, Landmarks& landmarks, Eigen::Matrix3d& turn)
{
  if(!read_and_map(SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off", a))
    return false;
  const SP::Sphere_point_location<Mesh> location(a, a.property_map<Vertex, Point>("v:sphere").first);
  SP::remesh_on_icosphere(location, 4, b);
  turn = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for(Vertex w : b.vertices()) {
    if(w.idx() % 100 == 0) {  // 26 landmarks spread over the remesh
      Vertex nearest = *a.vertices().begin();
      for(Vertex v : a.vertices())
        if(CGAL::squared_distance(a.point(v), b.point(w)) < CGAL::squared_distance(a.point(nearest), b.point(w)))
          nearest = v;
      landmarks.emplace_back(nearest, w);
    }
  }
  for(Vertex w : b.vertices()) {
    const Eigen::Vector3d p = turn * Eigen::Vector3d(b.point(w).x(), b.point(w).y(), b.point(w).z());
    b.point(w) = Point(p.x(), p.y(), p.z());
  }
  CGAL::IO::write_polygon_mesh("demonstration_B.off", b, CGAL::parameters::stream_precision(17));
  return map_onto_sphere(b, "B");  // B's own map, computed from scratch
}

bool read_landmarks(const std::string& path, Landmarks& landmarks)
{
  std::ifstream in(path);
  long i, j;
  while(in >> i >> j) landmarks.emplace_back(Vertex(std::uint32_t(i)), Vertex(std::uint32_t(j)));
  return in.eof();
}

int main(int argc, char** argv)
{
  Mesh a, b;
  Landmarks landmarks;
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  const bool demonstration = argc < 3;
  if(demonstration ? !make_demonstration(a, b, landmarks, turn)
                   : !read_and_map(argv[1], a) || !read_and_map(argv[2], b) ||
                       (argc > 3 && !read_landmarks(argv[3], landmarks)))
    return 1;
  const std::string output = argc > 4 ? argv[4] : (demonstration ? std::string("triceratops")
                                                                  : std::filesystem::path(argv[1]).stem().string()) + "_on_B.off";
  const auto sphere_a = a.property_map<Vertex, Point>("v:sphere").first;
  const auto sphere_b = b.property_map<Vertex, Point>("v:sphere").first;

  // Least-squares rotation of A's sphere onto B's at the landmarks (Kabsch), then A -> B.
  const Eigen::Matrix3d rotation = SP::rotation_from_landmarks(sphere_a, sphere_b, landmarks);
  const SP::Sphere_point_location<Mesh> on_b(b, sphere_b);
  Mesh a_on_b = a;
  SP::map_to_surface(a, sphere_a, on_b, a_on_b.points(), rotation);
  if(!CGAL::IO::write_polygon_mesh(output, a_on_b, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << output << "\n";
    return 1;
  }
  std::cout << "mapped the " << a.number_of_vertices() << " vertices of A onto B with " << landmarks.size()
            << " landmarks; wrote " << output << "\n";
  if(!demonstration)
    return 0;

  // B is A turned: each vertex of A should land near its turned position. Not exactly: B's
  // map is computed from its own triangles, and maps of different meshes of one shape agree
  // only roughly where the map squeezes thin parts (the horns and the tail).
  double mean = 0;
  for(Vertex v : a.vertices()) {
    const Eigen::Vector3d expected = turn * Eigen::Vector3d(a.point(v).x(), a.point(v).y(), a.point(v).z());
    mean += std::sqrt(CGAL::squared_distance(a_on_b.point(v), Point(expected.x(), expected.y(), expected.z())));
  }
  mean /= a.number_of_vertices();
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(a);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  std::cout << "mean distance to the turned vertex: " << mean / diagonal << " of the bounding box diagonal\n";
  return mean < 0.08 * diagonal ? 0 : 1;
}
