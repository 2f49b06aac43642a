// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Status of a spherical parameterization. `OK` and `NOT_CONVERGED` come with a valid map
/// (see `Result::is_valid()`); every other code says what went wrong. The codes up to
/// `INVALID_PARAMETER` are detected before any solve and leave the output map untouched.
enum class Error_code
{
  OK = 0,                  ///< valid map, converged
  EMPTY_MESH,              ///< the mesh has no face
  INVALID_MESH,            ///< the halfedge structure is not valid (`is_valid_polygon_mesh()`)
  NOT_TRIANGLE_MESH,       ///< some face is not a triangle
  NOT_CLOSED,              ///< the mesh has border edges
  NON_MANIFOLD,            ///< some vertex is non-manifold (its faces form several fans)
  ISOLATED_VERTICES,       ///< some vertex has no incident face
  NOT_CONNECTED,           ///< the mesh has several connected components
  NOT_GENUS_ZERO,          ///< the Euler characteristic is not 2
  NON_FINITE_INPUT,        ///< a coordinate is NaN, infinite or larger than 1e150 in magnitude
  DEGENERATE_INPUT,        ///< every input face has zero area (the surface has no area to map)
  INVALID_PARAMETER,       ///< a named parameter has an unusable value (weight, iterations, ...)
  INVALID_INITIALIZATION,  ///< the initial map is not on the sphere or does not have degree +-1
  NO_VALID_MAP,            ///< the solver stopped with flipped or degenerate faces
  NOT_CONVERGED,           ///< the map is valid but the iteration cap was hit before convergence,
                           ///< or the energy is not finite on it (not minimized)
  CANCELLED,               ///< the visitor asked to stop
  TIME_LIMIT               ///< `maximum_running_time` was reached
};

/// \ingroup PkgSphericalParameterizationRef
/// A one-line English description of `code`, never null.
inline const char* error_message(Error_code code)
{
  switch(code) {
  case Error_code::OK: return "success";
  case Error_code::EMPTY_MESH: return "the input mesh is empty";
  case Error_code::INVALID_MESH: return "the input is not a valid polygon mesh";
  case Error_code::NOT_TRIANGLE_MESH: return "the input mesh has faces that are not triangles";
  case Error_code::NOT_CLOSED: return "the input mesh is not closed (it has border edges)";
  case Error_code::NON_MANIFOLD: return "the input mesh has non-manifold vertices";
  case Error_code::ISOLATED_VERTICES: return "the input mesh has isolated vertices";
  case Error_code::NOT_CONNECTED: return "the input mesh has several connected components";
  case Error_code::NOT_GENUS_ZERO: return "the input mesh is not of genus 0";
  case Error_code::NON_FINITE_INPUT: return "the input has non-finite or overflowing coordinates";
  case Error_code::DEGENERATE_INPUT: return "the input mesh has no area";
  case Error_code::INVALID_PARAMETER: return "a parameter has an invalid value";
  case Error_code::INVALID_INITIALIZATION: return "the initial map is not a map onto the unit sphere of degree +-1";
  case Error_code::NO_VALID_MAP: return "no valid map found: some faces are flipped or degenerate";
  case Error_code::NOT_CONVERGED: return "the map is valid but the solver did not converge";
  case Error_code::CANCELLED: return "cancelled by the visitor";
  case Error_code::TIME_LIMIT: return "the time limit was reached";
  }
  return "unknown error";
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
