// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_COARSE_TO_FINE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_COARSE_TO_FINE_H

#include <CGAL/Spherical_parameterization/internal/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/kernel_placement.h>
#include <CGAL/Spherical_parameterization/internal/map_validity.h>

#include <cmath>
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

/// The levels of a coarse-to-fine solve, from the coarsest mesh of a progressive mesh of the
/// input back to the input, their sizes growing by a constant ratio. Going to the next level
/// makes the vertex splits in between: each new vertex goes to the mean value point of its
/// ring (`mean_value_point()`), moved into the kernel of its fan when that point is not well
/// inside (`place_in_kernel()`), so that a fold-free map of a level stays fold-free.
template <class Newton>
class Coarse_to_fine
{
public:
  Coarse_to_fine(const Triangle_soup& input, const Progressive_mesh& pm, double ratio)
    : input_(&input), refinement_(pm)
  {
    for(double size = double(refinement_.number_of_vertices()) * ratio; size * std::sqrt(ratio) < double(input.number_of_vertices());
        size *= ratio)
      sizes_.push_back(std::size_t(size));
    sizes_.push_back(input.number_of_vertices());
  }

  /// The current level, built on first use (its solver's analysis is not free), or null once
  /// the mesh is the input again (or was never coarsened).
  Level<Newton>* level()
  {
    if(refinement_.splits_left() == 0)
      return nullptr;
    if(!level_)
      make_level();
    return level_.get();
  }

  /// Makes the splits up to the next level's size, placing the new vertices in `x` (indexed
  /// like the input); then `level()` is that level. False when the input was reached before.
  bool refine(Points& x)
  {
    if(next_size_ == sizes_.size())
      return false;
    while(refinement_.number_of_vertices() < sizes_[next_size_]) {
      const Vertex_split& split = refinement_.split_next();
      refinement_.fan(split, fan_);
      x[split.removed] = place_in_kernel(x, fan_, mean_value_point(split.removed, input_->points, x, fan_));
      empty_kernels_ += !(fan_clearance(x[split.removed], x, fan_) > 0);
    }
    ++next_size_;
    level_.reset();
    return true;
  }

  /// The splits whose fan had no kernel: the map has a fold there, to untangle.
  std::size_t empty_kernels() const { return empty_kernels_; }

private:
  void make_level()
  {
    level_ = std::make_unique<Level<Newton>>();
    level_->soup = level_soup(*input_, refinement_, level_->to_input);
    level_->solver = std::make_unique<Newton>(level_->soup);
  }

  const Triangle_soup* input_;
  Refinement refinement_;
  std::vector<std::size_t> sizes_;  // of the levels after the coarsest, the input's last
  std::size_t next_size_ = 0;
  std::unique_ptr<Level<Newton>> level_;
  Fan fan_;
  std::size_t empty_kernels_ = 0;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_COARSE_TO_FINE_H
