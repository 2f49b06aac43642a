// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_SOLVER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_SOLVER_H

#include <CGAL/Spherical_parameterization/Progress.h>
#include <CGAL/Spherical_parameterization/Triangle_jet.h>
#include <CGAL/Spherical_parameterization/internal/energies/Fold_barrier.h>
#include <CGAL/Spherical_parameterization/internal/newton/Newton_options.h>
#include <CGAL/Spherical_parameterization/internal/energies/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/newton/mobius_boost.h>
#include <CGAL/Spherical_parameterization/internal/backends/parallel_for.h>
#include <CGAL/Spherical_parameterization/internal/newton/step_bound.h>
#include <CGAL/Spherical_parameterization/internal/newton/stopping_rules.h>
#include <CGAL/Spherical_parameterization/internal/newton/Tangent_newton_system.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// True if the solver traits `T` have the optional `allocate_factor()`.
template <class T, class = void>
struct has_allocate_factor : std::false_type
{
};
template <class T>
struct has_allocate_factor<T, std::void_t<decltype(std::declval<T&>().allocate_factor())>> : std::true_type
{
};

/// Newton's method on the product of unit spheres, one 2D tangent chart per vertex,
/// re-centred at every iteration (the retraction is the central projection):
/// - the exact Hessian in the tangent charts (`Tangent_newton_system`): each face's 9x9
///   ambient Hessian pulled to its 6 tangent variables, plus the sphere-curvature term
///   `-<g_v, x_v> I_2` of each vertex. Projecting it to PSD instead hides the negative
///   curvature of the near-Moebius modes along which a map slides, and costs an order of
///   magnitude more iterations;
/// - a diagonal shift `mu` (Levenberg-Marquardt), grown until the factorization is positive
///   definite and relaxed after every iteration; where it would grow too large, the per-face
///   Hessians made positive definite for a few iterations (`project_to_psd`);
/// - an Armijo line search that rejects non-finite energies (the d_min barrier).
/// The sparsity pattern and its symbolic analysis depend on the mesh only and are reused.
/// The unknowns are the first `free_vertices` vertices of the soup, by default all of them;
/// the others are held where they are (a patch of a larger map, see `Floor_patch`).
template <class SparseSolver, class ConcurrencyTag>
class Newton_solver
{
  using System = Tangent_newton_system<ConcurrencyTag>;
  using Vector = typename System::Vector;
  using Basis = typename System::Basis;

  // Fold-free steps stop at this share of the first root of a face's determinant: closer
  // leaves faces nearly degenerate for the next step, farther shortens every capped step.
  static constexpr double step_cap_share = 0.8;
  // The longest extension of a projected Newton step (`extend_step()`).
  static constexpr double max_step_extension = 64;
  // Armijo's sufficient decrease, and the halvings the line search tries.
  static constexpr double armijo = 1e-4;
  static constexpr int max_halvings = 50;
  // The exact Hessian takes shifts up to this share of its mean diagonal; beyond, the per-face
  // projected Hessian, and the exact one pauses for a few iterations (a failed attempt costs
  // factorizations).
  static constexpr double max_exact_shift = 1e-3;
  static constexpr int exact_pause_iterations = 4;
  // The shifts never go under this share of the mean diagonal, which also absorbs the three
  // rotations, so no vertex is fixed; they grow by `shift_growth` per failed factorization.
  static constexpr double min_shift = 1e-9;
  static constexpr double shift_growth = 8;
  static constexpr int max_shift_attempts = 60;  // from the floor, 8^60 covers every scale of a double
  // A direction of descent with no decrease at all: the shifts grow by this and the iteration
  // is retried, while the projected shift is under `max_retry_shift` times its floor.
  static constexpr double retry_shift_growth = 64;
  static constexpr double max_retry_shift = 1e6;
  // Relaxation of the shifts after an iteration: a full step says the model holds (fast
  // quadratic tails); one whose shift had to grow is then at most 8 times one that failed.
  static constexpr double relax_after_full_step = 16;
  static constexpr double relax_after_short_step = 4;
  static constexpr double relax_after_growth = 2;
  // A full step whose decrease is within this share of its model's (half the decrement).
  static constexpr double model_agreement = 0.1;
  // Stops (with those of `stopping_rules.h`): a model-matching full step with a decrement
  // under this many thresholds (the next one is quadratically smaller); a predicted
  // decrement under this share of the threshold (the prediction errs by up to 20 times); a
  // decrease under this share of it.
  static constexpr double quadratic_tail_margin = 10;
  static constexpr double predicted_margin = 1e-2;
  static constexpr double negligible_decrease = 1e-2;

public:
  explicit Newton_solver(const Triangle_soup& soup, std::size_t free_vertices = std::numeric_limits<std::size_t>::max())
    : faces_(&soup.faces), n_(soup.number_of_vertices()), free_(std::min(free_vertices, n_)),
      system_(soup.faces, n_, free_)
  {
    barrier_data_.reserve(faces_->size());
    for(std::size_t f = 0; f < soup.faces.size(); ++f)
      barrier_data_.emplace_back(soup.reference_triangle(f));
    solver_.analyze_pattern(system_.matrix());
  }

  /// Minimizes `energy` from `x`, which it updates to the last accepted iterate, with the
  /// stops and stages' settings of `options`; `visitor` sees every iteration and may cancel.
  template <class Energy, class Visitor>
  Newton_outcome minimize(const Spherical_energy<Energy>& energy, Points& x, const Newton_options& options,
                          Visitor& visitor)
  {
    take_settings(options);
    Newton_outcome out;
    double e = total_energy(energy, x);
    out.energy = e;
    if(!std::isfinite(e)) {
      out.stop = Newton_stop::NON_FINITE_START;
      return out;
    }
    if(options.fold_free_iterate && count_bad_faces(*faces_, x) == 0)
      *options.fold_free_iterate = x;
    Run run(e);
    Points trial(x.size());
    for(;;) {
      if(out.iterations >= options.max_iterations) { out.stop = Newton_stop::ITERATION_CAP; break; }
      if(Clock::now() > options.deadline) { out.stop = Newton_stop::TIME_LIMIT; break; }

      if(run.boosts.skip(threshold(options, e)))
        ++run.boosts.skipped;
      else
        run.boosts.record(boost_gain(energy, x, e));
      system_.update_bases(x);
      Step step;
      if(!find_direction(energy, x, options, out.iterations, step)) { out.stop = Newton_stop::STALLED; break; }
      if(!(step.decrement > threshold(options, e))) { out.stop = Newton_stop::CONVERGED; break; }

      const double e_new = take_step(energy, x, options, e, step, trial);
      if(!(e_new < e)) {
        if(grow_shifts_for_retry()) {
          ++out.iterations;
          continue;
        }
        out.stop = Newton_stop::STALLED;
        break;
      }
      x.swap(trial);
      run.capped_steps = step.capped ? run.capped_steps + 1 : 0;
      if(options.fold_free_iterate && too_many_folded(x, options, run.folded)) {
        ++out.iterations;
        out.stop = Newton_stop::FOLDED;
        break;
      }
      const double decrease = e - e_new;
      run.boosts.last_decrease = decrease;
      e = e_new;
      ++out.iterations;
      out.energy = e;
      relax_shifts(step.alpha >= 1, step.smoothing);

      if(!visitor(progress(options, out.iterations, e, step.decrement, step.alpha))) { out.stop = Newton_stop::CANCELLED; break; }
      run.history.push_back(e);
      const double limit = threshold(options, e);
      const Tail tail = tail_after(options, step, decrease, limit, run);
      // The decrement leaves the boosts out: a boost step that still gains goes on.
      if(tail.reached && options.predict_convergence && boost_gain(energy, x, e) > limit) {
        out.energy = e;
        continue;
      }
      if(tail.reached || converged_slowly(options, run, decrease, limit)) {
        out.stop = Newton_stop::CONVERGED;
        break;
      }
      if(options.leave_under_floor && options.fold_free_iterate && run.folded.in_a_row == 0 && tail.model_held &&
         tail.predicted <= limit && !is_above_floor(x, options.fold_floor)) {
        out.stop = Newton_stop::UNDER_FLOOR;
        break;
      }
      if(options.stop_when_fold_free && count_bad_faces(*faces_, x) == 0) { out.stop = Newton_stop::CONVERGED; break; }
    }
    return out;
  }

  /// Solves `(H + mu I) d = rhs` with the last factorization of this solver's last
  /// minimization, in the tangent charts of `bases()`; false if there is none.
  bool solve_with_last_factor(const Vector& rhs, Vector& d) const
  {
    if(!factored_)
      return false;
    d = solver_.solve(rhs);
    return d.allFinite();
  }

  /// The tangent basis of each vertex at the last iterate whose Hessian was assembled.
  const std::vector<Basis>& bases() const { return system_.bases(); }

  /// Forgets the shifts learnt by the minimizations so far, as for a first one: a map started
  /// afresh does not inherit the shifts a stalled one grew to, which would stop its first
  /// iteration at a negligible step.
  void forget_shifts()
  {
    mu_exact_ = mu_projected_ = 0;
    exact_pause_ = 0;
    shift_raised_ = false;
  }

  /// Frees the matrix and the per-face buffers, keeping the last factor and `bases()`: after
  /// this the solver can only `solve_with_last_factor()`. The level kept for the input's
  /// two-grid cycle would otherwise hold them until the input's first step.
  void keep_only_last_factor()
  {
    system_.keep_only_bases();
    std::vector<Fold_barrier::Face_data>().swap(barrier_data_);
    std::vector<double>().swap(face_value_);
    Points().swap(probe_);
  }

  /// Allocates the buffers of the first assembly and the factor (the solver traits'
  /// `allocate_factor()`, if they have it) and writes them once. Fresh memory is slow on
  /// virtual machines (a page fault in the host per page), so the coarse-to-fine solve calls
  /// this on another thread while it works on the coarser levels, when nothing else uses
  /// this solver.
  void prepare_memory()
  {
    system_.prepare_memory();
    face_value_.assign(faces_->size(), 0.0);
    if constexpr(has_allocate_factor<SparseSolver>::value)
      solver_.allocate_factor();
  }

  /// True if every face is at or above `floor` on the scale of `Fold_barrier` and has a
  /// determinant above `min_determinant`. The default margin is 10 times the degeneracy
  /// threshold, not the barrier's `determinant_floor`: large inputs have many small faces,
  /// none near the threshold, that the higher bar would send to the fold-free stages.
  bool is_above_floor(const Points& x, double floor, double min_determinant = 10 * degenerate_determinant)
  {
    face_value_.resize(faces_->size());
    parallel_for<ConcurrencyTag>(faces_->size(), [&](std::size_t f) {
      double det;
      const double t = face_scale(f, x, det);
      face_value_[f] = det > min_determinant && t >= floor;
    });
    return std::find(face_value_.begin(), face_value_.end(), 0.0) == face_value_.end();
  }

  /// The faces the fold barrier of `floor` holds (`Fold_barrier::face_activation()`), or
  /// that are flipped or degenerate; with `share`, only those under that share of their
  /// activation.
  std::vector<int> faces_under_floor(const Points& x, double floor, double share = 1)
  {
    face_value_.resize(faces_->size());
    parallel_for<ConcurrencyTag>(faces_->size(), [&](std::size_t f) {
      double det;
      const double t = face_scale(f, x, det);
      face_value_[f] = !(det > 0) || t < share * Fold_barrier::face_activation(barrier_data_[f], floor);
    });
    std::vector<int> under;
    for(std::size_t f = 0; f < face_value_.size(); ++f)
      if(face_value_[f] != 0)
        under.push_back(int(f));
    return under;
  }

private:
  // The scale t of face `f` (`Fold_barrier::scale`), with its chord determinant in `det`.
  double face_scale(std::size_t f, const Points& x, double& det) const
  {
    const auto& t = (*faces_)[f];
    const Chord_triangle<double> chord(x[t[0]], x[t[1]], x[t[2]]);
    det = chord.determinant();
    return Fold_barrier::scale(chord, det, barrier_data_[f]);
  }

  // After an iteration, the shifts are relaxed towards their floor: most after a full step,
  // which says the model holds; least if the shift had to grow in this iteration, as the
  // shift just found is then near the smallest that factors, and each failure costs the
  // factorization up to its failing column; the exact shift not at all while the exact
  // Hessian is paused, so that it does not climb back through failed factorizations to
  // where it was.
  void relax_shifts(bool full_step, bool smoothing)
  {
    const double relax = shift_raised_ && !smoothing ? relax_after_growth : full_step ? relax_after_full_step : relax_after_short_step;
    if(exact_pause_ == 0)
      mu_exact_ = std::max(mu_exact_ / relax, mu_floor_);
    mu_projected_ = std::max(mu_projected_ / relax, mu_floor_);
  }

  // The folded iterates in a row (`Newton_options::max_folded_iterations`); unless
  // `count_unfolding_iterates`, one with at most half the bad faces of the last iterate
  // does not count, so that a map being untangled is not stopped while it gets better.
  struct Folded_iterates
  {
    std::size_t in_a_row = 0;
    std::size_t last_bad = 0;  // folded and degenerate faces of the last iterate

    void record(std::size_t bad, bool count_unfolding)
    {
      const bool unfolding = 2 * bad <= last_bad;
      in_a_row = bad == 0 ? 0 : (unfolding && !count_unfolding ? in_a_row : in_a_row + 1);
      last_bad = bad;
    }
  };

  // What the visitor gets after an iteration.
  static Progress progress(const Newton_options& options, std::size_t iterations, double e, double decrement, double alpha)
  {
    Progress p;
    p.stage = options.stage;
    p.iteration = options.iteration_offset + iterations;
    p.energy = e;
    p.newton_decrement = decrement;
    p.step = alpha;
    p.elapsed_seconds = std::chrono::duration<double>(Clock::now() - options.start).count();
    return p;
  }

  // Whether the next iteration skips its Moebius boost step: when the last one gained less
  // than the tolerance's `threshold` and a hundredth of the Newton step that followed it, for
  // at most `max_skipped` iterations in a row: on capped stages a boost step (9 to 11
  // energy evaluations) gains next to nothing, while the conformal energies' slides along the
  // boosts, which they are for, gain more than the tolerance.
  struct Boost_skipping
  {
    static constexpr int max_skipped = 3;
    static constexpr double negligible_share = 1e-2;  // of the Newton step's decrease
    double last_gain = std::numeric_limits<double>::infinity();
    double last_decrease = 0;  // of the last Newton iteration
    int skipped = 0;           // iterations in a row without a boost step

    bool skip(double threshold) const
    {
      return skipped < max_skipped && last_gain < threshold && last_gain < negligible_share * last_decrease;
    }
    void record(double gain) { last_gain = gain; skipped = 0; }
  };

  // What one minimization carries from an iteration to the next.
  struct Run
  {
    explicit Run(double e) : history{e} {}
    Folded_iterates folded;
    std::vector<double> history;     // energy after each iteration, for the stall tests
    double last_full_decrement = 0;  // of the last iteration if its step was a full Newton step that held its model, else 0
    double last_long_decrement = 0;  // of the last iteration if its step was a Newton step of at least full length, else 0
    std::size_t capped_steps = 0;    // consecutive iterations whose step the fold-free cap shortened
    Boost_skipping boosts;
  };

  // An iteration's direction and how far along it the iteration went.
  struct Step
  {
    Vector d;
    double decrement = 0;    // -g.d, Newton's decrement for a Newton direction
    double alpha = 1;        // the accepted length, in units of d
    bool smoothing = false;  // a block Jacobi or two-grid direction (`Newton_options::smoothing_iterations`)
    bool two_grid = false;
    bool projected = false;  // a direction of the projected Hessian
    bool capped = false;     // the fold-free cap shortened it before the line search
  };

  // How an accepted step ends the quadratic or linear tail of the convergence.
  struct Tail
  {
    bool model_held = false;  // a full Newton step that decreased the energy as its model predicted
    double predicted = 0;     // the next decrement, extrapolated from the last two full steps
    bool reached = false;     // no need to factor again to see the next decrement under the threshold
  };

  // The settings of `options` that the helpers of a minimization read from the solver.
  void take_settings(const Newton_options& options)
  {
    with_barrier_ = options.keep_fold_free;
    floor_ = options.fold_floor;
    outer_weight_ = options.outer_barrier_weight;
    floored_activation_ = options.floored_activation;
    first_shift_ = options.first_shift;
    boost_search_ = options.boost_search;
    drop_rotation_curvature_ = options.drop_rotation_curvature;
  }

  // The decrement under which the minimization has converged at energy `e`.
  static double threshold(const Newton_options& options, double e)
  {
    return options.tolerance * std::abs(e + options.held_energy);
  }

  // The first `smoothing_iterations` take a smoothing step (the very first a two-grid cycle
  // with a coarse correction), the others Newton's; false if no Newton direction was found.
  template <class Energy>
  bool find_direction(const Spherical_energy<Energy>& energy, const Points& x, const Newton_options& options,
                      std::size_t iteration, Step& step)
  {
    step.smoothing = iteration < options.smoothing_iterations;
    if(step.smoothing)
      step.two_grid = smoothing_direction(energy, x, iteration == 0 ? options.coarse_correction : nullptr, step.d);
    else if(!newton_direction(energy, x, step.d))
      return false;
    step.projected = !step.smoothing && projected_;  // projected_ describes the last Newton direction only
    step.decrement = -system_.gradient().dot(step.d);
    return true;
  }

  // The step along `step.d`: capped short of any fold in the fold-free stages, then the
  // Armijo line search, then extended while the energy falls (`extend_step()`). Returns the
  // energy at the accepted point `trial`, +inf if none.
  template <class Energy>
  double take_step(const Spherical_energy<Energy>& energy, const Points& x, const Newton_options& options, double e,
                   Step& step, Points& trial)
  {
    auto cap_short_of_folds = [&] {
      step.alpha = 1;
      if(options.keep_fold_free)
        step.alpha = std::min(1.0, step_cap_share * largest_fold_free_step(*faces_, x, system_.ambient(step.d)));
      step.capped = step.alpha < 1;
    };
    cap_short_of_folds();
    double e_new = line_search(energy, x, step.d, e, step.decrement, step.alpha, trial);
    if(step.two_grid && step.alpha < 1) {
      // The line search had to shorten the two-grid step: the last level's Hessian does
      // not model the input's energy here (a level that ended on its fold barrier, as
      // squeezed protrusions do). Block Jacobi alone.
      system_.block_jacobi(-system_.gradient(), step.d);
      step.decrement = -system_.gradient().dot(step.d);
      cap_short_of_folds();
      e_new = line_search(energy, x, step.d, e, step.decrement, step.alpha, trial);
    }
    if(options.extend_projected_steps && step.alpha == 1 && !step.smoothing && projected_ && !options.keep_fold_free)
      e_new = extend_step(energy, x, step.d, e_new, step.alpha, trial);
    return e_new;
  }

  // No decrease along a direction of descent: precision is exhausted, or the shift is too
  // small for this non-convex stretch. The shifts grow for one more try; false if they are
  // already far above their floor.
  bool grow_shifts_for_retry()
  {
    if(!(mu_projected_ < max_retry_shift * mu_floor_))
      return false;
    mu_exact_ *= retry_shift_growth;
    mu_projected_ *= retry_shift_growth;
    return true;
  }

  // Keeps the accepted iterate `x` as the last fold-free one, or counts it as folded; true if
  // more than `max_folded_iterations` folded iterates came in a row.
  bool too_many_folded(const Points& x, const Newton_options& options, Folded_iterates& folded) const
  {
    folded.record(count_bad_faces(*faces_, x), options.count_unfolding_iterates);
    if(folded.in_a_row == 0)
      *options.fold_free_iterate = x;
    return folded.in_a_row > options.max_folded_iterations;
  }

  // Whether an accepted step ends the minimization, saving a factorization that would only
  // find the next decrement under the threshold:
  // - a full Newton step that held its model, its decrement close to the threshold, or its
  //   successor, predicted quadratically from the last two, far below it;
  // - with `predict_convergence`, a step of at least Newton's length, its decrement under
  //   `quadratic_tail_margin` thresholds, that gained under the threshold, or that was a
  //   full projected step after another long one and whose successor, at their linear
  //   rate, is under the threshold: the projected model's steps converge linearly (the
  //   exact one's quadratically, the first rule). Not after an extended step, whose
  //   decrement understates what the slide still gains.
  // Updates the run's last decrements.
  static Tail tail_after(const Newton_options& options, const Step& step, double decrease, double threshold, Run& run)
  {
    Tail tail;
    tail.model_held = !step.smoothing && step.alpha == 1 &&
                      std::abs(decrease - step.decrement / 2) <= model_agreement * step.decrement;
    tail.predicted = predicted_decrement(run.last_full_decrement, step.decrement);
    run.last_full_decrement = tail.model_held ? step.decrement : 0;
    const bool long_step = !step.smoothing && step.alpha >= 1;
    const double at_linear_rate = linearly_predicted_decrement(run.last_long_decrement, step.decrement);
    run.last_long_decrement = long_step ? step.decrement : 0;
    const bool quadratic = tail.model_held && (step.decrement <= quadratic_tail_margin * threshold ||
                                               (options.predict_convergence && tail.predicted <= predicted_margin * threshold));
    const bool close = options.predict_convergence && long_step && step.decrement <= quadratic_tail_margin * threshold;
    const bool gained_little = decrease <= threshold;
    const bool next_under_threshold = step.projected && step.alpha == 1 && at_linear_rate <= threshold;
    const bool linear = close && (gained_little || next_under_threshold);
    tail.reached = quadratic || linear;
    return tail;
  }

  // The stops on a decrease that is too small to go on for: negligible, ten iterations
  // gaining under the threshold, or the slow capped tail of a floor stage.
  static bool converged_slowly(const Newton_options& options, const Run& run, double decrease, double threshold)
  {
    return decrease <= negligible_decrease * threshold || stalled(run.history, threshold) ||
           (options.stop_slow_capped_tail && slow_capped_tail(run.history, run.capped_steps, threshold));
  }

  // One Moebius boost step if the minimization makes them: what it gains (the map and its
  // energy `e` updated), 0 without boost steps. Before every iteration, and before a stop on
  // a predicted decrement: the decrement leaves the boosts out, and the conformal energies
  // slide along them, so a stop on the decrement alone can be far above the minimum.
  template <class Energy>
  double boost_gain(const Spherical_energy<Energy>& energy, Points& x, double& e)
  {
    if(!boost_search_ || free_ != n_)
      return 0;
    const double before = e;
    boost_step(x, [&](const Points& y) { return total_energy(energy, y); }, e);
    return before - e;
  }

  template <class Number>
  Number barrier(std::size_t f, const Points& x) const
  {
    const auto& t = (*faces_)[f];
    return Fold_barrier::energy(Chord_triangle<Number>(x[t[0]], x[t[1]], x[t[2]]), barrier_data_[f], floor_,
                                outer_weight_, floored_activation_);
  }

  // Face `f`'s energy jet at `x`, with the fold barrier's if it holds the face (`held`).
  template <class Energy>
  Triangle_jet face_jet(const Spherical_energy<Energy>& energy, const Points& x, std::size_t f, bool& held) const
  {
    Triangle_jet jet = energy.template face<Triangle_jet>(f, x);
    held = with_barrier_ && barrier<double>(f, x) > 0;
    if(held)
      jet += barrier<Triangle_jet>(f, x);
    return jet;
  }

  template <class Energy>
  void assemble(const Spherical_energy<Energy>& energy, const Points& x, bool projected)
  {
    system_.assemble(
      x, [&](std::size_t f, bool& held) { return face_jet(energy, x, f, held); }, projected,
      drop_rotation_curvature_);
  }

  // Block Jacobi: each vertex's own 2x2 block of the exact Hessian, its eigenvalues replaced by
  // their absolute values (at least a small fraction of the block's size).
  // With a coarse correction c, a two-grid cycle on the Newton system H d = -g that shares
  // the one assembly: d = c + J^-1 (-g - H c), J the block diagonal. The coarse step
  // lowers the smooth error that block Jacobi hardly sees. Block Jacobi alone if the cycle's
  // direction is not one of descent. True if the direction is the two-grid cycle's.
  template <class Energy>
  bool smoothing_direction(const Spherical_energy<Energy>& energy, const Points& x,
                           const Coarse_correction* coarse_correction, Vector& d)
  {
    assemble(energy, x, false);
    const Vector& gradient = system_.gradient();
    Vector coarse_step;
    if(!coarse_correction || !coarse_step_of(*coarse_correction, x, coarse_step)) {
      system_.block_jacobi(-gradient, d);
      return false;
    }
    system_.block_jacobi(system_.residual(-gradient, coarse_step), d);
    d += coarse_step;
    if(gradient.dot(d) < 0)
      return true;
    system_.block_jacobi(-gradient, d);
    return false;
  }

  // The coarse correction of the gradient, in the tangent charts; false if it failed.
  bool coarse_step_of(const Coarse_correction& coarse_correction, const Points& x, Vector& step) const
  {
    std::vector<Eigen::Vector3d> displacement;
    if(!coarse_correction(x, system_.ambient(system_.gradient()), displacement) || displacement.size() != n_)
      return false;
    step = system_.tangent(displacement);
    return step.allFinite();
  }

  // The exact Hessian with a shift of at most `max_exact_shift` of its mean diagonal; where
  // that is not enough (strongly non-convex faces, such as a barrier or area term far from
  // its minimum), the per-face projected Hessian, whose shift then only handles the
  // curvature term.
  template <class Energy>
  bool newton_direction(const Spherical_energy<Energy>& energy, const Points& x, Vector& d)
  {
    // After the exact Hessian failed, skip it for a few iterations: each failure costs
    // factorizations, and the projection of the faces it assembled.
    const bool try_exact = exact_pause_ == 0;
    if(exact_pause_ > 0)
      --exact_pause_;
    projected_ = false;
    if(try_exact) {
      assemble(energy, x, false);
      if(shifted_newton_direction(mu_exact_, false, max_exact_shift, d))
        return true;
      exact_pause_ = exact_pause_iterations;
      system_.project_assembled_faces(x, drop_rotation_curvature_);
    } else {
      assemble(energy, x, true);
    }
    projected_ = true;
    return shifted_newton_direction(mu_projected_, true, std::numeric_limits<double>::infinity(), d);
  }

  // Solves (H + mu I) d = -g, H the assembled matrix, with the smallest shift mu >= its
  // floor, grown x8 per failed factorization. False if mu would exceed `max_relative_shift`
  // x the mean diagonal.
  bool shifted_newton_direction(double& mu, bool projected, double max_relative_shift, Vector& d)
  {
    const double mean_diagonal = system_.mean_abs_diagonal();
    if(!std::isfinite(mean_diagonal) || mean_diagonal == 0)
      return false;
    mu_floor_ = min_shift * mean_diagonal;
    mu = std::max(mu == 0 && !projected ? first_shift_ * mean_diagonal : mu, mu_floor_);
    const std::vector<double> diagonal = system_.diagonal();  // only the diagonal changes with the shift
    for(int attempt = 0; attempt < max_shift_attempts && mu <= max_relative_shift * mean_diagonal; ++attempt, mu *= shift_growth) {
      system_.set_shifted_diagonal(diagonal, mu);
      factored_ = solver_.factorize(system_.matrix());
      if(factored_) {
        shift_raised_ = attempt > 0;
        d = solver_.solve(-system_.gradient());
        return d.allFinite();
      }
    }
    mu = std::min(mu, max_relative_shift * mean_diagonal);
    return false;
  }

  // The energy (with the barrier in a fold-free stage), faces evaluated in parallel with
  // Parallel_tag and summed in a fixed order, so that the result does not depend on the
  // number of threads. +inf if some face is past a barrier.
  template <class Energy>
  double total_energy(const Spherical_energy<Energy>& energy, const Points& x)
  {
    face_value_.resize(faces_->size());
    parallel_for<ConcurrencyTag>(faces_->size(), [&](std::size_t f) {
      face_value_[f] = energy.template face<double>(f, x);
      if(with_barrier_)
        face_value_[f] += barrier<double>(f, x);
    });
    return finite_sum(face_value_);
  }

  // A full step of the projected Hessian, doubled while the energy falls; returns the energy
  // at the accepted point `trial`, `alpha` its step (`Newton_options::extend_projected_steps`).
  // Not in the capped stages, whose steps must not cross a fold, and never into a fold from a
  // fold-free step.
  template <class Energy>
  double extend_step(const Spherical_energy<Energy>& energy, const Points& x, const Vector& d, double e, double& alpha,
                     Points& trial)
  {
    probe_.resize(n_);
    const bool fold_free = count_bad_faces(*faces_, trial) == 0;
    for(double a = 2 * alpha; a <= max_step_extension; a *= 2) {
      system_.step_to(x, d, a, probe_);
      const double e_probe = total_energy(energy, probe_);
      if(!(e_probe < e) || (fold_free && count_bad_faces(*faces_, probe_) > 0))
        break;
      e = e_probe;
      alpha = a;
      trial.swap(probe_);
    }
    return e;
  }

  // Armijo backtracking from `alpha`; returns the accepted energy (or +inf) with the point in `trial`.
  template <class Energy>
  double line_search(const Spherical_energy<Energy>& energy, const Points& x, const Vector& d, double e0,
                     double decrement, double& alpha, Points& trial)
  {
    for(int k = 0; k < max_halvings && alpha > 0; ++k, alpha *= 0.5) {
      system_.step_to(x, d, alpha, trial);
      const double e = total_energy(energy, trial);
      if(std::isfinite(e) && e <= e0 - armijo * alpha * decrement)
        return e;
    }
    return std::numeric_limits<double>::infinity();
  }

  const Faces* faces_;
  std::size_t n_;
  std::size_t free_;  // the unknowns: vertices 0 to free_ - 1
  bool with_barrier_ = false;
  bool drop_rotation_curvature_ = false;  // Newton_options::drop_rotation_curvature of the minimization under way
  std::vector<Fold_barrier::Face_data> barrier_data_;
  double floor_ = 0;  // the barrier's activation
  double outer_weight_ = 0;
  double floored_activation_ = 0;
  System system_;
  SparseSolver solver_;
  bool factored_ = false;  // the last factorization succeeded: `solver_` holds a factor
  bool projected_ = false;  // the last Newton direction came from the projected Hessian
  int exact_pause_ = 0;  // iterations to go before the exact Hessian is tried again
  bool shift_raised_ = false;  // the last factorization needed a larger shift than its first try
  double mu_exact_ = 0, mu_projected_ = 0, mu_floor_ = 0;
  double first_shift_ = 1e-4;  // Newton_options::first_shift of the minimization under way
  bool boost_search_ = false;   // Newton_options::boost_search of the minimization under way
  std::vector<double> face_value_;  // per face, the energy or a flag of the last evaluation
  Points probe_;  // the points of a step's extension
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_SOLVER_H
