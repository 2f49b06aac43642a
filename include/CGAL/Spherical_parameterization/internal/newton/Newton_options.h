// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_OPTIONS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_OPTIONS_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <Eigen/Core>

#include <chrono>
#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

using Clock = std::chrono::steady_clock;

/// A step of a map from a coarser level: given the map and the energy's gradient at every
/// vertex (in its tangent plane), writes a displacement of every vertex that lowers the
/// energy's smooth error, or returns false (see `Coarse_to_fine`).
using Coarse_correction = std::function<bool(const Points& x, const std::vector<Eigen::Vector3d>& gradient,
                                             std::vector<Eigen::Vector3d>& step)>;

/// What one minimization is asked to do. The pipeline builds one per stage, by value; the
/// defaults are those of a plain Newton minimization.
struct Newton_options
{
  std::size_t max_iterations = 200;
  double tolerance = 1e-6;  ///< on the relative predicted and actual decrease of the energy
  /// Energy of the faces outside the soup, held fixed, that counts in the total the
  /// tolerance is relative to: a patch of a map then stops where the whole map would.
  double held_energy = 0;
  Clock::time_point start = Clock::now();
  Clock::time_point deadline = Clock::time_point::max();
  /// Keep the map fold-free: cap every step before a chord determinant reaches 0, and add
  /// a `Fold_barrier` to the energy of the faces that need one (see `Newton_solver`).
  bool keep_fold_free = false;
  /// The barrier's activation under which every face is held (`Fold_barrier::scale`,
  /// about half the area ratio): the floor of the map's area distortion.
  double fold_floor = 1e-7;
  /// With `keep_fold_free`: the weight of the barrier's weak outer layer (`Fold_barrier::energy()`).
  double outer_barrier_weight = 0;
  /// With `keep_fold_free`, if positive: the barrier measures a face whose input area is under
  /// its `Reference_triangle::area_floor` (the near-duplicate vertices of isosurfaces) as a
  /// face of the floor's area, and holds it from this activation on. Measured by its own tiny
  /// area, such a face would be held only at a determinant of 1e-12, and the steps that
  /// squeeze it on the way there would be capped to a few percent.
  double floored_activation = 0;
  bool stop_when_fold_free = false;  ///< a start-up stage: stop at the first fold-free map
  /// When set, receives the last iterate (or the start) on which every face is positively
  /// oriented: where a fold-free stage can take over after a stage that may fold.
  Points* fold_free_iterate = nullptr;
  /// With `fold_free_iterate`: stop (`Newton_stop::FOLDED`) after this many folded iterates
  /// in a row, a fold that the energy does not undo by itself.
  std::size_t max_folded_iterations = 5;
  /// With `fold_free_iterate`: whether a folded iterate with at most half the folded faces of
  /// the iterate before counts against `max_folded_iterations` (false: the energy is undoing
  /// the fold by itself).
  bool count_unfolding_iterates = true;
  /// Iterations that solve only the 2x2 diagonal blocks of the Hessian (block Jacobi) before
  /// Newton: a cheap smoother of the local error a vertex split leaves.
  std::size_t smoothing_iterations = 0;
  /// The exact Hessian's first shift in the solver's life, relative to its mean diagonal:
  /// starts are far from a minimum, and growing the shift from its floor costs failed
  /// factorizations.
  double first_shift = 1e-4;
  /// With `smoothing_iterations`: the first smoothing step is a two-grid cycle, this coarse
  /// correction of the map followed by block Jacobi (`Newton_solver::smoothing_direction()`).
  const Coarse_correction* coarse_correction = nullptr;
  /// Before every Newton iteration, a Newton step on the three parameters of a Moebius
  /// boost of the whole map (`boost_step()`), the directions in which the energies of
  /// conformal type are nearly flat.
  bool boost_search = false;
  /// Stop when the next decrement, predicted from the last two, is below the tolerance
  /// (`predicted_decrement()` far below it, `linearly_predicted_decrement()` below it from a
  /// decrement close to it): saves the factorization that would only confirm convergence.
  /// For the input level only: a coarser level stopped one iteration early hands the next
  /// level another start, and its path changes for no gain.
  bool predict_convergence = false;
  /// With `fold_free_iterate`: stop (`Newton_stop::UNDER_FLOOR`) at a fold-free iterate with a
  /// face under `fold_floor` once the next decrement is predicted below the tolerance:
  /// confirming the convergence of an energy that the floor stage is about to change is wasted.
  bool leave_under_floor = false;
  /// With `keep_fold_free`: also stop at the slow end of a stage whose steps the fold-free cap
  /// shortens (`slow_capped_tail()`), where every step is capped to a few percent of Newton's
  /// by faces the barrier does not hold yet and gains little against the tolerance. For the
  /// input's last stage only: an earlier stop anywhere else changes the stages that follow.
  bool stop_slow_capped_tail = false;
  /// Double a full step of the projected Hessian while the energy falls
  /// (`Newton_solver::extend_step()`). For energies with an area barrier
  /// (`has_area_barrier()`): their Hessian stays indefinite in every compressed face up to the
  /// minimum (`det` is trilinear in the points), the projection turns that negative curvature
  /// into positive, so the model is stiffer than the energy and its full steps slide at a
  /// linear rate. The paper's energies are nearly convex near their minima, where the exact
  /// Hessian takes over; extending their early steps only moves them to other basins.
  bool extend_projected_steps = false;
  /// Where the barrier does not hold a face, drop the negative curvature of its projected
  /// Hessian along the rotations of its three points instead of making it absolute
  /// (`Tangent_newton_system::project_free_face()`). For energies with an area barrier, for the same
  /// reason: their projected steps carry them to the minimum, and the absolute values stiffen
  /// the model along the map's smooth modes. The paper's energies reach their minima on the
  /// exact Hessian; a softer model in their early steps only moves their paths to other
  /// basins, as with `extend_projected_steps`.
  bool drop_rotation_curvature = false;
  const char* stage = "";            ///< for progress reports
  std::size_t iteration_offset = 0;  ///< iterations of earlier stages, for progress reports
};

/// How a minimization ended.
enum class Newton_stop { CONVERGED, ITERATION_CAP, STALLED, CANCELLED, TIME_LIMIT, NON_FINITE_START, FOLDED, UNDER_FLOOR };

/// How a minimization ended, after how many iterations, at what energy (barrier included).
struct Newton_outcome
{
  Newton_stop stop = Newton_stop::CONVERGED;
  std::size_t iterations = 0;
  double energy = 0;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_OPTIONS_H
