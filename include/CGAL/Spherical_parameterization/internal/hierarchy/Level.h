// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_LEVEL_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_LEVEL_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>

#include <memory>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// A mesh the solver runs on: the input, or a level of its progressive mesh, with its own
/// Newton solver (sparsity pattern and symbolic factorization).
template <class Newton>
struct Level
{
  Triangle_soup soup;
  std::vector<int> to_input;  ///< the input vertex of each level vertex; empty for the input itself
  std::unique_ptr<Newton> solver;

  std::size_t number_of_vertices() const { return soup.number_of_vertices(); }
  bool has_fold(const Points& x) const { return count_bad_faces(soup.faces, x) > 0; }

  /// The level's points of the input-indexed map `x`.
  void gather(const Points& x, Points& level_x) const
  {
    level_x.resize(to_input.size());
    for(std::size_t i = 0; i < to_input.size(); ++i)
      level_x[i] = x[to_input[i]];
  }

  /// Writes the level's points back into the input-indexed map `x`.
  void scatter(const Points& level_x, Points& x) const
  {
    for(std::size_t i = 0; i < to_input.size(); ++i)
      x[to_input[i]] = level_x[i];
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_LEVEL_H
