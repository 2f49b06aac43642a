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
#include <CGAL/Spherical_parameterization/internal/energies/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Level.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/input/check_input.h>
#include <CGAL/Spherical_parameterization/internal/input/indexed_triangles.h>
#include <CGAL/Spherical_parameterization/internal/input/initialization.h>
#include <CGAL/Spherical_parameterization/internal/input/locality_order.h>
#include <CGAL/Spherical_parameterization/internal/input/point_coordinates.h>
#include <CGAL/Spherical_parameterization/internal/newton/Newton_solver.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/Pipeline_settings.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/Robust_pipeline.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>

#include <CGAL/Default.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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
  using Geom_traits = typename internal::Geom_traits_of<TriangleMesh, GeomTraits>::type;
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
    // The input points are read once, through the traits; the checks and the solver see only these.
    const auto coordinates = [&](vertex_descriptor v) { return internal::point_coordinates(traits_, get(vpm, v)); };
    const internal::Input_report report = internal::check_input(tm, coordinates);
    input_detail_ = report.detail;
    if(report.code != Error_code::OK)
      return report.code;

    internal::Indexed_triangles<TriangleMesh> mesh = internal::indexed_triangles(tm);
    vertices_ = std::move(mesh.vertices);
    internal::Points points;
    points.reserve(vertices_.size());
    for(vertex_descriptor v : vertices_)
      points.push_back(coordinates(v));
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
    internal::Newton_options options;
    options.start = internal::Clock::now();
    const double max_seconds = choose_parameter(get_parameter(np, CGAL::internal_np::maximum_running_time), 0.0);
    if(max_seconds > 0)
      options.deadline = options.start + std::chrono::duration_cast<internal::Clock::duration>(
                                           std::chrono::duration<double>(max_seconds));
    const long long max_iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 200);
    options.tolerance = choose_parameter(get_parameter(np, internal_np::tolerance_t()), 1e-6);
    const bool correction = choose_parameter(get_parameter(np, internal_np::d_min_correction_t()), true);
    const Pipeline pipeline = choose_parameter(get_parameter(np, internal_np::pipeline_t()), Pipeline::ROBUST);
    if(!(options.tolerance >= 0) || max_iterations <= 0 || !(max_seconds >= 0)) {
      result.status = Error_code::INVALID_PARAMETER;
      result.detail = "number_of_iterations must be positive, tolerance and maximum_running_time non-negative";
      return result;
    }
    options.max_iterations = std::size_t(max_iterations);

    internal::Points x;
    if(!initial_map(np, pipeline, x, result))
      return result;
    auto visitor = choose_parameter(get_parameter(np, CGAL::internal_np::visitor), Default_visitor());
    internal::Run_log log;
    if(!run_pipeline(pipeline, correction, options, x, visitor, log)) {
      result.status = Error_code::INVALID_INITIALIZATION;
      result.detail = "no point inside the mesh found to centre the central projection";
      return result;
    }
    finish(log, correction, x, result);
    write_map(sphere_map, x);
    last_map_ = x;
    result.time_seconds = std::chrono::duration<double>(internal::Clock::now() - options.start).count();
    return result;
  }

private:
  using Level = internal::Level<Newton>;

  static Energy default_energy()
  {
    constexpr double t = default_area_preservation;
    if constexpr(std::is_same<Energy, Balanced_energy>::value) return balanced_energy(t);
    else if constexpr(std::is_same<Energy, Combined_energy>::value) return combined_energy(1, 1);
    else if constexpr(std::is_same<Energy, Energy_mix>::value) return *energy_by_name("balanced", 1 - t, t);
    else return Energy();
  }

  // The start: the user's map, or the last map (a re-solve), or for the paper's pipeline its
  // central projection. Empty `x` (robust pipeline from scratch): the coarse-to-fine solve
  // makes its own start.
  template <class NamedParameters>
  bool initial_map(const NamedParameters& np, Pipeline pipeline, internal::Points& x, Result& result) const
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
    } else if(pipeline == Pipeline::PAPER) {
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
    if(std::abs(degree - 1) > 1e-6 && pipeline == Pipeline::ROBUST) {
      result.status = Error_code::INVALID_INITIALIZATION;
      result.detail = "the initial map has degree " + std::to_string(degree) + ", not 1";
      return false;
    }
    return true;
  }

  // Runs the pipeline from `x` (empty: from scratch). False if no start was found.
  template <class Visitor>
  bool run_pipeline(Pipeline pipeline, bool correction, const internal::Newton_options& options, internal::Points& x,
                    Visitor& visitor, internal::Run_log& log)
  {
    internal::Robust_pipeline<Energy, Newton, ConcurrencyTag, Visitor> run(input_, energy_, correction, settings_, options,
                                                                           pipeline == Pipeline::ROBUST, visitor);
    bool started = true;
    if(pipeline == Pipeline::PAPER)
      run.plain(x);
    else if(!x.empty())
      run.robust_from(x);
    else
      started = run.coarse_to_fine(x, hierarchy_);
    log = run.log();
    return started;
  }

  void finish(const internal::Run_log& log, bool correction, internal::Points& x, Result& result) const
  {
    internal::Map_validity validity = internal::check_map(input_.soup.faces, x);
    if(log.interrupted() && !validity.is_valid() && log.last_valid_input_map) {
      x = *log.last_valid_input_map;  // an interruption returns the last valid map met
      validity = internal::check_map(input_.soup.faces, x);
    }
    result.valid = validity.is_valid();
    result.iterations = log.iterations;
    // The chosen energy alone: the last stages also carry the fold barrier.
    const internal::Spherical_energy<Energy> input_energy(input_.soup, energy_, correction, ConcurrencyTag());
    result.energy = input_energy.template value<ConcurrencyTag>(x);
    result.flipped = validity.flipped;
    result.degenerate = validity.degenerate;
    result.degree = validity.degree;  // the soup's faces carry the input's orientation outward
    result.inward_oriented = input_.soup.inward;
    result.min_area_ratio = internal::min_area_ratio(input_.soup, x);
    result.stages = log.stages;
    if(log.interrupted())
      result.status = *log.interruption == internal::Newton_stop::CANCELLED ? Error_code::CANCELLED : Error_code::TIME_LIMIT;
    else if(!result.valid)
      result.status = Error_code::NO_VALID_MAP;
    else if(log.input_stop == internal::Newton_stop::ITERATION_CAP || !std::isfinite(result.energy))
      result.status = Error_code::NOT_CONVERGED;
    else
      result.status = Error_code::OK;
    if(!result.valid)
      result.detail = std::to_string(validity.flipped) + " flipped and " + std::to_string(validity.degenerate) +
                      " degenerate faces, degree " + std::to_string(result.degree);
    else if(!std::isfinite(result.energy))
      // No stage can minimize an energy it cannot evaluate: the map is a valid start, not a minimum.
      result.detail = "the energy is not finite on the map";
    else if(result.status == Error_code::NOT_CONVERGED)
      result.detail = "the input's last stage reached the cap on iterations per stage";
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
  internal::Pipeline_settings settings_;
  Level input_;
  std::unique_ptr<internal::Progressive_mesh> hierarchy_;  // made by the first solve, kept for the next
  std::vector<vertex_descriptor> vertices_;
  internal::Points last_map_;
  std::string input_detail_;
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZER_3_H
