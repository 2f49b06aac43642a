// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SPHERE_POINT_LOCATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SPHERE_POINT_LOCATION_H

#include <CGAL/Spherical_parameterization/internal/sphere/Spherical_triangulation.h>
#include <CGAL/Spherical_parameterization/internal/input/indexed_triangles.h>

#include <CGAL/Default.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/assertions.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <array>
#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Where a direction falls on the spherical triangulation of a sphere map: the face whose
/// cone from the sphere's centre contains it, and the barycentric coordinates of the point
/// where the ray along the direction meets that face's chord triangle (the flat triangle of
/// its three sphere points). Because the sphere map is linear on each chord triangle, these
/// coordinates locate the matching point on the input face exactly.
template <class TriangleMesh>
struct Sphere_location
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;  ///< of `TriangleMesh`
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;      ///< of `TriangleMesh`

  face_descriptor face;                      ///< the face containing the direction
  std::size_t face_index = 0;                ///< its rank in `faces(tm)`, for per-face arrays
  std::array<vertex_descriptor, 3> vertices; ///< the corners of `face`, in an order that keeps the map's orientation
  std::array<double, 3> coordinates{{1.0 / 3, 1.0 / 3, 1.0 / 3}};  ///< barycentric, each `>= 0`, sum 1
};

namespace internal {

/// True for CGAL's `Point_3` types: they take a barycentric combination, not a weighted sum.
template <class T, class = void>
struct Is_point_3 : std::false_type {};
template <class T>
struct Is_point_3<T, std::void_t<typename T::R::Point_3>> : std::is_same<T, typename T::R::Point_3> {};

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Point location on the unit sphere for a valid sphere map of a closed triangle mesh: for
/// any direction, the face of the spherical triangulation containing it and its barycentric
/// coordinates (`Sphere_location`), and from them the point of the input surface, or any
/// per-vertex attribute, at that direction. This is the inverse of the sphere map, the tool
/// behind resampling, remeshing and maps between surfaces.
///
/// The class copies what it needs (sphere points, input positions, connectivity and the
/// descriptors) at construction, in O(F) time and about 130 bytes per face; the mesh must
/// not change while locations are in use. A query walks from a seed face, found in a grid on
/// the octahedral square of about one cell per two faces, across the faces between the seed
/// and the target: a few steps on average, more where the map squeezes many faces into one cell.
/// Queries are `const` and may run in parallel.
///
/// Choice of method: the walk answers several times faster than a ray shot from the centre
/// into a `CGAL::AABB_tree` of the chord triangles, which finds the same faces. Queries that
/// follow each other closely (a scanline) are faster still with a hint, `locate(d, previous)`.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam GeomTraits a CGAL kernel, for the `Point_3` and `Vector_3` types of the answers;
///   default: the kernel of the mesh's points
template <class TriangleMesh, class GeomTraits = Default>
class Sphere_point_location
{
public:
  /// The kernel: `GeomTraits`, or the kernel of the mesh's points by default.
  using Geom_traits = typename Default::Get<GeomTraits, typename GetGeomTraits<TriangleMesh>::type>::type;
  using Point_3 = typename Geom_traits::Point_3;    ///< the type of `surface_point()`
  using Vector_3 = typename Geom_traits::Vector_3;  ///< a direction for `locate()`
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;  ///< of `TriangleMesh`
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;      ///< of `TriangleMesh`
  using Location = Sphere_location<TriangleMesh>;  ///< the answer of `locate()`

  /// Prepares the point location of the map `sphere_map` of `tm`. The sphere points are
  /// normalized; a map of an inward-oriented mesh (degree -1) is handled like its mirror.
  ///
  /// \tparam SphereMap a readable property map `vertex_descriptor -> Point_3` (any kernel)
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{vertex_point_map} the input positions, for `surface_point()`;
  ///     default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
  /// \cgalNamedParamsEnd
  /// \pre `tm` is a closed triangle mesh with at least one face. The answers are meaningful when the map is a valid
  ///   embedding (`has_valid_map()`); otherwise each query that the walk cannot settle tries
  ///   every face, in O(F), and returns the face that comes closest to containing it.
  template <class SphereMap, class NamedParameters = CGAL::parameters::Default_named_parameters>
  Sphere_point_location(const TriangleMesh& tm, const SphereMap& sphere_map,
                        const NamedParameters& np = CGAL::parameters::default_values())
    : triangulation_(read_map(tm, sphere_map, np))
  {
  }

  /// True if every face of the spherical triangulation is positively oriented and the map
  /// has degree 1 (relative to its own orientation): the precondition of meaningful answers.
  bool has_valid_map() const
  {
    const internal::Map_validity& v = triangulation_.validity();
    return v.finite && v.flipped == 0 && v.degenerate == 0 && std::abs(v.degree - 1) < 1e-6;
  }

  /// True if the map has degree -1 with respect to the faces' own orientation, as the map of
  /// an inward-oriented mesh has. The locations are right either way; meshes resampled from
  /// this map reverse their faces so as to keep the input's orientation.
  bool inward_oriented() const { return triangulation_.reversed(); }

  /// The number of faces of the mesh, the range of `Sphere_location::face_index`.
  std::size_t number_of_faces() const { return face_descriptors_.size(); }

  /// The face containing the direction `d` (any nonzero length) and its barycentric coordinates.
  Location locate(const Eigen::Vector3d& d) const { return to_location(triangulation_.locate(d.normalized())); }
  /// As above, starting the walk at the face of `hint`: faster than the seed grid when
  /// consecutive queries are close to each other.
  Location locate(const Eigen::Vector3d& d, const Location& hint) const
  {
    return to_location(triangulation_.locate(d.normalized(), int(hint.face_index)));
  }
  /// The face containing the direction `d` (any nonzero length), given as a CGAL vector.
  Location locate(const Vector_3& d) const { return locate(internal::to_eigen(d)); }
  /// The direction from the centre to `p`.
  Location locate(const Point_3& p) const { return locate(internal::to_eigen(p - CGAL::ORIGIN)); }

  /// The point of the input surface at `location`: the barycentric combination of its
  /// corners' input positions.
  Point_3 surface_point(const Location& location) const
  {
    return to_point(combine(location, [this](std::size_t v) { return positions_[v]; }));
  }
  /// The point of the input surface that the sphere map sends to the direction `d`.
  Point_3 surface_point(const Eigen::Vector3d& d) const { return surface_point(locate(d)); }

  /// The unit vector at `location`: the same combination of the corners' sphere points,
  /// projected back onto the sphere. It maps a location found on the surface back to the
  /// sphere, the inverse of `locate()` up to rounding.
  Eigen::Vector3d sphere_point(const Location& location) const
  {
    return combine(location, [this](std::size_t v) { return triangulation_.sphere_points()[v]; }).normalized();
  }

  /// The value of a per-vertex attribute at `location`, interpolated linearly in the face:
  /// a barycentric combination for `Point_3` values, `w0 * a0 + w1 * a1 + w2 * a2` otherwise
  /// (numbers, `Vector_3`, Eigen vectors, colours as Eigen vectors, ...).
  /// \tparam VertexMap a readable property map `vertex_descriptor -> value`
  template <class VertexMap>
  typename boost::property_traits<VertexMap>::value_type interpolate(const Location& location,
                                                                     const VertexMap& attribute) const
  {
    using Value = typename boost::property_traits<VertexMap>::value_type;
    const auto& w = location.coordinates;
    const Value a = get(attribute, location.vertices[0]), b = get(attribute, location.vertices[1]),
                c = get(attribute, location.vertices[2]);
    if constexpr(internal::Is_point_3<Value>::value)
      return CGAL::barycenter(a, w[0], b, w[1], c, w[2]);
    else
      return Value(w[0] * a + w[1] * b + w[2] * c);
  }

  /// The face with the largest smallest weight, by trying every face: O(F), the reference
  /// for testing `locate()`, and the answer it falls back on.
  Location locate_by_trying_every_face(const Eigen::Vector3d& d) const
  {
    return to_location(triangulation_.locate_by_trying_every_face(d.normalized()));
  }

private:
  // Declared before the triangulation: read_map() fills them while it is being built.
  std::vector<face_descriptor> face_descriptors_;
  std::vector<vertex_descriptor> vertex_descriptors_;
  std::vector<Eigen::Vector3d> positions_;
  internal::Spherical_triangulation triangulation_;

  static Point_3 to_point(const Eigen::Vector3d& p) { return Point_3(p.x(), p.y(), p.z()); }

  template <class VertexValue>
  Eigen::Vector3d combine(const Location& location, const VertexValue& value_of) const
  {
    const auto& face = triangulation_.faces()[location.face_index];
    const auto& w = location.coordinates;
    return w[0] * value_of(face[0]) + w[1] * value_of(face[1]) + w[2] * value_of(face[2]);
  }

  /// Reads the mesh into the arrays of the triangulation and keeps the descriptors.
  template <class SphereMap, class NamedParameters>
  internal::Spherical_triangulation read_map(const TriangleMesh& tm, const SphereMap& sphere_map,
                                             const NamedParameters& np)
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                      get_const_property_map(CGAL::vertex_point, tm));
    internal::Indexed_triangles<TriangleMesh> mesh = internal::indexed_triangles(tm);
    internal::Points sphere;
    for(vertex_descriptor v : mesh.vertices) {
      positions_.push_back(internal::to_eigen(get(vpm, v)));
      sphere.push_back(internal::to_eigen(get(sphere_map, v)).normalized());
    }
    vertex_descriptors_ = std::move(mesh.vertices);
    face_descriptors_.assign(faces(tm).begin(), faces(tm).end());
    return internal::Spherical_triangulation(std::move(sphere), std::move(mesh.triangles));
  }

  Location to_location(const internal::Face_hit& hit) const
  {
    Location location;
    location.face_index = std::size_t(hit.face);
    location.face = face_descriptors_[location.face_index];
    const auto& corners = triangulation_.faces()[location.face_index];
    const Eigen::Vector3d w = hit.barycentric();
    for(int k = 0; k < 3; ++k) {
      location.vertices[k] = vertex_descriptors_[corners[k]];
      location.coordinates[k] = w[k];
    }
    return location;
  }
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPHERE_POINT_LOCATION_H
