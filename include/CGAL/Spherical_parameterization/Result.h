// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H

#include <CGAL/Spherical_parameterization/Error_code.h>

#include <cstddef>
#include <string>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// What a solve returns. A map is valid when every point is on the unit sphere (to 1e-12),
/// no face is flipped or degenerate (`|det(a, b, c)| > 1e-14`, with the sign of the input's
/// orientation) and the degree is 1 (relative to that orientation).
struct Result
{
  Error_code status = Error_code::OK;  ///< `OK`, or what went wrong
  std::string detail;             ///< what and where: "12 border edges", "2 flipped faces", ...

  bool valid = false;             ///< the map written is a valid embedding
  std::size_t iterations = 0;     ///< Newton iterations, all stages
  double energy = 0;              ///< final value of the chosen energy (input scaled to area 4 pi)
  std::size_t flipped = 0;        ///< faces whose orientation is opposite to the input's
  std::size_t degenerate = 0;     ///< faces with `|det| <= 1e-14`
  double degree = 0;              ///< signed spherical area / 4 pi, relative to the input orientation
  bool inward_oriented = false;   ///< the input's faces are oriented towards its inside
  double min_area_ratio = 0;      ///< min over faces of (spherical area share / input area share)
  double time_seconds = 0;        ///< wall time of the solve
  std::string stages;             ///< the stages run with their iterations, for instance "tutte:12 target:9"

  /// The message of `status`.
  const char* message() const { return error_message(status); }
  /// True if the map is valid (status `OK` or `NOT_CONVERGED`, or a time limit or
  /// cancellation that came after a valid map).
  bool is_valid() const { return valid; }
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
