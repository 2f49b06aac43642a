// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SOLVER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SOLVER_H

#include <CGAL/Spherical_parameterization/Progress.h>
#include <CGAL/Spherical_parameterization/Triangle_jet.h>
#include <CGAL/Spherical_parameterization/internal/Fold_barrier.h>
#include <CGAL/Spherical_parameterization/internal/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/mobius_boost.h>
#include <CGAL/Spherical_parameterization/internal/parallel_for.h>
#include <CGAL/Spherical_parameterization/internal/project_psd.h>
#include <CGAL/Spherical_parameterization/internal/step_bound.h>
#include <CGAL/Spherical_parameterization/internal/tangent_basis.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

using Clock = std::chrono::steady_clock;

/// True if the solver traits `T` have the optional `allocate_factor()`.
template <class T, class = void>
struct has_allocate_factor : std::false_type
{
};
template <class T>
struct has_allocate_factor<T, std::void_t<decltype(std::declval<T&>().allocate_factor())>> : std::true_type
{
};

/// A step of a map from a coarser level: given the map and the energy's gradient at every
/// vertex (in its tangent plane), writes a displacement of every vertex that lowers the
/// energy's smooth error, or returns false (see `Coarse_to_fine`).
using Coarse_correction = std::function<bool(const Points& x, const std::vector<Eigen::Vector3d>& gradient,
                                             std::vector<Eigen::Vector3d>& step)>;

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
  /// area, such a face is held only at a determinant of 1e-12, so the Newton steps, which
  /// nothing else keeps from flipping it, squeeze it about 5 times each on the way there,
  /// each capped to a few percent (see `Spherical_parameterizer_3`'s continuation).
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
  bool projected_hessian = false;  ///< project each face's Hessian to PSD instead of shifting the exact one
  /// Iterations that solve only the 2x2 diagonal blocks of the Hessian (block Jacobi) before
  /// Newton: a cheap smoother of the local error a vertex split leaves.
  std::size_t smoothing_iterations = 0;
  /// The exact Hessian's first shift in the solver's life, relative to its mean diagonal.
  /// 1e-4 by default: starts are far from a minimum, and growing from the floor cost 7
  /// failed factorizations on bear.
  double first_shift = 1e-4;
  /// With `smoothing_iterations`: the first smoothing step is a two-grid cycle, this coarse
  /// correction of the map followed by block Jacobi (`Newton_solver::smoothing_direction()`).
  const Coarse_correction* coarse_correction = nullptr;
  /// Before every Newton iteration, a Newton step on the three parameters of a Moebius
  /// boost of the whole map (`boost_step()`), the directions in which the energies of
  /// conformal type are nearly flat.
  bool boost_search = false;
  /// Stop when the next decrement, predicted from the last two, is far below the tolerance
  /// (`predicted_decrement()`): saves the last factorization, the one that would only confirm
  /// convergence. Set on the input level only: on the coarser levels, whose maps are starts
  /// for the next, stopping one iteration earlier changed the next level's path (Tutte on
  /// bunny00: 42 -> 53 iterations), for no gain.
  bool predict_convergence = false;
  /// With `fold_free_iterate`: stop (`Newton_stop::UNDER_FLOOR`) at a fold-free iterate with a
  /// face under `fold_floor` once the next decrement is predicted below the tolerance. The
  /// floor stage that follows then starts one factorization earlier: confirming the
  /// convergence of an energy that is about to change is wasted (6 s at 1.2M faces).
  bool leave_under_floor = false;
  /// With `keep_fold_free`: also stop at the slow end of a stage whose steps the fold-free cap
  /// shortens (`slow_capped_tail()`). There every step is capped at 1 to 5% of Newton's by
  /// faces the barrier does not hold yet, and gains little against the tolerance: on man
  /// (35k faces), the input's last 9 to 29 iterations gained 1e-6 to 5e-6 of the energy in
  /// all. Set on the input's last stage only: an earlier stop anywhere else changes the path
  /// of the stages that follow.
  bool stop_slow_capped_tail = false;
  const char* stage = "";
  std::size_t iteration_offset = 0;  ///< iterations of earlier stages, for progress reports
};

enum class Newton_stop { CONVERGED, ITERATION_CAP, STALLED, CANCELLED, TIME_LIMIT, NON_FINITE_START, FOLDED, UNDER_FLOOR };

struct Newton_outcome
{
  Newton_stop stop = Newton_stop::CONVERGED;
  std::size_t iterations = 0;
  double energy = 0;
};

/// Newton's method on the product of unit spheres, one 2D tangent chart per vertex,
/// re-centred at every iteration (the retraction is the central projection):
/// - the exact Hessian in the tangent charts: each face's 9x9 ambient Hessian pulled to its
///   6 tangent variables, plus the sphere-curvature term `-<g_v, x_v> I_2` of each vertex;
/// - a diagonal shift `mu` (Levenberg-Marquardt): grown x8 until the factorization is
///   positive definite, shrunk after every iteration (/16 after a full step, /4 after a
///   shorter one, /2 after one whose shift had to grow), never below 1e-9 x the mean
///   diagonal, which also absorbs the three rotation modes, so no vertex is fixed.
///   Where the shift would exceed 1e-3 x the mean diagonal, the iteration uses the per-face
///   Hessians made positive definite instead (`project_to_psd`), and the exact one is
///   skipped for the next 4 iterations, its shift held near that largest value. Projection
///   alone was measured 18x slower for Tutte on triceratops (200 against 11 iterations): it
///   hides the negative curvature of the near-Moebius modes along which the mesh slides;
/// - an Armijo line search rejects non-finite energies (the d_min barrier).
/// The sparsity pattern and its symbolic analysis depend on the mesh only and are reused.
/// The unknowns are the first `free_vertices` vertices of the soup, by default all of them;
/// the others are held where they are (a patch of a larger map, see `Floor_patch`).
template <class SparseSolver, class ConcurrencyTag>
class Newton_solver
{
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Vector = Eigen::VectorXd;
  using Basis = Eigen::Matrix<double, 3, 2>;
  using Face_hessian = Eigen::Matrix<double, 6, 6>;
  static constexpr int lower_entries = 21;  // of a symmetric 6x6 matrix

public:
  explicit Newton_solver(const Triangle_soup& soup, std::size_t free_vertices = std::numeric_limits<std::size_t>::max())
    : faces_(&soup.faces), n_(soup.number_of_vertices()), free_(std::min(free_vertices, n_))
  {
    barrier_data_.reserve(faces_->size());
    for(std::size_t f = 0; f < soup.faces.size(); ++f)
      barrier_data_.emplace_back(soup.reference_triangle(f));
    build_pattern();
    solver_.analyze_pattern(matrix_);
  }

  template <class Energy, class Visitor>
  Newton_outcome minimize(const Spherical_energy<Energy>& energy, Points& x, const Newton_options& options,
                          Visitor& visitor)
  {
    Newton_outcome out;
    with_barrier_ = options.keep_fold_free;
    floor_ = options.fold_floor;
    outer_weight_ = options.outer_barrier_weight;
    floored_activation_ = options.floored_activation;
    first_shift_ = options.first_shift;
    boost_search_ = options.boost_search;
    double e = total_energy(energy, x);
    out.energy = e;
    if(!std::isfinite(e)) {
      out.stop = Newton_stop::NON_FINITE_START;
      return out;
    }
    if(options.fold_free_iterate && count_bad_faces(*faces_, x) == 0)
      *options.fold_free_iterate = x;
    std::size_t folded = 0;  // consecutive folded iterates
    std::size_t last_bad = 0;  // folded and degenerate faces of the last iterate
    Points trial(x.size());
    std::vector<double> history{e};  // energy after each iteration, for the stall test
    double last_full_decrement = 0;  // of the last iteration if its step was a full Newton step, else 0
    std::size_t capped_steps = 0;    // consecutive iterations whose step the fold-free cap shortened
    Boost_skipping boosts;
    for(;;) {
      if(out.iterations >= options.max_iterations) { out.stop = Newton_stop::ITERATION_CAP; break; }
      if(Clock::now() > options.deadline) { out.stop = Newton_stop::TIME_LIMIT; break; }

      if(boosts.skip(options.tolerance * std::abs(e + options.held_energy)))
        ++boosts.skipped;
      else
        boosts.record(boost_gain(energy, x, e));
      compute_bases(x);
      Vector d;
      const bool smoothing = out.iterations < options.smoothing_iterations;
      bool two_grid = false;
      if(smoothing)
        two_grid = smoothing_direction(energy, x, out.iterations == 0 ? options.coarse_correction : nullptr, d);
      else if(!newton_direction(energy, x, options.projected_hessian, d)) { out.stop = Newton_stop::STALLED; break; }

      double decrement = -gradient_.dot(d);
      double threshold = options.tolerance * std::abs(e + options.held_energy);
      if(!(decrement > threshold)) { out.stop = Newton_stop::CONVERGED; break; }

      double alpha = 1;
      auto fold_free_cap = [&] {
        if(options.keep_fold_free)
          alpha = std::min(1.0, 0.8 * largest_fold_free_step(*faces_, x, ambient_step(d)));
      };
      fold_free_cap();
      bool capped = alpha < 1;
      double e_new = line_search(energy, x, d, e, decrement, alpha, trial);
      if(two_grid && alpha < 1) {
        // The line search had to shorten the two-grid step: the last level's Hessian does
        // not model the input's energy here (a level that ended on its fold barrier, as
        // Dirichlet's squeezed ears do at 302k faces: a step of 1/32). Block Jacobi alone.
        block_jacobi(-gradient_, d);
        decrement = -gradient_.dot(d);
        alpha = 1;
        fold_free_cap();
        capped = alpha < 1;
        e_new = line_search(energy, x, d, e, decrement, alpha, trial);
      }
      if(!(e_new < e)) {
        // No decrease along a direction of descent: precision is exhausted, or the
        // shift is too small for this non-convex stretch. Grow it once before giving up.
        if(mu_projected_ < 1e6 * mu_floor_) { mu_exact_ *= 64; mu_projected_ *= 64; ++out.iterations; continue; }
        out.stop = Newton_stop::STALLED;
        break;
      }
      x.swap(trial);
      capped_steps = capped ? capped_steps + 1 : 0;
      if(options.fold_free_iterate) {
        const std::size_t bad = count_bad_faces(*faces_, x);
        const bool unfolding = 2 * bad <= last_bad;
        folded = bad == 0 ? 0 : (unfolding && !options.count_unfolding_iterates ? folded : folded + 1);
        last_bad = bad;
        if(folded == 0)
          *options.fold_free_iterate = x;
        else if(folded > options.max_folded_iterations) {
          ++out.iterations;
          out.stop = Newton_stop::FOLDED;
          break;
        }
      }
      const double decrease = e - e_new;
      boosts.last_decrease = decrease;
      e = e_new;
      threshold = options.tolerance * std::abs(e + options.held_energy);
      ++out.iterations;
      out.energy = e;
      relax_shifts(alpha == 1, smoothing);

      Progress p;
      p.stage = options.stage;
      p.iteration = options.iteration_offset + out.iterations;
      p.energy = e;
      p.newton_decrement = decrement;
      p.step = alpha;
      p.elapsed_seconds = std::chrono::duration<double>(Clock::now() - options.start).count();
      if(!visitor(p)) { out.stop = Newton_stop::CANCELLED; break; }
      history.push_back(e);
      // A full Newton step that decreased the energy as its model predicted, with a decrement
      // close to the tolerance, or one whose successor, predicted from the last two decrements,
      // is far below it (margin 100; the prediction was measured off by up to 20x): the next
      // decrement is quadratically smaller, no need to factor again to see it.
      const bool model_held = !smoothing && alpha == 1 && std::abs(decrease - decrement / 2) <= 0.1 * decrement;
      const double predicted = predicted_decrement(last_full_decrement, decrement);
      last_full_decrement = model_held ? decrement : 0;
      const bool quadratic_tail =
        model_held && (decrement <= 10 * threshold ||
                       (options.predict_convergence && predicted <= 1e-2 * threshold));
      if(quadratic_tail && options.predict_convergence && boost_gain(energy, x, e) > threshold) {
        out.energy = e;
        continue;
      }
      if(quadratic_tail || decrease <= threshold * 1e-2 || stalled(history, threshold) ||
         (options.stop_slow_capped_tail && slow_capped_tail(history, capped_steps, threshold))) {
        out.stop = Newton_stop::CONVERGED;
        break;
      }
      if(options.leave_under_floor && options.fold_free_iterate && folded == 0 && model_held &&
         predicted <= threshold && !is_above_floor(x, options.fold_floor)) {
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
  const std::vector<Basis>& bases() const { return bases_; }

  /// Frees the matrix and the per-face buffers, keeping the last factor and `bases()`: after
  /// this the solver can only `solve_with_last_factor()`. At 1.2M faces the level kept for
  /// the input's two-grid cycle (243k faces) otherwise holds them until the input's first step.
  void keep_only_last_factor()
  {
    Matrix empty;
    matrix_.swap(empty);
    std::vector<int>().swap(entry_index_);
    std::vector<int>().swap(diagonal_index_);
    std::vector<Fold_barrier::Face_data>().swap(barrier_data_);
    std::vector<Triangle_jet::Gradient>().swap(face_gradient_);
    std::vector<double>().swap(face_hessian_);
    std::vector<double>().swap(face_value_);
    std::vector<Eigen::Vector3d>().swap(ambient_gradient_);
    Vector().swap(gradient_);
  }

  /// Allocates the buffers of the first assembly and the factor (the solver traits'
  /// `allocate_factor()`, if they have it) and writes them once. Fresh memory is slow on
  /// virtual machines (a page fault in the host per page): at 302k faces the first
  /// assembly and factorization took 0.5 and 1.45 s, the next ones 0.2 and 0.6 s. The
  /// coarse-to-fine solve calls this on another thread while it works on the coarser
  /// levels, when nothing else uses this solver.
  void prepare_memory()
  {
    const std::size_t nf = faces_->size();
    face_gradient_.assign(nf, Triangle_jet::Gradient::Zero());
    face_hessian_.assign(nf * lower_entries, 0.0);
    face_value_.assign(nf, 0.0);
    ambient_gradient_.assign(n_, Eigen::Vector3d::Zero());
    bases_.assign(n_, Basis::Zero());
    if constexpr(has_allocate_factor<SparseSolver>::value)
      solver_.allocate_factor();
  }

  /// True if every face is at or above `floor` on the scale of `Fold_barrier` and has a
  /// determinant above `min_determinant`. The default margin is 10 times the degeneracy
  /// threshold, not the barrier's `determinant_floor`: raising the bar to that made the input
  /// level of bunny00 after one subdivision (many small faces, none near the threshold)
  /// restart in fold-free mode, 4 -> 11 iterations.
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

  /// True if the last `capped_tail_window` iterations all had capped steps and gained less
  /// than `capped_tail_gain` of `threshold` each on average
  /// (`Newton_options::stop_slow_capped_tail`): the stall test of `stalled()`, on a shorter
  /// window, for the steps the cap holds back. `history` holds the energy after each
  /// iteration, the last one included.
  static bool slow_capped_tail(const std::vector<double>& history, std::size_t capped_steps, double threshold)
  {
    return capped_steps >= capped_tail_window &&
           recent_gain(history, capped_tail_window) <= capped_tail_gain * capped_tail_window * threshold;
  }
  // Half the threshold rather than a quarter: the slides this stops gain 1.5 to 4 times the
  // threshold per iteration for dozens of iterations on some rotations of an input and not on
  // others (rounding alone decides). 8 cases x 3 rotations of the input (camel Dirichlet,
  // armadillo and diplodocus Tutte, man@loop1 and bull@loop2 Combined, bunny00): 132.5 ->
  // 122.7 s, the energies at most 5.7e-6 of themselves higher. The full threshold: 114.0 s,
  // but up to 2.7e-5 higher, over the 1e-5 that test_parameterizer holds a map to.
  static constexpr double capped_tail_gain = 0.5;
  // 3 rather than 5 iterations: at the held-out size (man@loop1, dino@loop2, bull@loop2,
  // cow@loop2, diplodocus@loop1, medians of 3) the same energies, 2 iterations fewer on 5
  // of 6 meshes, about 4% of the time; the corpus (14 meshes x 3 energies) the same energies.
  static constexpr std::size_t capped_tail_window = 3;

private:
  // The scale t of face `f` (`Fold_barrier::scale`), with its chord determinant in `det`.
  double face_scale(std::size_t f, const Points& x, double& det) const
  {
    const auto& t = (*faces_)[f];
    const Chord_triangle<double> chord(x[t[0]], x[t[1]], x[t[2]]);
    det = chord.determinant();
    return Fold_barrier::scale(chord, det, barrier_data_[f]);
  }

  // After an iteration, the shifts are relaxed towards their floor:
  // - /16 after a full step, which says the model holds (rather than /4: the tail became
  //   quadratic on bunny00 after one subdivision, 3 Newton steps instead of 6), else /4;
  // - /2 if the shift had to grow in this iteration: it is then at most 8 times one that
  //   failed, and a failure costs a whole factorization (the negative modes are global,
  //   found in the last supernode);
  // - the exact shift not at all while the exact Hessian is paused: it stays where it
  //   failed (relaxed once as the pause ends), instead of coming back from 1e-8 and climbing
  //   through failed factorizations to where it was.
  // The last two cut the failed factorizations of bunny00 Tutte from 24 to 14 (doc/NOTES.md,
  // round seven).
  void relax_shifts(bool full_step, bool smoothing)
  {
    const double relax = shift_raised_ && !smoothing ? 2 : full_step ? 16 : 4;
    if(exact_pause_ == 0)
      mu_exact_ = std::max(mu_exact_ / relax, mu_floor_);
    mu_projected_ = std::max(mu_projected_ / relax, mu_floor_);
  }

  // Whether the next iteration skips its Moebius boost step: when the last one gained less
  // than the tolerance's `threshold` and a hundredth of the Newton step that followed it, for
  // at most `max_skipped` iterations in a row. On the protrusions' capped stages the boosts
  // gained 1e-5 per iteration against the steps' 0.1 to 0.6, at 10 to 17% of the solver's
  // time (its 9 to 11 energy evaluations); the conformal energies' slides along the boosts,
  // which they are for, gain more than the tolerance.
  struct Boost_skipping
  {
    static constexpr int max_skipped = 3;
    double last_gain = std::numeric_limits<double>::infinity();
    double last_decrease = 0;  // of the last Newton iteration
    int skipped = 0;           // iterations in a row without a boost step

    bool skip(double threshold) const
    {
      return skipped < max_skipped && last_gain < threshold && last_gain < 1e-2 * last_decrease;
    }
    void record(double gain) { last_gain = gain; skipped = 0; }
  };

  // One Moebius boost step if the minimization makes them: what it gains (the map and its
  // energy `e` updated), 0 without boost steps. Before every iteration, and before a stop on
  // a predicted decrement: the decrement leaves the boosts out, and the conformal energies
  // slide along them (Dirichlet at 302k faces stopped 2e-4 of its energy above its minimum
  // on a decrement of 1.5e-3).
  template <class Energy>
  double boost_gain(const Spherical_energy<Energy>& energy, Points& x, double& e)
  {
    if(!boost_search_ || free_ != n_)
      return 0;
    const double before = e;
    boost_step(x, [&](const Points& y) { return total_energy(energy, y); }, e);
    return before - e;
  }

  // Newton's decrement converges quadratically near a minimum, d_next = C d^2, with C
  // estimated from the last two: d^3 / previous^2. Without a previous full step, or if the
  // decrement did not shrink by 4, no prediction: the decrement itself is returned.
  static double predicted_decrement(double previous, double decrement)
  {
    if(!(previous > 4 * decrement))
      return decrement;
    return decrement * (decrement / previous) * (decrement / previous);
  }

  // The energy decreased by less than `threshold` over the last iterations: a slow
  // linear tail, such as faces pressed against the fold barrier in a squeezed protrusion,
  // where the map no longer changes visibly.
  static bool stalled(const std::vector<double>& history, double threshold)
  {
    return recent_gain(history, 10) <= threshold;
  }

  // The energy gained over the last `window` iterations; infinite if there were fewer.
  static double recent_gain(const std::vector<double>& history, std::size_t window)
  {
    if(history.size() <= window)
      return std::numeric_limits<double>::infinity();
    return history[history.size() - 1 - window] - history.back();
  }

  template <class Number>
  Number barrier(std::size_t f, const Points& x) const
  {
    const auto& t = (*faces_)[f];
    return Fold_barrier::energy(Chord_triangle<Number>(x[t[0]], x[t[1]], x[t[2]]), barrier_data_[f], floor_,
                                outer_weight_, floored_activation_);
  }

  void build_pattern()
  {
    // Lower triangle of the matrix of the free vertices: 2x2 blocks on the diagonal and at
    // every edge between two of them, written column by column from the vertex adjacency.
    // Per-face triplets took 0.9 s at 300k faces, of a set-up of 2.2 s.
    const std::vector<std::vector<int>> later = later_neighbours();
    const int size = int(2 * free_);
    std::size_t entries = 0;
    for(const std::vector<int>& n : later)
      entries += 4 * n.size() + 3;
    matrix_.resize(size, size);
    matrix_.resizeNonZeros(Eigen::Index(entries));
    int* outer = matrix_.outerIndexPtr();
    int* inner = matrix_.innerIndexPtr();
    int k = 0;
    for(int column = 0; column < size; ++column) {
      const int v = column / 2;
      outer[column] = k;
      for(int row = column; row < 2 * v + 2; ++row)  // the diagonal block
        inner[k++] = row;
      for(int u : later[v]) {
        inner[k++] = 2 * u;
        inner[k++] = 2 * u + 1;
      }
    }
    outer[size] = k;
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + k, 0.0);

    // Where the entry (row, col) of the lower triangle is: in column `col` of vertex v, the
    // diagonal block comes first, then the blocks of `later[v]` in their order.
    const auto position = [&](int row, int col) {
      const int v = col / 2, u = row / 2;
      if(u == v)
        return outer[col] + row - col;
      const std::vector<int>& n = later[v];
      const int rank = int(std::lower_bound(n.begin(), n.end(), u) - n.begin());
      return outer[col] + 2 - col % 2 + 2 * rank + row % 2;
    };
    entry_index_.resize(faces_->size() * lower_entries);
    for(std::size_t f = 0; f < faces_->size(); ++f)
      for_each_lower_entry((*faces_)[f], [&](int local, int row, int col) {
        entry_index_[f * lower_entries + local] = row < size ? position(row, col) : -1;
      });
    diagonal_index_.resize(size);
    for(int i = 0; i < size; ++i)
      diagonal_index_[i] = outer[i];
  }

  // For each free vertex, its free neighbours of larger index, sorted.
  std::vector<std::vector<int>> later_neighbours() const
  {
    std::vector<std::vector<int>> later(free_);
    for(const auto& t : *faces_)
      for(int i = 0; i < 3; ++i) {
        const int a = std::min(t[i], t[(i + 1) % 3]), b = std::max(t[i], t[(i + 1) % 3]);
        if(std::size_t(b) < free_)
          later[a].push_back(b);
      }
    for(std::vector<int>& n : later) {
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    return later;
  }

  // Calls fn(local, row, col) for the 21 lower entries (i >= j) of a face's 6x6 block,
  // with (row, col) the global entry, swapped into the lower triangle.
  template <class Fn>
  static void for_each_lower_entry(const std::array<int, 3>& t, Fn fn)
  {
    int local = 0;
    for(int i = 0; i < 6; ++i)
      for(int j = 0; j <= i; ++j) {
        int row = 2 * t[i / 2] + i % 2, col = 2 * t[j / 2] + j % 2;
        if(row < col) std::swap(row, col);
        fn(local++, row, col);
      }
  }

  // A face's 9x9 ambient Hessian pulled back to the tangent variables of its vertices.
  Face_hessian tangent_hessian(std::size_t f, const Triangle_jet::Hessian& ambient) const
  {
    const auto& t = (*faces_)[f];
    Face_hessian h;
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j)
        h.template block<2, 2>(2 * i, 2 * j) =
          bases_[t[i]].transpose() * ambient.template block<3, 3>(3 * i, 3 * j) * bases_[t[j]];
    return h;
  }

  void compute_bases(const Points& x)
  {
    bases_.resize(n_);
    for(std::size_t v = 0; v < n_; ++v)
      bases_[v] = tangent_basis(x[v]);
  }

  // Per face: the tangent Hessian, projected to PSD if asked. Fills gradient_ (tangent),
  // ambient_gradient_ and matrix_ (without shift).
  template <class Energy>
  void assemble(const Spherical_energy<Energy>& energy, const Points& x, bool projected)
  {
    const std::size_t nf = faces_->size();
    face_gradient_.resize(nf);
    face_hessian_.resize(nf * lower_entries);
    parallel_for<ConcurrencyTag>(nf, [&](std::size_t f) {
      Triangle_jet jet = energy.template face<Triangle_jet>(f, x);
      // The barrier is not convex in the points (det is trilinear): a face it holds gets
      // its Hessian made positive definite, while the others keep their exact one
      // (measured on camel's fold-free stage: 104 -> 90 iterations, 13 -> 7.8 s).
      const bool held = with_barrier_ && barrier<double>(f, x) > 0;
      if(held)
        jet += barrier<Triangle_jet>(f, x);
      face_gradient_[f] = jet.gradient;
      Face_hessian h = tangent_hessian(f, jet.hessian);
      if(projected || held)
        project_to_psd(h);
      double* out = &face_hessian_[f * lower_entries];
      for(int i = 0; i < 6; ++i)
        for(int j = 0; j <= i; ++j)
          *out++ = h(i, j);
    });

    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
    ambient_gradient_.assign(n_, Eigen::Vector3d::Zero());
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& t = (*faces_)[f];
      for(int i = 0; i < 3; ++i)
        ambient_gradient_[t[i]] += face_gradient_[f].template segment<3>(3 * i);
      const double* h = &face_hessian_[f * lower_entries];
      const int* index = &entry_index_[f * lower_entries];
      for(int k = 0; k < lower_entries; ++k)
        if(index[k] >= 0)
          matrix_.valuePtr()[index[k]] += h[k];
    }
    gradient_.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v) {
      gradient_.template segment<2>(2 * v) = bases_[v].transpose() * ambient_gradient_[v];
      // Second-order term of the retraction x = (p + B u) / |p + B u|: -<g_v, x_v> I_2.
      const double curvature = -ambient_gradient_[v].dot(x[v]);
      matrix_.valuePtr()[diagonal_index_[2 * v]] += curvature;
      matrix_.valuePtr()[diagonal_index_[2 * v + 1]] += curvature;
    }
  }

  // The exact Hessian with a shift of at most 1e-3 x its mean diagonal; where that is not
  // enough (strongly non-convex faces, such as a barrier or area term far from its minimum),
  // the per-face projected Hessian, whose shift then only handles the curvature term.
  // Block Jacobi: each vertex's own 2x2 block of the exact Hessian, its eigenvalues replaced by
  // their absolute values (at least a small fraction of the block's size).
  // With a coarse correction c, a two-grid cycle on the Newton system H d = -g that shares
  // the one assembly: d = c + J^-1 (-g - H c), J the block diagonal. The coarse step
  // lowers the smooth error that block Jacobi hardly sees (302k faces, Combined: the first
  // Newton decrement 1.34 -> 0.45). Block Jacobi alone if the cycle's direction is not one
  // of descent. True if the direction is the two-grid cycle's.
  template <class Energy>
  bool smoothing_direction(const Spherical_energy<Energy>& energy, const Points& x,
                           const Coarse_correction* coarse_correction, Vector& d)
  {
    assemble(energy, x, false);
    Vector coarse_step;
    Vector residual = -gradient_;
    if(coarse_correction && coarse_step_of(*coarse_correction, x, coarse_step))
      residual.noalias() -= matrix_.template selfadjointView<Eigen::Lower>() * coarse_step;
    block_jacobi(residual, d);
    if(coarse_step.size() == 0)
      return false;
    d += coarse_step;
    if(gradient_.dot(d) < 0)
      return true;
    block_jacobi(-gradient_, d);
    return false;
  }

  // The coarse correction of the gradient_, in the tangent charts; false if it failed.
  bool coarse_step_of(const Coarse_correction& coarse_correction, const Points& x, Vector& step) const
  {
    std::vector<Eigen::Vector3d> gradient(n_, Eigen::Vector3d::Zero()), displacement;
    for(std::size_t v = 0; v < free_; ++v)
      gradient[v] = bases_[v] * gradient_.template segment<2>(2 * v);
    if(!coarse_correction(x, gradient, displacement) || displacement.size() != n_)
      return false;
    step.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v)
      step.template segment<2>(2 * v) = bases_[v].transpose() * displacement[v];
    return step.allFinite();
  }

  // d = J^-1 r for the block diagonal J of the assembled Hessian.
  void block_jacobi(const Vector& r, Vector& d) const
  {
    d.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v) {
      const int k = diagonal_index_[2 * v];  // (2v, 2v), then (2v + 1, 2v) below it in the column
      Eigen::Matrix2d block;
      block << matrix_.valuePtr()[k], matrix_.valuePtr()[k + 1], matrix_.valuePtr()[k + 1],
               matrix_.valuePtr()[diagonal_index_[2 * v + 1]];
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(block);
      const double floor = 1e-6 * eigen.eigenvalues().cwiseAbs().maxCoeff() + std::numeric_limits<double>::min();
      const Eigen::Vector2d inverse = eigen.eigenvalues().cwiseAbs().cwiseMax(floor).cwiseInverse();
      d.template segment<2>(2 * v) =
        (eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose()) * r.template segment<2>(2 * v);
    }
  }

  template <class Energy>
  bool newton_direction(const Spherical_energy<Energy>& energy, const Points& x, bool projected_only, Vector& d)
  {
    // After the exact Hessian failed, skip it for a few iterations: each failure costs an
    // assembly and a factorization.
    const bool try_exact = !projected_only && exact_pause_ == 0;
    if(exact_pause_ > 0)
      --exact_pause_;
    if(try_exact && shifted_newton_direction(energy, x, false, mu_exact_, 1e-3, d))
      return true;
    if(try_exact)
      exact_pause_ = 4;
    return shifted_newton_direction(energy, x, true, mu_projected_, std::numeric_limits<double>::infinity(), d);
  }

  // Solves (H + mu I) d = -g with the smallest shift mu >= its floor, grown x8 per failed
  // factorization. False if mu would exceed `max_relative_shift` x the mean diagonal.
  template <class Energy>
  bool shifted_newton_direction(const Spherical_energy<Energy>& energy, const Points& x, bool projected,
                                double& mu, double max_relative_shift, Vector& d)
  {
    assemble(energy, x, projected);
    double mean_diagonal = 0;
    for(std::size_t i = 0; i < 2 * free_; ++i)
      mean_diagonal += std::abs(matrix_.valuePtr()[diagonal_index_[i]]);
    mean_diagonal /= double(2 * free_);
    if(!std::isfinite(mean_diagonal) || mean_diagonal == 0)
      return false;
    mu_floor_ = 1e-9 * mean_diagonal;
    mu = std::max(mu == 0 && !projected ? first_shift_ * mean_diagonal : mu, mu_floor_);
    std::vector<double> diagonal(2 * free_);  // only the diagonal changes with the shift
    for(std::size_t i = 0; i < 2 * free_; ++i)
      diagonal[i] = matrix_.valuePtr()[diagonal_index_[i]];
    for(int attempt = 0; attempt < 60 && mu <= max_relative_shift * mean_diagonal; ++attempt, mu *= 8) {
      for(std::size_t i = 0; i < 2 * free_; ++i)
        matrix_.valuePtr()[diagonal_index_[i]] = diagonal[i] + mu;
      factored_ = solver_.factorize(matrix_);
      if(factored_) {
        shift_raised_ = attempt > 0;
        d = solver_.solve(-gradient_);
        return d.allFinite();
      }
    }
    mu = std::min(mu, max_relative_shift * mean_diagonal);
    return false;
  }

  std::vector<Eigen::Vector3d> ambient_step(const Vector& d) const
  {
    std::vector<Eigen::Vector3d> v(n_, Eigen::Vector3d::Zero());
    for(std::size_t i = 0; i < free_; ++i)
      v[i] = bases_[i] * d.template segment<2>(2 * i);
    return v;
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

  // Armijo backtracking from `alpha`; returns the accepted energy (or +inf) with the point in `trial`.
  template <class Energy>
  double line_search(const Spherical_energy<Energy>& energy, const Points& x, const Vector& d, double e0,
                     double decrement, double& alpha, Points& trial)
  {
    for(int k = 0; k < 50 && alpha > 0; ++k, alpha *= 0.5) {
      for(std::size_t v = 0; v < n_; ++v)
        trial[v] = v < free_ ? retract(x[v], bases_[v], alpha * d.template segment<2>(2 * v)) : x[v];
      const double e = total_energy(energy, trial);
      if(std::isfinite(e) && e <= e0 - 1e-4 * alpha * decrement)
        return e;
    }
    return std::numeric_limits<double>::infinity();
  }

  const Faces* faces_;
  std::size_t n_;
  std::size_t free_;  // the unknowns: vertices 0 to free_ - 1
  bool with_barrier_ = false;
  std::vector<Fold_barrier::Face_data> barrier_data_;
  double floor_ = 0;  // the barrier's activation
  double outer_weight_ = 0;
  double floored_activation_ = 0;
  Matrix matrix_;
  std::vector<int> entry_index_;
  std::vector<int> diagonal_index_;
  SparseSolver solver_;
  bool factored_ = false;  // the last factorization succeeded: `solver_` holds a factor
  int exact_pause_ = 0;  // iterations to go before the exact Hessian is tried again
  bool shift_raised_ = false;  // the last factorization needed a larger shift than its first try
  double mu_exact_ = 0, mu_projected_ = 0, mu_floor_ = 0;
  double first_shift_ = 1e-4;  // Newton_options::first_shift of the minimization under way
  bool boost_search_ = false;   // Newton_options::boost_search of the minimization under way

  std::vector<Basis> bases_;
  std::vector<Triangle_jet::Gradient> face_gradient_;
  std::vector<double> face_hessian_;
  std::vector<double> face_value_;
  std::vector<Eigen::Vector3d> ambient_gradient_;
  Vector gradient_;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_SOLVER_H
