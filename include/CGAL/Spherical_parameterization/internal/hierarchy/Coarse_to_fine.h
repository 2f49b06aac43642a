// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_COARSE_TO_FINE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_COARSE_TO_FINE_H

#include <CGAL/Spherical_parameterization/internal/hierarchy/Level.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/kernel_placement.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/backends/parallel_for.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The rings of a sequence of vertex splits, in their order: the linear prolongation that
/// moves each split vertex with the mean of its ring (`spread()`), and its transpose.
class Split_rings
{
public:
  void clear()
  {
    vertices_.clear();
    ring_start_.assign(1, 0);
    ring_.clear();
  }

  void add(int vertex, const Fan& fan)
  {
    vertices_.push_back(vertex);
    for(const auto& [p, q] : fan)  // each ring vertex is the p of one face of the fan
      ring_.push_back(p);
    ring_start_.push_back(int(ring_.size()));
  }

  /// Sets each split vertex's value to the mean of its ring's, the splits in their order.
  void spread(std::vector<Eigen::Vector3d>& values) const
  {
    for(std::size_t s = 0; s < vertices_.size(); ++s) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for(int k = ring_start_[s]; k < ring_start_[s + 1]; ++k)
        sum += values[ring_[k]];
      values[vertices_[s]] = sum / double(ring_start_[s + 1] - ring_start_[s]);
    }
  }

  /// The transpose of `spread()`: each split vertex's value shared out to its ring, the
  /// splits in reverse order (and zeroed: `spread()` ignores it).
  void transpose_spread(std::vector<Eigen::Vector3d>& values) const
  {
    for(std::size_t s = vertices_.size(); s-- > 0;) {
      const Eigen::Vector3d share = values[vertices_[s]] / double(ring_start_[s + 1] - ring_start_[s]);
      values[vertices_[s]].setZero();
      for(int k = ring_start_[s]; k < ring_start_[s + 1]; ++k)
        values[ring_[k]] += share;
    }
  }

private:
  std::vector<int> vertices_, ring_start_{0}, ring_;
};

/// Removes from the displacement `step` of the points `x` its least-squares part along the
/// rotations (`w x p`) and the Moebius boosts (`b - (b . p) p`) of the whole map. Every
/// energy is invariant under rotations and the conformal ones nearly so under boosts, so a
/// converged level's factor is nearly singular along them and its solve blows up whatever
/// part of the right-hand side lies there into a huge step; the Moebius boost step of every
/// iteration handles them instead.
inline void remove_global_modes(const Points& x, std::vector<Eigen::Vector3d>& step)
{
  using Fields = Eigen::Matrix<double, 3, 6>;  // the six fields at a point, as columns
  auto fields = [](const Eigen::Vector3d& p) {
    Fields f;
    f.leftCols<3>() << 0, p.z(), -p.y(), -p.z(), 0, p.x(), p.y(), -p.x(), 0;  // e_k x p
    f.rightCols<3>() = Eigen::Matrix3d::Identity() - p * p.transpose();
    return f;
  };
  Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> moments = Eigen::Matrix<double, 6, 1>::Zero();
  for(std::size_t i = 0; i < x.size(); ++i) {
    const Fields f = fields(x[i]);
    gram += f.transpose() * f;
    moments += f.transpose() * step[i];
  }
  const Eigen::Matrix<double, 6, 1> c = gram.ldlt().solve(moments);
  if(!c.allFinite())
    return;
  for(std::size_t i = 0; i < x.size(); ++i)
    step[i] -= fields(x[i]) * c;
}

/// The levels of a coarse-to-fine solve, from the coarsest mesh of a progressive mesh of the
/// input back to the input, their sizes growing by a constant ratio. Going to the next level
/// makes the vertex splits in between: each new vertex goes to the mean value point of its
/// ring (`mean_value_point()`), moved into the kernel of its fan when that point is not well
/// inside (`place_in_kernel()`), so that a fold-free map of a level stays fold-free. With
/// `CGAL::Parallel_tag` the splits of one pass of the progressive mesh are placed in
/// parallel, to the same points: the placements read only their rings' points.
template <class Newton, class ConcurrencyTag = CGAL::Sequential_tag>
class Coarse_to_fine
{
public:
  /// `two_grid`: keep the last level before the input for `coarse_correction()`.
  Coarse_to_fine(const Triangle_soup& input, const Progressive_mesh& pm, double ratio, bool two_grid = false)
    : input_(&input), refinement_(pm), two_grid_(two_grid)
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

  /// True if the next `refine()` goes into the input: the current level is the last before it.
  bool last_before_input() const { return next_size_ + 1 == sizes_.size(); }

  /// Makes the splits up to the next level's size, placing the new vertices in `x` (indexed
  /// like the input); then `level()` is that level. False when the input was reached before.
  bool refine(Points& x)
  {
    if(next_size_ == sizes_.size())
      return false;
    const bool for_two_grid = two_grid_ && last_before_input();
    split_rings_.clear();
    while(refinement_.number_of_vertices() < sizes_[next_size_]) {
      // A batch of independent splits: the placements read only their rings' points, none
      // of which the batch moves, so they run in parallel with the same results.
      const std::size_t batch =
        std::min(refinement_.independent_splits(), sizes_[next_size_] - refinement_.number_of_vertices());
      if(fans_.size() < batch)
        fans_.resize(batch);
      removed_.resize(batch);
      for(std::size_t k = 0; k < batch; ++k) {
        const Vertex_split& split = refinement_.split_next();
        removed_[k] = split.removed;
        refinement_.fan(split, fans_[k]);
      }
      // A fan with an empty kernel leaves a fold, which the level's robust stages untangle.
      parallel_for<ConcurrencyTag>(batch, [&](std::size_t k) {
        const int u = removed_[k];
        x[u] = place_in_kernel(x, fans_[k], mean_value_point(u, input_->points, x, fans_[k]));
      });
      if(for_two_grid)
        for(std::size_t k = 0; k < batch; ++k)
          split_rings_.add(removed_[k], fans_[k]);
    }
    ++next_size_;
    // The last level before the input, with its last factorization, serves the input's
    // coarse correction (`coarse_correction()`).
    if(for_two_grid && level_) {
      last_level_ = std::move(level_);
      last_level_->solver->keep_only_last_factor();
    }
    level_.reset();
    return true;
  }

  /// The coarse correction of the input from the last level before it (a two-grid cycle's
  /// coarse step, see `Newton_options::coarse_correction`): the input's tangent `gradient`
  /// restricted to that level, solved with that level's last factorization of its own
  /// Hessian, and the level's step prolongated to the input. Restriction and prolongation
  /// follow the vertex splits in between: each split vertex moves with the mean of its ring.
  /// The level's step leaves out the rotations and Moebius boosts of the map `x` (see
  /// `remove_global_modes()`). Used once: that level and its factor are freed after. False
  /// if that level or its factorization is gone.
  bool coarse_correction(const Points& x, const std::vector<Eigen::Vector3d>& gradient,
                         std::vector<Eigen::Vector3d>& step)
  {
    const std::unique_ptr<Level<Newton>> used = std::move(last_level_);
    if(!used || gradient.size() != input_->number_of_vertices() || x.size() != gradient.size())
      return false;
    const Level<Newton>& level = *used;
    std::vector<Eigen::Vector3d> restricted = gradient;
    split_rings_.transpose_spread(restricted);
    const auto& bases = level.solver->bases();
    const std::size_t n = level.to_input.size();
    Eigen::VectorXd rhs(2 * n), level_step;
    for(std::size_t i = 0; i < n; ++i)
      rhs.template segment<2>(2 * i) = -bases[i].transpose() * restricted[level.to_input[i]];
    if(!level.solver->solve_with_last_factor(rhs, level_step))
      return false;
    Points level_x(n);
    std::vector<Eigen::Vector3d> displacement(n);
    for(std::size_t i = 0; i < n; ++i) {
      level_x[i] = x[level.to_input[i]];
      displacement[i] = bases[i] * level_step.template segment<2>(2 * i);
    }
    remove_global_modes(level_x, displacement);
    step.assign(gradient.size(), Eigen::Vector3d::Zero());
    for(std::size_t i = 0; i < n; ++i)
      step[level.to_input[i]] = displacement[i];
    split_rings_.spread(step);
    return true;
  }

  /// The rings of the splits from the last level to the input, once they are made.
  const Split_rings& split_rings() const { return split_rings_; }

private:
  // The current level: the one prepared while the level before ran, if any; then the next
  // level's preparation starts.
  void make_level()
  {
    if(preparing_) {
      preparing_->wait();
      preparing_.reset();
    }
    if(prepared_ && prepared_->number_of_vertices() == refinement_.number_of_vertices())
      level_ = std::move(prepared_);
    else
      level_ = new_level(refinement_);
    prepare_next_level();
  }

  // With `CGAL::Parallel_tag`, the next coarser level (the input's solver is the pipeline's
  // to prepare) is made as a background task while the current one runs: its faces come from
  // the same splits made on a second copy of the mesh, which needs no placements, and its
  // solver's analysis and first factorization's memory (fresh memory costs a page fault per
  // page) are ready when the level starts.
  void prepare_next_level()
  {
    if constexpr(is_parallel<ConcurrencyTag>) {
      if(next_size_ + 1 >= sizes_.size())
        return;
      if(!topology_ahead_)
        topology_ahead_.emplace(refinement_);  // copied on first use only: sequential builds never need it
      const std::size_t size = sizes_[next_size_];
      preparing_ = std::make_unique<Background_task<ConcurrencyTag>>([this, size] {
        while(topology_ahead_->number_of_vertices() < size)
          topology_ahead_->split_next();
        prepared_ = new_level(*topology_ahead_);
        prepared_->solver->prepare_memory();
      });
    }
  }

  std::unique_ptr<Level<Newton>> new_level(const Refinement& refinement) const
  {
    auto level = std::make_unique<Level<Newton>>();
    level->soup = level_soup(*input_, refinement, level->to_input);
    level->solver = std::make_unique<Newton>(level->soup);
    return level;
  }

  const Triangle_soup* input_;
  Refinement refinement_;
  std::optional<Refinement> topology_ahead_;  // the mesh of the level under preparation, see prepare_next_level()
  bool two_grid_;
  std::vector<std::size_t> sizes_;  // of the levels after the coarsest, the input's last
  std::size_t next_size_ = 0;
  std::unique_ptr<Level<Newton>> level_, last_level_;
  Split_rings split_rings_;  // of the splits from the last level to the input
  std::vector<Fan> fans_;    // of a batch of independent splits, see refine()
  std::vector<int> removed_;
  std::unique_ptr<Level<Newton>> prepared_;
  std::unique_ptr<Background_task<ConcurrencyTag>> preparing_;  // last: waited for before the rest goes
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HIERARCHY_COARSE_TO_FINE_H
