// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STOPPING_RULES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STOPPING_RULES_H

#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// The stops of `Newton_solver::minimize()` that read the history of the energy (its value
// after each iteration, the last one included) or of the decrement, rather than one step.

/// The energy gained over the last `window` iterations; infinite if there were fewer.
inline double recent_gain(const std::vector<double>& history, std::size_t window)
{
  if(history.size() <= window)
    return std::numeric_limits<double>::infinity();
  return history[history.size() - 1 - window] - history.back();
}

/// The iterations over which `stalled()` looks.
constexpr std::size_t stall_window = 10;

/// The energy decreased by less than `threshold` over the last `stall_window` iterations: a
/// slow linear tail, such as faces pressed against the fold barrier in a squeezed
/// protrusion, where the map no longer changes visibly.
inline bool stalled(const std::vector<double>& history, double threshold)
{
  return recent_gain(history, stall_window) <= threshold;
}

/// The share of the threshold per iteration under which `slow_capped_tail()` stops. Half
/// of it: the slides it stops gain a few thresholds per iteration for dozens of iterations,
/// depending on rounding alone; the whole threshold leaves energies higher than a
/// converged map's by more than the tests allow.
constexpr double capped_tail_gain = 0.5;
/// The iterations over which `slow_capped_tail()` looks. Three: as good a stop as five, two
/// iterations sooner.
constexpr std::size_t capped_tail_window = 3;

/// True if the last `capped_tail_window` iterations all had capped steps and gained less
/// than `capped_tail_gain` of `threshold` each on average
/// (`Newton_options::stop_slow_capped_tail`): the test of `stalled()`, on a shorter window,
/// for the steps the fold-free cap holds back.
inline bool slow_capped_tail(const std::vector<double>& history, std::size_t capped_steps, double threshold)
{
  return capped_steps >= capped_tail_window &&
         recent_gain(history, capped_tail_window) <= capped_tail_gain * capped_tail_window * threshold;
}

/// Newton's decrement converges quadratically near a minimum, d_next = C d^2, with C
/// estimated from the last two: d^3 / previous^2. Without a previous full step, or if the
/// decrement did not shrink by `min_quadratic_shrink`, no prediction: the decrement itself
/// is returned.
constexpr double min_quadratic_shrink = 4;
inline double predicted_decrement(double previous, double decrement)
{
  if(!(previous > min_quadratic_shrink * decrement))
    return decrement;
  return decrement * (decrement / previous) * (decrement / previous);
}

/// The next decrement if the last two shrank at a rate that holds, as the projected
/// Hessian's steps do when they converge linearly: decrement^2 / previous. Without a
/// previous long step (0), or if the decrement did not shrink, no prediction: the
/// decrement itself.
inline double linearly_predicted_decrement(double previous, double decrement)
{
  if(!(previous > decrement))
    return decrement;
  return decrement * (decrement / previous);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_STOPPING_RULES_H
