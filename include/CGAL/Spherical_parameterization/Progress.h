// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H

#include <CGAL/Spherical_parameterization/Result.h>

#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// What a visitor learns after each solver iteration.
struct Progress
{
  const char* stage = "";       ///< the stage's name, `stage_name()` of a `Stage`
  std::size_t iteration = 0;    ///< iterations done in all stages so far
  double energy = 0;            ///< energy of the stage after this iteration
  double newton_decrement = 0;  ///< predicted decrease, `-g . d`
  double step = 0;              ///< accepted line-search step
  double elapsed_seconds = 0;   ///< since the start of the solve
};

/// \ingroup PkgSphericalParameterizationRef
/// The visitor used when none is given: it never stops the solver.
/// A visitor is any object with `bool operator()(const Progress&)`; returning `false` cancels the solve.
struct Default_visitor
{
  /// Returns `true`: the solve goes on.
  bool operator()(const Progress&) const { return true; }
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H
