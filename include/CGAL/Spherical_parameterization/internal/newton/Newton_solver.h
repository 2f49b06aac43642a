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
#include <CGAL/Spherical_parameterization/internal/newton/project_psd.h>
#include <CGAL/Spherical_parameterization/internal/newton/step_bound.h>
#include <CGAL/Spherical_parameterization/internal/newton/tangent_basis.h>

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
/// - the exact Hessian in the tangent charts: each face's 9x9 ambient Hessian pulled to its
///   6 tangent variables, plus the sphere-curvature term `-<g_v, x_v> I_2` of each vertex.
///   Projecting it to PSD instead hides the negative curvature of the near-Moebius modes
///   along which a map slides, and costs an order of magnitude more iterations;
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
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Vector = Eigen::VectorXd;
  using Basis = Eigen::Matrix<double, 3, 2>;
  using Face_hessian = Eigen::Matrix<double, 6, 6>;
  static constexpr int lower_entries = 21;  // of a symmetric 6x6 matrix

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
  // Stops: a model-matching full step with a decrement under this many thresholds (the next
  // one is quadratically smaller); a predicted decrement under this share of the threshold
  // (the prediction errs by up to 20 times); a decrease under this share of it; less than
  // the threshold gained over the last `stall_window` iterations.
  static constexpr double quadratic_tail_margin = 10;
  static constexpr double predicted_margin = 1e-2;
  static constexpr double negligible_decrease = 1e-2;
  static constexpr std::size_t stall_window = 10;

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
    drop_rotation_curvature_ = options.drop_rotation_curvature;
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
      else if(!newton_direction(energy, x, d)) { out.stop = Newton_stop::STALLED; break; }

      double decrement = -gradient_.dot(d);
      double threshold = options.tolerance * std::abs(e + options.held_energy);
      if(!(decrement > threshold)) { out.stop = Newton_stop::CONVERGED; break; }

      double alpha = 1;
      auto fold_free_cap = [&] {
        if(options.keep_fold_free)
          alpha = std::min(1.0, step_cap_share * largest_fold_free_step(*faces_, x, ambient_step(d)));
      };
      fold_free_cap();
      bool capped = alpha < 1;
      double e_new = line_search(energy, x, d, e, decrement, alpha, trial);
      if(two_grid && alpha < 1) {
        // The line search had to shorten the two-grid step: the last level's Hessian does
        // not model the input's energy here (a level that ended on its fold barrier, as
        // squeezed protrusions do). Block Jacobi alone.
        block_jacobi(-gradient_, d);
        decrement = -gradient_.dot(d);
        alpha = 1;
        fold_free_cap();
        capped = alpha < 1;
        e_new = line_search(energy, x, d, e, decrement, alpha, trial);
      }
      if(options.extend_projected_steps && alpha == 1 && !smoothing && projected_ && !options.keep_fold_free)
        e_new = extend_step(energy, x, d, e_new, alpha, trial);
      if(!(e_new < e)) {
        // No decrease along a direction of descent: precision is exhausted, or the
        // shift is too small for this non-convex stretch. Grow it once before giving up.
        if(mu_projected_ < max_retry_shift * mu_floor_) {
          mu_exact_ *= retry_shift_growth;
          mu_projected_ *= retry_shift_growth;
          ++out.iterations;
          continue;
        }
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
      relax_shifts(alpha >= 1, smoothing);

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
      // is far below it: the next decrement is quadratically smaller, no need to factor again
      // to see it.
      const bool model_held = !smoothing && alpha == 1 && std::abs(decrease - decrement / 2) <= model_agreement * decrement;
      const double predicted = predicted_decrement(last_full_decrement, decrement);
      last_full_decrement = model_held ? decrement : 0;
      const bool quadratic_tail =
        model_held && (decrement <= quadratic_tail_margin * threshold ||
                       (options.predict_convergence && predicted <= predicted_margin * threshold));
      // With `predict_convergence`, also a step of at least Newton's length that gained under
      // the threshold, its decrement under `quadratic_tail_margin` thresholds: the projected
      // model's extended steps, whose decrements shrink at a linear rate, stop here rather
      // than factor once more only to find the next decrement under the threshold.
      const bool linear_tail = options.predict_convergence && !smoothing && alpha >= 1 && decrease <= threshold &&
                               decrement <= quadratic_tail_margin * threshold;
      const bool tail = quadratic_tail || linear_tail;
      if(tail && options.predict_convergence && boost_gain(energy, x, e) > threshold) {
        out.energy = e;
        continue;
      }
      if(tail || decrease <= negligible_decrease * threshold || stalled(history, threshold) ||
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
    Points().swap(probe_);
  }

  /// Allocates the buffers of the first assembly and the factor (the solver traits'
  /// `allocate_factor()`, if they have it) and writes them once. Fresh memory is slow on
  /// virtual machines (a page fault in the host per page), so the coarse-to-fine solve calls
  /// this on another thread while it works on the coarser levels, when nothing else uses
  /// this solver.
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
  // Half the threshold: the slides this stops gain a few thresholds per iteration for dozens
  // of iterations, depending on rounding alone; the whole threshold leaves energies higher
  // than a converged map's by more than the tests allow.
  static constexpr double capped_tail_gain = 0.5;
  // Three iterations: as good a stop as five, two iterations sooner.
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

  // After an iteration, the shifts are relaxed towards their floor: most after a full step,
  // which says the model holds; least if the shift had to grow in this iteration, as a
  // failure costs a whole factorization (the negative modes are global, found in the last
  // supernode); the exact shift not at all while the exact Hessian is paused, so that it
  // does not climb back through failed factorizations to where it was.
  void relax_shifts(bool full_step, bool smoothing)
  {
    const double relax = shift_raised_ && !smoothing ? relax_after_growth : full_step ? relax_after_full_step : relax_after_short_step;
    if(exact_pause_ == 0)
      mu_exact_ = std::max(mu_exact_ / relax, mu_floor_);
    mu_projected_ = std::max(mu_projected_ / relax, mu_floor_);
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

  // Newton's decrement converges quadratically near a minimum, d_next = C d^2, with C
  // estimated from the last two: d^3 / previous^2. Without a previous full step, or if the
  // decrement did not shrink by 4, no prediction: the decrement itself is returned.
  static constexpr double min_quadratic_shrink = 4;
  static double predicted_decrement(double previous, double decrement)
  {
    if(!(previous > min_quadratic_shrink * decrement))
      return decrement;
    return decrement * (decrement / previous) * (decrement / previous);
  }

  // The energy decreased by less than `threshold` over the last iterations: a slow
  // linear tail, such as faces pressed against the fold barrier in a squeezed protrusion,
  // where the map no longer changes visibly.
  static bool stalled(const std::vector<double>& history, double threshold)
  {
    return recent_gain(history, stall_window) <= threshold;
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
    // every edge between two of them, written column by column from the vertex adjacency
    // (per-face triplets would cost nearly half the set-up).
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

  // An orthonormal basis of the tangent directions that rotate the three points of face `f`
  // together about the centre (the face's energy is invariant along them). A face whose
  // points coincide has only two; a direction lost to rounding is left out (a zero column).
  Eigen::Matrix<double, 6, 3> face_rotations(std::size_t f, const Points& x) const
  {
    const auto& t = (*faces_)[f];
    Eigen::Matrix<double, 6, 3> r;
    for(int k = 0; k < 3; ++k) {
      for(int i = 0; i < 3; ++i)
        r.template block<2, 1>(2 * i, k) = bases_[t[i]].transpose() * Eigen::Vector3d::Unit(k).cross(x[t[i]]);
      const double length = r.col(k).norm();
      for(int j = 0; j < k; ++j)  // Gram-Schmidt
        r.col(k) -= r.col(j).dot(r.col(k)) * r.col(j);
      const double left = r.col(k).norm();
      if(left > 1e-8 * length)
        r.col(k) /= left;
      else
        r.col(k).setZero();
    }
    return r;
  }

  void compute_bases(const Points& x)
  {
    bases_.resize(n_);
    for(std::size_t v = 0; v < n_; ++v)
      bases_[v] = tangent_basis(x[v]);
  }

  // A face's Hessian made PSD where the barrier does not hold it. With
  // `drop_rotation_curvature`, its negative curvature along the rotations of its three
  // points, which comes from the chart (the energy is invariant along them), is dropped
  // rather than made absolute: made absolute, it adds about the face's energy to the
  // stiffness of every smooth mode of the map, which is the order of those modes' own.
  void project_free_face(Face_hessian& h, std::size_t f, const Points& x) const
  {
    if(drop_rotation_curvature_)
      project_to_psd(h, face_rotations(f, x));
    else
      project_to_psd(h);
  }

  // A face the barrier holds keeps the absolute value of every negative eigenvalue: its
  // gradient is the barrier's, which makes the curvature along its rotations large, and
  // made absolute it damps the capped steps of the continuation and floor stages.
  static void project_held_face(Face_hessian& h) { project_to_psd(h); }

  // Per face: the tangent Hessian, projected to PSD if asked. Fills gradient_ (tangent),
  // ambient_gradient_ and matrix_ (without shift).
  template <class Energy>
  void assemble(const Spherical_energy<Energy>& energy, const Points& x, bool projected)
  {
    const std::size_t nf = faces_->size();
    face_gradient_.resize(nf);
    face_hessian_.resize(nf * lower_entries);
    held_.resize(nf);
    parallel_for<ConcurrencyTag>(nf, [&](std::size_t f) {
      Triangle_jet jet = energy.template face<Triangle_jet>(f, x);
      // The barrier is not convex in the points (det is trilinear): a face it holds gets
      // its Hessian made positive definite, while the others keep their exact one.
      const bool held = with_barrier_ && barrier<double>(f, x) > 0;
      held_[f] = held;
      if(held)
        jet += barrier<Triangle_jet>(f, x);
      face_gradient_[f] = jet.gradient;
      Face_hessian h = tangent_hessian(f, jet.hessian);
      if(held)
        project_held_face(h);
      else if(projected)
        project_free_face(h, f, x);
      store_lower(h, f);
    });
    sum_face_terms(x);
  }

  // After an assembly of the exact Hessian at `x`: the same face terms with every face's
  // Hessian projected, as `assemble(energy, x, true)` gives them, without evaluating the
  // faces again (the projection reads only the lower triangle that the assembly kept).
  void project_assembled_faces(const Points& x)
  {
    parallel_for<ConcurrencyTag>(faces_->size(), [&](std::size_t f) {
      if(held_[f])
        return;  // projected already
      Face_hessian h;
      const double* in = &face_hessian_[f * lower_entries];
      for(int i = 0; i < 6; ++i)
        for(int j = 0; j <= i; ++j)
          h(i, j) = h(j, i) = *in++;
      project_free_face(h, f, x);
      store_lower(h, f);
    });
    sum_face_terms(x);
  }

  void store_lower(const Face_hessian& h, std::size_t f)
  {
    double* out = &face_hessian_[f * lower_entries];
    for(int i = 0; i < 6; ++i)
      for(int j = 0; j <= i; ++j)
        *out++ = h(i, j);
  }

  // The matrix (without shift) and the gradients from the face terms.
  void sum_face_terms(const Points& x)
  {
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
    ambient_gradient_.assign(n_, Eigen::Vector3d::Zero());
    for(std::size_t f = 0; f < faces_->size(); ++f) {
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

  // The exact Hessian with a shift of at most `max_exact_shift` of its mean diagonal; where that is not
  // enough (strongly non-convex faces, such as a barrier or area term far from its minimum),
  // the per-face projected Hessian, whose shift then only handles the curvature term.
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

  // d = J^-1 r for the block diagonal J of the assembled Hessian, each block's eigenvalues
  // replaced by their absolute values, at least this share of the largest (a near-singular
  // block, such as a vertex whose faces are all flat along one direction, must not blow up).
  static constexpr double block_jacobi_floor = 1e-6;
  void block_jacobi(const Vector& r, Vector& d) const
  {
    d.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v) {
      const int k = diagonal_index_[2 * v];  // (2v, 2v), then (2v + 1, 2v) below it in the column
      Eigen::Matrix2d block;
      block << matrix_.valuePtr()[k], matrix_.valuePtr()[k + 1], matrix_.valuePtr()[k + 1],
               matrix_.valuePtr()[diagonal_index_[2 * v + 1]];
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(block);
      const double floor =
        block_jacobi_floor * eigen.eigenvalues().cwiseAbs().maxCoeff() + std::numeric_limits<double>::min();
      const Eigen::Vector2d inverse = eigen.eigenvalues().cwiseAbs().cwiseMax(floor).cwiseInverse();
      d.template segment<2>(2 * v) =
        (eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose()) * r.template segment<2>(2 * v);
    }
  }

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
      project_assembled_faces(x);
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
    double mean_diagonal = 0;
    for(std::size_t i = 0; i < 2 * free_; ++i)
      mean_diagonal += std::abs(matrix_.valuePtr()[diagonal_index_[i]]);
    mean_diagonal /= double(2 * free_);
    if(!std::isfinite(mean_diagonal) || mean_diagonal == 0)
      return false;
    mu_floor_ = min_shift * mean_diagonal;
    mu = std::max(mu == 0 && !projected ? first_shift_ * mean_diagonal : mu, mu_floor_);
    std::vector<double> diagonal(2 * free_);  // only the diagonal changes with the shift
    for(std::size_t i = 0; i < 2 * free_; ++i)
      diagonal[i] = matrix_.valuePtr()[diagonal_index_[i]];
    for(int attempt = 0; attempt < max_shift_attempts && mu <= max_relative_shift * mean_diagonal; ++attempt, mu *= shift_growth) {
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
      step_to(x, d, a, probe_);
      const double e_probe = total_energy(energy, probe_);
      if(!(e_probe < e) || (fold_free && count_bad_faces(*faces_, probe_) > 0))
        break;
      e = e_probe;
      alpha = a;
      trial.swap(probe_);
    }
    return e;
  }

  // The points `x` moved by `alpha d` in their tangent charts; the fixed vertices stay.
  void step_to(const Points& x, const Vector& d, double alpha, Points& out) const
  {
    for(std::size_t v = 0; v < n_; ++v)
      out[v] = v < free_ ? retract(x[v], bases_[v], alpha * d.template segment<2>(2 * v)) : x[v];
  }

  // Armijo backtracking from `alpha`; returns the accepted energy (or +inf) with the point in `trial`.
  template <class Energy>
  double line_search(const Spherical_energy<Energy>& energy, const Points& x, const Vector& d, double e0,
                     double decrement, double& alpha, Points& trial)
  {
    for(int k = 0; k < max_halvings && alpha > 0; ++k, alpha *= 0.5) {
      step_to(x, d, alpha, trial);
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
  Matrix matrix_;
  std::vector<int> entry_index_;
  std::vector<int> diagonal_index_;
  SparseSolver solver_;
  bool factored_ = false;  // the last factorization succeeded: `solver_` holds a factor
  bool projected_ = false;  // the last Newton direction came from the projected Hessian
  int exact_pause_ = 0;  // iterations to go before the exact Hessian is tried again
  bool shift_raised_ = false;  // the last factorization needed a larger shift than its first try
  double mu_exact_ = 0, mu_projected_ = 0, mu_floor_ = 0;
  double first_shift_ = 1e-4;  // Newton_options::first_shift of the minimization under way
  bool boost_search_ = false;   // Newton_options::boost_search of the minimization under way

  std::vector<Basis> bases_;
  std::vector<Triangle_jet::Gradient> face_gradient_;
  std::vector<double> face_hessian_;
  std::vector<char> held_;  // per face: held by the fold barrier at the last assembly
  std::vector<double> face_value_;
  std::vector<Eigen::Vector3d> ambient_gradient_;
  Vector gradient_;
  Points probe_;  // the points of a step's extension
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_NEWTON_SOLVER_H
