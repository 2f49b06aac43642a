// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_POINT_COORDINATES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_POINT_COORDINATES_H

#include <CGAL/Default.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The geometric traits `GeomTraits`, or by default (`CGAL::Default`) the kernel of the mesh's
/// points (of the vertex point map of `NamedParameters`, if it has one). Chosen lazily, so
/// that a point type with no kernel of its own needs only the traits the user gives.
template <class TriangleMesh, class GeomTraits, class NamedParameters = parameters::Default_named_parameters>
struct Geom_traits_of
{
  using type = GeomTraits;
};
template <class TriangleMesh, class NamedParameters>
struct Geom_traits_of<TriangleMesh, CGAL::Default, NamedParameters>
{
  using type = typename GetGeomTraits<TriangleMesh, NamedParameters>::type;
};

/// The coordinates of `p` as doubles, read through the traits' `Compute_x_3`, `Compute_y_3`
/// and `Compute_z_3`: the only way the package reads an input point, so that any kernel (exact
/// ones included) or a user's point type with traits of its own works.
template <class GeomTraits, class Point>
Eigen::Vector3d point_coordinates(const GeomTraits& traits, const Point& p)
{
  return Eigen::Vector3d(CGAL::to_double(traits.compute_x_3_object()(p)), CGAL::to_double(traits.compute_y_3_object()(p)),
                         CGAL::to_double(traits.compute_z_3_object()(p)));
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INPUT_POINT_COORDINATES_H
