// Texture coordinates from the sphere in two layouts, longitude-latitude (equirectangular)
// and octahedral, written as OBJ files whose vertices are split on the seams in the texture
// coordinates only. Each comes with an MTL file and a checkerboard texture (binary PPM),
// drawn through the sphere so that both layouts show the same checks on the model: where
// a seam was mishandled, the checks would break up along it.
//
//   textured_obj_with_seams [INPUT [OUTPUT_STEM]]
//        (defaults: data/triceratops.off, OUTPUT_STEM = triceratops)
//
// Writes OUTPUT_STEM_equirectangular.{obj,mtl,ppm} and OUTPUT_STEM_octahedral.{obj,mtl,ppm}.
// Exit status 0 on success.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/octahedral_map.h>
#include <CGAL/Spherical_parameterization/texture_coordinates.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
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

// The octahedral square fills [margin, 1 - margin]^2 of the texture; the margin holds the
// mirror images that the faces across the octahedron's cut reach into.
const double octahedral_margin = 1.0 / 32;

// The point of the sphere that texture coordinates (u, v) stand for, in either layout.
Eigen::Vector3d sphere_point(double u, double v, SP::Texture_layout layout)
{
  if(layout == SP::Texture_layout::EQUIRECTANGULAR) {
    const double longitude = (u - 0.5) * 2 * M_PI, colatitude = (1 - v) * M_PI;
    return Eigen::Vector3d(std::sin(colatitude) * std::cos(longitude), std::sin(colatitude) * std::sin(longitude),
                           std::cos(colatitude));
  }
  const Eigen::Vector2d s = (Eigen::Vector2d(u, v) - Eigen::Vector2d::Constant(octahedral_margin)) /
                              (1 - 2 * octahedral_margin) * 2 - Eigen::Vector2d::Ones();
  return SP::octahedral_square_to_sphere(SP::fold_into_octahedral_square(s));
}

// 16 x 8 checks of 22.5 degrees in longitude and latitude, blue in the north, red in the south.
bool write_checkerboard(const std::string& path, SP::Texture_layout layout)
{
  const int width = layout == SP::Texture_layout::EQUIRECTANGULAR ? 1024 : 512, height = 512;
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << width << ' ' << height << "\n255\n";
  for(int row = 0; row < height; ++row)  // the first row of the file is the top, v = 1
    for(int column = 0; column < width; ++column) {
      const Eigen::Vector3d d = sphere_point((column + 0.5) / width, 1 - (row + 0.5) / height, layout);
      const double longitude = std::atan2(d.y(), d.x()) + M_PI, colatitude = std::acos(std::clamp(d.z(), -1.0, 1.0));
      const bool dark = (int(longitude / (M_PI / 8)) + int(colatitude / (M_PI / 8))) % 2 != 0;
      const unsigned char light[3] = {235, 235, 225}, blue[3] = {40, 70, 160}, red[3] = {160, 50, 40};
      out.write(reinterpret_cast<const char*>(!dark ? light : d.z() > 0 ? blue : red), 3);
    }
  return bool(out);
}

bool write_layout(const Mesh& mesh, const Mesh::Property_map<Mesh::Vertex_index, Point>& sphere,
                  SP::Texture_layout layout, const std::string& stem)
{
  const SP::Seamed_texture_coordinates texture = SP::seamed_texture_coordinates(
    mesh, sphere, layout, layout == SP::Texture_layout::OCTAHEDRAL ? octahedral_margin : 0);
  const std::string name = std::filesystem::path(stem).filename().string();
  std::ofstream obj(stem + ".obj"), mtl(stem + ".mtl");
  obj << "mtllib " << name << ".mtl\nusemtl checker\n";  // before the faces
  mtl << "newmtl checker\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nmap_Kd " << name << ".ppm\n";
  if(!SP::write_textured_OBJ(obj, mesh, texture) || !mtl || !write_checkerboard(stem + ".ppm", layout))
    return false;
  std::cout << "wrote " << stem << ".obj: " << texture.uv.size() << " texture coordinates for "
            << mesh.number_of_vertices() << " vertices, " << texture.seam_faces << " faces across the seam, "
            << texture.singular_faces << " holding a singular point\n";
  if(texture.required_octahedral_margin > octahedral_margin && layout == SP::Texture_layout::OCTAHEDRAL)
    std::cout << "  some faces across the cut reach beyond the texture's margin: it would take "
              << texture.required_octahedral_margin << "\n";
  return true;
}

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  const std::string stem = argc > 2 ? argv[2] : std::filesystem::path(input).stem().string();
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
  return write_layout(mesh, sphere, SP::Texture_layout::EQUIRECTANGULAR, stem + "_equirectangular") &&
             write_layout(mesh, sphere, SP::Texture_layout::OCTAHEDRAL, stem + "_octahedral")
           ? 0
           : 1;
}
