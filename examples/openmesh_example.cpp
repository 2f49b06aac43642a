// An OpenMesh triangle mesh mapped through CGAL's BGL adapter: the package only needs the
// FaceListGraph interface, so no conversion to a CGAL mesh is needed.
//
//   openmesh_example [INPUT [OUTPUT]]   (defaults: data/triceratops.off, triceratops_sphere_openmesh.off)
//
// Exit status 0 if and only if the map is valid (the file is written in any case).

#include <CGAL/boost/graph/graph_traits_TriMesh_ArrayKernelT.h>  // includes OpenMesh's headers first

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

// OpenMesh stores float points by default. The solver works in double anyway, but a map
// rounded to float is off the unit sphere by about 1e-7, far above the 1e-12 of the validity
// check: double points keep the sphere exact in the mesh and in the file.
struct Double_traits : public OpenMesh::DefaultTraits
{
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Double_traits>;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  const std::string output = argc > 2 ? argv[2] : "triceratops_sphere_openmesh.off";
  Mesh mesh;
  if(!OpenMesh::IO::read_mesh(mesh, input) || mesh.n_faces() == 0) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }

  // CGAL's adapter reads OpenMesh's points as CGAL points; the sphere points go to a dynamic
  // property (an OpenMesh property underneath) so the input stays for measure_distortion().
  auto sphere = get(CGAL::dynamic_vertex_property_t<Point>(), mesh);
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere);
  std::cout << "OpenMesh TriMesh, " << mesh.n_vertices() << " vertices: " << r.message() << ", " << r.iterations
            << " iterations (" << r.stage_summary() << "), valid map: " << (r.is_valid() ? "yes" : "no") << "\n";
  if(!r.is_valid())
    return 1;
  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  std::cout << "mean angle error " << d.angle_error.mean << " deg, mean |log area ratio| " << d.log_area_ratio.mean
            << "\n";

  for(auto v : mesh.vertices()) {
    const Point p = get(sphere, v);
    mesh.set_point(v, Mesh::Point(p.x(), p.y(), p.z()));
  }
  // OpenMesh writes 6 digits unless told otherwise.
  if(!OpenMesh::IO::write_mesh(mesh, output, OpenMesh::IO::Options::Default, 17)) {
    std::cerr << "cannot write " << output << "\n";
    return 1;
  }
  std::cout << "wrote " << output << "\n";
  return d.is_valid() ? 0 : 1;
}
