// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SURFACE_MAP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SURFACE_MAP_H

#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/internal/input/indexed_triangles.h>

#include <CGAL/boost/graph/iterator.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The rotation `R` that minimizes `sum_i |R from[i] - to[i]|^2` (Kabsch 1976; the orthogonal
/// Procrustes problem restricted to rotations): with `H = sum_i from[i] to[i]^T = U S V^T`,
/// `R = V diag(1, 1, det(V U^T)) U^T`, where the last sign rules out a reflection.
/// - No pair: the identity.
/// - One pair: the smallest rotation taking `from[0]` to `to[0]` (the twist about it is free).
/// - Pairs whose `from` points are all on one line through the centre leave the twist
///   about that line free as well; the SVD then picks one.
/// \pre `from.size() == to.size()`; no vector is zero
inline Eigen::Matrix3d best_rotation(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to)
{
  CGAL_precondition(from.size() == to.size());
  if(from.empty())
    return Eigen::Matrix3d::Identity();
  if(from.size() == 1)
    return Eigen::Quaterniond::FromTwoVectors(from[0], to[0]).toRotationMatrix();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for(std::size_t i = 0; i < from.size(); ++i)
    h += from[i] * to[i].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d u = svd.matrixU(), v = svd.matrixV();
  Eigen::Vector3d signs(1, 1, (v * u.transpose()).determinant() < 0 ? -1 : 1);
  return v * signs.asDiagonal() * u.transpose();
}

/// \ingroup PkgSphericalParameterizationRef
/// The rotation of the sphere that best aligns the sphere map `sphere_a` of a mesh A with
/// the sphere map `sphere_b` of a mesh B at landmarks, pairs `(vertex of A, vertex of B)`
/// that the user declares to correspond: `best_rotation()` of their sphere points, in the
/// least squares sense. Sphere maps are unique only up to rotation (the energies are
/// invariant under rotations), so two independent maps need this before `map_to_surface()`.
/// Two landmarks not on one diameter fix the rotation; more average out the error.
///
/// \tparam SphereMapA, SphereMapB readable property maps `vertex_descriptor -> Point_3`
/// \tparam LandmarkRange a range of `std::pair<vertex of A, vertex of B>`
template <class SphereMapA, class SphereMapB, class LandmarkRange>
Eigen::Matrix3d rotation_from_landmarks(const SphereMapA& sphere_a, const SphereMapB& sphere_b,
                                        const LandmarkRange& landmarks)
{
  std::vector<Eigen::Vector3d> from, to;
  for(const auto& pair : landmarks) {
    from.push_back(internal::to_eigen(get(sphere_a, pair.first)).normalized());
    to.push_back(internal::to_eigen(get(sphere_b, pair.second)).normalized());
  }
  return best_rotation(from, to);
}

/// \ingroup PkgSphericalParameterizationRef
/// A map between two surfaces through their sphere maps: sends every vertex `v` of mesh A
/// to the point of surface B at the direction `rotation * sphere_a(v)`, and writes it to
/// `out` (`surface_b.surface_point()`). The composition of A's sphere map, the rotation and
/// the inverse of B's sphere map is continuous and one-to-one; this samples it at A's
/// vertices. For more than positions (the face of B and barycentric coordinates, to
/// transfer attributes), call `surface_b.locate()` on the same directions.
///
/// \tparam TriangleMeshA a model of `VertexListGraph`
/// \tparam SphereMapA a readable property map `vertex of A -> Point_3`
/// \tparam OutputPointMap a writable property map `vertex of A -> Point_3` (B's kernel)
/// \pre `surface_b.has_valid_map()`; `rotation` is a rotation matrix
template <class TriangleMeshA, class SphereMapA, class TriangleMeshB, class GeomTraitsB, class OutputPointMap>
void map_to_surface(const TriangleMeshA& tm_a, const SphereMapA& sphere_a,
                    const Sphere_point_location<TriangleMeshB, GeomTraitsB>& surface_b, OutputPointMap out,
                    const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity())
{
  for(auto v : vertices(tm_a))
    put(out, v, surface_b.surface_point(Eigen::Vector3d(rotation * internal::to_eigen(get(sphere_a, v)))));
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SURFACE_MAP_H
