// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_RESAMPLING_ERROR_H
#define CGAL_SPHERICAL_PARAMETERIZATION_RESAMPLING_ERROR_H

#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// How much of the surface a resampling through the sphere map keeps: the distances from the
/// input's vertices and face centroids to the surface resampled on an icosphere, relative to
/// the diagonal of the input's bounding box. A map that squeezes a protrusion into a few
/// icosphere cells loses it, and these distances show it where the map's validity does not.
struct Resampling_error
{
  double mean = 0;          ///< mean over the samples (vertices and face centroids)
  double max = 0;           ///< largest
  std::size_t samples = 0;  ///< vertices plus faces of the input
};

/// \ingroup PkgSphericalParameterizationRef
/// The distance from every vertex and every face centroid of `tm` to the surface `resampled`
/// (for instance the output of `remesh_on_icosphere()`), relative to the diagonal of the
/// bounding box of `tm` (`Resampling_error`).
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam ResampledMesh a model of `FaceListGraph` whose points are those of
///         `Exact_predicates_inexact_constructions_kernel`, such as `Surface_mesh<Epick::Point_3>`
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} the input positions; default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
/// \cgalNamedParamsEnd
template <class TriangleMesh, class ResampledMesh,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Resampling_error distance_to_resampled(const TriangleMesh& tm, const ResampledMesh& resampled,
                                       const NamedParameters& np = CGAL::parameters::default_values())
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<ResampledMesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  auto point = [&](auto v) {
    const auto& p = get(vpm, v);
    return Kernel::Point_3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  };

  Tree tree(faces(resampled).first, faces(resampled).second, resampled);
  tree.accelerate_distance_queries();

  CGAL::Bbox_3 box;
  for(auto v : vertices(tm))
    box += point(v).bbox();
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  Resampling_error error;
  double sum = 0;
  auto add = [&](const Kernel::Point_3& p) {
    const double d = std::sqrt(tree.squared_distance(p)) / diagonal;
    sum += d;
    error.max = std::max(error.max, d);
    ++error.samples;
  };
  for(auto v : vertices(tm))
    add(point(v));
  for(auto f : faces(tm)) {
    const auto h = halfedge(f, tm);
    add(CGAL::centroid(point(source(h, tm)), point(target(h, tm)), point(target(next(h, tm), tm))));
  }
  error.mean = error.samples > 0 ? sum / double(error.samples) : 0;
  return error;
}

/// \ingroup PkgSphericalParameterizationRef
/// Resamples `tm` through the valid sphere map `sphere_map` on the geodesic icosphere of
/// subdivision `level` (`remesh_on_icosphere()`) and measures the distance from every vertex
/// and every face centroid of `tm` to the resampled surface (`distance_to_resampled()`).
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam SphereMap a readable property map `vertex_descriptor -> Point_3`
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} the input positions; default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre the map is valid (`Sphere_point_location::has_valid_map()`) and `0 <= level <= 9`
template <class TriangleMesh, class SphereMap, class NamedParameters = CGAL::parameters::Default_named_parameters>
Resampling_error resampling_error(const TriangleMesh& tm, const SphereMap& sphere_map, int level = 6,
                                  const NamedParameters& np = CGAL::parameters::default_values())
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  const Sphere_point_location<TriangleMesh, Kernel> location(tm, sphere_map, np);
  CGAL::Surface_mesh<Kernel::Point_3> resampled;
  remesh_on_icosphere(location, level, resampled);
  return distance_to_resampled(tm, resampled, np);
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_RESAMPLING_ERROR_H
