// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZER_3_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZER_3_H

#include <CGAL/Spherical_parameterization/Balanced_energy.h>
#include <CGAL/Spherical_parameterization/Energy_mix.h>
#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/Progress.h>
#include <CGAL/Spherical_parameterization/Result.h>
#include <CGAL/Spherical_parameterization/Sparse_solver_traits.h>
#include <CGAL/Spherical_parameterization/Weighted_sum_energy.h>
#include <CGAL/Spherical_parameterization/named_parameters.h>
#include <CGAL/Spherical_parameterization/internal/Coarse_to_fine.h>
#include <CGAL/Spherical_parameterization/internal/Floor_patch.h>
#include <CGAL/Spherical_parameterization/internal/Newton_solver.h>
#include <CGAL/Spherical_parameterization/internal/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/Untangling_energy.h>
#include <CGAL/Spherical_parameterization/internal/check_input.h>
#include <CGAL/Spherical_parameterization/internal/indexed_triangles.h>
#include <CGAL/Spherical_parameterization/internal/initialization.h>
#include <CGAL/Spherical_parameterization/internal/locality_order.h>
#include <CGAL/Spherical_parameterization/internal/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/parallel_for.h>

#include <CGAL/Default.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Maps a closed, connected, genus-0 triangle mesh one-to-one onto the unit sphere by
/// minimizing `sum_f d_min(f)^-2 E_flat(f)` (Friedel, Schroeder and Desbrun 2007) over the
/// sphere points, with no vertex fixed.
///
/// `precompute()` checks the input and builds what depends on the mesh only (reference
/// triangles, the sparsity pattern and its symbolic factorization); `solve()` runs the
/// pipeline and writes the map. `solve()` can be called again, for instance after changing
/// the weights through `energy()`: without an `initial_sphere_map` it then starts from the
/// last map.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam Energy a model of `SphericalEnergy`, by default `Balanced_energy`
/// \tparam GeomTraits the kernel of the input points, by default that of the mesh's vertex
///         point map; its `Compute_x_3` (y, z) functors read the coordinates
/// \tparam SolverTraits a model of `SphericalSparseSolverTraits`, by default CHOLMOD when
///         available, else Eigen's `SimplicialLDLT`
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or, by
///         default, `CGAL::Parallel_if_available_tag`
template <class TriangleMesh,
          class Energy = Balanced_energy,
          class GeomTraits = CGAL::Default,
          class SolverTraits = Default_sparse_solver_traits,
          class ConcurrencyTag = CGAL::Parallel_if_available_tag>
class Spherical_parameterizer_3
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using Geom_traits = typename CGAL::Default::Get<GeomTraits, typename GetGeomTraits<TriangleMesh>::type>::type;
  using Newton = internal::Newton_solver<SolverTraits, ConcurrencyTag>;

public:
  /// A parameterizer minimizing `energy`, reading the input points with `traits`. The default
  /// energy is `balanced_energy()` for `Balanced_energy`, `combined_energy(1, 1)` for
  /// `Combined_energy`, the same balanced energy for `Energy_mix`, and `Energy()` otherwise.
  explicit Spherical_parameterizer_3(const Energy& energy = default_energy(), const Geom_traits& traits = Geom_traits())
    : energy_(energy), traits_(traits) {}

  /// The energy; change its weights between two solves.
  Energy& energy() { return energy_; }
  /// The energy.
  const Energy& energy() const { return energy_; }

  /// Checks the mesh and stores it as arrays. What else depends on the mesh only (the
  /// solver's symbolic factorization, the coarse-to-fine hierarchy) is made by the first
  /// `solve()` and kept for the next ones.
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{vertex_point_map} the input positions;
  ///     default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
  /// \cgalNamedParamsEnd
  /// \return `Error_code::OK` or the input error; the reason is in `input_detail()`.
  template <class NamedParameters = parameters::Default_named_parameters>
  Error_code precompute(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                      get_const_property_map(CGAL::vertex_point, tm));
    input_ = Level();
    hierarchy_.reset();
    last_map_.clear();
    const internal::Input_report report = internal::check_input(tm, vpm);
    input_detail_ = report.detail;
    if(report.code != Error_code::OK)
      return report.code;

    internal::Indexed_triangles<TriangleMesh> mesh = internal::indexed_triangles(tm);
    vertices_ = std::move(mesh.vertices);
    internal::Points points;
    for(vertex_descriptor v : vertices_) {
      const auto& p = get(vpm, v);
      points.emplace_back(CGAL::to_double(traits_.compute_x_3_object()(p)),
                          CGAL::to_double(traits_.compute_y_3_object()(p)),
                          CGAL::to_double(traits_.compute_z_3_object()(p)));
    }
    // Neighbours near each other in memory, and a map that does not depend on the input's order.
    internal::order_by_locality(vertices_, points, mesh.triangles);
    input_.soup = internal::make_triangle_soup(std::move(points), std::move(mesh.triangles));
    return Error_code::OK;
  }

  /// Where the input is bad, after `precompute()` returned an error.
  const std::string& input_detail() const { return input_detail_; }

  /// Computes the map and writes it to `sphere_map` (a writable property map
  /// `vertex -> Point_3`; it may be the mesh's own point map). The map is written whenever
  /// the solver ran; check `Result::is_valid()`.
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{pipeline} `Pipeline::ROBUST` (default) or `Pipeline::PAPER` \cgalParamNEnd
  ///   \cgalParamNBegin{initial_sphere_map} a start on the sphere; default: the pipeline's.
  ///     With the robust pipeline its degree must be 1 relative to the input's orientation;
  ///     the paper pipeline takes it as it is \cgalParamNEnd
  ///   \cgalParamNBegin{d_min_correction} default `true` \cgalParamNEnd
  ///   \cgalParamNBegin{number_of_iterations} cap on Newton iterations per stage; default 200 \cgalParamNEnd
  ///   \cgalParamNBegin{tolerance} relative energy decrease at which to stop; default 1e-6 \cgalParamNEnd
  ///   \cgalParamNBegin{maximum_running_time} seconds; default unlimited \cgalParamNEnd
  ///   \cgalParamNBegin{visitor} called after each iteration with a `Progress`; returns
  ///     `false` to cancel \cgalParamNEnd
  /// \cgalNamedParamsEnd
  template <class SphereMap, class NamedParameters = parameters::Default_named_parameters>
  Result solve(SphereMap sphere_map, const NamedParameters& np = parameters::default_values())
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    Result result;
    if(input_.soup.faces.empty()) {
      result.status = Error_code::EMPTY_MESH;
      result.detail = "precompute() was not called or failed";
      return result;
    }
    Run run;
    run.options.start = internal::Clock::now();
    const double max_seconds = choose_parameter(get_parameter(np, CGAL::internal_np::maximum_running_time), 0.0);
    if(max_seconds > 0)
      run.options.deadline = run.options.start + std::chrono::duration_cast<internal::Clock::duration>(
                                                   std::chrono::duration<double>(max_seconds));
    const long long max_iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 200);
    run.options.tolerance = choose_parameter(get_parameter(np, internal_np::tolerance_t()), 1e-6);
    run.correction = choose_parameter(get_parameter(np, internal_np::d_min_correction_t()), true);
    run.pipeline = choose_parameter(get_parameter(np, internal_np::pipeline_t()), Pipeline::ROBUST);
    if(!(run.options.tolerance >= 0) || max_iterations <= 0 || !(max_seconds >= 0)) {
      result.status = Error_code::INVALID_PARAMETER;
      result.detail = "number_of_iterations must be positive, tolerance and maximum_running_time non-negative";
      return result;
    }
    run.options.max_iterations = std::size_t(max_iterations);

    internal::Points x;
    if(!initial_map(np, run, x, result))
      return result;
    auto visitor = choose_parameter(get_parameter(np, CGAL::internal_np::visitor), Default_visitor());
    if(!run_pipeline(run, x, visitor)) {
      result.status = Error_code::INVALID_INITIALIZATION;
      result.detail = "no point inside the mesh found to centre the central projection";
      return result;
    }
    finish(run, x, result);
    write_map(sphere_map, x);
    last_map_ = x;
    result.time_seconds = std::chrono::duration<double>(internal::Clock::now() - run.options.start).count();
    return result;
  }

private:
  struct Run
  {
    internal::Newton_options options;
    bool correction = true;
    Pipeline pipeline = Pipeline::ROBUST;
    std::size_t iterations = 0;
    std::optional<internal::Newton_stop> interrupted;  // cancelled or out of time
    std::optional<internal::Points> best_valid;         // last fold-free map met, for interruptions
    std::string stages;
    bool optimistic_stage_rejected = false;  // on the last level
    bool last_before_input = false;          // the level being solved is the last coarser one, never the input
  };

  static Energy default_energy()
  {
    constexpr double t = default_area_preservation;
    if constexpr(std::is_same<Energy, Balanced_energy>::value) return balanced_energy(t);
    else if constexpr(std::is_same<Energy, Combined_energy>::value) return combined_energy(1, 1);
    else if constexpr(std::is_same<Energy, Energy_mix>::value) return *energy_by_name("balanced", 1 - t, t);
    else return Energy();
  }

  using Level = internal::Level<Newton>;

  // The start: the user's map or the last map (re-solve), or for the paper's pipeline its
  // central projection. Empty `x` (robust pipeline from scratch): the coarse-to-fine solve
  // makes its own start.
  template <class NamedParameters>
  bool initial_map(const NamedParameters& np, const Run& run, internal::Points& x, Result& result)
  {
    using CGAL::parameters::get_parameter;
    const auto user_map = get_parameter(np, internal_np::initial_sphere_map_t());
    x.clear();
    if constexpr(!std::is_same<std::decay_t<decltype(user_map)>, CGAL::internal_np::Param_not_found>::value) {
      for(vertex_descriptor v : vertices_) {
        const auto& p = get(user_map, v);
        x.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
        if(!x.back().allFinite() || !(x.back().norm() > 0)) {
          result.status = Error_code::INVALID_INITIALIZATION;
          result.detail = "a point of the initial map is zero or not finite";
          return false;
        }
        x.back().normalize();
      }
    } else if(!last_map_.empty()) {
      x = last_map_;
    } else if(run.pipeline == Pipeline::PAPER) {
      // The paper's start: central projection about the area centroid, the soup's origin.
      std::optional<internal::Points> start = internal::central_projection(input_.soup.points, Eigen::Vector3d::Zero());
      if(!start) {
        result.status = Error_code::INVALID_INITIALIZATION;
        result.detail = "a vertex lies at the centroid, the centre of the central projection";
        return false;
      }
      x = std::move(*start);
    } else {
      return true;
    }
    const double degree = internal::check_map(input_.soup.faces, x).degree;
    if(std::abs(degree - 1) > 1e-6 && run.pipeline == Pipeline::ROBUST) {
      result.status = Error_code::INVALID_INITIALIZATION;
      result.detail = "the initial map has degree " + std::to_string(degree) + ", not 1";
      return false;
    }
    return true;
  }

  // False if no start was found (robust pipeline from scratch).
  template <class Visitor>
  bool run_pipeline(Run& run, internal::Points& x, Visitor& visitor)
  {
    if(run.pipeline == Pipeline::ROBUST && x.empty())
      return solve_coarse_to_fine(run, x, visitor);
    make_input_solver();
    if(run.pipeline == Pipeline::PAPER)
      minimize(energy_, "target", false, run, input_, x, visitor);
    else
      robust_stages(run, input_, x, visitor);
    return true;
  }

  // From a start of degree 1 on `level`: Tutte with the d_min barrier while faces are folded
  // (robust, and fold-free on most meshes), untangling if that is not enough, then the
  // user's energy without ever letting a face flip. False if interrupted.
  template <class Visitor>
  bool robust_stages(Run& run, Level& level, internal::Points& x, Visitor& visitor)
  {
    if(level.has_fold(x) && !minimize(Tutte_energy(), "tutte", false, run, level, x, visitor, true))
      return false;
    if(level.has_fold(x) && !untangle(run, level, x, visitor))
      return false;
    if(level.has_fold(x))  // no fold-free map found: plain minimization
      return minimize(energy_, "target", false, run, level, x, visitor);
    return minimize_fold_free(run, level, x, visitor, "target");
  }

  // The user's energy from a fold-free map. First alone, as in the paper: on most meshes its
  // minimum is fold-free and Newton with the exact Hessian converges in a few iterations,
  // passing through folds on its way at times. If it ends folded or with a face squeezed
  // under the floor (protrusions, where the energy's infimum is degenerate), the fold-free
  // stage takes over from the last fold-free iterate: steps that never cross det = 0 and a
  // barrier on the faces squeezed under the floor (internal::Fold_barrier). Barrier and
  // step cap from the start were measured to triple bunny00's iterations: both slow Newton
  // where they are not needed.
  // `smoothing`: block Jacobi iterations first, after vertex splits (see Newton_options).
  template <class Visitor>
  bool minimize_fold_free(Run& run, Level& level, internal::Points& x, Visitor& visitor, const char* stage,
                          std::size_t smoothing = 0)
  {
    if(&level == &input_)
      run.best_valid = x;
    internal::Points fold_free;
    run.options.fold_free_iterate = &fold_free;
    run.options.smoothing_iterations = smoothing;
    // A coarser level after one whose optimistic stage was rejected: the smoothing step
    // alone, the optimistic stage's Newton iterations would be thrown away again (corpus,
    // Combined: man 129 -> 125 iterations, armadillo 102 -> 94; bull@loop2 23.6 -> 22.4 s).
    // Not on the input, whose optimistic minimum may be fold-free all the same
    // (triceratops@loop2: 1.6 -> 3.1 s).
    const bool optimistic = !(run.optimistic_stage_rejected && smoothing > 0 && &level != &input_);
    const std::size_t max_iterations = run.options.max_iterations;
    if(!optimistic)
      run.options.max_iterations = std::min(max_iterations, smoothing);
    // The input after a level whose optimistic stage was rejected: a fold that lasts three
    // iterates will not come undone either (see `input_max_folded_iterations`), unless the
    // folded faces at least halve from one iterate to the next.
    const std::size_t max_folded = run.options.max_folded_iterations;
    const bool after_rejected_level = &level == &input_ && run.optimistic_stage_rejected;
    if(after_rejected_level) {
      run.options.max_folded_iterations = std::min(max_folded, input_max_folded_iterations);
      run.options.count_unfolding_iterates = false;
    }
    const bool uninterrupted = minimize(energy_, stage, false, run, level, x, visitor);
    run.options.max_folded_iterations = max_folded;
    run.options.count_unfolding_iterates = true;
    run.options.max_iterations = max_iterations;
    run.options.smoothing_iterations = 0;
    run.options.coarse_correction = nullptr;
    run.options.fold_free_iterate = nullptr;
    const bool folded = level.has_fold(x);
    const bool fold_free_minimum = optimistic && !folded && last_level_stop_ != internal::Newton_stop::FOLDED;
    run.optimistic_stage_rejected = !fold_free_minimum;
    const double floor = run.options.fold_floor;
    const bool is_input = &level == &input_;
    if(!uninterrupted || (fold_free_minimum && (level.solver->is_above_floor(x, floor) || few_under_floor(run, level, x)))) {
      if(folded)  // interrupted on the way: the last fold-free iterate is the result
        x = std::move(fold_free);
      return uninterrupted;
    }
    // A fold-free minimum of the input with faces under the floor: the floor stage alone,
    // from there, on the neighbourhood of those faces first (`lift_locally()`), and on the
    // whole map only if that was not enough; then the patch has lifted the deepest faces in
    // cheap iterations and the whole map's stage has less to do (bunny00 Tutte, 304 faces
    // under a tenth of the floor: 7 -> 35 + 3 iterations, 7.4 -> 6.8 s; doc/NOTES.md,
    // session 46).
    // From faces squeezed far under the floor the floor stage lifts them in a few full
    // Newton steps, where the continuation would first undo the minimum and then find it
    // again in capped ones (armadillo@loop1, Combined, 3707 faces under the floor, 211 under
    // a hundredth of it: 16 + 2 iterations -> 6, 17.4 -> 9.8 s, the same energy).
    // Not on the coarser levels: there the continuation's cushion is what keeps the next
    // levels clear of the floor (bunny00, floor stage alone on every level: Dirichlet 35 -> 63
    // iterations, Tutte 38 -> 42).
    // The last stage, on the floor, only ever on the input; its slow capped tail may stop it.
    auto floor_stage = [&] {
      const internal::Newton_options before = run.options;
      run.options.stop_slow_capped_tail = true;
      run.options.outer_barrier_weight = floor_outer_barrier_weight;
      const bool done = minimize(energy_, stage, true, run, level, x, visitor);
      run.options.outer_barrier_weight = before.outer_barrier_weight;
      run.options.stop_slow_capped_tail = before.stop_slow_capped_tail;
      return done && lift_deep_faces(run, x, visitor);
    };
    if(is_input && fold_free_minimum) {
      if(lift_locally(run, x, visitor) || run.interrupted)
        return !run.interrupted && lift_deep_faces(run, x, visitor);
      return floor_stage();
    }
    // The input's optimistic stage ended folded, on isosurfaces often near its minimum with
    // 3 or 4 faces of tiny input area flipped (the energy's terms do not see their
    // orientation): those faces untangled on their neighbourhood, then the floor stage from
    // there, rather than the continuation from the last fold-free iterate, which may be the
    // stage's start (starfish100, 52k faces: 111 -> 91 iterations, 7.2 -> 4.5 s, to a lower
    // energy; starfish150 21.8 -> 11.0 s). Where the patch does not untangle, its few
    // iterations are lost (cow Dirichlet 69 -> 70 iterations, the same minimum).
    // The same on a coarser level, whose optimistic stage may end folded next to its minimum
    // by one face flipped from the first iterate on (cortex100, 40500 vertices): untangled
    // locally, that minimum is the level's result if it is above the floor, else the
    // continuation's start, rather than the stage's start (cortex100 Combined 42 -> 28
    // iterations, metaballs180 43 -> 29, the same energies; see doc/NOTES.md, session 45).
    const bool untangled = optimistic && folded && untangle_locally(run, level, x, visitor);
    if(untangled && is_input)
      return floor_stage();
    if(untangled && level.solver->is_above_floor(x, floor)) {
      run.optimistic_stage_rejected = false;
      return !run.interrupted;
    }
    if(!untangled)
      x = std::move(fold_free);
    // Continuation on the floor, from the last fold-free iterate of a rejected optimistic
    // stage (or on a coarser level): first 1000 times higher, to a loose tolerance, so that
    // the large moves happen while the squeezed faces are still large and well conditioned;
    // then, on the input, the floor itself (cow: 41 -> 28 iterations, camel: 90 -> 44, each
    // to a lower energy).
    // Its barrier has a weak outer layer (`Fold_barrier::energy()`): the faces coming down
    // to the barrier no longer cap most steps to a few percent of Newton's before they reach
    // it. On the floor a ten times weaker one (`floor_outer_barrier_weight`).
    const internal::Newton_options saved = run.options;
    run.options.fold_floor = 1000 * saved.fold_floor;
    run.options.tolerance = std::max(saved.tolerance, 1e-4);
    run.options.outer_barrier_weight = is_input ? input_outer_barrier_weight : level_outer_barrier_weight;
    run.options.floored_activation = floored_activation;
    const bool first = minimize(energy_, stage, true, run, level, x, visitor);
    run.options.fold_floor = saved.fold_floor;
    run.options.tolerance = saved.tolerance;
    run.options.outer_barrier_weight = 0;
    run.options.floored_activation = 0;
    // A coarser level stops there: the next level's splits start from faces on the cushion
    // of the continuation instead of on the floor, which that level's continuation would
    // only have to lift again (man@loop1, Combined: 237 -> 185 iterations, 27.5 -> 18.7 s).
    if(!first || !is_input)
      return first;
    return floor_stage();
  }

  // The last level before the input, at a fold-free minimum with a few faces under the
  // floor (at most `few_under_floor_share` of its faces): that minimum is its result, without
  // the continuation. Its cushion keeps the splits of the next levels clear of the floor, but
  // the input's splits stay fold-free near a few such faces, and the input lifts its own on a
  // patch (`lift_locally()`). bunny00 after one subdivision, Combined, 8 of 81k faces under
  // the floor at 40.5k vertices: 5 iterations of that level's continuation saved, the input's 3
  // and its minimum unchanged (28 -> 23 iterations, 7.4 / 7.0 -> 5.8 / 6.3 s; after two
  // subdivisions 52 -> 43). Not with many: there, Tutte, 5088 of 243k faces, the input's
  // splits folded (86 -> 123 s). Not on earlier levels, whose continuation keeps the later
  // ones off the floor (bunny00 Dirichlet, 2 of 27k faces at 13.5k vertices: 31 -> 179
  // iterations). The corpus and the held-out sizes otherwise unchanged (doc/NOTES.md, session 49).
  bool few_under_floor(const Run& run, Level& level, const internal::Points& x) const
  {
    if(!run.last_before_input)
      return false;
    const double few = few_under_floor_share * double(level.soup.faces.size());
    return double(level.solver->faces_under_floor(x, run.options.fold_floor).size()) <= few;
  }

  // The floor stage on the neighbourhood of the input's faces under the floor, the rest of
  // the map held (internal::Floor_patch). True if that was all the floor stage had to do:
  // the map was a minimum of the energy, and energy plus barrier cannot fall below it, so
  // the floor stage on the whole map could gain at most what the patch's stage `added`.
  // The patch runs to a 100 times tighter tolerance, relative to the whole map's energy:
  // its iterations are cheap, and the smaller `added` then passes the test. Measured:
  // bunny00 after two subdivisions, Combined: 6236 free vertices, 16 iterations in 0.35 s
  // instead of 2 global ones (14 s); bunny00 Tutte 6.5 -> 4.8 s, after one subdivision
  // 51 -> 29 s. False if interrupted (`run.interrupted`).
  template <class Visitor>
  bool lift_locally(Run& run, internal::Points& x, Visitor& visitor)
  {
    const double minimum = last_energy_;
    const bool at_minimum = last_level_stop_ != internal::Newton_stop::ITERATION_CAP;
    const std::optional<double> added =
      floor_stage_on_patch(run, x, visitor, input_.solver->faces_under_floor(x, run.options.fold_floor), minimum,
                           "floor patch", patch_rings, input_.number_of_vertices() / 4, 100);
    return added && !run.interrupted && at_minimum && last_level_stop_ == internal::Newton_stop::CONVERGED &&
           *added <= 0.5 * run.options.tolerance * std::abs(minimum);
  }

  // The input's floor stage may end with faces of tiny input area far under the floor, even
  // degenerate: their barrier weighs less than the tolerance, so the stage converges (or its
  // capped tail stops) without lifting them (cow with 50 slivers of relative height 1e-6: two
  // faces at det 2e-17, no valid map). Faces under a hundredth of their activation (the
  // floor, raised for faces of tiny input area) are lifted on their own patch, one ring around them
  // (`floor_stage_on_patch()`), where the cap of the faces elsewhere no longer holds their
  // steps back, to a tolerance 1e4 times tighter: each Newton step on a log barrier lifts a
  // face's `t` about 4 times and gains about twice the barrier's weight, 5e-6 for a tiny face
  // (`Fold_barrier::face_weight()`), which a tolerance 100 times tighter (6e-7 of an energy
  // of 60) called converged after one step. However large that patch: a valid map needs it.
  // At most `deep_lift_iterations`: the lift itself takes about 20 (t from 1e-10 of the
  // floor to the floor), the rest is the patch's slow slide under the tighter tolerance, which
  // the user's tolerance, already met, does not ask for (cow with slivers: 149 iterations).
  // False if interrupted.
  template <class Visitor>
  bool lift_deep_faces(Run& run, internal::Points& x, Visitor& visitor)
  {
    const std::vector<int> deep = input_.solver->faces_under_floor(x, run.options.fold_floor, 1e-2);
    if(deep.empty())
      return true;
    const std::size_t max_iterations = run.options.max_iterations;
    run.options.max_iterations = std::min<std::size_t>(max_iterations, deep_lift_iterations);
    floor_stage_on_patch(run, x, visitor, deep, last_energy_, "deep faces", 1, input_.number_of_vertices(), 1e4);
    run.options.max_iterations = max_iterations;
    return !run.interrupted;
  }

  // The floor stage on the neighbourhood of the input's faces `seeds`, the rest of the map held
  // (internal::Floor_patch), freeing `rings` rings around them, to a tolerance `tightening`
  // times tighter, relative to the whole map's energy `minimum`. Returns the energy it added,
  // none if the patch would free more than `max_free` vertices (nothing done).
  template <class Visitor>
  std::optional<double> floor_stage_on_patch(Run& run, internal::Points& x, Visitor& visitor, const std::vector<int>& seeds,
                                             double minimum, const char* stage, int rings, std::size_t max_free,
                                             double tightening)
  {
    internal::Floor_patch patch = internal::make_floor_patch(input_.soup, seeds, rings);
    if(patch.free_vertices > max_free)
      return std::nullopt;
    Level level = patch_level(std::move(patch));
    internal::Points y;
    level.gather(x, y);
    const internal::Spherical_energy<Energy> patch_energy(level.soup, energy_, run.correction, ConcurrencyTag());
    const double before = patch_energy.template value<ConcurrencyTag>(y);
    const double tolerance = run.options.tolerance;
    run.options.held_energy = minimum - before;
    run.options.tolerance = tolerance / tightening;
    minimize(energy_, stage, true, run, level, y, visitor);
    run.options.held_energy = 0;
    run.options.tolerance = tolerance;
    level.scatter(y, x);
    return last_energy_ - before;
  }

  // A level of the patch's soup whose unknowns are the patch's free vertices.
  static Level patch_level(internal::Floor_patch patch)
  {
    Level level;
    level.soup = std::move(patch.soup);
    level.to_input = std::move(patch.to_input);
    level.solver = std::make_unique<Newton>(level.soup, patch.free_vertices);
    return level;
  }

  // The folded faces of the map `x` of `whole` (the input or a coarser level) untangled on
  // their neighbourhood (`patch_rings` rings), the rest of the map held. True if the map is
  // then fold-free; not tried (false) if the patch would free more than
  // `max_untangled_share` of the vertices.
  template <class Visitor>
  bool untangle_locally(Run& run, const Level& whole, internal::Points& x, Visitor& visitor)
  {
    internal::Floor_patch patch =
      internal::make_floor_patch(whole.soup, internal::bad_faces(whole.soup.faces, x), patch_rings);
    if(double(patch.free_vertices) > max_untangled_share * double(whole.number_of_vertices()))
      return false;
    Level level = patch_level(std::move(patch));
    internal::Points y;
    level.gather(x, y);
    if(!untangle(run, level, y, visitor, local_untangling_rounds) || level.has_fold(y))
      return false;
    level.scatter(y, x);  // every folded face was a seed, so the patch held them all
    return true;
  }

  // Garanzha et al.'s continuation: unfold with a finite energy, then tighten the barrier.
  // Rounds of at most 20 iterations: converging each round to the tolerance wasted most of
  // the work (bull: 221 untangling iterations against 59).
  template <class Visitor>
  bool untangle(Run& run, Level& level, internal::Points& x, Visitor& visitor, int max_rounds = 40)
  {
    internal::Untangling_energy untangling;
    const std::size_t max_iterations = run.options.max_iterations;
    run.options.max_iterations = std::min<std::size_t>(max_iterations, 20);
    bool uninterrupted = true;
    for(int round = 0; round < max_rounds && uninterrupted; ++round) {
      uninterrupted = minimize(untangling, "untangle", false, run, level, x, visitor, true);
      if(!level.has_fold(x))
        break;
      untangling.epsilon = std::max(untangling.epsilon / 10, 1e-12);
    }
    run.options.max_iterations = max_iterations;
    return uninterrupted;
  }

  // Coarse to fine: the robust stages on the coarsest mesh of a progressive mesh of the
  // input, then back to the input a level at a time, each level keeping the map fold-free
  // through its vertex splits (internal::Coarse_to_fine) and minimizing the user's energy.
  // Only the input level runs to the tolerance. See doc/NOTES.md for the measurements.
  template <class Visitor>
  bool solve_coarse_to_fine(Run& run, internal::Points& x, Visitor& visitor)
  {
    // Only the input level needs the input's solver (its pattern and symbolic analysis, 0.7 s
    // at 302k faces, mostly METIS) and the memory of its first assembly and factorization
    // (fresh memory is slow on virtual machines): both are made on another core while the
    // hierarchy is built (on one core, 0.45 s at 302k faces) and the coarser levels run.
    // Started after the hierarchy, the input level waited 0.4 to 0.7 s for them at 302k faces
    // (3.94 / 3.72 -> 3.29 / 2.99 s, alternated runs).
    internal::Background_task<ConcurrencyTag> input_solver([this] {
      make_input_solver();
      input_.solver->prepare_memory();
    });
    const bool small = input_.number_of_vertices() <= 2 * coarse_vertices;  // no gain in a hierarchy
    hierarchy(small ? input_.number_of_vertices() : coarse_vertices);
    const bool two_grid = input_.number_of_vertices() > two_grid_vertices;  // see minimize_level()
    internal::Coarse_to_fine<Newton, ConcurrencyTag> levels(input_.soup, *hierarchy_, level_ratio, two_grid);
    const internal::Coarse_correction coarse_correction = [&levels](const auto& map, const auto& gradient, auto& step) {
      return levels.coarse_correction(map, gradient, step);
    };
    internal::Points level_x;
    Level* coarse = levels.level();
    if(!coarse || !coarse_start(*coarse, level_x)) {  // the input itself, from its own central projection
      input_solver.wait();
      if(!coarse_start(input_, x))
        return false;
      robust_stages(run, input_, x, visitor);
      return true;
    }
    x.assign(input_.number_of_vertices(), Eigen::Vector3d::Zero());
    run.stages += "coarse " + std::to_string(coarse->number_of_vertices()) + "v:";
    run.last_before_input = levels.last_before_input();
    bool uninterrupted = robust_stages(run, *coarse, level_x, visitor);
    coarse->scatter(level_x, x);
    while(levels.refine(x)) {
      if(!uninterrupted)
        continue;  // only the splits: a valid map of the input, fast
      Level* level = levels.level();
      if(level)
        level->gather(x, level_x);
      else
        input_solver.wait();
      Level& current = level ? *level : input_;
      run.last_before_input = level && levels.last_before_input();
      internal::Points& y = level ? level_x : x;
      run.stages += std::string(" | ") + (level ? "" : "input ") + std::to_string(current.number_of_vertices()) + "v:";
      uninterrupted = current.has_fold(y) ? robust_stages(run, current, y, visitor)
                                          : minimize_level(run, current, y, visitor, !level, two_grid ? &coarse_correction : nullptr);
      if(level)
        level->scatter(y, x);
    }
    if(levels.empty_kernels() > 0)
      run.stages += " (" + std::to_string(levels.empty_kernels()) + " empty kernels)";
    return true;
  }

  // A level after its vertex splits: an intermediate one to a loose tolerance, a few
  // iterations; the input to the tolerance, starting with a two-grid cycle if given one.
  template <class Visitor>
  bool minimize_level(Run& run, Level& level, internal::Points& x, Visitor& visitor, bool is_input,
                      const internal::Coarse_correction* two_grid)
  {
    // One block Jacobi step after the splits halved the Newton iterations of bunny00 after
    // one subdivision (7 -> 3): most of the error a split leaves is local.
    if(is_input) {
      run.options.predict_convergence = true;
      run.options.leave_under_floor = true;
      // On a large input the smooth error matters too. The smooth modes' curvature is
      // about 7 / n of the Hessian's mean diagonal (a Laplacian's lowest eigenvalues), so
      // the default first shift, 1e-4, damps them from some 70k vertices on, and block
      // Jacobi does not see them. There the block Jacobi step is a two-grid cycle with the
      // last level's factorization, and the first shift a fifth of that curvature
      // (bunny00 after one subdivision, 151k vertices, Combined: the first Newton decrement
      // 1.34 -> 0.45, 3 Newton iterations -> 2, 4.9 -> 4.1 s), but at least 1e-5 (at 603k
      // vertices, 2.5e-6 made Dirichlet 58 -> 67 s). On smaller inputs the cycle changed
      // paths for no gain (the corpus' 14 meshes up to 38k vertices, 42 runs, first shift
      // 1e-5: iterations 4037 -> 4139, time +8%).
      if(two_grid) {
        run.options.coarse_correction = two_grid;
        run.options.first_shift = std::max(1.5 / double(level.number_of_vertices()), 1e-5);
      }
      const bool uninterrupted = minimize_fold_free(run, level, x, visitor, "target", 1);
      run.options.predict_convergence = false;
      run.options.leave_under_floor = false;
      run.options.first_shift = internal::Newton_options().first_shift;
      return uninterrupted;
    }
    const internal::Newton_options saved = run.options;
    run.options.max_iterations = std::min<std::size_t>(run.options.max_iterations, level_iterations);
    run.options.tolerance = std::max(run.options.tolerance, level_tolerance);
    const bool uninterrupted = minimize_fold_free(run, level, x, visitor, "refine", 1);
    run.options.max_iterations = saved.max_iterations;
    run.options.tolerance = saved.tolerance;
    return uninterrupted;
  }

  // The central projection of the coarse level about a point inside it.
  bool coarse_start(const Level& level, internal::Points& x) const
  {
    const std::optional<Eigen::Vector3d> center = internal::interior_center(level.soup);
    std::optional<internal::Points> start;
    if(center)
      start = internal::central_projection(level.soup.points, *center);
    if(!start || std::abs(internal::check_map(level.soup.faces, *start).degree - 1) > 1e-6)
      return false;
    x = std::move(*start);
    return true;
  }

  // The input's Newton solver: its sparsity pattern and symbolic factorization.
  void make_input_solver()
  {
    if(!input_.solver)
      input_.solver = std::make_unique<Newton>(input_.soup);
  }

  const internal::Progressive_mesh& hierarchy(std::size_t target_vertices)
  {
    if(!hierarchy_)
      hierarchy_ = std::make_unique<internal::Progressive_mesh>(input_.soup, target_vertices);
    return *hierarchy_;
  }

  // One Newton stage; false if the run was interrupted.
  template <class StageEnergy, class Visitor>
  bool minimize(const StageEnergy& energy, const char* stage, bool keep_fold_free, Run& run, Level& level,
                internal::Points& x, Visitor& visitor, bool stop_when_fold_free = false)
  {
    run.options.stop_when_fold_free = stop_when_fold_free;
    run.options.boost_search = !stop_when_fold_free && run.pipeline == Pipeline::ROBUST;
    const internal::Spherical_energy<StageEnergy> spherical(level.soup, energy, run.correction, ConcurrencyTag());
    run.options.stage = stage;
    run.options.keep_fold_free = keep_fold_free;
    run.options.iteration_offset = run.iterations;
    const internal::Newton_outcome out = level.solver->minimize(spherical, x, run.options, visitor);
    run.iterations += out.iterations;
    run.stages += std::string(run.stages.empty() || run.stages.back() == ':' ? "" : " ") + stage + ":" +
                  std::to_string(out.iterations);
    last_level_stop_ = out.stop;
    last_energy_ = out.energy;
    if(&level == &input_)
      last_stop_ = out.stop;
    if(out.stop == internal::Newton_stop::CANCELLED || out.stop == internal::Newton_stop::TIME_LIMIT) {
      run.interrupted = out.stop;
      return false;
    }
    return true;
  }

  void finish(Run& run, internal::Points& x, Result& result)
  {
    internal::Map_validity validity = internal::check_map(input_.soup.faces, x);
    if(run.interrupted && !validity.is_valid() && run.best_valid) {
      x = *run.best_valid;  // an interruption returns the last valid map met
      validity = internal::check_map(input_.soup.faces, x);
    }
    result.valid = validity.is_valid();
    result.iterations = run.iterations;
    // The chosen energy alone: the target stage also carries the fold barrier.
    const internal::Spherical_energy<Energy> input_energy(input_.soup, energy_, run.correction, ConcurrencyTag());
    result.energy = input_energy.template value<ConcurrencyTag>(x);
    result.flipped = validity.flipped;
    result.degenerate = validity.degenerate;
    result.degree = validity.degree;  // the soup's faces carry the input's orientation outward
    result.inward_oriented = input_.soup.inward;
    result.min_area_ratio = min_area_ratio(x);
    result.stages = run.stages;
    if(run.interrupted)
      result.status = *run.interrupted == internal::Newton_stop::CANCELLED ? Error_code::CANCELLED : Error_code::TIME_LIMIT;
    else if(!result.valid)
      result.status = Error_code::NO_VALID_MAP;
    else if(last_stop_ == internal::Newton_stop::ITERATION_CAP)
      result.status = Error_code::NOT_CONVERGED;
    else
      result.status = Error_code::OK;
    if(!result.valid)
      result.detail = std::to_string(validity.flipped) + " flipped and " + std::to_string(validity.degenerate) +
                      " degenerate faces, degree " + std::to_string(result.degree);
  }

  // min over faces of (spherical area / 4 pi) / (input area / total input area)
  double min_area_ratio(const internal::Points& x) const
  {
    double smallest = std::numeric_limits<double>::infinity();
    for(std::size_t f = 0; f < input_.soup.faces.size(); ++f) {
      const auto& t = input_.soup.faces[f];
      const double sphere = internal::signed_spherical_area(x[t[0]], x[t[1]], x[t[2]]);
      smallest = std::min(smallest, sphere / input_.soup.face_area(f));  // both totals are 4 pi
    }
    return smallest;
  }

  template <class SphereMap>
  void write_map(SphereMap sphere_map, const internal::Points& x) const
  {
    using Point = typename boost::property_traits<SphereMap>::value_type;
    for(std::size_t i = 0; i < vertices_.size(); ++i)
      put(sphere_map, vertices_[i], Point(x[i].x(), x[i].y(), x[i].z()));
  }

  Energy energy_;
  Geom_traits traits_;
  // Coarse-to-fine: the coarsest level's size, the growth from one level to the next, and
  // the work done at the levels before the input (measured, doc/NOTES.md).
  static constexpr std::size_t coarse_vertices = 500;
  static constexpr double level_ratio = 3;
  // Each stage of a level between the coarsest and the input stops after `level_iterations`.
  // No run of CGAL's meshes needs more than 37 (armadillo, Dirichlet); long tubes slide on for
  // 100 at several levels, which the next level's slide redoes (tubes, Combined, 100 -> 40:
  // capsule150 578 -> 362 iterations, helix2 457 -> 339, helix4 815 -> 719, the same energies).
  static constexpr std::size_t level_iterations = 40;
  static constexpr double level_tolerance = 1e-5;
  static constexpr std::size_t two_grid_vertices = 50000;  // see minimize_level()
  // The weight of the continuation barrier's outer layer, on the coarser levels and on the
  // input (`Fold_barrier::energy()`, reaching out to 3 times the continuation's activation).
  // Measured, Combined, one run each side by side: at 90k to 280k faces (15 meshes) the
  // protrusion meshes 12 to 42% fewer iterations (dino@loop2 167 -> 97, 15.2 -> 10.4 s;
  // man@loop1 155 -> 105, 16.8 -> 13.5 s), the smooth ones unchanged, all final energies
  // within 6e-6; the corpus (14 meshes x 3 energies) 3183 -> 2253 iterations, 93.6 ->
  // 73.4 s, where the path to another local minimum changed on 4 runs (bunny00 Tutte and
  // armadillo Tutte lower and slower, camel Dirichlet lower, diplodocus Dirichlet 0.8%
  // higher). The layer's reach 3 rather than the whole range of t (-log t on every face):
  // the held faces' projected Hessians cost 20% per iteration, and bunny00 Dirichlet took
  // 33 -> 62 iterations, its coarser levels ending in another basin. The weights were
  // chosen with that whole-range layer on man, dino, bull and diplodocus (doc/NOTES.md,
  // session 34) and checked again for reach 3 on the same four (session 35): level weight
  // 1e-1, input weight 3e-2 or 3e-3, reach 1.5 all took more iterations (383 -> 390 to
  // 454); reach 5 or 10 fewer (362) but sent bunny00 Dirichlet to a higher minimum (1.4 ->
  // 7.2 s).
  static constexpr double level_outer_barrier_weight = 3e-2;
  static constexpr double input_outer_barrier_weight = 1e-2;
  // The outer layer of the floor stage's barrier. Without it, the faces just above the floor
  // capped the floor stage's steps to 3 to 10% of Newton's for its last 20 iterations on
  // bull@loop2 (13k faces of 99k that the full step would flip, all between 10 and 100 times
  // the floor), each gaining about the tolerance. With it, one run each side by side,
  // Combined: bull@loop2 floor stage 27 -> 17 iterations, 25.4 -> 22.8 s, to a lower energy
  // (51.65766 -> 51.65756); the other 14 meshes at the held-out size within 2 iterations and
  // their energies to 5 digits; defects 522 -> 518 iterations, tubes 1597 -> 1550 (helix4 703
  // -> 631), isosurfaces the same. A layer of weight 1e-2 gained as much on bull@loop2 (15
  // iterations) but took camel's path from 69 to 94 iterations.
  static constexpr double floor_outer_barrier_weight = 1e-3;
  // The continuation's activation for the faces under their area floor, measured against
  // that floor (`Newton_options::floored_activation`); not on the floor, where it would
  // change the minimum. Isosurfaces, Combined, one run each: the sphere through 84 grid
  // points (lattice50) E 82.6 -> 44.7; a starfish of five thin arms (starfish60, 18.5k
  // faces) NOT_CONVERGED at E 67.5 after 337 iterations, 6.3 s -> OK, E 62.58, 84
  // iterations, 1.8 s; starfish100 258 -> 112 iterations, E 82.9 -> 63.05. Measured against
  // the floor with the continuation's own activation (1e-4): starfish100 168 iterations;
  // with 1e-2 110, 3e-1 122; in the floor stage too, 1e-1: 162.
  static constexpr double floored_activation = 1e-1;
  // The folded iterates in a row after which the input's optimistic stage stops, after a
  // level whose own optimistic stage was rejected (elsewhere `Newton_options`' 5). There the
  // input's stage folds from its first iterate on the protrusion meshes and its iterations
  // are thrown away. Measured, one run each side by side: at 90k to 280k faces, Combined,
  // bull@loop2 110 -> 106 iterations (15.0 -> 12.9 s), cow@loop2 78 -> 75 (7.0 -> 5.6 s),
  // man@loop1 105 -> 103, 79.0 -> 74.8 s over the 5 meshes that changed; the corpus
  // (14 x 3) 2252 -> 2234 iterations, 60.7 -> 58.0 s, all energies within 2.3e-6, camel
  // Tutte the one slower run (91 -> 116). Smooth meshes, whose optimistic stage may pass
  // through 3 or 4 folded iterates and end fold-free (session 23), seldom reach the input
  // with a rejected level, and none of the corpus did. Defects corpus: 6 of 7 meshes 26.3 ->
  // 21.9 s; bull@loop2@slivers200 107 -> 144 iterations, its floor stage sliding (9 -> 49
  // iterations; with 1, 3 or 5 folded iterates 7, 31, 9: the slide is chaotic, not caused).
  // Isosurfaces (marching cubes or tetrahedra) after such a level fold 8772, 2200, 353, 4 and
  // then no faces (metaballs180, Combined), where the protrusions' folds stay (man@loop1:
  // 37819, 36309, 36247, ...; cow@loop2 7210, 4520, 2623): a folded iterate with at most half
  // the folded faces of the one before does not count (`count_unfolding_iterates`).
  // metaballs180: 250 -> 33 iterations, 107 -> 6.4 s; CGAL's meshes (3 energies) and their
  // subdivisions at the held-out size took the same paths. Counting them on every level and
  // stage instead prolonged some rejected stages (armadillo's 13.5k level, Tutte, 6 -> 8
  // iterations) for nothing.
  static constexpr std::size_t input_max_folded_iterations = 2;
  // `untangle_locally()` is for a few flipped faces: not for the protrusions' thousands (2.6k
  // to 46k at the held-out size), whose patch would be much of the mesh and whose fold the
  // continuation undoes; 3 rounds of the untangling energy, where the patches of the
  // isosurfaces untangled in the first or not at all.
  static constexpr double max_untangled_share = 0.05;
  static constexpr int local_untangling_rounds = 3;
  // The rings around the faces under the floor that the floor patch frees (`lift_locally()`).
  static constexpr int patch_rings = 3;
  static constexpr std::size_t deep_lift_iterations = 40;  // see `lift_deep_faces()`
  static constexpr double few_under_floor_share = 1e-3;  // see `few_under_floor()`

  Level input_;
  std::unique_ptr<internal::Progressive_mesh> hierarchy_;
  std::vector<vertex_descriptor> vertices_;
  internal::Points last_map_;
  std::string input_detail_;
  internal::Newton_stop last_stop_ = internal::Newton_stop::CONVERGED;        // of the input level
  internal::Newton_stop last_level_stop_ = internal::Newton_stop::CONVERGED;  // of the last stage
  double last_energy_ = 0;                                                      // at its end
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZER_3_H
