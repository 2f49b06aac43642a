// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_ROBUST_PIPELINE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_ROBUST_PIPELINE_H

#include <CGAL/Spherical_parameterization/Result.h>
#include <CGAL/Spherical_parameterization/Tutte_energy.h>
#include <CGAL/Spherical_parameterization/internal/backends/parallel_for.h>
#include <CGAL/Spherical_parameterization/internal/energies/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/energies/Untangling_energy.h>
#include <CGAL/Spherical_parameterization/internal/energies/area_barrier.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Coarse_to_fine.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Level.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/input/initialization.h>
#include <CGAL/Spherical_parameterization/internal/newton/Newton_solver.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/Floor_patch.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/Pipeline_settings.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/next_stage.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// What a run of the pipeline did: the stages with their iterations, whether it was
/// interrupted, and what an interruption returns. Stages append to it; the only thing the
/// pipeline reads back is whether it was interrupted.
struct Run_log
{
  std::vector<Stage_report> stages;
  std::size_t iterations = 0;
  std::optional<Newton_stop> interruption;      ///< `CANCELLED` or `TIME_LIMIT`
  std::optional<Points> last_valid_input_map;   ///< the start of the input's fold-free minimization
  Newton_stop input_stop = Newton_stop::CONVERGED;  ///< how the input's last stage ended

  bool interrupted() const { return interruption.has_value(); }
};

/// Where a level stands in the coarse-to-fine solve.
struct Level_role
{
  std::size_t vertices = 0;        ///< of the level, for the stage reports
  bool is_input = false;
  bool last_before_input = false;  ///< the last coarser level
  bool previous_rejected = false;  ///< the level before ended without its optimistic minimum
};

/// How a level's minimization ended.
struct Level_outcome
{
  bool uninterrupted = true;
  bool optimistic_rejected = false;  ///< its result is not its optimistic stage's minimum
};

/// The robust pipeline (doc/DESIGN.md, "The pipeline, stage by stage"): coarse to fine, each
/// level kept fold-free through its vertex splits and minimized by `fold_free_minimization()`,
/// whose stages `next_stage()` chooses. Every stage is a function of the level, the map and
/// the Newton options it is given by value; the settings are constant.
template <class Energy, class Newton, class ConcurrencyTag, class Visitor>
class Robust_pipeline
{
public:
  using Level = internal::Level<Newton>;

  /// `options` holds the user's tolerance, iteration cap and deadline. With `moebius_boosts`
  /// false (the paper's pipeline) no stage makes boost steps.
  Robust_pipeline(Level& input, const Energy& energy, bool correction, const Pipeline_settings& settings,
                  const Newton_options& options, bool moebius_boosts, Visitor& visitor)
    : input_(input), energy_(energy), correction_(correction), settings_(settings), options_(options),
      moebius_boosts_(moebius_boosts), visitor_(visitor)
  {
    options_.fold_floor = settings_.fold_floor;
  }

  const Run_log& log() const { return log_; }

  /// The paper's recipe: the chosen energy from `x`, with no fold-free guarantee.
  void plain(Points& x)
  {
    make_input_solver();
    minimize(energy_, Stage::PLAIN, input_role(), input_, x, options_);
  }

  /// The robust stages on the input from `x`, a map of degree 1 (a re-solve, or the user's start).
  void robust_from(Points& x)
  {
    make_input_solver();
    robust_stages(input_, x, input_role(), options_);
  }

  /// The coarse-to-fine solve from scratch, keeping the progressive mesh in `hierarchy` for
  /// the next solves. False if no start of degree 1 was found.
  bool coarse_to_fine(Points& x, std::unique_ptr<Progressive_mesh>& hierarchy)
  {
    // The input's solver (its symbolic analysis) and the memory of its first assembly and
    // factorization are made on another core while the hierarchy is built and the coarser
    // levels run: only the input level needs them.
    Background_task<ConcurrencyTag> input_solver([this] {
      make_input_solver();
      input_.solver->prepare_memory();
    });
    const std::size_t n = input_.number_of_vertices();
    if(!hierarchy)
      hierarchy = std::make_unique<Progressive_mesh>(input_.soup,
                                                     n <= 2 * settings_.coarse_vertices ? n : settings_.coarse_vertices);
    // A large input's two-grid cycle, for energies without an area barrier only (see
    // `Pipeline_settings::input_smoothing_steps`).
    const bool two_grid = is_large_input() && !has_area_barrier(energy_);
    Coarse_to_fine<Newton, ConcurrencyTag> levels(input_.soup, *hierarchy, settings_.level_ratio, two_grid);
    const Coarse_correction coarse_correction = [&levels](const auto& map, const auto& gradient, auto& step) {
      return levels.coarse_correction(map, gradient, step);
    };

    Points level_x;
    Level* coarse = levels.level();
    if(!coarse || !central_start(*coarse, level_x)) {  // the input itself, from its own projection
      input_solver.wait();
      if(!central_start(input_, x))
        return false;
      robust_stages(input_, x, input_role(), options_, false);  // a restart would be this start again
      return true;
    }
    x.assign(n, Eigen::Vector3d::Zero());
    Level_outcome outcome = robust_stages(
      *coarse, level_x, {coarse->number_of_vertices(), false, levels.last_before_input(), false}, options_, false);
    coarse->scatter(level_x, x);
    while(levels.refine(x)) {
      if(!outcome.uninterrupted)
        continue;  // only the splits: a valid map of the input, quickly
      Level* level = levels.level();
      if(level)
        level->gather(x, level_x);
      else
        input_solver.wait();
      Level& current = level ? *level : input_;
      Points& y = level ? level_x : x;
      const Level_role role{current.number_of_vertices(), !level, level && levels.last_before_input(),
                            outcome.optimistic_rejected};
      outcome = current.has_fold(y) ? robust_stages(current, y, role, options_)
                                    : after_splits(current, y, role, two_grid ? &coarse_correction : nullptr);
      if(level)
        level->scatter(y, x);
    }
    return true;
  }

private:
  Level_role input_role() const { return {input_.number_of_vertices(), true, false, false}; }

  // The input starts differently after its splits (`Pipeline_settings::large_input_vertices`).
  bool is_large_input() const { return input_.number_of_vertices() > settings_.large_input_vertices; }

  // From a start of degree 1: Tutte with the d_min barrier while faces are folded (fold-free
  // on most meshes), untangling if that is not enough, then the chosen energy without ever
  // letting a face flip. A start that stays folded may hold a face at the hemisphere barrier,
  // where every step is rejected: with `may_restart`, the level starts once more from its own
  // central projection. With no fold-free map, the chosen energy plainly.
  Level_outcome robust_stages(Level& level, Points& x, const Level_role& role, const Newton_options& options,
                              bool may_restart = true)
  {
    const Level_outcome interrupted{false, role.previous_rejected};
    if(level.has_fold(x) && !tutte_stage(level, x, role, options))
      return interrupted;
    if(level.has_fold(x) && !untangle(level, x, role, options, settings_.untangling_rounds, Stage::UNTANGLING))
      return interrupted;
    if(level.has_fold(x) && may_restart) {
      Points restart;
      if(central_start(level, restart)) {
        x = std::move(restart);
        level.solver->forget_shifts();
        return robust_stages(level, x, role, options, false);
      }
    }
    if(level.has_fold(x)) {
      minimize(energy_, Stage::PLAIN, role, level, x, options);
      return {!log_.interrupted(), true};
    }
    return fold_free_minimization(level, x, role, options, 0, nullptr);
  }

  // A level after its vertex splits, fold-free: a few iterations for a coarser level, whose
  // map is only the next level's start; the input to the tolerance, its first step a
  // two-grid cycle if given one.
  Level_outcome after_splits(Level& level, Points& x, const Level_role& role, const Coarse_correction* two_grid)
  {
    Newton_options options = options_;
    const bool large_input = role.is_input && is_large_input();
    if(role.is_input) {
      options.predict_convergence = true;
      options.leave_under_floor = true;
      if(large_input)
        options.first_shift = std::max(settings_.large_input_shift_numerator / double(level.number_of_vertices()),
                                       settings_.large_input_min_shift);
    } else {
      options.max_iterations = std::min(options.max_iterations, settings_.level_iterations);
      options.tolerance = std::max(options.tolerance, settings_.level_tolerance);
    }
    // One smoothing step first: most of the error a split leaves is local; on a large input
    // and an energy with an area barrier, `input_smoothing_steps`.
    const std::size_t smoothing = large_input && has_area_barrier(energy_) ? settings_.input_smoothing_steps : 1;
    return fold_free_minimization(level, x, role, options, smoothing, role.is_input ? two_grid : nullptr);
  }

  // The chosen energy from a fold-free map: the optimistic stage, then what `next_stage()`
  // says. `smoothing`: block Jacobi iterations first (after vertex splits), the first a
  // two-grid cycle with `two_grid`.
  Level_outcome fold_free_minimization(Level& level, Points& x, const Level_role& role, const Newton_options& options,
                                       std::size_t smoothing, const Coarse_correction* two_grid)
  {
    if(role.is_input)
      log_.last_valid_input_map = x;
    Level_facts facts;
    facts.is_input = role.is_input;
    // After a level whose optimistic stage was rejected, a coarser level's would fold again
    // from its first iterate: the smoothing step alone.
    facts.optimistic_ran = !(role.previous_rejected && smoothing > 0 && !role.is_input);
    Points fold_free;  // the optimistic stage's last fold-free iterate
    Newton_outcome last = optimistic_stage(level, x, role, options, smoothing, two_grid, facts.optimistic_ran, fold_free);
    facts.folded = level.has_fold(x);
    facts.fold_free_minimum = facts.optimistic_ran && !facts.folded && last.stop != Newton_stop::FOLDED;
    if(facts.fold_free_minimum) {
      facts.above_floor = level.solver->is_above_floor(x, options.fold_floor);
      facts.few_under_floor = !facts.above_floor && role.last_before_input && few_under_floor(level, x, options.fold_floor);
    }
    bool rejected = !facts.fold_free_minimum;

    Stage done = Stage::OPTIMISTIC;
    for(;;) {
      facts.interrupted = log_.interrupted();
      const std::optional<Stage> next = next_stage(done, facts);
      if(!next)
        break;
      switch(*next) {
      case Stage::LOCAL_UNTANGLING:
        facts.untangled = untangle_locally(level, x, role, options);
        if(facts.untangled && !role.is_input) {
          facts.above_floor = level.solver->is_above_floor(x, options.fold_floor);
          rejected = !facts.above_floor;
        }
        break;
      case Stage::CONTINUATION:
        if(!facts.untangled)
          x = fold_free;
        last = continuation_stage(level, x, role, options);
        break;
      case Stage::FLOOR_PATCH: {
        const std::optional<Patch_outcome> patch = floor_patch_stage(x, role, options, last);
        facts.patch_sufficed = patch && patch->sufficed;
        if(patch)
          last = patch->newton;
        break;
      }
      case Stage::FLOOR:
        last = floor_stage(level, x, role, options);
        break;
      case Stage::DEEP_FACES:
        deep_faces_stage(x, role, options, last.energy);
        break;
      default:
        break;
      }
      done = *next;
    }
    if(log_.interrupted() && level.has_fold(x) && !fold_free.empty())
      x = fold_free;  // interrupted on the way: the last fold-free iterate is the result
    return {!log_.interrupted(), rejected};
  }

  // The chosen energy alone, with no barrier and no cap, as in the paper: most minima are
  // fold-free and Newton reaches them in a few iterations with the exact Hessian, passing
  // through folds at times. `fold_free` receives the last fold-free iterate.
  Newton_outcome optimistic_stage(Level& level, Points& x, const Level_role& role, Newton_options options,
                                  std::size_t smoothing, const Coarse_correction* two_grid, bool optimistic,
                                  Points& fold_free)
  {
    options.fold_free_iterate = &fold_free;
    options.smoothing_iterations = smoothing;
    options.coarse_correction = two_grid;
    options.max_folded_iterations = settings_.max_folded_iterations;
    if(!optimistic)
      options.max_iterations = std::min(options.max_iterations, smoothing);
    if(role.is_input && role.previous_rejected) {
      options.max_folded_iterations = std::min(options.max_folded_iterations, settings_.input_max_folded_iterations);
      options.count_unfolding_iterates = false;
    }
    return minimize(energy_, Stage::OPTIMISTIC, role, level, x, options);
  }

  // The chosen energy plus the fold barrier far above the floor, steps capped before any
  // face flips, from a fold-free map.
  Newton_outcome continuation_stage(Level& level, Points& x, const Level_role& role, Newton_options options)
  {
    options.keep_fold_free = true;
    options.fold_floor *= settings_.continuation_floor_factor;
    options.tolerance = std::max(options.tolerance, settings_.continuation_tolerance);
    options.outer_barrier_weight =
      role.is_input ? settings_.input_outer_barrier_weight : settings_.level_outer_barrier_weight;
    options.floored_activation = settings_.floored_activation;
    return minimize(energy_, Stage::CONTINUATION, role, level, x, options);
  }

  // The chosen energy plus the fold barrier at the floor, steps capped; its slow capped tail
  // may stop it, as it is the input's last stage.
  Newton_outcome floor_stage(Level& level, Points& x, const Level_role& role, Newton_options options)
  {
    options.keep_fold_free = true;
    options.stop_slow_capped_tail = true;
    options.outer_barrier_weight = settings_.floor_outer_barrier_weight;
    return minimize(energy_, Stage::FLOOR, role, level, x, options);
  }

  struct Patch_outcome
  {
    Newton_outcome newton;
    double added = 0;  // energy the patch's stage added to the whole map's
    bool sufficed = false;
  };

  // The floor stage on the neighbourhood of the input's faces under the floor, the rest of
  // the map held. It suffices if the map was a minimum (`optimistic`) and the patch added
  // under half the tolerance: energy plus barrier cannot fall below that minimum, so the
  // floor stage on the whole map could gain at most what the patch added. None if the
  // patch would be too large.
  std::optional<Patch_outcome> floor_patch_stage(Points& x, const Level_role& role, const Newton_options& options,
                                                 const Newton_outcome& optimistic)
  {
    const std::size_t max_free = std::size_t(settings_.max_floor_patch_share * double(input_.number_of_vertices()));
    std::optional<Patch_outcome> patch =
      stage_on_patch(x, input_.solver->faces_under_floor(x, options.fold_floor), optimistic.energy, Stage::FLOOR_PATCH,
                     role, settings_.patch_rings, max_free, settings_.floor_patch_tightening, options);
    if(patch)
      patch->sufficed = !log_.interrupted() && optimistic.stop != Newton_stop::ITERATION_CAP &&
                        patch->newton.stop == Newton_stop::CONVERGED &&
                        patch->added <= 0.5 * options.tolerance * std::abs(optimistic.energy);
    return patch;
  }

  // Faces far under their activation after the floor stage (tiny input area, a barrier
  // weighing less than the tolerance) lifted on their one-ring, where the cap of the faces
  // elsewhere no longer holds their steps back, to a much tighter tolerance: a valid map
  // needs them lifted, however large that patch.
  void deep_faces_stage(Points& x, const Level_role& role, Newton_options options, double whole_energy)
  {
    const std::vector<int> deep = input_.solver->faces_under_floor(x, options.fold_floor, settings_.deep_face_share);
    if(deep.empty())
      return;
    options.max_iterations = std::min(options.max_iterations, settings_.deep_lift_iterations);
    stage_on_patch(x, deep, whole_energy, Stage::DEEP_FACES, role, 1, input_.number_of_vertices(),
                   settings_.deep_faces_tightening, options);
  }

  // The floor stage on the neighbourhood (`rings` rings) of the input's faces `seeds`, the
  // rest of the map held, to a tolerance `tightening` times tighter relative to the whole
  // map's energy `whole_energy`. None if the patch would free more than `max_free` vertices.
  std::optional<Patch_outcome> stage_on_patch(Points& x, const std::vector<int>& seeds, double whole_energy, Stage stage,
                                              const Level_role& role, int rings, std::size_t max_free,
                                              double tightening, Newton_options options)
  {
    Floor_patch patch = make_floor_patch(input_.soup, seeds, rings);
    if(patch.free_vertices > max_free)
      return std::nullopt;
    Level level = patch_level(std::move(patch));
    Points y;
    level.gather(x, y);
    const Spherical_energy<Energy> patch_energy(level.soup, energy_, correction_, ConcurrencyTag());
    const double before = patch_energy.template value<ConcurrencyTag>(y);
    options.keep_fold_free = true;
    options.held_energy = whole_energy - before;
    options.tolerance /= tightening;
    Patch_outcome outcome;
    outcome.newton = minimize(energy_, stage, role, level, y, options);
    outcome.added = outcome.newton.energy - before;
    level.scatter(y, x);
    return outcome;
  }

  // The folded faces of `whole`'s map untangled on their neighbourhood, the rest held. True
  // if the map is then fold-free; not tried if the patch would free too many vertices.
  bool untangle_locally(const Level& whole, Points& x, const Level_role& role, const Newton_options& options)
  {
    Floor_patch patch = make_floor_patch(whole.soup, bad_faces(whole.soup.faces, x), settings_.patch_rings);
    if(double(patch.free_vertices) > settings_.max_untangled_share * double(whole.number_of_vertices()))
      return false;
    Level level = patch_level(std::move(patch));
    Points y;
    level.gather(x, y);
    if(!untangle(level, y, role, options, settings_.local_untangling_rounds, Stage::LOCAL_UNTANGLING) ||
       level.has_fold(y))
      return false;
    level.scatter(y, x);  // every folded face was a seed, so the patch held them all
    return true;
  }

  // Tutte's energy with the d_min barrier until the map is fold-free. False if interrupted.
  bool tutte_stage(Level& level, Points& x, const Level_role& role, Newton_options options)
  {
    options.stop_when_fold_free = true;
    minimize(Tutte_energy(), Stage::TUTTE, role, level, x, options);
    return !log_.interrupted();
  }

  // Garanzha et al.'s continuation: rounds of a few iterations, each stopped once fold-free,
  // epsilon shrinking from one round to the next. False if interrupted.
  bool untangle(Level& level, Points& x, const Level_role& role, Newton_options options, int rounds, Stage stage)
  {
    options.max_iterations = std::min(options.max_iterations, settings_.untangling_round_iterations);
    options.stop_when_fold_free = true;
    Untangling_energy untangling;
    for(int round = 0; round < rounds; ++round) {
      minimize(untangling, stage, role, level, x, options);
      if(!level.has_fold(x) || log_.interrupted())
        break;
      untangling.epsilon =
        std::max(untangling.epsilon / settings_.untangling_epsilon_decay, settings_.untangling_min_epsilon);
    }
    return !log_.interrupted();
  }

  // One Newton minimization, recorded in the log.
  template <class StageEnergy>
  Newton_outcome minimize(const StageEnergy& energy, Stage stage, const Level_role& role, Level& level, Points& x,
                          Newton_options options)
  {
    options.boost_search = moebius_boosts_ && !options.stop_when_fold_free;
    options.extend_projected_steps = has_area_barrier(energy);
    options.drop_rotation_curvature = has_area_barrier(energy);
    options.stage = stage_name(stage);
    options.iteration_offset = log_.iterations;
    const Spherical_energy<StageEnergy> spherical(level.soup, energy, correction_, ConcurrencyTag());
    const Newton_outcome out = level.solver->minimize(spherical, x, options, visitor_);
    log_.iterations += out.iterations;
    Stage_report* last = log_.stages.empty() ? nullptr : &log_.stages.back();
    if(last && last->stage == stage && last->level_vertices == role.vertices && last->input_level == role.is_input)
      last->iterations += out.iterations;  // one report for the rounds of an untangling
    else
      log_.stages.push_back({stage, role.vertices, role.is_input, out.iterations});
    if(&level == &input_)
      log_.input_stop = out.stop;
    if(out.stop == Newton_stop::CANCELLED || out.stop == Newton_stop::TIME_LIMIT)
      log_.interruption = out.stop;
    return out;
  }

  // The last level before the input with at most `few_under_floor_share` of its faces under the floor.
  bool few_under_floor(Level& level, const Points& x, double floor) const
  {
    const double few = settings_.few_under_floor_share * double(level.soup.faces.size());
    return double(level.solver->faces_under_floor(x, floor).size()) <= few;
  }

  // The central projection of `level` about a point inside it, if of degree 1: the start of
  // the coarsest level, and of a level restarted by `robust_stages()`.
  static bool central_start(const Level& level, Points& x)
  {
    const std::optional<Eigen::Vector3d> center = interior_center(level.soup);
    std::optional<Points> start;
    if(center)
      start = central_projection(level.soup.points, *center);
    if(!start || std::abs(check_map(level.soup.faces, *start).degree - 1) > 1e-6)
      return false;
    x = std::move(*start);
    return true;
  }

  // A level of the patch's soup whose unknowns are the patch's free vertices.
  static Level patch_level(Floor_patch patch)
  {
    Level level;
    level.soup = std::move(patch.soup);
    level.to_input = std::move(patch.to_input);
    level.solver = std::make_unique<Newton>(level.soup, patch.free_vertices);
    return level;
  }

  void make_input_solver()
  {
    if(!input_.solver)
      input_.solver = std::make_unique<Newton>(input_.soup);
  }

  Level& input_;
  const Energy& energy_;
  const bool correction_;
  const Pipeline_settings settings_;
  Newton_options options_;
  const bool moebius_boosts_;
  Visitor& visitor_;
  Run_log log_;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_ROBUST_PIPELINE_H
