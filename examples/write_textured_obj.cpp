// Textures a mesh through its spherical map: writes OUTPUT.obj (the input's positions with
// texture coordinates taken from the sphere), OUTPUT.mtl and OUTPUT_checker.png, a checkerboard
// to view it with. Equal checks on the model mean a map without distortion; how the checks
// shrink and shear shows where the map squeezes area and angles.
//
//   write_textured_obj INPUT SPHERE [OUTPUT.obj]     (default OUTPUT: textured.obj)
//
// SPHERE is the map of INPUT as spherical_parameterize writes it: the same vertices in the
// same order, on the unit sphere. Texture coordinates are equirectangular (longitude,
// colatitude): u = atan2(y, x) / (2 pi) + 1/2, v = acos(z) / pi. They cannot cover a pole:
// the few faces around each pole show a fan of stretched checks.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
using Polygon = std::vector<std::size_t>;

namespace {

// A PNG needs zlib data, but zlib allows uncompressed ("stored") blocks: with them a valid
// PNG takes a CRC and an Adler checksum, and no compression library.
std::uint32_t crc32(const std::string& bytes)
{
  std::uint32_t c = 0xffffffffu;
  for(unsigned char b : bytes) {
    c ^= b;
    for(int k = 0; k < 8; ++k)
      c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

std::string big_endian(std::uint32_t x)
{
  return {char(x >> 24), char(x >> 16), char(x >> 8), char(x)};
}

std::string png_chunk(const std::string& type, const std::string& data)
{
  return big_endian(std::uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

bool write_png(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb)
{
  std::string raw;  // each row starts with filter type 0 (none)
  for(int y = 0; y < height; ++y) {
    raw += '\0';
    raw.append(reinterpret_cast<const char*>(&rgb[std::size_t(y) * width * 3]), std::size_t(width) * 3);
  }
  std::string zlib = "\x78\x01";
  for(std::size_t at = 0; at < raw.size(); at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    const bool last = at + n == raw.size();
    zlib += char(last ? 1 : 0);
    zlib += {char(n & 0xff), char(n >> 8), char(~n & 0xff), char((~n >> 8) & 0xff)};
    zlib.append(raw, at, n);
  }
  std::uint32_t a = 1, b = 0;
  for(unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  zlib += big_endian((b << 16) | a);

  const std::string header = big_endian(std::uint32_t(width)) + big_endian(std::uint32_t(height)) +
                             std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, no interlace
  std::ofstream out(path, std::ios::binary);
  out << "\x89PNG\r\n\x1a\n" << png_chunk("IHDR", header) << png_chunk("IDAT", zlib) << png_chunk("IEND", "");
  return bool(out);
}

// 16 x 8 checks over 360 x 180 degrees: square checks of 22.5 degrees. The two colours differ
// between the northern and the southern hemisphere so the poles can be told apart.
std::vector<unsigned char> checkerboard(int width, int height)
{
  std::vector<unsigned char> rgb(std::size_t(width) * height * 3);
  for(int y = 0; y < height; ++y)
    for(int x = 0; x < width; ++x) {
      const bool dark = ((x * 16 / width) + (y * 8 / height)) % 2 != 0;
      const bool north = y < height / 2;
      const std::array<unsigned char, 3> c = dark ? (north ? std::array<unsigned char, 3>{40, 70, 160}
                                                           : std::array<unsigned char, 3>{160, 50, 40})
                                                  : std::array<unsigned char, 3>{235, 235, 225};
      std::copy(c.begin(), c.end(), &rgb[(std::size_t(y) * width + x) * 3]);
    }
  return rgb;
}

struct Texture_coordinate
{
  double u, v;
};

} // namespace

int main(int argc, char** argv)
{
  if(argc < 3) {
    std::cerr << "usage: write_textured_obj INPUT SPHERE [OUTPUT.obj]\n";
    return 1;
  }
  const std::filesystem::path obj_path = argc > 3 ? argv[3] : "textured.obj";
  std::filesystem::path mtl_path = obj_path, png_path = obj_path;
  mtl_path.replace_extension(".mtl");
  png_path.replace_filename(obj_path.stem().string() + "_checker.png");

  // Soups, not meshes: the vertex order of the files is all that ties the two together.
  std::vector<Point> points, sphere;
  std::vector<Polygon> faces, sphere_faces;
  if(!CGAL::IO::read_polygon_soup(argv[1], points, faces) || !CGAL::IO::read_polygon_soup(argv[2], sphere, sphere_faces)) {
    std::cerr << "cannot read " << argv[1] << " or " << argv[2] << "\n";
    return 1;
  }
  if(points.size() != sphere.size() || faces.size() != sphere_faces.size()) {
    std::cerr << argv[2] << " does not have the vertices and faces of " << argv[1] << "\n";
    return 1;
  }

  std::vector<Texture_coordinate> vt;  // one per vertex, then the duplicates of the seam faces
  for(const Point& p : sphere) {
    const double norm = std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z());
    if(!(std::abs(norm - 1) < 1e-6)) {  // most likely the two files were swapped
      std::cerr << argv[2] << " has a point off the unit sphere: is it the sphere mesh?\n";
      return 1;
    }
    const double z = std::clamp(p.z() / norm, -1.0, 1.0);
    vt.push_back({std::atan2(p.y(), p.x()) / (2 * M_PI) + 0.5, std::acos(z) / M_PI});
  }

  // A face whose corners straddle u = 0 / u = 1 would be drawn across the whole texture.
  // Its corners near u = 0 get copies shifted to u + 1 (textures repeat), so the face covers
  // its true, narrow strip. A corner at a pole has no longitude: it takes the face's mean.
  std::vector<std::vector<std::size_t>> face_vt(faces.size());
  std::size_t seam_faces = 0;
  for(std::size_t f = 0; f < faces.size(); ++f) {
    const Polygon& face = faces[f];
    std::vector<double> u;
    for(std::size_t v : face) u.push_back(vt[v].u);
    const bool crosses = *std::max_element(u.begin(), u.end()) - *std::min_element(u.begin(), u.end()) > 0.5;
    if(crosses)
      for(double& x : u) if(x < 0.5) x += 1;
    double mean = 0;
    int off_pole = 0;
    for(std::size_t k = 0; k < face.size(); ++k)
      if(vt[face[k]].v > 1e-9 && vt[face[k]].v < 1 - 1e-9) { mean += u[k]; ++off_pole; }
    for(std::size_t k = 0; k < face.size(); ++k) {
      const std::size_t v = face[k];
      const bool at_pole = !(vt[v].v > 1e-9 && vt[v].v < 1 - 1e-9) && off_pole > 0;
      if(at_pole) u[k] = mean / off_pole;
      if(u[k] != vt[v].u) {
        face_vt[f].push_back(vt.size());
        vt.push_back({u[k], vt[v].v});
      } else {
        face_vt[f].push_back(v);
      }
    }
    seam_faces += crosses;
  }

  std::ofstream obj(obj_path), mtl(mtl_path);
  obj.precision(17);
  obj << "# " << argv[1] << " textured through its spherical map " << argv[2] << "\n"
      << "mtllib " << mtl_path.filename().string() << "\n";
  for(const Point& p : points) obj << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
  for(const Texture_coordinate& t : vt) obj << "vt " << t.u << ' ' << t.v << "\n";
  obj << "usemtl checker\n";
  for(std::size_t f = 0; f < faces.size(); ++f) {
    obj << "f";
    for(std::size_t k = 0; k < faces[f].size(); ++k) obj << ' ' << faces[f][k] + 1 << '/' << face_vt[f][k] + 1;
    obj << "\n";
  }
  mtl << "newmtl checker\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nmap_Kd " << png_path.filename().string() << "\n";
  const int width = 512, height = 256;  // 32-pixel checks; the PNG is stored uncompressed
  if(!obj || !mtl || !write_png(png_path.string(), width, height, checkerboard(width, height))) {
    std::cerr << "cannot write " << obj_path.string() << " and its companions\n";
    return 1;
  }
  std::cout << "wrote " << obj_path.string() << ", " << mtl_path.string() << " and " << png_path.string() << ": "
            << points.size() << " vertices, " << vt.size() << " texture coordinates (" << seam_faces
            << " faces across the seam)\n";
  return 0;
}
