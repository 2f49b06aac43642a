// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_GEOMETRY_IMAGE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_GEOMETRY_IMAGE_H

#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/internal/sphere/add_triangles.h>
#include <CGAL/Spherical_parameterization/octahedral_map.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// An octahedral geometry image (Praun and Hoppe 2003): the surface sampled on a regular
/// `size x size` grid of the octahedral square (`octahedral_map.h`). Sample `(column, row)`
/// sits at the square point `(-1 + 2 column / (size - 1), -1 + 2 row / (size - 1))`: the grid
/// includes the square's sides and corners, and with an odd size also the centre (north pole),
/// the axes and the fold lines, so that the grid's triangles follow the octahedron's faces.
/// Samples on the sides come in mirrored pairs of equal value (`(column, 0)` and
/// `(size - 1 - column, 0)`, ...), and the four corners are all the south pole.
struct Geometry_image
{
  int size = 0;                          ///< samples per row and per column
  std::vector<Eigen::Vector3d> samples;  ///< row after row, row 0 at `v = -1`, column 0 at `u = -1`
  bool inward_oriented = false;          ///< the map was of an inward-oriented mesh: its mesh reverses its faces

  /// The surface point of sample `(column, row)`.
  const Eigen::Vector3d& at(int column, int row) const { return samples[std::size_t(row) * size + column]; }

  /// The point of the octahedral square of sample `(column, row)`.
  Eigen::Vector2d square_point(int column, int row) const
  {
    return Eigen::Vector2d(-1 + 2.0 * column / (size - 1), -1 + 2.0 * row / (size - 1));
  }
};

/// \ingroup PkgSphericalParameterizationRef
/// Samples the surface of a sphere map on the octahedral grid of `size x size` points
/// (see `Geometry_image`). Consecutive samples of a row are located by a walk from the
/// previous one.
/// \pre `location.has_valid_map()`, and `size` is odd and at least 3 (Praun and Hoppe use
///   `2^k + 1`): the grid then contains the fold lines and the mirrored sides match up.
template <class TriangleMesh, class GeomTraits>
Geometry_image make_geometry_image(const Sphere_point_location<TriangleMesh, GeomTraits>& location, int size)
{
  CGAL_precondition(size >= 3 && size % 2 == 1);
  Geometry_image image;
  image.size = size;
  image.inward_oriented = location.inward_oriented();
  image.samples.reserve(std::size_t(size) * size);
  for(int row = 0; row < size; ++row) {
    auto previous = location.locate(octahedral_square_to_sphere(image.square_point(0, row)));
    for(int column = 0; column < size; ++column) {
      previous = location.locate(octahedral_square_to_sphere(image.square_point(column, row)), previous);
      image.samples.push_back(internal::to_eigen(location.surface_point(previous)));
    }
  }
  return image;
}

/// \ingroup PkgSphericalParameterizationRef
/// Writes `image` as a Portable Float Map (PFM), the float image format of Debevec's
/// HDRShop that most HDR image tools read:
/// - a text header of three lines: `PF` (three channels), then `size size` (width, height),
///   then the scale `-1` (little-endian floats; `1` on a big-endian machine);
/// - then `size * size` pixels of three 32-bit IEEE floats (x, y, z), row after row from the
///   bottom of the image (row 0, `v = -1`) to the top, as the PFM format orders them, each
///   row from left (`u = -1`) to right.
/// \return false if writing failed
inline bool write_geometry_image_PFM(std::ostream& os, const Geometry_image& image)
{
  const std::uint16_t one = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &one, 1);
  const bool little_endian = first_byte == 1;
  os << "PF\n" << image.size << ' ' << image.size << '\n' << (little_endian ? "-1" : "1") << '\n';
  std::vector<float> row(3 * std::size_t(image.size));
  for(int r = 0; r < image.size; ++r) {
    for(int c = 0; c < image.size; ++c)
      for(int k = 0; k < 3; ++k)
        row[3 * std::size_t(c) + k] = float(image.at(c, r)[k]);
    os.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
  }
  return bool(os);
}

namespace internal {

/// The index of the sample that stands for sample `(column, row)` once the mirrored sides
/// of the octahedral square are glued: the lower of each mirrored pair, `(0, 0)` for the corners.
inline int glued_sample(int column, int row, int size)
{
  const int last = size - 1;
  const bool column_on_side = column == 0 || column == last, row_on_side = row == 0 || row == last;
  if(column_on_side && row_on_side)
    return 0;
  if(row_on_side)
    column = std::min(column, last - column);
  else if(column_on_side)
    row = std::min(row, last - row);
  return row * size + column;
}

/// The two triangles of the grid cell whose lower left sample is `(c, r)`, as sample indices,
/// counterclockwise in the square. The cell is cut along the diagonal parallel to the
/// diamond's edge in its quadrant, so that no triangle straddles a fold line.
inline std::array<std::array<int, 3>, 2> cell_triangles(int c, int r, int size)
{
  const int a = r * size + c, b = a + 1, d = a + size, e = d + 1;  // a b lower, d e upper
  const double middle = (size - 1) / 2.0;
  const bool same_signs = (c + 0.5 - middle) * (r + 0.5 - middle) > 0;
  if(same_signs)  // quadrants I and III: fold line along (1, -1), diagonal b-d
    return {{{{a, b, d}}, {{b, e, d}}}};
  return {{{{a, b, e}}, {{a, e, d}}}};  // quadrants II and IV: diagonal a-e
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Appends to `out` the closed mesh of a geometry image: one vertex per distinct sample
/// (the mirrored sides glued, the four corners merged), two triangles per grid cell cut
/// along the fold lines, oriented as the input of the map. It is a genus-0 mesh with
/// `size^2 - 2 size + 3` vertices and `2 (size - 1)^2` faces.
/// \tparam PolygonMesh a model of `MutableFaceGraph` with an internal point property map
/// \return false if `out` refused a face
template <class PolygonMesh>
bool geometry_image_to_mesh(const Geometry_image& image, PolygonMesh& out)
{
  const int n = image.size;
  std::vector<int> vertex_of_sample(std::size_t(n) * n, -1);
  std::vector<Eigen::Vector3d> points;
  for(int r = 0; r < n; ++r)
    for(int c = 0; c < n; ++c) {
      const int glued = internal::glued_sample(c, r, n);
      if(vertex_of_sample[glued] < 0) {
        vertex_of_sample[glued] = int(points.size());
        points.push_back(image.samples[glued]);
      }
      vertex_of_sample[std::size_t(r) * n + c] = vertex_of_sample[glued];
    }
  std::vector<std::array<int, 3>> faces;
  for(int r = 0; r + 1 < n; ++r)
    for(int c = 0; c + 1 < n; ++c)
      for(const auto& t : internal::cell_triangles(c, r, n))
        faces.push_back({{vertex_of_sample[t[0]], vertex_of_sample[t[1]], vertex_of_sample[t[2]]}});
  return !internal::add_triangles(points, faces, image.inward_oriented, out).empty();
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_GEOMETRY_IMAGE_H
