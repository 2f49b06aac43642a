// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_TEXTURE_COORDINATES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_TEXTURE_COORDINATES_H

#include <CGAL/Spherical_parameterization/internal/input/indexed_triangles.h>
#include <CGAL/Spherical_parameterization/octahedral_map.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/assertions.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>
#include <cmath>
#include <limits>
#include <ostream>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// How texture coordinates are taken from the sphere.
enum class Texture_layout
{
  /// Longitude and latitude: `u = atan2(y, x) / (2 pi) + 1/2`, `v = 1 - acos(z) / pi`, so the
  /// north pole (`z = 1`) is at the top of the image (`v = 1`, the OBJ convention). The seam
  /// is the half meridian `y = 0, x < 0`; the poles are singular.
  EQUIRECTANGULAR,
  /// The octahedral square of Praun and Hoppe (`octahedral_map.h`) scaled to `[0, 1]^2`:
  /// `(u, v) = (s + 1) / 2`. The seam is the cut of the octahedron, the four half meridians
  /// `x = 0` and `y = 0` of the southern half; the four vertices of the octahedron on the
  /// equator are singular (the unfolded square has half the angle around them).
  OCTAHEDRAL
};

/// \ingroup PkgSphericalParameterizationRef
/// The texture coordinates of the direction `d` (any nonzero length) in `layout`, without
/// any seam handling: the coordinates a vertex has when no face across a seam needs a copy.
inline Eigen::Vector2d texture_coordinates(const Eigen::Vector3d& d, Texture_layout layout)
{
  if(layout == Texture_layout::OCTAHEDRAL)
    return (sphere_to_octahedral_square(d) + Eigen::Vector2d::Ones()) / 2;
  const double z = std::clamp(d.z() / d.norm(), -1.0, 1.0);
  return Eigen::Vector2d(std::atan2(d.y(), d.x()) / (2 * M_PI) + 0.5, 1 - std::acos(z) / M_PI);
}

/// \ingroup PkgSphericalParameterizationRef
/// Texture coordinates of a mesh from its sphere map, with the vertices on seams split for
/// output only: each vertex has its own coordinates, and a face across a seam gets copies
/// of some of its corners, placed so that the face's texture triangle is the continuous
/// image of the face. For an OBJ file (`write_textured_OBJ()`) or any format with per-corner
/// texture coordinates; the mesh itself is not changed.
struct Seamed_texture_coordinates
{
  /// Per vertex first (in the order of `vertices(tm)`), then the copies.
  std::vector<Eigen::Vector2d> uv;
  /// Per face (in the order of `faces(tm)`), the index in `uv` of each corner (in the order
  /// of `vertices_around_face(halfedge(f, tm), tm)`).
  std::vector<std::array<int, 3>> corner_uv;
  /// Faces that needed at least one copy.
  std::size_t seam_faces = 0;
  /// Faces holding a singular point of the layout strictly inside (a pole, an equatorial
  /// vertex of the octahedron): no linear texture triangle can cover them correctly, so
  /// their texture is distorted. At most one face per singular point on a valid map.
  std::size_t singular_faces = 0;
  /// The smallest `octahedral_margin` that holds every corner of the faces across the
  /// octahedral cut inside `[0, 1]^2`; 0 for the equirectangular layout, whose seam faces
  /// rely on the texture repeating instead.
  double required_octahedral_margin = 0;
};

namespace internal {

/// The coordinates of one layout in its own chart (longitude-latitude, or the octahedral
/// square `[-1, 1]^2`), with the other coordinates that stand for the same point across the
/// seams: a face's corners pick among them to lie next to each other.
class Texture_chart
{
public:
  Texture_chart(Texture_layout layout, double margin) : layout_(layout), margin_(margin) {}

  Eigen::Vector2d chart_point(const Eigen::Vector3d& d) const
  {
    return layout_ == Texture_layout::OCTAHEDRAL ? sphere_to_octahedral_square(d)
                                                 : texture_coordinates(d, Texture_layout::EQUIRECTANGULAR);
  }

  /// The chart points standing for the same point of the sphere as `p`: for the
  /// longitude, one turn either way; for the octahedral square, its reflections about the
  /// midpoints of its sides and its translations around the corners (`fold_into_octahedral_square()`).
  std::vector<Eigen::Vector2d> copies(const Eigen::Vector2d& p) const
  {
    if(layout_ == Texture_layout::EQUIRECTANGULAR)
      return {p, p + Eigen::Vector2d(1, 0), p - Eigen::Vector2d(1, 0)};
    std::vector<Eigen::Vector2d> c{p};
    for(const Eigen::Vector2d& middle : {Eigen::Vector2d(1, 0), Eigen::Vector2d(-1, 0), Eigen::Vector2d(0, 1),
                                         Eigen::Vector2d(0, -1)})
      c.push_back(2 * middle - p);
    for(const double x : {-2.0, 2.0})
      for(const double y : {-2.0, 2.0})
        c.push_back(p + Eigen::Vector2d(x, y));
    return c;
  }

  /// The copy of `p` nearest to `target`.
  Eigen::Vector2d nearest_copy(const Eigen::Vector2d& p, const Eigen::Vector2d& target) const
  {
    Eigen::Vector2d best = p;
    for(const Eigen::Vector2d& c : copies(p))
      if((c - target).squaredNorm() < (best - target).squaredNorm())
        best = c;
    return best;
  }

  /// Texture coordinates of a chart point: the octahedral square goes to `[margin, 1 - margin]^2`.
  Eigen::Vector2d to_texture(const Eigen::Vector2d& p) const
  {
    if(layout_ == Texture_layout::EQUIRECTANGULAR)
      return p;
    return Eigen::Vector2d::Constant(margin_) + (1 - 2 * margin_) * (p + Eigen::Vector2d::Ones()) / 2;
  }

  /// The points of the sphere where the layout is singular.
  std::vector<Eigen::Vector3d> singular_points() const
  {
    if(layout_ == Texture_layout::EQUIRECTANGULAR)
      return {Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
    return {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY()};
  }

  /// True for a direction at a pole of the longitude-latitude chart, whose longitude means nothing.
  bool at_pole(const Eigen::Vector3d& d) const
  {
    return layout_ == Texture_layout::EQUIRECTANGULAR && std::abs(d.z()) >= (1 - 1e-12) * d.norm();
  }

private:
  Texture_layout layout_;
  double margin_;
};

/// True if the direction `s` is strictly inside the cone over the chord triangle `x`.
inline bool strictly_contains(const std::array<Eigen::Vector3d, 3>& x, const Eigen::Vector3d& s)
{
  const double orientation = x[0].dot(x[1].cross(x[2]));
  return orientation * s.dot(x[1].cross(x[2])) > 0 && orientation * x[0].dot(s.cross(x[2])) > 0 &&
         orientation * x[0].dot(x[1].cross(s)) > 0;
}

/// The chart points of a face's corners, continuous across the seams: each corner takes
/// the copy nearest to the chart point of the face's centre. A corner at a pole takes the
/// mean longitude of the others.
inline std::array<Eigen::Vector2d, 3> unfold_face(const Texture_chart& chart, const std::array<Eigen::Vector3d, 3>& x)
{
  Eigen::Vector3d centre = x[0] + x[1] + x[2];
  if(!(centre.norm() > 1e-12))
    centre = x[0];
  const Eigen::Vector2d target = chart.chart_point(centre);
  std::array<Eigen::Vector2d, 3> p;
  double longitude_sum = 0;
  int off_pole = 0;
  for(int k = 0; k < 3; ++k) {
    p[k] = chart.nearest_copy(chart.chart_point(x[k]), target);
    if(!chart.at_pole(x[k])) {
      longitude_sum += p[k].x();
      ++off_pole;
    }
  }
  for(int k = 0; k < 3; ++k)
    if(chart.at_pole(x[k]) && off_pole > 0)
      p[k].x() = longitude_sum / off_pole;
  return p;
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Texture coordinates of the closed triangle mesh `tm` from its sphere map, in `layout`,
/// with vertices split where faces cross the seam (see `Seamed_texture_coordinates`).
///
/// How seams are handled: each face places its three corners in the layout's chart next to
/// the chart point of its centre, choosing for each corner among the points that stand for
/// it across the seams. A face across the equirectangular seam gets `u` beyond 1 or below 0,
/// right for a texture that repeats (the usual wrap mode). A face across the octahedral cut
/// gets the corner's mirror image beyond the square's side, which a texture reads right
/// only if it holds that mirror image there: pass `octahedral_margin > 0` to shrink the
/// square to `[margin, 1 - margin]^2`, and fill the margin of the texture through
/// `fold_into_octahedral_square()`. A corner at a pole of the equirectangular layout takes
/// the mean `u` of the face's other corners.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam SphereMap a readable property map `vertex_descriptor -> Point_3` (any kernel)
/// \pre `0 <= octahedral_margin < 1/2`; every face is a triangle
template <class TriangleMesh, class SphereMap>
Seamed_texture_coordinates seamed_texture_coordinates(const TriangleMesh& tm, const SphereMap& sphere_map,
                                                      Texture_layout layout, double octahedral_margin = 0)
{
  CGAL_precondition(octahedral_margin >= 0 && octahedral_margin < 0.5);
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  const internal::Texture_chart chart(layout, octahedral_margin);
  Seamed_texture_coordinates result;
  const internal::Indexed_triangles<TriangleMesh> mesh = internal::indexed_triangles(tm);
  std::vector<Eigen::Vector3d> sphere;
  for(vertex_descriptor v : mesh.vertices) {
    sphere.push_back(internal::to_eigen(get(sphere_map, v)));
    result.uv.push_back(chart.to_texture(chart.chart_point(sphere.back())));
  }
  // The copies of each vertex made so far, so that faces sharing a copy share its index.
  std::unordered_map<int, std::vector<int>> copies_of_vertex;
  auto uv_index = [&](int v, const Eigen::Vector2d& uv) {
    if(uv == result.uv[v])
      return v;
    for(int copy : copies_of_vertex[v])
      if(uv == result.uv[copy])
        return copy;
    result.uv.push_back(uv);
    copies_of_vertex[v].push_back(int(result.uv.size()) - 1);
    return int(result.uv.size()) - 1;
  };
  const std::vector<Eigen::Vector3d> singular = chart.singular_points();
  double overhang = 0;
  for(const std::array<int, 3>& corner : mesh.triangles) {
    const std::array<Eigen::Vector3d, 3> x{{sphere[corner[0]], sphere[corner[1]], sphere[corner[2]]}};
    const std::array<Eigen::Vector2d, 3> unfolded = internal::unfold_face(chart, x);
    if(layout == Texture_layout::OCTAHEDRAL)
      for(const Eigen::Vector2d& p : unfolded)
        overhang = std::max(overhang, p.cwiseAbs().maxCoeff() - 1);  // beyond the square, in its units
    std::array<int, 3> uv;
    bool copied = false;
    for(int c = 0; c < 3; ++c) {
      uv[c] = uv_index(corner[c], chart.to_texture(unfolded[c]));
      copied = copied || uv[c] != corner[c];
    }
    result.corner_uv.push_back(uv);
    result.seam_faces += copied;
    for(const Eigen::Vector3d& s : singular)
      result.singular_faces += internal::strictly_contains(x, s);
  }
  // The square spans 2 (1 - 2 m) / 2 of the texture: an overhang o needs o (1 - 2 m) / 2 <= m.
  result.required_octahedral_margin = overhang / (2 + 2 * overhang);
  return result;
}

/// \ingroup PkgSphericalParameterizationRef
/// Writes `tm` as a Wavefront OBJ with texture coordinates: the vertices (`v`, in the order
/// of `vertices(tm)`), the texture coordinates (`vt`, `texture.uv`) and the faces as
/// `f v/vt v/vt v/vt`. The vertex positions are not duplicated: seams are split in the
/// texture coordinates only. To use a material, write its `mtllib` and `usemtl` lines to `os`
/// before calling.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} the positions written; default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
///   \cgalParamNBegin{stream_precision} digits of the numbers; default 17 \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre `texture` was computed for `tm` as it is now
/// \return false if writing failed
template <class TriangleMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
bool write_textured_OBJ(std::ostream& os, const TriangleMesh& tm, const Seamed_texture_coordinates& texture,
                        const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  CGAL_precondition(texture.corner_uv.size() == num_faces(tm));
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  const auto precision = os.precision(choose_parameter(get_parameter(np, CGAL::internal_np::stream_precision), 17));
  std::unordered_map<vertex_descriptor, std::size_t> index;
  for(vertex_descriptor v : vertices(tm)) {
    const auto& p = get(vpm, v);
    index.emplace(v, index.size() + 1);  // OBJ counts from 1
    os << "v " << CGAL::to_double(p.x()) << ' ' << CGAL::to_double(p.y()) << ' ' << CGAL::to_double(p.z()) << '\n';
  }
  for(const Eigen::Vector2d& uv : texture.uv)
    os << "vt " << uv.x() << ' ' << uv.y() << '\n';
  std::size_t face_rank = 0;
  for(auto f : faces(tm)) {
    os << 'f';
    int k = 0;
    for(vertex_descriptor v : vertices_around_face(halfedge(f, tm), tm))
      if(k < 3)
        os << ' ' << index.at(v) << '/' << texture.corner_uv[face_rank][k++] + 1;
    os << '\n';
    ++face_rank;
  }
  os.precision(precision);
  return bool(os);
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_TEXTURE_COORDINATES_H
